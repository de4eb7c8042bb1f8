#include "quadrix/frame/frame.h"

#include <sys/mman.h>

#include <cstdint>
#include <mutex>

namespace quadrix {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
std::size_t RoundUp(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

// Mappings freed and kept for the next allocation of the same length: the Frame's arrays, the
// image and the window's pixels made and dropped for every frame (the viewer's) then cost neither
// mmap/munmap nor the kernel's zeroing and faulting of their pages each time (measured in
// docs/performance.md "Viewer"). A 1280x720 frame's set (depth, normals, two id arrays, the RGB
// image, the display words: 20 MiB) fits; at most kKeptSlots mappings of at most kKeptBytes each
// and kKeptTotal in all are kept, so a big Frame's memory is returned when it is freed.
constexpr std::size_t kKeptBytes = std::size_t{32} << 20;
constexpr std::size_t kKeptTotal = std::size_t{96} << 20;
constexpr int kKeptSlots = 8;
struct KeptMapping {
    void* p = nullptr;
    std::size_t length = 0;
};
std::mutex keptMutex;
KeptMapping kept[kKeptSlots];
std::size_t keptTotal = 0;

// A kept mapping of exactly `len` bytes, else the start of the shortest longer one, whose rest
// is unmapped (lengths are whole huge pages, so the start stays aligned): a picture's encoder
// then writes into pages the freed Frame had already faulted in (render_command.cpp releases
// the Frame before the write when nothing there reads it), not into fresh ones.
void* TakeKept(std::size_t len) {
    std::lock_guard lock(keptMutex);
    KeptMapping* best = nullptr;
    for (KeptMapping& k : kept) {
        if (!k.p || k.length < len) continue;
        if (!best || k.length < best->length) best = &k;
        if (k.length == len) break;
    }
    if (!best) return nullptr;
    void* p = best->p;
    if (best->length > len) munmap(static_cast<char*>(p) + len, best->length - len);
    keptTotal -= best->length;
    *best = {};
    return p;
}

bool Keep(void* p, std::size_t len) {
    if (len > kKeptBytes) return false;
    std::lock_guard lock(keptMutex);
    if (keptTotal + len > kKeptTotal) return false;
    for (KeptMapping& k : kept) {
        if (k.p) continue;
        k = {p, len};
        keptTotal += len;
        return true;
    }
    return false;
}

}  // namespace

void* AllocateFrameBytes(std::size_t bytes) {
    const std::size_t len = RoundUp(bytes);
    if (len < bytes || len + kHugePage < len) throw std::bad_alloc();
    if (void* p = TakeKept(len)) {
#ifdef MADV_HUGEPAGE
        madvise(p, len, MADV_HUGEPAGE);  // AdviseSmallPages may have changed it
#endif
        return p;
    }
    // Map 2 MiB more than needed, then unmap the ends so that what is left is aligned.
    void* m =
        mmap(nullptr, len + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED) throw std::bad_alloc();
    const auto base = reinterpret_cast<std::uintptr_t>(m);
    const std::uintptr_t aligned = (base + kHugePage - 1) / kHugePage * kHugePage;
    if (aligned > base) munmap(m, aligned - base);
    const std::uintptr_t end = base + len + kHugePage;
    if (end > aligned + len) munmap(reinterpret_cast<void*>(aligned + len), end - (aligned + len));
    void* p = reinterpret_cast<void*>(aligned);
#ifdef MADV_HUGEPAGE
    madvise(p, len, MADV_HUGEPAGE);  // advice only: without huge pages the memory is the same
#endif
    return p;
}

void FreeFrameBytes(void* p, std::size_t bytes) {
    if (p && !Keep(p, RoundUp(bytes))) munmap(p, RoundUp(bytes));
}

void ReleaseKeptFrameBytes() {
    std::lock_guard lock(keptMutex);
    for (KeptMapping& k : kept)
        if (k.p) {
            munmap(k.p, k.length);
            k = {};
        }
    keptTotal = 0;
}

namespace {
template <class Array>
void AdviseSmall(Array& a) {
    const std::size_t bytes = a.size() * sizeof(typename Array::value_type);
#ifdef MADV_NOHUGEPAGE
    if (bytes >= kFrameHugeBytes) madvise(a.data(), RoundUp(bytes), MADV_NOHUGEPAGE);
#else
    (void)bytes;
#endif
}
}  // namespace

void AdviseSmallPages(Frame& frame) {
    AdviseSmall(frame.depth);
    AdviseSmall(frame.normal);
    AdviseSmall(frame.surface);
    AdviseSmall(frame.body);
}

void ComposeMin(Frame& into, const Frame& other) {
    for (std::size_t i = 0; i < into.depth.size() && i < other.depth.size(); ++i)
        into.Offer(i, other.depth[i], other.normal[i], other.surface[i], other.body[i]);
    if (into.bodySolid.size() < other.bodySolid.size()) into.bodySolid = other.bodySolid;
}

}  // namespace quadrix
