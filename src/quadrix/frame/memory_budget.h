// The memory budget (docs/output.md "Limits"): big allocations — the Frame and image of a render —
// are checked against it before they are made, so that a size the machine cannot hold is a clear
// error instead of std::bad_alloc or the kernel's OOM killer.
//
// The budget is the smallest of: the address-space and data limits (ulimit -v / -d: RLIMIT_AS,
// RLIMIT_DATA), the cgroup's memory.max (containers, systemd units), the physical memory, and
// the value set with SetMemoryBudget (the --max-memory option). What the process already holds
// is not subtracted (a render's own tables are small next to its Frame).
#pragma once

#include <cstddef>
#include <string>

namespace quadrix {

// Bytes a render may use; see above.
std::size_t MemoryBudget();
// Caps the budget (0 = no cap of our own).
void SetMemoryBudget(std::size_t bytes);

// Memory a render of W×H pixels needs (the Frame's depth, normal and ids, the shaded RGB image,
// and the engines' per-pixel scratch), in bytes.
std::size_t RenderBytes(long long width, long long height);

// "2G", "512M", "1.5GiB", "64k", "1000000" (bytes; K/M/G/T are powers of 1024, with or without
// "iB"/"B"). Returns false for anything else or a value below 1 MiB.
bool ParseByteSize(const std::string& text, std::size_t& bytes);

// Empty when `bytes` fit the budget, else "WHAT needs about N; the memory budget is M (SOURCE)".
std::string CheckMemory(std::size_t bytes, const std::string& what);

}  // namespace quadrix
