// Tests of the reader's id table (id_table.h) against std::map as the oracle: inserts, replaced
// values, misses, growth, and ids whose hashes collide in the table's slots.
#include "quadrix/lang/id_table.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <vector>

namespace quadrix::lang {
namespace {

TEST(LangIdTable, MatchesAMapOverInsertsReplacementsAndMisses) {
    // The objects the values name: value v is the object ids[v], as in a scope's vectors.
    std::vector<std::string> ids;
    std::map<std::string, int> oracle;
    IdTable table;
    auto idOf = [&](int v) -> const std::string& { return ids[v]; };
    std::mt19937 rng(7);
    for (int step = 0; step < 20000; ++step) {
        // Few distinct names, so that many Set calls replace the value of an id already there.
        std::string id = "s" + std::to_string(rng() % 5000);
        ids.push_back(id);
        const int value = static_cast<int>(ids.size()) - 1;
        table.Set(id, value, idOf);
        oracle[id] = value;
    }
    EXPECT_EQ(table.Size(), oracle.size());
    for (const auto& [id, value] : oracle) EXPECT_EQ(table.Find(id, idOf), value) << id;
    for (int i = 5000; i < 6000; ++i) EXPECT_EQ(table.Find("s" + std::to_string(i), idOf), -1);
    EXPECT_EQ(table.Find("", idOf), -1);
}

TEST(LangIdTable, EmptyTableFindsNothing) {
    IdTable table;
    auto idOf = [](int) -> std::string { return "x"; };
    EXPECT_EQ(table.Find("x", idOf), -1);
    EXPECT_EQ(table.Size(), 0u);
}

TEST(LangIdTable, IdsThatShareSlotsAreKeptApart) {
    // 100,000 ids in a table that doubles from 16 slots: every id shares a probe run with others,
    // and only the comparison through idOf tells them apart.
    std::vector<std::string> ids;
    for (int i = 0; i < 100000; ++i) ids.push_back("q" + std::to_string(i));
    IdTable table;
    auto idOf = [&](int v) -> const std::string& { return ids[v]; };
    for (int i = 0; i < 100000; ++i) table.Set(ids[i], i, idOf);
    for (int i = 0; i < 100000; i += 7) ASSERT_EQ(table.Find(ids[i], idOf), i);
    EXPECT_EQ(table.Find("q100000", idOf), -1);
}

TEST(LangIdTable, ReserveKeepsWhatIsStoredAndRoomForMore) {
    std::vector<std::string> ids;
    for (int i = 0; i < 50000; ++i) ids.push_back("b" + std::to_string(i));
    IdTable table;
    auto idOf = [&](int v) -> const std::string& { return ids[v]; };
    for (int i = 0; i < 1000; ++i) table.Set(ids[i], i, idOf);
    table.Reserve(50000);  // rehashes the 1,000 already there
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(table.Find(ids[i], idOf), i);
    for (int i = 1000; i < 50000; ++i) table.Set(ids[i], i, idOf);
    table.Reserve(10);  // never shrinks
    EXPECT_EQ(table.Size(), 50000u);
    for (int i = 0; i < 50000; i += 3) ASSERT_EQ(table.Find(ids[i], idOf), i);
    EXPECT_EQ(table.Find("b50000", idOf), -1);
}

TEST(LangIdTable, NumberedIdsKeepTheirOrderInGroupsOfSixteen) {
    // q16 ... q31 hash to 16 consecutive values (one run of slots), q32 starts another group.
    const std::uint32_t first = IdTable::Hash("q16");
    EXPECT_EQ(first % 16, 0u);
    for (int i = 17; i < 32; ++i)
        EXPECT_EQ(IdTable::Hash("q" + std::to_string(i)),
                  first + static_cast<std::uint32_t>(i - 16));
    EXPECT_NE(IdTable::Hash("q32") >> 4, first >> 4);
    // The prefix and the number of digits are part of the hash.
    EXPECT_NE(IdTable::Hash("q1"), IdTable::Hash("s1"));
    EXPECT_NE(IdTable::Hash("q1"), IdTable::Hash("q01"));
}

TEST(LangIdTable, OverlappingNumberedFamiliesAndOtherIdsMatchAMap) {
    // Families whose numbers overlap (p0.., q0.., q00..), ids with long numbers, digits only in
    // the middle, generated ids (l#3): all kept apart, as std::map keeps them.
    std::vector<std::string> ids;
    for (int i = 0; i < 30000; ++i) {
        ids.push_back("p" + std::to_string(i));
        ids.push_back("q" + std::to_string(i));
        ids.push_back("q0" + std::to_string(i));
        if (i % 100 == 0) ids.push_back("x" + std::to_string(1234567890123LL + i));
        if (i % 100 == 0) ids.push_back("a" + std::to_string(i) + "b");
        if (i % 100 == 0) ids.push_back("l#" + std::to_string(i));
    }
    IdTable table;
    std::map<std::string, int> oracle;
    auto idOf = [&](int v) -> const std::string& { return ids[v]; };
    for (int v = 0; v < static_cast<int>(ids.size()); ++v) {
        table.Set(ids[v], v, idOf);
        oracle.emplace(ids[v], v);
    }
    EXPECT_EQ(table.Size(), oracle.size());
    for (const auto& [id, value] : oracle) ASSERT_EQ(table.Find(id, idOf), value) << id;
    EXPECT_EQ(table.Find("p30000", idOf), -1);
    EXPECT_EQ(table.Find("q00", idOf), 2);  // "q0" + "0"
    EXPECT_EQ(table.Find("r1", idOf), -1);
}

}  // namespace
}  // namespace quadrix::lang
