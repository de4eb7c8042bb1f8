// Transparent huge pages for big buffers that the program fills at once (issue 24): advice that
// the 2 MiB pages of a buffer be backed by huge pages (madvise(MADV_HUGEPAGE); Debian's default
// setting is `[madvise]`, as on the benchmark machines). Writing fresh memory costs one page
// fault per page, and on a virtual machine a fault is expensive: writing 64 MiB costs 195 ms of
// CPU in 4 KiB pages and 16 ms in 2 MiB pages on the benchmark machine. The advice changes
// nothing else: where huge pages are not available the memory is the same.
//
// Only whole 2 MiB pages of a buffer can be huge, and a malloc'ed buffer is rarely aligned to
// them. glibc maps a request of k·2 MiB − 24 bytes (and more than its mmap threshold) as exactly
// k·2 MiB, and Linux places such a mapping on a 2 MiB boundary: HugePageRequest rounds a size up
// to that, so that the whole buffer can be huge. Elsewhere the rounding only wastes address space
// (never touched memory), and the buffer's whole inner pages are still advised.
//
//   text.reserve(HugePageRequest(size) - 1);   // std::string asks for one byte more
//   AdviseHugePages(text.data(), text.capacity() + 1);
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>

namespace quadrix {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// The malloc request of at least `bytes` that fills whole huge pages (above); `bytes` itself
// when it is under one huge page.
inline std::size_t HugePageRequest(std::size_t bytes) {
    constexpr std::size_t kMallocOverhead = 24;
    if (bytes < kHugePageBytes || bytes > (std::size_t{1} << 60)) return bytes;
    const std::size_t pages = (bytes + kMallocOverhead + kHugePageBytes - 1) / kHugePageBytes;
    return pages * kHugePageBytes - kMallocOverhead;
}

// Advises the 2 MiB pages of [p, p + bytes), a buffer of malloc or operator new (`bytes` being
// the size asked for, which may be a little more than what is used of it): the whole pages inside
// it, and the first and last pages when they overhang it by no more than malloc's own header and
// trailer of the block (64 bytes), as a HugePageRequest buffer does. Advice on a few bytes of a
// neighbouring block would be harmless: it changes no data, only the page size.
inline void AdviseHugePages(const void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
    constexpr std::uintptr_t kSlack = 64;
    if (bytes < kHugePageBytes) return;
    const auto begin = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first =
        (begin - kSlack + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    const std::uintptr_t last = (begin + bytes + kSlack) / kHugePageBytes * kHugePageBytes;
    if (last <= first) return;
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#ifndef MADV_COLLAPSE
#define MADV_COLLAPSE 25  // Linux 6.1 (linux/mman.h); older kernels refuse it, harmlessly
#endif
    // malloc wrote its header in the first page before the advice came, so that page is already
    // mapped in 4 KiB pages and the rest of it would fault in 4 KiB pages too: collapse it now.
    if (first < begin) madvise(reinterpret_cast<void*>(first), kHugePageBytes, MADV_COLLAPSE);
#else
    (void)p;
    (void)bytes;
#endif
}

}  // namespace quadrix
