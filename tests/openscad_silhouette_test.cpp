// Issue 20's OpenSCAD acceptance: a hex nut (cylinder(r=10, h=6, $fn=6) minus a hole), an
// extruded L-profile, a polyhedron die and rotate-extruded rings of polygons (exact, and the
// hexagonal ring of $fn = 6) have the same silhouette in `quadrix render` as in OpenSCAD's own
// PNG export of the same .scad with the same orthographic camera (pipeline/camera.h follows
// OpenSCAD's --camera/--projection=ortho scale, so the two pictures share pixel coordinates).
//
// OpenSCAD 2021.01 (Debian 12) cannot export PNG without a display (it crashes, leaving an empty
// file): the PNGs are made under one xvfb-run, the models' OpenSCAD runs in parallel. Masks:
// OpenSCAD's pixels that differ from its background colour, ours that are not black. The test
// counts pixels where the masks differ and neither mask has a silhouette pixel within 1 px: it
// must be 0. OpenSCAD draws curved surfaces as facets, Quadrix exactly; the models' curved parts
// are fine enough (or $fn-given) that facets stay within that pixel. The models use variables,
// modules and loops, so every one is evaluated by OpenSCAD itself on our side too
// (import/openscad/scad_source.h).
#include <gtest/gtest.h>
#include <png.h>

#include <string>
#include <vector>

#include "quadrix/import/openscad/openscad_program.h"
#include "test_util.h"

namespace quadrix {
namespace {

using testing::HaveProgram;
using testing::QuadrixBinary;
using testing::RunShell;
using testing::TempDir;

constexpr int kW = 120, kH = 90;

struct Model {
    const char* name;
    const char* scad;
    const char* camera;  // eye, center
};

const Model kModels[] = {
    {"hexnut",
     "module nut(r, h, hole) {\n"
     "  difference() {\n"
     "    cylinder(r = r, h = h, $fn = 6);\n"
     "    translate([0, 0, -1]) cylinder(r = hole, h = h + 2);\n"
     "  }\n"
     "}\n"
     "nut(10, 6, 5);\n",
     "30,-40,45,0,0,3"},
    {"lprofile",
     "t = 2; leg = 10;\n"
     "linear_extrude(height = 20)\n"
     "  polygon([[0, 0], [leg, 0], [leg, t], [t, t], [t, leg - 2], [0, leg - 2]]);\n",
     "44,-28,32,4,3,10"},
    {"die",
     "s = 10;\n"
     "pts = [[0,0,0],[s,0,0],[s,s,0],[0,s,0],[0,0,s],[s,0,s],[s,s,s],[0,s,s]];\n"
     "faces = [[0,1,2,3],[4,7,6,5],[0,4,5,1],[1,5,6,2],[2,6,7,3],[3,7,4,0]];\n"
     "difference() {\n"
     "  intersection() {\n"
     "    polyhedron(points = pts, faces = faces);\n"
     "    translate([s, s, s] / 2) sphere(r = 7.4, $fn = 48);\n"
     "  }\n"
     "  for (p = [[s/2, s/2, s], [s/2, 0, s/2], [s, s/2, s/2]])\n"
     "    translate(p) sphere(r = 1.2, $fn = 24);\n"
     "}\n",
     "30,-22,26,5,5,5"},
    {"rings",
     "module ring(n) { rotate_extrude($fn = n) translate([8, 0]) "
     "polygon([[0, 0], [3, 0], [3, 2], [1, 4]]); }\n"
     "ring(64);\n"
     "translate([26, 0, 0]) rotate_extrude($fn = 6) translate([7, 0]) square([3, 2]);\n",
     "13,-60,55,13,0,0"},
};

bool ReadRgbPng(const std::string& path, std::vector<unsigned char>& rgb, int& w, int& h) {
    png_image p{};
    p.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&p, path.c_str())) return false;
    p.format = PNG_FORMAT_RGB;
    w = static_cast<int>(p.width), h = static_cast<int>(p.height);
    rgb.assign(static_cast<std::size_t>(w) * h * 3, 0);
    const bool ok = png_image_finish_read(&p, nullptr, rgb.data(), 0, nullptr) != 0;
    png_image_free(&p);
    return ok;
}

// Coverage mask: pixels that differ from the colour of the top-left corner (the background).
std::vector<bool> Mask(const std::vector<unsigned char>& rgb, int w, int h) {
    std::vector<bool> m(static_cast<std::size_t>(w) * h);
    for (std::size_t k = 0; k < m.size(); ++k) {
        int d = 0;
        for (int c = 0; c < 3; ++c) d += std::abs(int(rgb[k * 3 + c]) - int(rgb[c]));
        m[k] = d > 24;
    }
    return m;
}

bool NearEdge(const std::vector<bool>& m, int w, int h, int x, int y) {
    const bool v = m[static_cast<std::size_t>(y) * w + x];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
            if (m[static_cast<std::size_t>(yy) * w + xx] != v) return true;
        }
    return false;
}

TEST(OpenScadSilhouettes, SameShapeAsOpenScadsOwnPng) {
    if (import::scad::FindOpenScad().empty())
        GTEST_SKIP() << "openscad is not installed (apt-get install openscad)";
    if (!HaveProgram("xvfb-run"))
        GTEST_SKIP() << "xvfb-run (package xvfb) is not installed: OpenSCAD 2021.01 needs a "
                        "display to export PNG";
    TempDir dir;
    std::string script;
    for (const Model& m : kModels) {
        const std::string scad = dir.Write(std::string(m.name) + ".scad", m.scad);
        script += "openscad -o '" + dir.File(std::string(m.name) + "_openscad.png") +
                  "' --imgsize=" + std::to_string(kW) + "," + std::to_string(kH) +
                  " --projection=ortho --colorscheme=Tomorrow --camera=" + m.camera + " '" + scad +
                  "' >/dev/null 2>&1 &\n";
    }
    script += "wait\n";
    const std::string sh = dir.Write("openscad.sh", script);
    auto r = testing::RunUnderXvfb(sh);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const Model& m : kModels) {
        SCOPED_TRACE(m.name);
        const std::string ours = dir.File(std::string(m.name) + "_quadrix.png");
        auto q =
            RunShell(QuadrixBinary() + " render '" + dir.File(std::string(m.name) + ".scad") +
                     "' -o '" + ours + "' --size " + std::to_string(kW) + "x" + std::to_string(kH) +
                     " --camera " + m.camera + " --projection ortho --aa off --no-shadows");
        ASSERT_EQ(q.exitCode, 0) << q.err;
        std::vector<unsigned char> a, b;
        int wa = 0, ha = 0, wb = 0, hb = 0;
        ASSERT_TRUE(ReadRgbPng(dir.File(std::string(m.name) + "_openscad.png"), a, wa, ha))
            << "OpenSCAD wrote no PNG";
        ASSERT_TRUE(ReadRgbPng(ours, b, wb, hb));
        ASSERT_EQ(wa, kW);
        ASSERT_EQ(ha, kH);
        ASSERT_EQ(wb, kW);
        ASSERT_EQ(hb, kH);
        const std::vector<bool> ma = Mask(a, kW, kH), mb = Mask(b, kW, kH);
        int covered = 0, mismatch = 0, edge = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const std::size_t k = static_cast<std::size_t>(y) * kW + x;
                covered += ma[k];
                if (ma[k] == mb[k]) continue;
                if (NearEdge(ma, kW, kH, x, y) || NearEdge(mb, kW, kH, x, y))
                    ++edge;
                else
                    ++mismatch;
            }
        RecordProperty(std::string(m.name) + "_covered", covered);
        RecordProperty(std::string(m.name) + "_edge_differences", edge);
        // The model fills a good part of the picture, and the pictures agree.
        EXPECT_GT(covered, kW * kH / 20);
        EXPECT_EQ(mismatch, 0) << "edge differences: " << edge << " of " << covered;
    }
}

}  // namespace
}  // namespace quadrix
