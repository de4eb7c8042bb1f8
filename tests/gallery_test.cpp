// The gallery (docs/gallery.md, examples/gallery/): `quadrix pipe` regenerates the committed
// inputs and scenes byte for byte, the written scenes' joints are watertight when read back
// through the language, and every gallery scene renders through raycast.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "quadrix/lang/reader.h"
#include "quadrix/model/pipe.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

std::string ReadAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct GalleryPipe {
    const char* name;      // examples/gallery/<name>.pipe and <name>_tubes.uq
    const char* generate;  // the --generate arguments that made the .pipe
    double radius;
    std::size_t elements;
};

const GalleryPipe kPipes[] = {
    {"hilbert3", "--generate hilbert:3 --radius .25", 0.25, 63},  // 4³ − 1
    {"clover_knot", "--generate trefoil:24 --radius .3", 0.3, 24},
    {"triangles", "--generate sierpinski:2 --radius .12", 0.12, 27},
    {"name", "--generate text:QUADRIX --radius .2 --ball .3", 0.2, 43},
};

TEST(Gallery, PipeCommandRegeneratesTheCommittedFiles) {
    TempDir dir;
    for (const GalleryPipe& g : kPipes) {
        const std::string pipe = SourcePath(std::string("examples/gallery/") + g.name + ".pipe");
        const std::string tubes =
            SourcePath(std::string("examples/gallery/") + g.name + "_tubes.uq");
        const std::string genOut = dir.File(std::string(g.name) + ".pipe");
        CommandResult r =
            RunShell(QuadrixBinary() + " pipe " + g.generate + " -o '" + genOut + "'");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(ReadAll(genOut), ReadAll(pipe)) << g.name;
        // The tubes are written from the committed input, named as in the gallery's commands.
        const std::string uqOut = dir.File(std::string(g.name) + "_tubes.uq");
        r = RunShell("cd '" + SourcePath("examples/gallery") + "' && " + QuadrixBinary() +
                     " pipe " + g.name + ".pipe -o '" + uqOut + "' --definition " + g.name +
                     "_tubes");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(ReadAll(uqOut), ReadAll(tubes)) << g.name;
    }
}

// True when p is inside every literal of the body (as the engines evaluate it).
bool InBody(const scene::Scope& scope, const scene::Body& b, const Vec3& p) {
    for (const scene::Literal& lit : b.literals) {
        const scene::HalfSpace& h = scope.halfSpaces[lit.halfSpace];
        double f =
            h.kind == scene::HalfSpace::Kind::kPlane ? h.plane.Evaluate(p) : h.quadric.Evaluate(p);
        if ((f <= 0) == lit.complemented) return false;
    }
    return true;
}

// The committed scenes of tubes, read back through the language: every point within 0.99 r of
// a mitered joint is inside exactly one tube (no gap, no overlap), and points on each miter plane
// nudged to either side belong to that side's tube (the ray test along the joint plane).
TEST(Gallery, MiteredJointsOfTheWrittenScenesAreWatertight) {
    for (const GalleryPipe& g : kPipes) {
        if (std::string(g.name) == "name") continue;  // ball joints, tested below
        const std::string dirPath = SourcePath("examples/gallery/");
        scene::Scene sc;
        Diagnostics d;
        lang::Reader reader(sc, d);
        ASSERT_TRUE(reader.ReadFile(dirPath + g.name + "_tubes.uq")) << g.name;
        ASSERT_EQ(sc.definitions.size(), 1u);
        const scene::Scope& def = sc.definitions[0];
        ASSERT_EQ(def.bodies.size(), g.elements) << g.name;

        Diagnostics pd;
        model::PipeSpec spec;
        model::PipeModel m;
        ASSERT_TRUE(model::ReadPipeText(ReadAll(dirPath + g.name + ".pipe"), g.name, spec, pd));
        ASSERT_TRUE(model::BuildPipes(spec, m, pd));
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(-1, 1);
        int checked = 0;
        for (const model::PipeJoint& j : m.joints) {
            if (j.elements.size() < 2) continue;
            for (int k = 0; k < 200; ++k) {
                Vec3 dv{u(rng), u(rng), u(rng)};
                if (Length(dv) > 1) continue;
                Vec3 p = j.point + dv * (0.99 * g.radius);
                int count = 0;
                for (const scene::Body& b : def.bodies) count += InBody(def, b, p);
                ASSERT_EQ(count, 1)
                    << g.name << " joint " << j.point.x << " " << j.point.y << " " << j.point.z;
                ++checked;
            }
            // Each miter plane at this joint: the body on each side owns the nudged points.
            for (int ei : j.elements) {
                const scene::Body& b = def.bodies[ei];
                for (std::size_t lit = 1; lit < b.literals.size(); ++lit) {
                    const Plane& plane = def.halfSpaces[b.literals[lit].halfSpace].plane;
                    if (std::fabs(plane.Evaluate(j.point)) > 1e-12) continue;  // other joint
                    const Vec3 n = Normalize(plane.Normal());
                    const Vec3 t1 =
                        Normalize(Cross(n, std::fabs(n.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
                    const Vec3 t2 = Cross(n, t1);
                    for (int k = 0; k < 50; ++k) {
                        Vec3 q = j.point + t1 * (0.6 * g.radius * u(rng)) +
                                 t2 * (0.6 * g.radius * u(rng));
                        // With two elements the inner side is this tube; with more, a point
                        // of this plane may lie in a third tube's sector: then exactly one
                        // tube on each side is what "no gap, no overlap" means.
                        if (j.elements.size() == 2) {
                            EXPECT_TRUE(InBody(def, b, q - n * 1e-9)) << g.name;
                        }
                        int inside = 0, outside = 0;
                        for (const scene::Body& other : def.bodies) {
                            inside += InBody(def, other, q - n * 1e-9);
                            outside += InBody(def, other, q + n * 1e-9);
                        }
                        EXPECT_EQ(inside, 1) << g.name;
                        EXPECT_EQ(outside, 1) << g.name;
                    }
                }
            }
        }
        EXPECT_GT(checked, 1000) << g.name;
    }
}

TEST(Gallery, EveryGallerySceneRenders) {
    const char* scenes[] = {"hilbert3", "clover_knot", "triangles", "name", "gear", "solids"};
    for (const char* name : scenes) {
        PipelineOptions o;
        o.scenePaths = {SourcePath(std::string("examples/gallery/") + name + ".uq")};
        o.width = 160;
        o.height = 120;
        PipelineResult r;
        Diagnostics d;
        std::string msgs;
        bool ok = RunPipeline(o, r, d);
        for (const auto& item : d.Items()) msgs += item.Format() + "\n";
        ASSERT_TRUE(ok) << name << "\n" << msgs;
        EXPECT_EQ(d.WarningCount(), 0) << name << "\n" << msgs;
        // Each subject fills a fair part of its picture.
        EXPECT_GT(r.frame.CoveredCount(), 160u * 120u / 20) << name;
    }
}

TEST(Gallery, PipeCommandReportsBadInputWithPositions) {
    TempDir dir;
    std::string bad = dir.Write("bad.pipe", "radius .5\npath\n0 0 0\n1 0\n");
    CommandResult r =
        RunShell(QuadrixBinary() + " pipe '" + bad + "' -o '" + dir.File("out.uq") + "'");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("bad.pipe:4:1: error: a point has 3 coordinates"), std::string::npos)
        << r.err;
    EXPECT_FALSE(FileExists(dir.File("out.uq")));
    r = RunShell(QuadrixBinary() + " pipe --generate spiral -o '" + dir.File("x.pipe") + "'");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown curve"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace quadrix::testing
