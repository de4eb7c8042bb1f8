// The parallel loops (parallel.h): inside a SerialScope they run the whole range once, in order,
// on the calling thread; outside, oneTBB splits them; nesting restores the state before.
#include "quadrix/util/parallel.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace quadrix {
namespace {

TEST(ParallelLoops, ASerialScopeRunsTheWholeRangeOnceInOrderOnTheCallingThread) {
    tbb::task_arena arena(2);
    arena.execute([] {
        const std::thread::id me = std::this_thread::get_id();
        SerialScope serial;
        int calls = 0;
        ParallelFor(tbb::blocked_range<int>(0, 1000, 1), [&](const tbb::blocked_range<int>& r) {
            ++calls;
            EXPECT_EQ(r.begin(), 0);
            EXPECT_EQ(r.end(), 1000);
            EXPECT_EQ(std::this_thread::get_id(), me);
        });
        EXPECT_EQ(calls, 1);
        std::vector<int> order;
        ParallelFor(3, 9, [&](int i) {
            order.push_back(i);
            EXPECT_EQ(std::this_thread::get_id(), me);
        });
        EXPECT_EQ(order, (std::vector<int>{3, 4, 5, 6, 7, 8}));
        ParallelFor(tbb::blocked_range<int>(5, 5), [&](const tbb::blocked_range<int>&) {
            ADD_FAILURE() << "an empty range runs no body";
        });
        const double sum = ParallelReduce(
            tbb::blocked_range<int>(1, 101, 1), 0.5,
            [](const tbb::blocked_range<int>& r, double s) {
                for (int i = r.begin(); i < r.end(); ++i) s += i;
                return s;
            },
            [](double a, double b) { return a + b; });
        EXPECT_EQ(sum, 5050.5);
        EXPECT_EQ(ParallelReduce(
                      tbb::blocked_range<int>(0, 0), 7,
                      [](const tbb::blocked_range<int>&, int) { return -1; },
                      [](int a, int b) { return a + b; }),
                  7);
    });
}

TEST(ParallelLoops, WithoutAScopeOneTbbSplitsTheRange) {
    EXPECT_FALSE(SerialLoopsOnThisThread());
    tbb::task_arena arena(2);
    arena.execute([] {
        std::atomic<int> calls{0}, sum{0};
        ParallelFor(tbb::blocked_range<int>(0, 1000, 1), [&](const tbb::blocked_range<int>& r) {
            ++calls;
            for (int i = r.begin(); i < r.end(); ++i) sum += i;
        });
        EXPECT_GT(calls.load(), 1);
        EXPECT_EQ(sum.load(), 499500);
    });
}

TEST(ParallelLoops, ALoopArenaScopeRunsTheLoopsInItsArena) {
    // An arena of one thread, started on another thread (as RenderContext does); the default
    // arena has two. Started before the loops: loops begun while it starts run their first
    // grains outside it (the next test).
    tbb::task_arena one(1);
    std::thread starter([&] { one.initialize(); });
    starter.join();
    std::atomic<int> widest{0};
    auto note = [&] {
        const int c = tbb::this_task_arena::max_concurrency();
        int w = widest.load();
        while (c > w && !widest.compare_exchange_weak(w, c)) {
        }
    };
    {
        LoopArenaScope loops(&one);
        ParallelFor(tbb::blocked_range<int>(0, 100, 1), [&](const tbb::blocked_range<int>&) {
            note();
            // A nested loop stays in the same arena.
            ParallelFor(0, 4, [&](int) { note(); });
        });
        const int sum = ParallelReduce(
            tbb::blocked_range<int>(0, 10, 1), 0,
            [&](const tbb::blocked_range<int>& r, int v) {
                note();
                for (int i = r.begin(); i < r.end(); ++i) v += i;
                return v;
            },
            [](int a, int b) { return a + b; });
        EXPECT_EQ(sum, 45);
    }
    EXPECT_EQ(widest.load(), 1);
    EXPECT_EQ(LoopArenaOnThisThread(), nullptr);
    // Without the scope: the default arena's threads.
    widest = 0;
    ParallelFor(tbb::blocked_range<int>(0, 100, 1),
                [&](const tbb::blocked_range<int>&) { note(); });
    EXPECT_EQ(widest.load(), tbb::this_task_arena::max_concurrency());
}

TEST(ParallelLoops, BeforeTheArenaIsActiveLoopsRunGrainByGrainOnTheCallingThread) {
    // An arena nobody starts stays inactive: every loop runs here, its grains in order.
    tbb::task_arena idle(2);
    const std::thread::id me = std::this_thread::get_id();
    LoopArenaScope loops(&idle);
    EXPECT_TRUE(LoopArenaStarting());
    std::vector<std::pair<int, int>> grains;
    ParallelFor(tbb::blocked_range<int>(0, 10, 3), [&](const tbb::blocked_range<int>& r) {
        EXPECT_EQ(std::this_thread::get_id(), me);
        grains.emplace_back(r.begin(), r.end());
    });
    EXPECT_EQ(grains, (std::vector<std::pair<int, int>>{{0, 3}, {3, 6}, {6, 9}, {9, 10}}));
    std::vector<std::size_t> order;
    ParallelFor(std::size_t{3}, std::size_t{7}, [&](std::size_t i) { order.push_back(i); });
    EXPECT_EQ(order, (std::vector<std::size_t>{3, 4, 5, 6}));
    // A reduction's parts joined in order (a join that is not commutative shows it).
    const std::string digits = ParallelReduce(
        tbb::blocked_range<int>(0, 10, 4), std::string(),
        [](const tbb::blocked_range<int>& r, std::string s) {
            for (int i = r.begin(); i < r.end(); ++i) s += static_cast<char>('0' + i);
            return s + "|";
        },
        [](const std::string& a, const std::string& b) { return a + b; });
    EXPECT_EQ(digits, "0123|4567|89|");
    EXPECT_FALSE(idle.is_active());
}

TEST(ParallelLoops, LoopsBegunWhileTheArenaStartsCoverTheirRangeOnce) {
    // The arena started on another thread while the loops run (RenderContext): each index is
    // visited once whichever part ran before the start was done, and the reduction is exact.
    for (int round = 0; round < 20; ++round) {
        tbb::task_arena two(2);
        std::thread starter([&] { two.initialize(); });
        std::vector<std::atomic<int>> seen(20000);
        long long sum = 0;
        {
            LoopArenaScope loops(&two);
            ParallelFor(tbb::blocked_range<std::size_t>(0, seen.size(), 16),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                            for (std::size_t i = r.begin(); i < r.end(); ++i) ++seen[i];
                        });
            ParallelFor(0, 5000, [&](int i) { ++seen[static_cast<std::size_t>(i)]; });
            sum = ParallelReduce(
                tbb::blocked_range<int>(0, 20000, 8), 0LL,
                [](const tbb::blocked_range<int>& r, long long v) {
                    for (int i = r.begin(); i < r.end(); ++i) v += i;
                    return v;
                },
                [](long long a, long long b) { return a + b; });
        }
        starter.join();
        for (std::size_t i = 0; i < seen.size(); ++i)
            ASSERT_EQ(seen[i].load(), i < 5000 ? 2 : 1) << "index " << i << ", round " << round;
        EXPECT_EQ(sum, 20000LL * 19999 / 2);
    }
}

TEST(ParallelLoops, ScopesNestAndRestore) {
    EXPECT_FALSE(SerialLoopsOnThisThread());
    {
        SerialScope outer;
        EXPECT_TRUE(SerialLoopsOnThisThread());
        {
            SerialScope inner;
            EXPECT_TRUE(SerialLoopsOnThisThread());
        }
        EXPECT_TRUE(SerialLoopsOnThisThread());
        // Another thread's loops are its own business.
        bool other = true;
        std::thread([&] { other = SerialLoopsOnThisThread(); }).join();
        EXPECT_FALSE(other);
    }
    EXPECT_FALSE(SerialLoopsOnThisThread());
}

// OnTwoThreads: every item once, on the calling thread or the one helper (in a SerialScope of
// its own, so its loops stay inline), both done on return; a helper's exception is rethrown.
TEST(ParallelLoops, OnTwoThreadsRunsEveryItemOnceOnTwoThreadsAtMost) {
    const std::thread::id me = std::this_thread::get_id();
    constexpr int kItems = 2000;
    std::vector<std::atomic<int>> runs(kItems);
    std::vector<std::thread::id> by(kItems);
    std::atomic<int> helperItems{0};
    OnTwoThreads(kItems, [&](int i) {
        ++runs[static_cast<std::size_t>(i)];
        by[static_cast<std::size_t>(i)] = std::this_thread::get_id();
        if (std::this_thread::get_id() != me) {
            ++helperItems;
            EXPECT_TRUE(SerialLoopsOnThisThread());
        }
        // Some work, so that the helper, once it has a processor, takes items too.
        volatile double x = i;
        for (int k = 0; k < 2000; ++k) x = x * 0.999 + 1;
    });
    std::vector<std::thread::id> threads;
    for (int i = 0; i < kItems; ++i) {
        EXPECT_EQ(runs[static_cast<std::size_t>(i)].load(), 1) << i;
        if (std::find(threads.begin(), threads.end(), by[static_cast<std::size_t>(i)]) ==
            threads.end())
            threads.push_back(by[static_cast<std::size_t>(i)]);
    }
    EXPECT_LE(threads.size(), 2u);
    EXPECT_FALSE(SerialLoopsOnThisThread());  // the caller's state is untouched
    // An item that throws, on whichever thread runs it: the exception reaches the caller once
    // both threads have stopped, and no item runs twice.
    std::vector<std::atomic<int>> seen(kItems);
    try {
        OnTwoThreads(kItems, [&](int i) {
            ++seen[static_cast<std::size_t>(i)];
            if (i == 700) throw std::runtime_error("item 700");
        });
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "item 700");
    }
    EXPECT_EQ(seen[700].load(), 1);
    for (int i = 0; i < kItems; ++i) EXPECT_LE(seen[static_cast<std::size_t>(i)].load(), 1);
}

}  // namespace
}  // namespace quadrix
