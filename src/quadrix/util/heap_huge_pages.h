// Transparent huge pages for the process's heap (a program's start-up policy, called from main).
//
// A page's first touch costs 12-18 µs on the virtual machines Quadrix is measured on, and the
// heap grows in 4 KiB pages: a 1280x720 render of the machined part took ~5,800 page faults,
// ~3,700 of them in the heap (measured with glibc's own switch, GLIBC_TUNABLES=
// glibc.malloc.hugetlb=1, which needs the environment set before the program starts). This does
// the same from inside the program for the main arena: it makes the heap take `reserve` bytes
// at once, advises them to use transparent huge pages (madvise MADV_HUGEPAGE: a 2 MiB page is
// one fault), serves allocations up to 32 MiB from the heap rather than their own mappings, and
// keeps freed memory in the heap (no trimming), so that memory freed by one stage is reused by
// the next one without faulting again. Only virtual memory is reserved; pages are made as they
// are touched.
//
// Only whole 2 MiB pages with nothing in them yet can become huge: a 2 MiB page of which one
// 4 KiB page is mapped stays in 4 KiB pages (512 faults to fill). So the advice begins past the
// pages the reservation itself wrote, and one block, kept and never touched, fills the heap from
// its top to there: the program's next blocks begin in huge pages. (Without it, they filled the
// rest of the 2 MiB page the heap's top began in, or, when the reservation's write fell in the
// first advised page, all of that page, 4 KiB at a time: 0 to 512 faults a process as the heap's
// address fell. The machined part at 64 x 64 took 445 faults, 325 with it; at 1280 x 720 615-805,
// 437.)
//
// Threads started afterwards share that heap (M_ARENA_MAX 1) instead of each taking an arena of
// its own: glibc maps such an arena in 64 MiB and grows it a few pages at a time, so a thread's
// memory comes in 4 KiB pages. The raycast engine's second thread builds each tile's CSG
// programs in its own memory: for the 20,211-body helicopter at 1280 x 720 that was 862 faults in
// the render phase, 19 with the shared heap, and the render phase took 34.1 / 35.6 ms against
// 25.6 / 28.4 (min / median, 21 alternating processes; docs/performance.md, twenty-sixth
// session). Small allocations do not contend for the shared heap's lock (each thread keeps its
// own cache of them, glibc's tcache); the machined part's whole process took no longer (50.8
// against 52.9 ms, and 82.1 against 84.5 ms of CPU, medians).
//
// Nothing happens (false) where the C library is not glibc, under AddressSanitizer (its own
// allocator), under an address-space or data limit (the reservation would count against it), or
// when the kernel refuses; allocations behave as before then. `reserve`: 4 MiB to 512 MiB.
#pragma once

#include <cstddef>

namespace quadrix {

bool UseHugePagesForTheHeap(std::size_t reserve);

}  // namespace quadrix
