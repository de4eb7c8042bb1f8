// The memory budget; see memory_budget.h.
#include "quadrix/frame/memory_budget.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <limits>

#include "quadrix/io/bounded_read.h"

namespace quadrix {

namespace {

std::atomic<std::size_t> gCap{0};

constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();

std::size_t RlimitBytes(int resource) {
    struct rlimit r {};
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return kUnlimited;
    return static_cast<std::size_t>(r.rlim_cur);
}

std::size_t CgroupBytes() {
    // cgroup v2; "max" or a missing file means no limit.
    std::FILE* f = std::fopen("/sys/fs/cgroup/memory.max", "r");
    if (!f) return kUnlimited;
    unsigned long long v = 0;
    bool ok = std::fscanf(f, "%llu", &v) == 1;
    std::fclose(f);
    return ok ? static_cast<std::size_t>(v) : kUnlimited;
}

std::size_t PhysicalBytes() {
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || size <= 0) return kUnlimited;
    return static_cast<std::size_t>(pages) * static_cast<std::size_t>(size);
}

// The budget and what sets it.
std::pair<std::size_t, const char*> Budget() {
    std::pair<std::size_t, const char*> b{kUnlimited, "no limit"};
    auto take = [&](std::size_t v, const char* source) {
        if (v < b.first) b = {v, source};
    };
    take(PhysicalBytes(), "physical memory");
    take(CgroupBytes(), "cgroup memory.max");
    take(RlimitBytes(RLIMIT_DATA), "ulimit -d");
    take(RlimitBytes(RLIMIT_AS), "ulimit -v");
    if (std::size_t cap = gCap.load(); cap != 0) take(cap, "--max-memory");
    return b;
}

}  // namespace

std::size_t MemoryBudget() { return Budget().first; }

void SetMemoryBudget(std::size_t bytes) { gCap.store(bytes); }

std::size_t RenderBytes(long long width, long long height) {
    // Frame: 16 bytes a pixel (frame.h); the RGB image 3 and its linear floats 12; engines keep
    // at most about one more double depth, normal and id per pixel (44), and merging keeps a
    // second Frame (16). 96 bytes a pixel covers all of these.
    constexpr std::size_t kBytesPerPixel = 96;
    if (width <= 0 || height <= 0) return 0;
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * kBytesPerPixel;
}

bool ParseByteSize(const std::string& text, std::size_t& bytes) {
    double value = 0;
    int used = 0;
    if (std::sscanf(text.c_str(), "%lf%n", &value, &used) != 1 || !(value > 0)) return false;
    std::string unit = text.substr(static_cast<std::size_t>(used));
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (unit.size() >= 2 && unit.compare(unit.size() - 2, 2, "IB") == 0)
        unit.resize(unit.size() - 2);
    else if (!unit.empty() && unit.back() == 'B')
        unit.pop_back();
    double scale = 1;
    if (unit == "K")
        scale = 1024.0;
    else if (unit == "M")
        scale = 1024.0 * 1024;
    else if (unit == "G")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "T")
        scale = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty())
        return false;
    const double b = value * scale;
    if (!(b >= 1024.0 * 1024) || b > 1e18) return false;
    bytes = static_cast<std::size_t>(b);
    return true;
}

std::string CheckMemory(std::size_t bytes, const std::string& what) {
    auto [budget, source] = Budget();
    if (bytes <= budget) return {};
    return fmt::format("{} needs about {} of memory; the memory budget is {} ({})", what,
                       ByteSizeText(static_cast<double>(bytes)),
                       ByteSizeText(static_cast<double>(budget)), source);
}

}  // namespace quadrix
