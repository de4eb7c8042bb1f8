#include "quadrix/frame/frame.h"

#include <sys/mman.h>

#include <cstdint>

namespace quadrix {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
std::size_t RoundUp(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }
}  // namespace

void* AllocateFrameBytes(std::size_t bytes) {
    const std::size_t len = RoundUp(bytes);
    if (len < bytes || len + kHugePage < len) throw std::bad_alloc();
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
    if (p) munmap(p, RoundUp(bytes));
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
    AdviseSmall(frame.solid);
}

void ComposeMin(Frame& into, const Frame& other) {
    for (std::size_t i = 0; i < into.depth.size() && i < other.depth.size(); ++i)
        into.Offer(i, other.depth[i], other.normal[i], other.surface[i], other.body[i],
                   other.solid[i]);
}

}  // namespace quadrix
