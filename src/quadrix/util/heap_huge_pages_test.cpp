#include "quadrix/util/heap_huge_pages.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "quadrix/util/sanitizers.h"

namespace quadrix {
namespace {

long MinorFaults() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
}

// The VmFlags line of /proc/self/smaps for the mapping that holds `p` ("" when not found).
std::string VmFlagsOf(const void* p) {
    const auto a = reinterpret_cast<std::uintptr_t>(p);
    std::ifstream f("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(f, line)) {
        unsigned long lo = 0, hi = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2 &&
            line.find(' ') > line.find('-')) {
            inside = a >= lo && a < hi;
        } else if (inside && line.rfind("VmFlags:", 0) == 0) {
            return line + " ";
        }
    }
    return "";
}

// Why the heap cannot be put in huge pages here, or "" when it can.
std::string WhyNot() {
    if (QUADRIX_ASAN) return "AddressSanitizer allocates the heap itself";
#if !defined(__GLIBC__)
    return "the C library is not glibc";
#endif
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string mode;
    if (!std::getline(f, mode)) return "this kernel has no transparent huge pages";
    if (mode.find("[never]") != std::string::npos) return "transparent huge pages are off here";
    rlimit r{};
    if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
        return "an address-space limit is set (ulimit -v)";
    return "";
}

// Each gtest case runs in a process of its own (gtest_discover_tests), so changing the
// process's allocator here touches no other test.
TEST(HeapHugePages, AllocationsOfMegabytesComeFromTheHeapInHugePages) {
    if (std::string why = WhyNot(); !why.empty()) GTEST_SKIP() << why;
    ASSERT_TRUE(UseHugePagesForTheHeap(std::size_t{64} << 20));
    constexpr std::size_t kBytes = std::size_t{8} << 20;
    char* p = static_cast<char*>(std::malloc(kBytes));
    ASSERT_NE(p, nullptr);
    // From the heap, below the break (glibc would have mapped 8 MiB on its own before).
    const auto brk = reinterpret_cast<std::uintptr_t>(sbrk(0));
    EXPECT_LE(reinterpret_cast<std::uintptr_t>(p) + kBytes, brk);
    // Advised: the mapping that holds its middle carries the huge-page advice ("hg" in its
    // VmFlags; the whole 2 MiB pages of the reserved range are advised, and the block's first
    // bytes may lie before the first of them).
    // Whether the kernel then finds free 2 MiB pages depends on the machine's memory at that
    // moment (it falls back to 4 KiB pages when it cannot), so the faults are reported, not
    // asserted: 8 MiB in 4 KiB pages is 2,048 faults, in 2 MiB pages a handful.
    const std::string flags = VmFlagsOf(p + kBytes / 2);
    EXPECT_NE(flags.find(" hg "), std::string::npos) << flags;
    const long before = MinorFaults();
    std::memset(p, 1, kBytes);
    const long faults = MinorFaults() - before;
    RecordProperty("faults_for_8_MiB", static_cast<int>(faults));
    std::printf("8 MiB touched with %ld page faults\n", faults);
    // Freed and allocated again: the same memory, no new faults.
    std::free(p);
    char* q = static_cast<char*>(std::malloc(kBytes));
    ASSERT_NE(q, nullptr);
    const long again = MinorFaults();
    std::memset(q, 2, kBytes);
    EXPECT_LT(MinorFaults() - again, 16);
    std::free(q);
}

// The next blocks come from the advised range, not from the rest of the 2 MiB page in which the
// heap's top began (whose 4 KiB pages would each fault): a block of 1 MiB, larger than any free
// one left by the program's start, is advised from its first byte.
TEST(HeapHugePages, TheNextBlocksBeginInTheAdvisedRange) {
    if (std::string why = WhyNot(); !why.empty()) GTEST_SKIP() << why;
    ASSERT_TRUE(UseHugePagesForTheHeap(std::size_t{64} << 20));
    char* p = static_cast<char*>(std::malloc(std::size_t{1} << 20));
    ASSERT_NE(p, nullptr);
    EXPECT_NE(VmFlagsOf(p).find(" hg "), std::string::npos) << VmFlagsOf(p);
    std::free(p);
}

// Told to, a thread started afterwards allocates from the same heap (M_ARENA_MAX 1): its blocks
// lie below the break, in the advised range, not in an arena of its own (a mapping of glibc's
// elsewhere).
TEST(HeapHugePages, LaterThreadsShareTheHeapWhenTold) {
    if (std::string why = WhyNot(); !why.empty()) GTEST_SKIP() << why;
    ASSERT_TRUE(UseHugePagesForTheHeap(std::size_t{64} << 20));
    ASSERT_TRUE(ShareTheHeapWithLaterThreads());
    constexpr std::size_t kBytes = std::size_t{1} << 20;
    void* own = std::malloc(kBytes);
    ASSERT_NE(own, nullptr);
    void* block = nullptr;
    void* small = nullptr;
    std::thread([&] {
        block = std::malloc(kBytes);
        small = std::malloc(4000);  // past the thread's small-block cache
    }).join();
    ASSERT_NE(block, nullptr);
    ASSERT_NE(small, nullptr);
    const auto brk = reinterpret_cast<std::uintptr_t>(sbrk(0));
    const auto heapLo = reinterpret_cast<std::uintptr_t>(own) - (std::uintptr_t{64} << 20);
    for (void* p : {block, small}) {
        const auto a = reinterpret_cast<std::uintptr_t>(p);
        EXPECT_LE(a + 4000, brk) << p;
        EXPECT_GE(a, heapLo) << p;
    }
    EXPECT_NE(VmFlagsOf(static_cast<char*>(block) + kBytes / 2).find(" hg "), std::string::npos);
    std::free(small);
    std::free(block);
    std::free(own);
}

TEST(HeapHugePages, UnderAnAddressSpaceLimitTheHeapIsLeftAsItIs) {
    if (QUADRIX_ASAN) GTEST_SKIP() << "AddressSanitizer cannot run under an address-space limit";
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        rlimit r{};
        getrlimit(RLIMIT_AS, &r);
        r.rlim_cur = std::size_t{8} << 30;
        if (setrlimit(RLIMIT_AS, &r) != 0) _exit(3);
        if (UseHugePagesForTheHeap(std::size_t{256} << 20)) _exit(1);
        void* p = std::malloc(std::size_t{1} << 20);  // allocation works as before
        _exit(p ? 0 : 2);
    }
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: reserved under the limit, 2: malloc failed after, "
                                         "3: setrlimit failed";
}

TEST(HeapHugePages, SizesOutsideTheRangeAreRefused) {
    EXPECT_FALSE(UseHugePagesForTheHeap(1 << 20));
    EXPECT_FALSE(UseHugePagesForTheHeap(std::size_t{1} << 31));
}

}  // namespace
}  // namespace quadrix
