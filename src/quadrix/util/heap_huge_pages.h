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
// Nothing happens (false) where the C library is not glibc, under AddressSanitizer (its own
// allocator), under an address-space or data limit (the reservation would count against it), or
// when the kernel refuses; allocations behave as before then. `reserve`: 4 MiB to 512 MiB.
#pragma once

#include <cstddef>

namespace quadrix {

bool UseHugePagesForTheHeap(std::size_t reserve);

// For a program about to do one short job on several threads (`quadrix render` of one picture):
// the threads it starts from now on allocate from the heap UseHugePagesForTheHeap set up
// (M_ARENA_MAX 1) instead of each taking an arena of its own, which glibc maps in 64 MiB and
// makes writable a few pages at a time, so in 4 KiB pages, each a fault. The raycast engine's
// second thread builds each tile's CSG programs in its own memory: for the 20,211-body helicopter
// at 1280 x 720 that was 862 faults in the render phase, 19 in the shared heap, and the render
// phase took 35.9 / 38.5 ms against 26.8 / 31.8 (min / median of 21 alternating processes). But
// threads that go on working share the heap's lock and its cache lines: 12 turntable frames of the
// machined part in one process took 3.5 % longer (449 -> 460-469 ms, CPU 851 -> 882-896 ms),
// so animations, batches and the viewer keep the threads' own arenas (docs/performance.md,
// twenty-sixth session). False, and nothing done, when the heap is not in huge pages. Call it
// before the threads exist: glibc gives a thread its arena at its first allocation.
bool ShareTheHeapWithLaterThreads();

}  // namespace quadrix
