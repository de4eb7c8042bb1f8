#include "quadrix/frame/frame.h"

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <new>

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

std::size_t PrefaultFrameMemory(int width, int height, const std::atomic<bool>* stop) {
    if (width <= 0 || height <= 0) return 0;
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (n > (std::size_t{1} << 40)) return 0;
    // The Frame's depth, normal, surface and body (4 bytes a pixel each), then the image's bytes.
    const std::size_t sizes[] = {4 * n, 4 * n, 4 * n, 4 * n, 3 * n};
    void* made[5] = {};
    std::size_t bytes[5] = {};
    int count = 0;
    for (std::size_t size : sizes) {
        if (size < kFrameHugeBytes || RoundUp(size) > kKeptBytes) continue;
        try {
            made[count] = AllocateFrameBytes(size);  // mapped, nothing touched yet
        } catch (const std::bad_alloc&) {
            break;  // the render will ask (and say so) itself
        }
        bytes[count++] = size;
    }
    // Huge page by huge page, in the order the render first writes them: the Frame's arrays from
    // the top rows down, side by side, then the image. One write per 4 KiB page (one fault for a
    // huge page; each of its small pages where the kernel gave none). The contents of a Frame's
    // memory are unspecified. Stopped between huge pages when asked.
    auto touch = [&](int k, std::size_t at) {
        auto* c = static_cast<volatile unsigned char*>(made[k]);
        const std::size_t end = std::min(bytes[k], at + kHugePage);
        for (std::size_t i = at; i < end; i += 4096) c[i] = 0;
    };
    auto stopped = [&] { return stop && stop->load(std::memory_order_relaxed); };
    const int frameArrays = count > 0 && bytes[count - 1] == 3 * n ? count - 1 : count;
    for (std::size_t at = 0; at < 4 * n && !stopped(); at += kHugePage)
        for (int k = 0; k < frameArrays && !stopped(); ++k) touch(k, at);
    for (int k = frameArrays; k < count; ++k)
        for (std::size_t at = 0; at < bytes[k] && !stopped(); at += kHugePage) touch(k, at);
    std::size_t kept = 0;
    for (int i = 0; i < count; ++i) {
        if (Keep(made[i], RoundUp(bytes[i])))
            kept += RoundUp(bytes[i]);
        else
            munmap(made[i], RoundUp(bytes[i]));
    }
    return kept;
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
