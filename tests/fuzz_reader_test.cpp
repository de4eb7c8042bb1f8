// The reader's fuzzing corpus in the ordinary suite (issue 7 "Robust reader"):
//   - every seed and regression input of tests/fuzz_reader/ keeps the reader's properties
//     (reader_fuzz_check.h) and, when it reads without error, goes through the whole pipeline;
//   - grammar-generated scenes (valid statements with extreme values) go through reader,
//     Flattener, engine, shader and a device, whose listing parses back;
//   - mutated interactive scripts never crash `quadrix -i`, and the session always ends with its
//     summary.
// The libFuzzer target itself (tests/fuzz_reader/run.sh) runs outside the suite, for a bounded
// time.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "fuzz_reader/reader_fuzz_check.h"
#include "quadrix/device/device.h"
#include "quadrix/engines/engine.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/lang/input_files.h"
#include "quadrix/lang/reader_state.h"
#include "quadrix/shade/shader.h"
#include "test_util.h"

namespace quadrix::fuzz {
namespace {

namespace fs = std::filesystem;
using quadrix::testing::TempDir;

std::string Slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<fs::path> CorpusFiles() {
    std::vector<fs::path> files;
    for (const char* dir : {"tests/fuzz_reader/corpus", "tests/fuzz_reader/regressions"})
        for (const auto& e : fs::directory_iterator(quadrix::testing::SourcePath(dir)))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

// Renders a scene that read without errors at a tiny size through every stage after the reader;
// returns a problem description or empty. Errors of the Flattener (unbounded scene, empty scene)
// are fine: they are user errors with messages.
std::string RunPipeline(const std::string& text, const std::string& name) {
    scene::Scene scene;
    Diagnostics diags;
    lang::Reader reader(scene, diags);
    if (!reader.ReadText(text, name)) return {};
    FlattenOptions fo;
    fo.width = 12;
    fo.height = 10;
    auto flat = Flatten(scene, fo, diags);
    if (!flat) return diags.HasErrors() ? "" : "Flatten failed without an error";
    Frame frame;
    auto engine = MakeEngine("raycast");
    RenderOptions ro;
    ro.threads = 1;
    engine->Render(*flat, ro, frame);
    if (frame.width != 12 || frame.height != 10) return "engine left a wrong-sized frame";
    for (std::size_t i = 0; i < frame.depth.size(); ++i)
        if (frame.surface[i] != Frame::kNone && std::isnan(frame.depth[i]))
            return "NaN depth at a covered pixel";
    Image image = Shade(frame, *flat);
    TempDir dir;
    std::string error;
    device::DeviceSettings ds;
    ds.xInches = 0.12;  // 12 × 10 pixels at the ascii device's 100 dots per inch
    ds.yInches = 0.10;
    auto dev = device::MakeDevice("ascii:" + dir.File("l.out"), ds, error);
    if (!dev) return error;
    dev->Open(image.channels == 3);
    device::DrawImage(*dev, image, &frame, 4);
    if (auto e = dev->Close(); !e.empty()) return e;
    device::Listing listing;
    if (auto e = device::ParseListing(Slurp(dir.File("l.out")), listing); !e.empty())
        return "listing does not parse: " + e;
    return {};
}

TEST(FuzzReader, CorpusAndRegressionsKeepTheReaderProperties) {
    TempDir dir;
    dir.Write("part", "plane from_part <1 0 0 0>; body (from_part);");
    dir.Write("loop", "read loop;");
    const std::string name = dir.File("fuzz.uq");
    std::istringstream emptyInput;  // `read -;` and naked reads see an empty standard input
    std::streambuf* saved = std::cin.rdbuf(emptyInput.rdbuf());
    auto files = CorpusFiles();
    EXPECT_GE(files.size(), 10u);
    for (const fs::path& f : files) {
        // Reading 256 MiB of zeros three times would dominate the suite; the next test has it.
        if (f.filename() == "read_dev_zero.uq") continue;
        std::string text = Slurp(f);
        for (bool handler : {false, true})
            EXPECT_EQ(CheckReaderInput(text, name, handler), "") << f;
        EXPECT_EQ(RunPipeline(text, name), "") << f;
    }
    std::cin.rdbuf(saved);
}

TEST(FuzzReader, EndlessFileIsRefusedWithAMessage) {
    // regressions/read_dev_zero.uq: once a std::bad_alloc crash.
    scene::Scene scene;
    Diagnostics diags;
    lang::Reader reader(scene, diags);
    EXPECT_FALSE(reader.ReadText("read \"/dev/zero\";\nplane after <0 1 0 -1>;\n", "z.uq"));
    ASSERT_EQ(diags.ErrorCount(), 1);
    EXPECT_NE(diags.Items()[0].message.find("larger than 256 MiB"), std::string::npos)
        << diags.Items()[0].message;
    EXPECT_EQ(scene.top.halfSpaces.size(), 1u);  // reading went on after the error
}

// A random scene of well-formed statements with extreme but finite numbers.
std::string GenerateScene(std::mt19937& rng) {
    auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
    auto number = [&]() -> std::string {
        switch (pick(6)) {
            case 0:
                return "0";
            case 1:
                return fmt::format("{}", pick(9) - 4);
            case 2:
                return fmt::format("{:.3g}", std::ldexp(1.0, pick(60) - 30));
            case 3:
                return fmt::format("-{:.3g}", std::ldexp(1.0, pick(60) - 30));
            case 4:
                return "1e-300";
            default:
                return fmt::format("{:.2f}", (pick(2001) - 1000) / 100.0);
        }
    };
    std::string s;
    const int surfaces = 1 + pick(5);
    for (int i = 0; i < surfaces; ++i) {
        if (pick(2)) {
            s += fmt::format("plane h{} <{} {} {} {}>;\n", i, number(), number(), number(),
                             number());
        } else {
            s += fmt::format("quadric h{} <", i);
            for (int k = 0; k < 10; ++k) s += number() + (k < 9 ? " " : "");
            s += pick(4) == 0 ? "> =t;\n" : ">;\n";
        }
    }
    const int bodies = 1 + pick(3);
    for (int b = 0; b < bodies; ++b) {
        s += fmt::format("body b{} (", b);
        int n = 1 + pick(3);
        for (int k = 0; k < n; ++k) s += fmt::format("{}h{} ", pick(2) ? "!" : "", pick(surfaces));
        s += pick(3) == 0 ? ") =c .5 .2 1;\n" : ");\n";
    }
    if (bodies > 1 && pick(2)) {
        const char* ops[] = {"|", "&", "-"};
        s += fmt::format("csg c (b0 {} b1);\n", ops[pick(3)]);
    }
    if (pick(2)) s += fmt::format("light {} {} {} {};\n", "0.8", number(), number(), number());
    if (pick(2))
        s += fmt::format("view v dop {} {} {} whh 5 whw 5;\n", number(), number(), number());
    return s;
}

TEST(FuzzReader, GeneratedScenesGoThroughEveryStage) {
    std::mt19937 rng(7007);  // fixed: reproducible
    int rendered = 0;
    for (int i = 0; i < 200; ++i) {
        std::string text = GenerateScene(rng);
        ASSERT_EQ(CheckReaderInput(text, "gen.uq", false), "") << text;
        ASSERT_EQ(RunPipeline(text, "gen.uq"), "") << text;
        ++rendered;
    }
    EXPECT_EQ(rendered, 200);
}

TEST(FuzzReader, MutatedInteractiveScriptsNeverCrashTheSession) {
    TempDir dir;
    dir.Write("scenefile", Slurp(quadrix::testing::SourcePath("examples/tube.uq")));
    const std::string base =
        Slurp(quadrix::testing::SourcePath("tests/fuzz_reader/corpus/seed_session.uq"));
    std::mt19937 rng(4242);
    for (int i = 0; i < 12; ++i) {
        std::string script = base;
        for (int m = 0; m < 6; ++m) {
            std::size_t pos = rng() % (script.size() + 1);
            switch (rng() % 3) {
                case 0:
                    script.insert(pos, 1, ";{}()<>\"!"[rng() % 9]);
                    break;
                case 1:
                    script.erase(pos, rng() % 12);
                    break;
                default:
                    script.insert(pos, " read scenefile; show; ");
                    break;
            }
        }
        std::string in = dir.Write("script.txt", script);
        auto r = quadrix::testing::RunShell("cd '" + dir.path() + "' && env -u UQDEV " +
                                            quadrix::testing::QuadrixBinary() +
                                            " -i -d ascii -sx .1 -sy .1 < '" + in + "'");
        EXPECT_TRUE(r.exitCode == 0 || r.exitCode == 1) << r.exitCode << "\n" << script;
        EXPECT_NE(r.err.find("\nparser:"), std::string::npos) << r.err;  // the summary
    }
}

}  // namespace
}  // namespace quadrix::fuzz

namespace quadrix::fuzz {
namespace {

TEST(FuzzReader, StatementLimitStopsReadingWithAMessage) {
    // The limit is ten million statements; start the count just below it rather than reading
    // that many.
    scene::Scene scene;
    Diagnostics diags;
    lang::ReaderState state(scene, diags, lang::ReadOptions{});
    state.statementCount = lang::ReaderState::kMaxStatements - 2;
    lang::ReadTopLevelText(state, "plane a1 <1 0 0 0>;\nplane a2 <1 0 0 0>;\nplane a3 <1 0 0 0>;\n",
                           "many.uq");
    EXPECT_EQ(scene.top.halfSpaces.size(), 2u);
    ASSERT_EQ(diags.ErrorCount(), 1);
    const Diagnostic& d = diags.Items()[0];
    EXPECT_EQ(d.message, "more than 10000000 statements; reading stopped");
    EXPECT_EQ(d.loc.line, 3);
    EXPECT_EQ(d.kind, "parser");
}

}  // namespace
}  // namespace quadrix::fuzz
