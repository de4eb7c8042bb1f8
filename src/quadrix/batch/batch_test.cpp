// The batch module: frame numbering and names, frame ranges, view lists, job files, and the
// frame loop's reuse of reads and flattenings (issue 22). Pictures made by the loop are compared
// with the same frames rendered one by one through a fresh RenderContext.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "quadrix/batch/job.h"
#include "quadrix/batch/job_file.h"
#include "quadrix/batch/job_renderer.h"
#include "quadrix/batch/output_clashes.h"
#include "quadrix/batch/run.h"
#include "quadrix/batch/sort_first.h"
#include "quadrix/batch/view_list.h"
#include "quadrix/io/exr.h"
#include "quadrix/io/output_check.h"
#include "quadrix/shade/picture_defaults.h"
#include "quadrix/shade/row_shading.h"

namespace quadrix::batch {
namespace {

namespace fs = std::filesystem;

class Dir {
  public:
    Dir() {
        for (int i = 0;; ++i) {
            path_ = fs::temp_directory_path() /
                    ("quadrix_batch_test_" + std::to_string(::getpid()) + "_" + std::to_string(i));
            if (fs::create_directory(path_)) break;
        }
    }
    ~Dir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    std::string File(const std::string& name) const { return (path_ / name).string(); }
    std::string Write(const std::string& name, const std::string& text) const {
        std::ofstream(File(name), std::ios::binary) << text;
        return File(name);
    }

  private:
    fs::path path_;
};

std::string Bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(BatchFramePath, PatternsAndInsertedNumbers) {
    EXPECT_EQ(FramePath("out.png", 3, true), "out_0003.png");
    EXPECT_EQ(FramePath("out.png", 3, false), "out.png");
    EXPECT_EQ(FramePath("dir.v2/out", 12, true), "dir.v2/out_0012");
    EXPECT_EQ(FramePath("out_%04d.png", 7, true), "out_0007.png");
    EXPECT_EQ(FramePath("f%d.ppm", 123, true), "f123.ppm");
    EXPECT_EQ(FramePath("f%3d.ppm", 5, true), "f  5.ppm");
    EXPECT_EQ(FramePath("100%%_%02d.png", 4, true), "100%_04.png");
    EXPECT_TRUE(HasFramePattern("a%04d.png"));
    EXPECT_FALSE(HasFramePattern("a%%.png"));
}

TEST(BatchJob, ClockRunsFromZeroToOne) {
    Job j;
    j.frames = 5;
    EXPECT_EQ(j.Clock(0), 0.0);
    EXPECT_EQ(j.Clock(2), 0.5);
    EXPECT_EQ(j.Clock(4), 1.0);
    j.frames = 1;
    EXPECT_EQ(j.Clock(0), 0.0);
}

TEST(BatchJob, FrameRangesAndChecks) {
    int a = 0, b = 0;
    EXPECT_EQ(ParseFrameRange("2:5", a, b), "");
    EXPECT_EQ(a, 2);
    EXPECT_EQ(b, 5);
    EXPECT_EQ(ParseFrameRange("3:", a, b), "");
    EXPECT_EQ(b, -1);
    EXPECT_EQ(ParseFrameRange("7", a, b), "");
    EXPECT_EQ(a, 7);
    EXPECT_EQ(b, 7);
    EXPECT_NE(ParseFrameRange("x:2", a, b), "");
    EXPECT_NE(ParseFrameRange(":", a, b), "");
    Job j;
    j.frames = 4;
    j.output.image = "o.png";
    j.first = 1;
    j.last = 3;
    EXPECT_EQ(CheckJob(j), "");
    j.last = 4;
    EXPECT_NE(CheckJob(j).find("not one of the 4 frames"), std::string::npos);
    j.last = 0;
    EXPECT_NE(CheckJob(j).find("before"), std::string::npos);
    Job still;
    still.output.image = "o_%04d.png";
    EXPECT_NE(CheckJob(still).find("no frames"), std::string::npos);
    still.output.image = "o_%x.png";
    still.frames = 2;
    EXPECT_NE(CheckJob(still).find("'%'"), std::string::npos);
}

TEST(BatchViewList, ViewStatementsInOrder) {
    Diagnostics d;
    auto v = ParseViewList("view front vrp 0 0 0 dop 0 0 -1;\nview side dop 1 0 0;\n", "v.uq", d);
    ASSERT_TRUE(v) << (d.Items().empty() ? "" : d.Items()[0].Format());
    ASSERT_EQ(v->size(), 2u);
    EXPECT_EQ((*v)[0].name, "front");
    EXPECT_EQ((*v)[1].name, "side");
    ASSERT_TRUE((*v)[1].view->dop);
    EXPECT_EQ((*v)[1].view->dop->x, 1);
}

TEST(BatchViewList, RtScriptWithFramesAndErrorPositions) {
    Diagnostics d;
    const std::string text =
        "start 0;\nviewsize 10;\neye_pt 0 0 20;\nviewrot 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1;\nend;\n"
        "start 1;\nviewsize 20;\neye_pt 0 0 20;\nviewrot 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1;\nend;\n";
    auto v = ParseViewList(text, "v.rt", d);
    ASSERT_TRUE(v) << (d.Items().empty() ? "" : d.Items()[0].Format());
    ASSERT_EQ(v->size(), 2u);
    EXPECT_EQ((*v)[0].rtView->viewsize, 10);
    EXPECT_EQ((*v)[1].rtView->viewsize, 20);
    Diagnostics bad;
    EXPECT_FALSE(ParseViewList("viewsize 10;\neye_pt 0 0;\n", "bad.rt", bad));
    ASSERT_FALSE(bad.Items().empty());
    EXPECT_EQ(bad.Items()[0].loc.FileName(), "bad.rt");
    EXPECT_GE(bad.Items()[0].loc.line, 1);
    Diagnostics none;
    EXPECT_FALSE(ParseViewList("plane p <0 1 0 0>;", "none.uq", none));
}

TEST(BatchJobFile, GoodAndBadLines) {
    const std::string text =
        "# comment\n"
        "{\"inputs\": [\"a.uq\"], \"output\": \"a.png\", \"size\": \"64x48\", \"az\": 30}\n"
        "\n"
        "{\"input\": \"b.uq\", \"output\": \"b_%03d.png\", \"turntable\": 8, \"el\": 10}\n"
        "{\"inputs\": [\"c.uq\"], \"output\": \"c.png\", \"colour\": 1}\n"
        "not json\n"
        "{\"inputs\": [\"d.uq\"], \"output\": \"d.png\", \"engine\": \"nonesuch\"}\n"
        "{\"inputs\": [\"e.uq\"], \"output\": \"e.png\", \"output\": \"f.png\"}\n"
        "{\"inputs\": [\"g.uq\"], \"output\": \"g.png\"\n";
    auto jobs = ParseJobFile(text, "jobs.jsonl");
    ASSERT_EQ(jobs.size(), 7u);
    EXPECT_EQ(jobs[0].error, "");
    EXPECT_EQ(jobs[0].job.view.width, 64);
    EXPECT_EQ(jobs[0].job.view.height, 48);
    EXPECT_EQ(jobs[0].job.view.azimuth, 30);
    EXPECT_EQ(jobs[1].error, "");
    EXPECT_EQ(jobs[1].job.FrameCount(), 8);
    ASSERT_TRUE(jobs[1].job.turntable);
    EXPECT_EQ(jobs[1].job.turntable->elevation, 10);
    EXPECT_EQ(jobs[2].error, "jobs.jsonl:5: unknown key \"colour\"");
    // Syntax errors with the column where parsing stopped, a key given twice (nlohmann would keep
    // the last one: the job wrote f.png only) at its second spelling.
    EXPECT_EQ(jobs[3].error.rfind("jobs.jsonl:6:2: invalid JSON: syntax error", 0), 0u)
        << jobs[3].error;
    EXPECT_NE(jobs[4].error.find("jobs.jsonl:7: "), std::string::npos);
    EXPECT_NE(jobs[4].error.find("nonesuch"), std::string::npos);
    EXPECT_EQ(jobs[5].error, "jobs.jsonl:8:41: the key \"output\" is given twice in one object");
    EXPECT_EQ(jobs[6].error.rfind("jobs.jsonl:9:", 0), 0u) << jobs[6].error;
    EXPECT_NE(jobs[6].error.find("invalid JSON"), std::string::npos) << jobs[6].error;
}

// Picture options and the extra EXR output of a job line.
TEST(BatchJobFile, PictureDefaultsAndExr) {
    const std::string text =
        "{\"input\": \"a.uq\", \"output\": \"a.png\"}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": \"off\", \"shadows\": false}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": 16, \"shadows\": true}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": 7}\n"
        "{\"input\": \"a.uq\", \"output\": \"a_%02d.png\", \"exr\": \"a_%02d.exr\", "
        "\"frames\": 2}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"exr\": \"a.tiff\"}\n";
    auto jobs = ParseJobFile(text, "j");
    ASSERT_EQ(jobs.size(), 6u);
    EXPECT_TRUE(jobs[0].job.picture.shadows && jobs[0].job.picture.antialiasing);
    EXPECT_EQ(jobs[1].error, "");
    EXPECT_FALSE(jobs[1].job.picture.shadows || jobs[1].job.picture.antialiasing);
    EXPECT_FALSE(jobs[1].job.shade.shadows);
    EXPECT_EQ(jobs[1].job.shade.aaSamples, 0);
    EXPECT_TRUE(jobs[2].job.shade.shadows);
    EXPECT_EQ(jobs[2].job.shade.aaSamples, 16);
    EXPECT_NE(jobs[3].error.find("\"aa\" must be"), std::string::npos) << jobs[3].error;
    if (HaveOpenExr()) {
        EXPECT_EQ(jobs[4].error, "");
        EXPECT_EQ(jobs[4].job.output.exr, "a_%02d.exr");
        EXPECT_TRUE(jobs[4].job.shade.linear);
    }
    EXPECT_NE(jobs[5].error.find("not a .exr file"), std::string::npos) << jobs[5].error;
}

// "aa" takes what render's --aa takes, with its meaning: "default" is the picture default
// (decided frame by frame, shade/picture_defaults.h); "off", 0 and 1 turn it off.
TEST(BatchJobFile, AaTakesWhatRenderTakes) {
    const std::string text =
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": \"default\"}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": \"4\"}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": 0}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": \"1\"}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": \"Default\"}\n"
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"aa\": true}\n";
    auto jobs = ParseJobFile(text, "j");
    ASSERT_EQ(jobs.size(), 6u);
    EXPECT_EQ(jobs[0].error, "");
    EXPECT_TRUE(jobs[0].job.picture.antialiasing);  // as a job without "aa"
    EXPECT_EQ(jobs[0].job.shade.aaSamples, 0);
    EXPECT_EQ(jobs[1].error, "");
    EXPECT_FALSE(jobs[1].job.picture.antialiasing);
    EXPECT_EQ(jobs[1].job.shade.aaSamples, 4);
    for (int k : {2, 3}) {
        EXPECT_EQ(jobs[k].error, "") << k;
        EXPECT_FALSE(jobs[k].job.picture.antialiasing) << k;
        EXPECT_EQ(jobs[k].job.shade.aaSamples, 0) << k;
    }
    EXPECT_EQ(jobs[4].error,
              "j:5: \"aa\" must be \"off\", \"default\", 4, 16 or 64, found \"Default\"");
    EXPECT_EQ(jobs[5].error, "j:6: \"aa\" must be \"off\", \"default\", 4, 16 or 64");
}

// "top" with only UniQuadrix inputs does what `quadrix render x.uq --top NAME` does: the scene is
// drawn whole, with a warning — here positioned at the key. With an importer's file it stays.
TEST(BatchJobFile, TopOnUniQuadrixInputsWarnsAtTheKey) {
    const std::string text =
        "{\"input\": \"a.uq\", \"output\": \"a.png\", \"top\": [\"all\"]}\n"
        "{\"inputs\": [\"a.uq\", \"m.g\"], \"output\": \"b.png\", \"top\": \"all\"}\n"
        "{\"output\": \"c.png\", \"top\"  : [\"x\"], \"inputs\": [\"A.UQ\", \"b.uq\"]}\n";
    auto jobs = ParseJobFile(text, "jobs.jsonl");
    ASSERT_EQ(jobs.size(), 3u);
    for (const JobEntry& e : jobs) EXPECT_EQ(e.error, "");
    ASSERT_EQ(jobs[0].warnings.size(), 1u);
    EXPECT_EQ(jobs[0].warnings[0].rfind("jobs.jsonl:1:38: warning: \"top\" has no effect", 0), 0u)
        << jobs[0].warnings[0];
    EXPECT_TRUE(jobs[0].job.input.topObjects.empty());
    EXPECT_TRUE(jobs[1].warnings.empty());
    EXPECT_EQ(jobs[1].job.input.topObjects, std::vector<std::string>{"all"});
    ASSERT_EQ(jobs[2].warnings.size(), 1u);
    EXPECT_EQ(jobs[2].warnings[0].rfind("jobs.jsonl:3:21: warning:", 0), 0u) << jobs[2].warnings[0];
}

// Two jobs, or two outputs of one job, that write one file (for some frame) are found before
// anything is rendered, each named with its position.
TEST(BatchJobFile, OutputsThatClashAreFoundWithBothPositions) {
    Dir dir;
    const std::string d = dir.File("");
    const std::string text =
        "{\"input\": \"a.uq\", \"output\": \"" + d + "a.png\"}\n" +    // 1
        "{\"input\": \"b.uq\", \"output\": \"" + d + "./a.png\"}\n" +  // 2: job 0's
        "{\"input\": \"a.uq\", \"output\": \"" + d + "t_%02d.png\", \"frames\": 3}\n" +  // 3
        "# the frames 3..5 of another animation do not meet frames 0..2\n" +
        "{\"input\": \"a.uq\", \"output\": \"" + d +
        "t_%02d.png\", \"frames\": 6, \"frame_range\": \"3:5\"}\n" +    // 5
        "{\"input\": \"a.uq\", \"output\": \"" + d + "t_01.png\"}\n" +  // 6: job 2's frame 1
        "{\"input\": \"a.uq\", \"output\": \"" + d + "f.qxf\", \"dump_frame\": \"" + d +
        "f_%04d.qxf\", \"frames\": 2}\n" +  // 7: within itself
        "{\"input\": \"a.uq\", \"output\": \"" + d + "a.png\", \"colour\": 1}\n";  // 8: invalid
    auto jobs = ParseJobFile(text, "jobs.jsonl");
    ASSERT_EQ(jobs.size(), 7u);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(jobs[k].error, "") << k;
    EXPECT_EQ(jobs[1].line, 2);
    EXPECT_EQ(jobs[5].line, 7);
    const std::vector<std::string> clashes = OutputClashes(jobs);
    ASSERT_EQ(clashes.size(), 4u);
    EXPECT_EQ(clashes[0], "jobs.jsonl:2: \"output\" writes '" + d +
                              "./a.png', which job 0 (jobs.jsonl:1), \"output\", writes too: the "
                              "outputs of a batch must be different files");
    EXPECT_EQ(clashes[1].rfind("jobs.jsonl:6: \"output\" writes '" + d +
                                   "t_01.png', which job 2 (jobs.jsonl:3), \"output\", frame 1, "
                                   "writes too",
                               0),
              0u)
        << clashes[1];
    // Frame k of the picture is f_000k.qxf, which the job's own dump of frame k writes too.
    EXPECT_EQ(clashes[2].rfind("jobs.jsonl:7: \"dump_frame\", frame 0, writes '" + d +
                                   "f_0000.qxf', which this job's \"output\", frame 0, writes too",
                               0),
              0u)
        << clashes[2];
    EXPECT_NE(clashes[3].find("frame 1"), std::string::npos) << clashes[3];
    // A limit on the messages, and no clash in a file without one.
    EXPECT_EQ(OutputClashes(jobs, 1).back(), "... and 3 more");
    EXPECT_TRUE(
        OutputClashes(ParseJobFile("{\"input\": \"a.uq\", \"output\": \"" + d + "x.png\"}\n" +
                                       "{\"input\": \"a.uq\", \"output\": \"" + d + "y.png\"}\n",
                                   "j"))
            .empty());
}

// Sort-first shading (shade/row_shading.h): each part of the picture's rows, shaded from a Frame
// that is right only on those rows and the two rows around them (the rest overwritten with
// another picture's pixels), gives the same bytes and linear values as shading the whole Frame —
// with shadows, anti-aliasing (whose edge and shadow-boundary tests look two pixels away) and
// edge lines.
TEST(BatchSortFirst, RowsShadedFromTheirHaloAreTheWholePicturesBits) {
    RenderContext ctx(1), other(1);
    Diagnostics d;
    InputRequest in;
    in.paths = {std::string(QUADRIX_SOURCE_DIR) + "/examples/machined_part.uq"};
    ASSERT_TRUE(ctx.Read(in, d));
    ASSERT_TRUE(other.Read(in, d));
    ViewRequest v;
    v.width = 90;
    v.height = 75;  // 4 full bands of 16 and a short one of 11
    ASSERT_TRUE(ctx.Flatten(v, d));
    v.azimuth = 100;  // another view: the pixels outside a part's rows are wrong, not empty
    ASSERT_TRUE(other.Flatten(v, d));
    Frame whole, wrong;
    RenderReport rep;
    EngineRequest engine;
    ASSERT_TRUE(ctx.Render(engine, whole, rep, d));
    ASSERT_TRUE(other.Render(engine, wrong, rep, d));
    for (const bool edges : {false, true}) {
        ShadeOptions so;
        so.shadows = true;
        so.aaSamples = 4;
        so.edges = edges;
        so.linear = !edges;
        ASSERT_TRUE(DeclaresLights(ctx.Flat()));
        const Image reference = ctx.Shade(whole, so);
        Image assembled(reference.width, reference.height, reference.channels);
        assembled.linear.assign(reference.linear.size(), -1.0f);
        for (int part = 0; part < 3; ++part) {
            const std::vector<RowSpan> rows = SortFirstRows(90, 75, part, 3);
            const std::vector<std::uint8_t> kinds = RowKinds(rows, 75);
            Frame partial = wrong;
            const PixelRegion keep{[&] {
                std::vector<PixelRect> r;
                for (int y = 0; y < 75; ++y)
                    if (kinds[static_cast<std::size_t>(y)] != 0) r.push_back({0, y, 90, y + 1});
                return r;
            }()};
            CopyRegion(partial, whole, keep);
            const Image mine = ShadeRows(partial, ctx.Flat(), so, rows);
            ASSERT_EQ(mine.linear.size(), reference.linear.size());
            const std::size_t row = 90 * static_cast<std::size_t>(mine.channels);
            for (const RowSpan& s : rows)
                for (int y = s.y0; y < s.y1; ++y) {
                    std::copy_n(mine.pixels.begin() + y * row, row,
                                assembled.pixels.begin() + y * row);
                    if (!mine.linear.empty())
                        std::copy_n(mine.linear.begin() + y * row, row,
                                    assembled.linear.begin() + y * row);
                }
        }
        EXPECT_EQ(assembled.pixels, reference.pixels) << "edges " << edges;
        EXPECT_EQ(assembled.linear, reference.linear) << "edges " << edges;
    }
}

// What a resumed run accepts as done (io/output_check.h): whole files of the job's size.
TEST(BatchOutputCheck, CompleteFilesOfTheRightSizeOnly) {
    Dir dir;
    Frame frame(6, 4);
    frame.Offer(frame.Index(2, 1), 0.5, Vec3{0, 0, 1}, 0, 0);
    Image image(6, 4, 3);
    for (auto& p : image.pixels) p = 128;
    for (const char* name : {"p.png", "p.ppm", "p.pgm", "p.qxf", "p.exr"}) {
        if (std::string(name) == "p.exr" && !HaveOpenExr()) continue;
        OutputRequest o;
        o.image = dir.File(name);
        ASSERT_EQ(WriteOutputs(o, frame, &image), "") << name;
        EXPECT_EQ(CheckCompleteOutput(o.image, 6, 4), "") << name;
        EXPECT_NE(CheckCompleteOutput(o.image, 6, 5).find("6×4 pixels, not 6×5"), std::string::npos)
            << name << ": " << CheckCompleteOutput(o.image, 6, 5);
        const std::string bytes = Bytes(o.image);
        dir.Write(name, bytes.substr(0, bytes.size() - 3));  // cut short
        EXPECT_NE(CheckCompleteOutput(o.image, 6, 4), "") << name;
    }
    dir.Write("empty.png", "");
    EXPECT_EQ(CheckCompleteOutput(dir.File("empty.png"), 6, 4), "empty");
}

constexpr const char* kStill =
    "quadric ball <1 1 1 0 0 0 0 0 0 -1>; body ballb <ball> =c .8 .3 .2;\n"
    "plane floor <0 1 0 1.2>; quadric big <1 1 1 0 0 0 0 0 0 -9>; body floorb <floor big>;\n";
constexpr const char* kMoving =
    "quadric ball <1 1 1 0 0 0 (-1 * clock) 0 0 (clock * clock - 1)>;\n"
    "body ballb <ball> =c .8 .3 .2;\nview v vrp 0 0 0 dop .3 .3 -1 whw 3;\n";

Job MakeJob(const std::string& scene, const std::string& out) {
    Job j;
    j.input.paths = {scene};
    j.view.width = 48;
    j.view.height = 40;
    j.output.image = out;
    return j;
}

// Frame `frame` of `job` rendered alone through a fresh RenderContext (the reference).
std::string RenderAlone(const Job& job, int frame, const std::string& out) {
    RenderContext ctx(1);
    Diagnostics d;
    InputRequest in = job.input;
    in.clock = job.Clock(frame);
    EXPECT_TRUE(ctx.Read(in, d));
    ViewRequest v = job.view;
    if (job.turntable) {
        RenderContext probe(1);
        Diagnostics pd;
        EXPECT_TRUE(probe.Read(in, pd));
        v.view = TurntableView(*job.turntable, frame, job.FrameCount(), SceneWorldBounds(probe, pd),
                               v.width, v.height);
    }
    EXPECT_TRUE(ctx.Flatten(v, d));
    Frame f;
    RenderReport rep;
    EXPECT_TRUE(ctx.Render(job.engine, f, rep, d));
    ShadeOptions so = job.shade;
    ApplyPictureDefaults(ctx.Flat(), job.picture, so);  // as `quadrix render` does
    Image img = ctx.Shade(f, so);
    OutputRequest o = job.output;
    o.image = out;
    EXPECT_EQ(WriteOutputs(o, f, &img), "");
    return Bytes(out);
}

TEST(BatchJobRenderer, StillSceneIsReadOnceAndFlattenedOnce) {
    Dir dir;
    Job job = MakeJob(dir.Write("s.uq", kStill), dir.File("s_%02d.ppm"));
    job.frames = 3;
    JobRenderer r(1);
    for (int f = 0; f < 3; ++f) {
        FrameResult fr = r.Render(job, 0, f);
        EXPECT_EQ(fr.error, "");
        EXPECT_EQ(fr.read, f == 0);
        EXPECT_EQ(fr.flattened, f == 0);
    }
    EXPECT_EQ(r.reads, 1);
    EXPECT_EQ(r.flattens, 1);
    EXPECT_EQ(Bytes(dir.File("s_00.ppm")), Bytes(dir.File("s_02.ppm")));
    EXPECT_EQ(Bytes(dir.File("s_01.ppm")), RenderAlone(job, 1, dir.File("ref.ppm")));
}

TEST(BatchJobRenderer, ClockSceneIsReadPerFrameAndMatchesSingleRenders) {
    Dir dir;
    Job job = MakeJob(dir.Write("m.uq", kMoving), dir.File("m.ppm"));
    job.frames = 3;
    JobRenderer r(1);
    for (int f = 0; f < 3; ++f) EXPECT_EQ(r.Render(job, 0, f).error, "");
    EXPECT_EQ(r.reads, 3);
    EXPECT_EQ(r.flattens, 3);
    EXPECT_EQ(r.GeometryFlattens(), 3);  // the geometry moves with the clock
    EXPECT_NE(Bytes(dir.File("m_0000.ppm")), Bytes(dir.File("m_0002.ppm")));  // the ball moved
    for (int f = 0; f < 3; ++f)
        EXPECT_EQ(Bytes(dir.File("m_000" + std::to_string(f) + ".ppm")),
                  RenderAlone(job, f, dir.File("ref.ppm")))
            << f;
}

// A clock only in the view (an animated camera): the scene is read once, only its view
// statements again per frame, and its geometry is flattened once; every frame equals its single
// render (which reads the whole scene at that clock).
TEST(BatchJobRenderer, CameraClockKeepsTheGeometry) {
    Dir dir;
    Job job = MakeJob(dir.Write("c.uq",
                                "solid box cube =from -1 -1 -1 =to 1 1 1 =c .3 .6 .9;\n"
                                "solid sphere ball =at 1 1 1 =r .6 =c .9 .5 .2;\n"
                                "view cam vrp 0 0 0 dop (clock) .4 -1 whw 5;\n"),
                      dir.File("c.ppm"));
    job.frames = 3;
    JobRenderer r(1);
    for (int f = 0; f < 3; ++f) {
        const FrameResult fr = r.Render(job, 0, f);
        EXPECT_EQ(fr.error, "");
        EXPECT_EQ(fr.read, f == 0);
    }
    EXPECT_EQ(r.reads, 1);
    EXPECT_EQ(r.flattens, 3);
    EXPECT_EQ(r.GeometryFlattens(), 2);  // frame 0 in one go, then the kept world stage
    EXPECT_NE(Bytes(dir.File("c_0000.ppm")), Bytes(dir.File("c_0002.ppm")));  // the camera moved
    for (int f = 0; f < 3; ++f)
        EXPECT_EQ(Bytes(dir.File("c_000" + std::to_string(f) + ".ppm")),
                  RenderAlone(job, f, dir.File("ref.ppm")))
            << f;
}

// The view statements read again at each clock are those of the whole reading, in order and at
// their places: views in a file read by `read`, a view over several lines after another
// statement on its line, a `redef view` that builds on the view as it is, an anonymous view, and
// the default view asked for by name. Every frame equals the whole scene read at its clock.
TEST(BatchJobRenderer, CameraClockReadsOnlyTheViewsAgainInOrder) {
    Dir dir;
    dir.Write("cams.uq",
              "view side vrp 0 0 0 dop (clock - .5) .2 -1 whw 4;\n"
              "view vrp 0 0 0 dop 0 0 -1 whw (3 + clock);\n");
    const std::string scene =
        dir.Write("s.uq",
                  "solid box cube =from -1 -1 -1 =to 1 1 1 =c .3 .6 .9;\n"
                  "read \"cams.uq\";\n"
                  "solid sphere ball =at 1 1 1 =r .6 =c .9 .5 .2; view top vrp 0 0 0\n"
                  "  dop .2 -1 (.1 + clock) whw 3;\n"
                  "redef view side vup (clock) 1 0 whh 3;\n");
    for (const std::string name : {"side", "top", "v#1", ""}) {
        Job job = MakeJob(scene, dir.File("f_" + name + ".ppm"));
        job.view.viewName = name;
        job.frames = 3;
        JobRenderer r(1);
        for (int f = 0; f < 3; ++f) EXPECT_EQ(r.Render(job, 0, f).error, "") << name << f;
        EXPECT_EQ(r.reads, 1) << name;
        EXPECT_EQ(r.GeometryFlattens(), 2) << name;
        EXPECT_NE(Bytes(dir.File("f_" + name + "_0000.ppm")),
                  Bytes(dir.File("f_" + name + "_0002.ppm")))
            << name;
        for (int f = 0; f < 3; ++f)
            EXPECT_EQ(Bytes(dir.File("f_" + name + "_000" + std::to_string(f) + ".ppm")),
                      RenderAlone(job, f, dir.File("ref.ppm")))
                << name << f;
    }
}

// A view statement that is wrong at some clock (a window of size 0 at clock 1): that frame fails
// with the message, at the view's file:line:column, that a single render at that clock gives;
// the frames before it are rendered.
TEST(BatchJobRenderer, CameraClockErrorAtOneFrameIsTheSingleRendersError) {
    Dir dir;
    const std::string scene = dir.Write("e.uq",
                                        "solid box cube =from -1 -1 -1 =to 1 1 1;\n"
                                        "view cam vrp 0 0 0 dop 0 0 -1\n   whw (1 - clock);\n");
    Job job = MakeJob(scene, dir.File("e.ppm"));
    job.frames = 2;
    JobRenderer r(1);
    EXPECT_EQ(r.Render(job, 0, 0).error, "");
    const FrameResult bad = r.Render(job, 0, 1);
    RenderContext ctx(1);
    Diagnostics d;
    InputRequest in = job.input;
    in.clock = 1;
    EXPECT_FALSE(ctx.Read(in, d));
    std::string single;
    for (const Diagnostic& e : d.Items())
        if (e.severity == Diagnostic::Severity::kError) single += e.Format(false) + "\n";
    EXPECT_NE(single, "");
    EXPECT_EQ(bad.error, single);
    EXPECT_NE(bad.error.find("e.uq:3:"), std::string::npos) << bad.error;
}

TEST(BatchJobRenderer, TurntableOrbitsTheBoundsAndKeepsOneRead) {
    Dir dir;
    const std::string scene =
        dir.Write("t.uq",
                  "quadric c <1 0 1 0 0 0 0 0 0 -1>; plane top <0 1 0 -2>; plane bot <0 -1 0 -1>;\n"
                  "body rod <c top bot> =c .2 .6 .9;\n"
                  "plane px <1 0 0 -3>; plane nx <-1 0 0 2>; plane py <0 1 0 -.5>;\n"
                  "plane ny <0 -1 0 0>; plane pz <0 0 1 -.5>; plane nz <0 0 -1 -.5>;\n"
                  "body arm <px nx py ny pz nz> =c .9 .7 .1;\n");
    Job job = MakeJob(scene, dir.File("t.ppm"));
    job.frames = 4;
    job.turntable = Turntable{0, 20};
    JobRenderer r(1);
    for (int f = 0; f < 4; ++f) EXPECT_EQ(r.Render(job, 0, f).error, "");
    EXPECT_EQ(r.reads, 1);
    EXPECT_EQ(r.flattens, 4);            // one per frame (the bounds probe is not a frame)
    EXPECT_EQ(r.GeometryFlattens(), 2);  // the bounds probe in one go, then the world stage
    // The world box: the rod x,z in [-1,1], y in [-1,2]; the arm reaches x = 3.
    RenderContext ctx(1);
    Diagnostics d;
    InputRequest in = job.input;
    ASSERT_TRUE(ctx.Read(in, d));
    const Box3 box = SceneWorldBounds(ctx, d);
    EXPECT_NEAR(box.hi.x, 3, 0.05);
    EXPECT_NEAR(box.lo.y, -1, 0.05);
    EXPECT_NEAR(box.hi.y, 2, 0.05);
    EXPECT_LE(box.lo.x, -0.99);
    EXPECT_NE(Bytes(dir.File("t_0000.ppm")), Bytes(dir.File("t_0001.ppm")));
    EXPECT_EQ(Bytes(dir.File("t_0003.ppm")), RenderAlone(job, 3, dir.File("ref.ppm")));
}

// A job's extra EXR (picture and Frame layers) is numbered like the image and counts for
// resumption: a frame is skipped only when both exist and are complete.
TEST(BatchJobRenderer, ExrBesideThePictureAndResumption) {
    if (!HaveOpenExr()) GTEST_SKIP() << "built without OpenEXR";
    Dir dir;
    Job job = MakeJob(dir.Write("m.uq", kMoving), dir.File("m_%d.png"));
    job.output.exr = dir.File("m_%d.exr");
    job.frames = 2;
    JobRenderer r(1);
    for (int f = 0; f < 2; ++f) EXPECT_EQ(r.Render(job, 0, f).error, "");
    for (const char* name : {"m_0.png", "m_1.png", "m_0.exr", "m_1.exr"})
        EXPECT_EQ(CheckCompleteOutput(dir.File(name), 48, 40), "") << name;
    EXPECT_TRUE(r.Render(job, 0, 1, true).skipped);
    fs::remove(dir.File("m_1.exr"));
    FrameResult again = r.Render(job, 0, 1, true);
    EXPECT_FALSE(again.skipped);
    EXPECT_EQ(CheckCompleteOutput(dir.File("m_1.exr"), 48, 40), "");
}

TEST(BatchRun, FailedJobIsReportedAndTheRestIsDoneThenResumed) {
    Dir dir;
    std::vector<JobEntry> jobs(3);
    jobs[0].job = MakeJob(dir.Write("a.uq", kStill), dir.File("a.ppm"));
    jobs[1].job = MakeJob(dir.Write("bad.uq", "plane p <0 1 0>;\n"), dir.File("bad.ppm"));
    jobs[1].job.label = "the bad job";
    jobs[2].job = MakeJob(dir.Write("m.uq", kMoving), dir.File("m.ppm"));
    jobs[2].job.frames = 2;
    RunOptions o;
    o.threads = 1;
    o.quiet = true;
    o.skipExisting = true;
    o.useMpi = false;
    Summary s = RunJobs(jobs, o);
    EXPECT_EQ(s.frames, 4);
    EXPECT_EQ(s.rendered, 3);
    EXPECT_EQ(s.failed, 1);
    EXPECT_EQ(s.failedJobs, 1);
    ASSERT_EQ(s.failures.size(), 1u);
    EXPECT_NE(s.failures[0].find("the bad job: "), std::string::npos);
    EXPECT_NE(s.failures[0].find("bad.uq:1:"), std::string::npos) << s.failures[0];
    EXPECT_TRUE(fs::exists(dir.File("a.ppm")));
    EXPECT_FALSE(fs::exists(dir.File("bad.ppm")));
    EXPECT_TRUE(fs::exists(dir.File("m_0001.ppm")));
    // Resume: one output removed (as if the run had been interrupted) is the only one rendered.
    fs::remove(dir.File("m_0001.ppm"));
    Summary again = RunJobs(jobs, o);
    EXPECT_EQ(again.rendered, 1);
    EXPECT_EQ(again.skipped, 2);
    EXPECT_EQ(again.failed, 1);
    EXPECT_TRUE(fs::exists(dir.File("m_0001.ppm")));
}

}  // namespace
}  // namespace quadrix::batch
