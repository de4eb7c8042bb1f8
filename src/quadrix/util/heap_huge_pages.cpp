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

#if QUADRIX_HEAP_HUGE_PAGES
namespace {
// Kept (UseHugePagesForTheHeap); volatile, or the compiler drops a block that is never read and
// the call that made it.
void* volatile heapFiller = nullptr;
bool heapInHugePages = false;  // UseHugePagesForTheHeap has succeeded
}  // namespace
#endif

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
    constexpr std::uintptr_t kProbe = 256 << 10;
    void* probe = std::malloc(kProbe);
    const auto lo = reinterpret_cast<std::uintptr_t>(probe);
    std::free(probe);
    mallopt(M_TOP_PAD, 128 << 10);
    if (!probe) return false;
    // The advised range begins at the first 2 MiB page the probe did not touch: malloc wrote the
    // header of the top that followed it, and a 2 MiB page with a 4 KiB page in it stays in 4 KiB
    // pages (512 faults).
    const auto hi = reinterpret_cast<std::uintptr_t>(sbrk(0));
    const std::uintptr_t start = (lo + kProbe + 64 + kHuge - 1) & ~(kHuge - 1),
                         end = hi & ~(kHuge - 1);
    if (hi == static_cast<std::uintptr_t>(-1) || end <= start) return false;
    if (madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE) != 0) return false;
    // The heap's top begins below `start`, in memory that cannot be in huge pages (the heap's
    // first pages or the probe's share its 2 MiB page): what the program allocated next would
    // fill it 4 KiB at a time, up to 512 faults a process as the heap's address falls. One block,
    // kept and never touched, fills it instead, so that the next blocks begin in the advised range.
    heapFiller = std::malloc(start - lo + 64);
    heapInHugePages = true;
    return true;
#else
    (void)reserve;
    return false;
#endif
}

bool ShareTheHeapWithLaterThreads() {
#if QUADRIX_HEAP_HUGE_PAGES
    return heapInHugePages && mallopt(M_ARENA_MAX, 1) == 1;
#else
    return false;
#endif
}

}  // namespace quadrix
