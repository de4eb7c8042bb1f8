// Output formats used downstream (issue 21, deliverable 6), through the real binary: OpenEXR with
// depth, normal and id layers read back with the OpenEXR library and checked against the
// analytic sphere; 16-bit PNG; JSON statistics of every registered engine.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "quadrix/engines/registry.h"
#include "quadrix/io/exr.h"
#include "quadrix/math/srgb.h"
#include "quadrix/pipeline/output.h"
#include "quadrix/pipeline/render_context.h"
#include "test_util.h"

#ifdef QUADRIX_HAVE_OPENEXR
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#endif

namespace quadrix::testing {
namespace {

// Two unit spheres, at x = 0 and x = 3, seen along -z; whw 4 over 128 px is 16 px a unit, so the
// spheres are 16 px in radius, centred on pixels (64, 32) and (112, 32) (pixel corners).
constexpr const char* kTwoSpheres =
    "quadric ball <1 1 1 0 0 0 0 0 0 -1>; body bb (ball);\n"
    "quadric b2 <1 1 1 0 0 0 -3 0 0 8>; body bc (b2);\n"
    "view v dop 0 0 -1 whh 2 whw 4;\n";
constexpr int kW = 128, kH = 64;
constexpr double kScale = 16;  // pixels per unit

CommandResult Quadrix(const std::string& args) { return RunShell(QuadrixBinary() + " " + args); }

#ifdef QUADRIX_HAVE_OPENEXR
struct ExrLayers {
    std::vector<float> r, a, z, nx, ny, nz;
    std::vector<std::uint32_t> surface, body, solid;
    std::vector<std::string> channels;
};

ExrLayers ReadExr(const std::string& path) {
    ExrLayers L;
    Imf::InputFile in(path.c_str());
    const auto& dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    EXPECT_EQ(w, kW);
    EXPECT_EQ(h, kH);
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
        L.channels.emplace_back(it.name());
    const std::size_t n = static_cast<std::size_t>(w) * h;
    Imf::FrameBuffer fb;
    auto f = [&](const char* name, std::vector<float>& v) {
        v.resize(n);
        fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), sizeof(float),
                                   sizeof(float) * w));
    };
    auto u = [&](const char* name, std::vector<std::uint32_t>& v) {
        v.resize(n);
        fb.insert(name, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(v.data()),
                                   sizeof(std::uint32_t), sizeof(std::uint32_t) * w));
    };
    f("R", L.r);
    f("A", L.a);
    f("Z", L.z);
    f("N.x", L.nx);
    f("N.y", L.ny);
    f("N.z", L.nz);
    u("id.surface", L.surface);
    u("id.body", L.body);
    u("id.solid", L.solid);
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return L;
}
#endif

// Device z of the sphere centred on pixel corner (cx, cy) at the centre of pixel (x, y): the
// sphere's centre plane is z = 0 and z grows away from the viewer.
double SphereDepth(int x, int y, double cx, double cy) {
    const double u = (x + 0.5 - cx) / kScale, v = (y + 0.5 - cy) / kScale;
    return -kScale * std::sqrt(1 - u * u - v * v);
}

TEST(OutputFormats, ExrHoldsDepthNormalsAndIds) {
#ifndef QUADRIX_HAVE_OPENEXR
    GTEST_SKIP() << "built without OpenEXR (libopenexr-dev)";
#else
    TempDir dir;
    const std::string scene = dir.Write("s.uq", kTwoSpheres);
    CommandResult r = Quadrix("render " + scene + " --size 128x64 -o " + dir.File("a.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ExrLayers L = ReadExr(dir.File("a.exr"));
    for (const char* c :
         {"R", "G", "B", "A", "Z", "N.x", "N.y", "N.z", "id.surface", "id.body", "id.solid"})
        EXPECT_NE(std::find(L.channels.begin(), L.channels.end(), c), L.channels.end()) << c;
    auto at = [](int x, int y) { return static_cast<std::size_t>(y) * kW + x; };
    // Depths of known pixels against the analytic sphere (float storage: 1e-5 relative).
    for (auto [x, y] : {std::pair{64, 32}, {72, 32}, {60, 40}, {63, 31}}) {
        const double want = SphereDepth(x, y, 64, 32);
        EXPECT_NEAR(L.z[at(x, y)], want, 1e-5 * std::abs(want)) << x << "," << y;
        // The normal of the sphere there, facing the viewer (-z); world y is up, rows go down.
        const double u = (x + 0.5 - 64) / kScale, v = (y + 0.5 - 32) / kScale;
        // The Frame's packed normal (within 7e-5, frame/packed_normal.h), stored as floats.
        EXPECT_NEAR(L.nx[at(x, y)], u, 1e-6 + 7e-5);
        EXPECT_NEAR(L.ny[at(x, y)], -v, 1e-6 + 7e-5);
        EXPECT_NEAR(L.nz[at(x, y)], -std::sqrt(1 - u * u - v * v), 1e-6 + 7e-5);
        EXPECT_EQ(L.a[at(x, y)], 1.0f);
        EXPECT_GT(L.r[at(x, y)], 0.0f);
    }
    EXPECT_NEAR(L.z[at(112, 32)], SphereDepth(112, 32, 112, 32), 1e-4);
    // Ids: FlatScene index + 1; 0 on the background, whose depth is +inf.
    EXPECT_EQ(L.solid[at(64, 32)], 1u);
    EXPECT_EQ(L.body[at(64, 32)], 1u);
    EXPECT_EQ(L.surface[at(64, 32)], 1u);
    EXPECT_EQ(L.solid[at(112, 32)], 2u);
    EXPECT_EQ(L.surface[at(112, 32)], 2u);
    EXPECT_EQ(L.solid[at(0, 0)], 0u);
    EXPECT_EQ(L.surface[at(90, 32)], 0u);
    EXPECT_TRUE(std::isinf(L.z[at(0, 0)]));
    EXPECT_EQ(L.a[at(0, 0)], 0.0f);
    // The same through standard output (--format exr -o -).
    CommandResult piped = RunShell(QuadrixBinary() + " render " + scene +
                                   " --size 128x64 --format exr -o - > " + dir.File("b.exr"));
    ASSERT_EQ(piped.exitCode, 0) << piped.err;
    const ExrLayers P = ReadExr(dir.File("b.exr"));
    EXPECT_EQ(P.z, L.z);
    EXPECT_EQ(P.solid, L.solid);
#endif
}

// Reads a PNG as it is stored (no transformation): bit depth, channels, rows of samples (16-bit
// samples big-endian, two bytes each).
struct RawPng {
    int bitDepth = 0, channels = 0, width = 0, height = 0;
    std::vector<std::vector<png_byte>> rows;
};
bool ReadRawPng(const std::string& path, RawPng& out) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        std::fclose(f);
        return false;
    }
    png_init_io(png, f);
    png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    out.bitDepth = png_get_bit_depth(png, info);
    out.channels = png_get_channels(png, info);
    out.width = static_cast<int>(png_get_image_width(png, info));
    out.height = static_cast<int>(png_get_image_height(png, info));
    png_bytepp rows = png_get_rows(png, info);
    const std::size_t stride = png_get_rowbytes(png, info);
    for (int y = 0; y < out.height; ++y) out.rows.emplace_back(rows[y], rows[y] + stride);
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    return true;
}

// 16-bit PNG (--png16): 16 bits a sample, and each sample agrees with the 8-bit file's. The
// 8-bit file encodes the 8-bit linear pixels (io/writers.h EncodeSrgb8) and the 16-bit file the
// floats, so the 8-bit sample is sRGB(round(255 l) / 255) for the 16-bit file's linear value l,
// within one level (the float's own rounding to 8 bits may go either way at a half).
TEST(OutputFormats, Png16IsSixteenBitsAndAgreesWithEightBits) {
    TempDir dir;
    const std::string scene = dir.Write("s.uq", kTwoSpheres);
    ASSERT_EQ(
        Quadrix("render " + scene + " --size 128x64 --png16 -o " + dir.File("a.png")).exitCode, 0);
    ASSERT_EQ(Quadrix("render " + scene + " --size 128x64 -o " + dir.File("b.png")).exitCode, 0);
    RawPng a, b;
    ASSERT_TRUE(ReadRawPng(dir.File("a.png"), a));
    ASSERT_TRUE(ReadRawPng(dir.File("b.png"), b));
    EXPECT_EQ(a.bitDepth, 16);
    EXPECT_EQ(b.bitDepth, 8);
    ASSERT_EQ(a.channels, b.channels);
    ASSERT_EQ(a.width, kW);
    int distinct16 = 0;
    for (int y = 0; y < kH; ++y)
        for (int k = 0; k < kW * b.channels; ++k) {
            const int hi = a.rows[y][2 * k], lo = a.rows[y][2 * k + 1];
            const double v16 = (hi * 256 + lo) / 65535.0 * 255.0;
            const double l = LinearFromSrgb(v16 / 255.0);
            const double expected8 = 255.0 * SrgbFromLinear(std::round(255.0 * l) / 255.0);
            ASSERT_NEAR(expected8, b.rows[y][k], 1.0) << k << "," << y << ": 16-bit " << v16;
            distinct16 += lo != 0 && lo != hi;  // not merely an 8-bit value scaled up
        }
    EXPECT_GT(distinct16, 100);
}

// A picture alone is written after the Frame's memory is freed for the encoder (render_command.cpp,
// pipeline/output.h NeedsFrame); with a Frame dump or statistics the Frame is kept. The same
// bytes either way, at a size whose Frame arrays are mappings of their own (2 MiB and more).
TEST(OutputFormats, APictureIsTheSameWhetherTheFrameIsKeptOrFreed) {
    OutputRequest png, dump, exr, qxf;
    png.image = "a.png";
    dump.image = "a.png";
    dump.dumpFrame = "a.qxf";
    exr.image = "a.ppm";
    exr.exr = "a.exr";
    qxf.image = "a.qxf";
    EXPECT_FALSE(NeedsFrame(png));
    EXPECT_TRUE(NeedsFrame(dump));
    EXPECT_TRUE(NeedsFrame(exr));
    EXPECT_TRUE(NeedsFrame(qxf));

    TempDir dir;
    const std::string part = SourcePath("examples/machined_part.uq");
    const std::string size = " --size 1280x720 -o ";
    ASSERT_EQ(Quadrix("render " + part + size + dir.File("freed.png")).exitCode, 0);
    ASSERT_EQ(Quadrix("render " + part + size + dir.File("dumped.png") + " --dump-frame " +
                      dir.File("f.qxf"))
                  .exitCode,
              0);
    ASSERT_EQ(Quadrix("render " + part + size + dir.File("stats.png") + " --stats").exitCode, 0);
    auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::string freed = bytes(dir.File("freed.png"));
    EXPECT_GT(freed.size(), 10000u);
    EXPECT_EQ(freed, bytes(dir.File("dumped.png")));
    EXPECT_EQ(freed, bytes(dir.File("stats.png")));
}

// --stats --json for every registered engine: one valid JSON object on standard output with the
// engine's name, the size and the same counters as the render context reports in process.
TEST(OutputFormats, JsonStatsOfEveryEngine) {
    TempDir dir;
    // A quadric and a freeform surface, so that every engine draws something of its own.
    const std::string text =
        std::string(kTwoSpheres) + "bezier sheet 1 1 < 5 -1 0  7 -1 0  5 1 0  7 1 0 >;\n";
    const std::string scene = dir.Write("s.uq", text);
    int engines = 0;
    for (const EngineInfo& info : Engines()) {
        if (info.hidden) continue;
        ++engines;
        CommandResult r = Quadrix("render " + scene + " --size 128x64 -o " + dir.File("a.png") +
                                  " --engine " + info.name + " --stats --json");
        ASSERT_EQ(r.exitCode, 0) << info.name << ": " << r.err;
        nlohmann::json j;
        ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << info.name << ":\n" << r.out;
        ASSERT_TRUE(j.is_object()) << info.name;
        EXPECT_EQ(j["engine"], info.name);
        EXPECT_EQ(j["width"], kW);
        EXPECT_EQ(j["height"], kH);
        // 128 × 64 pixels of a small scene with the threads not given: run inline.
        EXPECT_EQ(j["threads"]["count"], 1) << info.name;
        EXPECT_EQ(j["threads"]["inline"], true) << info.name;
        ASSERT_TRUE(j["counters"].is_object()) << info.name;
        EXPECT_FALSE(j["counters"].empty()) << info.name << " reports no counters";
        for (const auto& [name, value] : j["counters"].items())
            EXPECT_TRUE(value.is_number()) << info.name << ": " << name;
        // The same counter names as the render context gives in process.
        RenderContext ctx(1);
        Diagnostics diags;
        InputRequest in;
        in.paths = {scene};
        ViewRequest view;
        view.width = kW;
        view.height = kH;
        EngineRequest request;
        request.engine = info.name;
        Frame frame;
        RenderReport report;
        ASSERT_TRUE(ctx.Read(in, diags) && ctx.Flatten(view, diags) &&
                    ctx.Render(request, frame, report, diags))
            << info.name;
        for (const auto& [name, value] : report.stats.counters)
            EXPECT_TRUE(j["counters"].contains(name)) << info.name << ": " << name;
        // The engine's paper tables, cell for cell: text as strings, numbers as numbers.
        ASSERT_TRUE(j["tables"].is_array()) << info.name;
        ASSERT_EQ(j["tables"].size(), report.stats.tables.size()) << info.name;
        for (std::size_t t = 0; t < report.stats.tables.size(); ++t) {
            const StatsTable& table = report.stats.tables[t];
            const nlohmann::json& jt = j["tables"][t];
            EXPECT_EQ(jt["title"], table.title);
            ASSERT_EQ(jt["rows"].size(), table.rows.size()) << table.title;
            for (std::size_t r = 0; r < table.rows.size(); ++r)
                for (std::size_t c = 0; c < table.rows[r].size(); ++c) {
                    const StatsCell& cell = table.rows[r][c];
                    const nlohmann::json& jc = jt["rows"][r][c];
                    if (cell.kind == StatsCell::Kind::kText) {
                        EXPECT_EQ(jc, cell.text);
                    }
                    if (cell.kind == StatsCell::Kind::kInteger) {
                        EXPECT_EQ(jc, cell.integer);
                    }
                    if (cell.kind == StatsCell::Kind::kReal) {
                        EXPECT_TRUE(jc.is_number());
                    }
                    if (cell.kind == StatsCell::Kind::kEmpty) {
                        EXPECT_TRUE(jc.is_null());
                    }
                }
        }
        // The engines with a paper's tables give them (scanline 7.1–7.3, pixelpowers Table 1,
        // patch Tables 1.6 and 1.1–1.7).
        const std::map<std::string, std::size_t> expected{
            {"scanline", 3}, {"pixelpowers", 1}, {"patch", 7}};
        if (auto it = expected.find(info.name); it != expected.end()) {
            EXPECT_EQ(report.stats.tables.size(), it->second) << info.name;
        }
    }
    EXPECT_GE(engines, 5);
}

}  // namespace
}  // namespace quadrix::testing
