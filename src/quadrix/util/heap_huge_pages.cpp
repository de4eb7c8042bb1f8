#include "quadrix/util/heap_huge_pages.h"

#include <cstdint>
#include <cstdlib>

#include "quadrix/util/huge_pages.h"
#include "quadrix/util/sanitizers.h"

#if defined(__GLIBC__) && defined(__linux__) && !QUADRIX_ASAN
#define QUADRIX_HEAP_HUGE_PAGES 1
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#else
#define QUADRIX_HEAP_HUGE_PAGES 0
#endif

namespace quadrix {

bool UseHugePagesForTheHeap(std::size_t reserve) {
#if QUADRIX_HEAP_HUGE_PAGES
    constexpr std::uintptr_t kHuge = kHugePageBytes;
    if (reserve < 2 * kHuge || reserve > (std::size_t{512} << 20)) return false;
    // Under an address-space or data limit (ulimit -v, -d) the reservation would count against
    // it: the heap is left as it is.
    const int limits[] = {RLIMIT_AS, RLIMIT_DATA};
    for (int resource : limits) {
        rlimit r{};
        if (getrlimit(resource, &r) != 0 || r.rlim_cur != RLIM_INFINITY) return false;
    }
    const int size = static_cast<int>(reserve);
    if (mallopt(M_MMAP_THRESHOLD, 32 << 20) != 1) return false;
    mallopt(M_TRIM_THRESHOLD, 2 * size);  // never trims the reserved region
    // One allocation larger than the heap's free top makes it grow by `reserve` more (the top
    // pad); freed, it goes back to the top, which then reaches the end of the new region. Later
    // growth takes the usual pad again.
    mallopt(M_TOP_PAD, size);
    void* probe = std::malloc(256 << 10);
    const auto lo = reinterpret_cast<std::uintptr_t>(probe);
    std::free(probe);
    mallopt(M_TOP_PAD, 128 << 10);
    if (!probe) return false;
    const auto hi = reinterpret_cast<std::uintptr_t>(sbrk(0));
    const std::uintptr_t start = (lo + kHuge - 1) & ~(kHuge - 1), end = hi & ~(kHuge - 1);
    if (hi == static_cast<std::uintptr_t>(-1) || end <= start) return false;
    return madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE) == 0;
#else
    (void)reserve;
    return false;
#endif
}

}  // namespace quadrix
