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
// are touched. Other threads' arenas are left as they are (measured: sharing the main arena
// saved few faults more).
//
// Nothing happens (false) where the C library is not glibc, under AddressSanitizer (its own
// allocator), under an address-space or data limit (the reservation would count against it), or
// when the kernel refuses; allocations behave as before then. `reserve`: 4 MiB to 512 MiB.
#pragma once

#include <cstddef>

namespace quadrix {

bool UseHugePagesForTheHeap(std::size_t reserve);

}  // namespace quadrix
