#include "quadrix/util/hash_slots.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace quadrix {
namespace {

TEST(HashSlots, AnEmptyTableFindsNothing) {
    HashSlots none;
    EXPECT_EQ(none.Find(42, [](int) { return true; }), -1);
    HashSlots sized(100);
    EXPECT_EQ(sized.Find(0, [](int) { return true; }), -1);
    EXPECT_EQ(sized.size(), 0u);
}

// Items that share a hash are each a candidate: the caller's test decides which one is found.
TEST(HashSlots, ItemsUnderOneHashAreToldApartByTheCallersTest) {
    const std::vector<std::string> items = {"a", "b", "c", "d"};
    HashSlots slots;
    for (int i = 0; i < 4; ++i) slots.Insert(7, i);  // every item under one hash
    for (int i = 0; i < 4; ++i) {
        const int found =
            slots.Find(7, [&](int v) { return items[std::size_t(v)] == items[std::size_t(i)]; });
        EXPECT_EQ(found, i);
    }
    EXPECT_EQ(slots.Find(7, [&](int v) { return items[std::size_t(v)] == "e"; }), -1);
    // Another hash never offers them.
    EXPECT_EQ(slots.Find(8, [](int) { return true; }), -1);
}

// Growing from no room to many thousands keeps every value under its hash, including hashes that
// differ only in their high bits or low bits, and 0.
TEST(HashSlots, EveryValueIsFoundAfterGrowing) {
    std::mt19937_64 rng(12345);
    std::vector<std::uint64_t> hashes;
    for (int i = 0; i < 3000; ++i) hashes.push_back(rng());
    for (std::uint64_t k = 0; k < 1000; ++k) hashes.push_back(k);        // low bits differ
    for (std::uint64_t k = 1; k < 1000; ++k) hashes.push_back(k << 40);  // high bits differ
    HashSlots slots;
    for (std::size_t i = 0; i < hashes.size(); ++i) slots.Insert(hashes[i], int(i));
    ASSERT_EQ(slots.size(), hashes.size());
    for (std::size_t i = 0; i < hashes.size(); ++i)
        ASSERT_EQ(slots.Find(hashes[i], [&](int v) { return v == int(i); }), int(i)) << i;
    // A hash never inserted is not found, whatever the test says.
    EXPECT_EQ(slots.Find(0xdeadbeefcafef00dull, [](int) { return true; }), -1);
}

}  // namespace
}  // namespace quadrix
