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

}  // namespace
}  // namespace quadrix::lang
