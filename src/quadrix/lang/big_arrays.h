// Growth of the reader's big arrays (a scope's half-spaces, bodies and csg nodes, issue 24): the
// same capacities as push_back would give, but a buffer of several MiB is advised to use
// transparent huge pages before its elements move in (util/huge_pages.h).
//
// A scene of 100,000 spheres holds about 50 MB of scene objects; the reader is the first to write
// them, and in 4 KiB pages it paid one page fault per 4 KiB (12,000 faults at several µs each on
// a virtual machine: a third of reading). In 2 MiB pages it pays about 25. The advice changes
// nothing else: without huge pages the memory is the same, and the elements are only moved as
// vector::reserve moves them.
//
//   ReserveAdvised(scope.halfSpaces, n);    // capacity >= n
//   PrepareAppend(scope.halfSpaces);         // before push_back: room for one more
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "quadrix/util/huge_pages.h"

namespace quadrix::lang {

// Makes the capacity at least `n` (rounded up to fill whole huge pages when the buffer is big),
// advising a big new buffer before the elements move into it.
template <class T, class A>
void ReserveAdvised(std::vector<T, A>& v, std::size_t n) {
    if (n <= v.capacity()) return;
    if (n > v.max_size() || n * sizeof(T) < kHugePageBytes) {
        v.reserve(n);
        return;
    }
    // The capacity that fills the request's huge pages; the allocation of n * sizeof(T) bytes
    // (a little less than the request) is mapped the same.
    const std::size_t request = HugePageRequest(n * sizeof(T));
    n = request / sizeof(T);
    // reserve() allocates and moves in one step, so the advice would come after the first
    // touch: allocate an empty vector of the capacity, advise it, then move the elements in.
    std::vector<T, A> bigger(v.get_allocator());
    bigger.reserve(n);
    AdviseHugePages(bigger.data(), request);
    for (T& x : v) bigger.push_back(std::move(x));
    v.swap(bigger);
}

// Room for one more element: doubles a full vector's capacity, as push_back does.
template <class T, class A>
void PrepareAppend(std::vector<T, A>& v) {
    if (v.size() < v.capacity()) return;
    ReserveAdvised(v, std::max<std::size_t>(16, 2 * v.capacity()));
}

}  // namespace quadrix::lang
