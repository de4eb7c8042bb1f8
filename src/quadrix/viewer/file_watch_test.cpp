#include "quadrix/viewer/file_watch.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util.h"

namespace quadrix::viewer {
namespace {

TEST(ViewerFileWatch, SeesChangesOnceAndFilesAppearingAndGoing) {
    testing::TempDir dir;
    const std::string a = dir.Write("a.uq", "plane p <0 1 0 0>;\n");
    const std::string b = dir.File("b.uq");  // not there yet
    FileWatch w;
    w.SetFiles({a, b, a, "-"});
    EXPECT_EQ(w.Files().size(), 2u);
    EXPECT_FALSE(w.Changed());
    dir.Write("a.uq", "plane p <0 1 0 1>;\n");  // same size: the time says it changed
    std::filesystem::last_write_time(a,
                                     std::filesystem::last_write_time(a) + std::chrono::seconds(2));
    EXPECT_TRUE(w.Changed());
    // The change's time is the file's new modification time (the save-to-picture latency
    // starts there), 2 s ahead of now.
    ASSERT_TRUE(w.LastChangeTime());
    const double ahead =
        std::chrono::duration<double>(*w.LastChangeTime() - std::chrono::system_clock::now())
            .count();
    EXPECT_GT(ahead, 1.0);
    EXPECT_LT(ahead, 2.5);
    EXPECT_FALSE(w.Changed());
    dir.Write("b.uq", "x");
    EXPECT_TRUE(w.Changed());
    std::filesystem::remove(b);
    EXPECT_TRUE(w.Changed());
    EXPECT_FALSE(w.LastChangeTime());  // the only changed file is gone
    EXPECT_FALSE(w.Changed());
}

}  // namespace
}  // namespace quadrix::viewer
