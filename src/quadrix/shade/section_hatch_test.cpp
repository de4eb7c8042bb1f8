// Hatching of the section's cut faces (section_hatch.h), on Frames rendered by raycast: lines
// only on the cap's pixels, and where the file comment's rule puts them, computed here from each
// pixel's world point alone: the same rule holds in a rolled and panned view and with the plane
// moved, so the pattern belongs to the plane, not to the screen.
#include "quadrix/shade/section_hatch.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "quadrix/pipeline/render_context.h"
#include "quadrix/shade/row_shading.h"
#include "test_util.h"

namespace quadrix {
namespace {

// Two boxes side by side (solids 0 and 1), seen along +z in a parallel view of half-height
// whh = 1.5 on 240×150 pixels: a pixel is 0.02 world units.
constexpr int kWidth = 240, kHeight = 150;
constexpr double kWhh = 1.5;

std::string Scene(const std::string& view) {
    return "solid box left =from -2.1 -1 -1 =to -0.1 1 1;\n"
           "solid box right =from 0.1 -1 -1 =to 2.1 1 1;\n" +
           view;
}

struct Drawn {
    Frame frame;
    Image plain, hatched;
};

Drawn Draw(RenderContext& ctx, const std::string& text, const Plane& section,
           ShadeOptions so = {}) {
    Drawn d;
    Diagnostics diags;
    InputRequest in;
    in.text = text;
    ViewRequest view;
    view.width = kWidth;
    view.height = kHeight;
    view.section = section;
    EngineRequest engine;
    RenderReport report;
    EXPECT_TRUE(ctx.Read(in, diags) && ctx.Flatten(view, diags) &&
                ctx.Render(engine, d.frame, report, diags));
    d.plain = ctx.Shade(d.frame, so);
    so.hatch = true;
    so.hatchColor = {0, 0, 0};
    d.hatched = ctx.Shade(d.frame, so);
    return d;
}

// The expected state of a cap pixel with world point p on solid `solid`, from the file comment:
// the section's normal is ±z, so n = +z, the least aligned axis is x, e1 = x, e2 = n × e1 = y;
// lines across m = (e2 − e1)/√2 (even solids) or (e1 + e2)/√2 (odd), spacing 2^round(log2(8 ·
// 0.02)) = 1/8, width 1.25 pixels = 0.025 (the plane faces the viewer: h changes by one pixel's
// size per pixel). Returns -1 for points within 1e-9 of a line's border (rounding may go either
// way there).
int Expected(const Vec3& p, int solid) {
    const double pixel = 2 * kWhh / kHeight;
    const double s = std::exp2(std::round(std::log2(8 * pixel)));
    EXPECT_EQ(s, 0.125);
    const double h = (solid % 2 == 0 ? p.y - p.x : p.x + p.y) / std::sqrt(2.0);
    const double off = std::fabs(h - s * std::round(h / s));
    const double half = 0.5 * 1.25 * pixel;
    if (std::fabs(off - half) < 1e-9) return -1;
    return off < half;
}

// Checks `d` against Expected; returns the hatched pixels of each solid.
std::array<int, 2> CheckAgainstRule(const Drawn& d, const FlatScene& flat) {
    std::array<int, 2> hatched{0, 0};
    int cap = 0;
    const Mat4& worldFromDevice = flat.projection.deviceFromWorld.Inverse();
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = d.frame.Index(x, y);
            const bool changed = d.plain.pixels[i] != d.hatched.pixels[i];
            if (d.frame.surface[i] != flat.sectionHalfSpace) {
                EXPECT_FALSE(changed) << "hatch outside the cut at " << x << " " << y;
                continue;
            }
            ++cap;
            const Vec3 p = worldFromDevice.MapPoint({x + 0.5, y + 0.5, d.frame.depth[i]});
            const int solid = d.frame.Solid(i);
            if (solid != 0 && solid != 1) {
                ADD_FAILURE() << "solid " << solid;
                continue;
            }
            const int want = Expected(p, solid);
            if (want < 0) continue;
            // A line pixel is painted black; the boxes' shading is not black.
            EXPECT_EQ(d.hatched.pixels[i] == 0, want == 1) << x << " " << y << " solid " << solid;
            EXPECT_GT(d.plain.pixels[i], 0);
            hatched[static_cast<std::size_t>(solid)] += want == 1;
        }
    EXPECT_GT(cap, 10000);
    return hatched;
}

TEST(SectionHatch, LinesOnlyOnTheCutAndFixedToThePlane) {
    const Plane section{0, 0, -1, 0};  // keeps z >= 0: the cut faces the viewer at z = 0
    const std::string front = "view front vrp 0 0 0 vpn 0 0 1 vup 0 1 0 dop 0 0 -1 whh 1.5;";
    // Rolled by 30° about the view direction and panned by fractions of a pixel.
    const std::string rolled =
        "view rolled vrp 0.0137 -0.0211 0 vpn 0 0 1 vup 0.5 0.8660254037844386 0 dop 0 0 -1 "
        "whh 1.5;";
    RenderContext a, b, c;
    const Drawn da = Draw(a, Scene(front), section);
    const std::array<int, 2> na = CheckAgainstRule(da, a.Flat());
    // About 1.25 / 8 of the cap is on a line.
    for (int n : na) {
        EXPECT_GT(n, 0.10 * kWidth * kHeight / 2 * 0.8);
        EXPECT_LT(n, 0.25 * kWidth * kHeight / 2);
    }
    const Drawn db = Draw(b, Scene(rolled), section);
    EXPECT_NE(da.hatched.pixels, db.hatched.pixels);
    CheckAgainstRule(db, b.Flat());
    // The plane moved along its normal (keeping z >= 0.3): the lines stay where they were in
    // the plane's x and y.
    const Drawn dc = Draw(c, Scene(front), Plane{0, 0, -1, 0.3});
    CheckAgainstRule(dc, c.Flat());
    // The geometry is the plane's: the same in every view.
    const std::optional<SectionHatch> ha = SectionHatchOf(a.Flat(), kHatchSpacingPixels);
    const std::optional<SectionHatch> hb = SectionHatchOf(b.Flat(), kHatchSpacingPixels);
    ASSERT_TRUE(ha && hb);
    EXPECT_EQ(ha->e1, hb->e1);
    EXPECT_EQ(ha->e2, hb->e2);
    EXPECT_EQ(ha->spacing, hb->spacing);
    // Keeping the other side gives the same axes (the normal's sign is canonical).
    RenderContext flipped;
    Draw(flipped, Scene(front), Plane{0, 0, 1, 0});
    const std::optional<SectionHatch> hf = SectionHatchOf(flipped.Flat(), kHatchSpacingPixels);
    ASSERT_TRUE(hf);
    EXPECT_EQ(hf->e1, ha->e1);
    EXPECT_EQ(hf->e2, ha->e2);
}

TEST(SectionHatch, ZoomChangesTheSpacingByPowersOfTwoAndRowsShadeAlike) {
    // Zoomed in 1.3 times: the same spacing (8 / 1.3 pixels of 1/8 rounds to 1/8 still), 2.5
    // times: half of it.
    RenderContext ctx;
    const Plane section{0, 0, -1, 0};
    auto spacing = [&](double whh) {
        Draw(ctx,
             Scene("view v vrp 0 0 0 vpn 0 0 1 vup 0 1 0 dop 0 0 -1 whh " + std::to_string(whh) +
                   ";"),
             section);
        return SectionHatchOf(ctx.Flat(), kHatchSpacingPixels)->spacing;
    };
    EXPECT_EQ(spacing(1.5), 0.125);
    EXPECT_EQ(spacing(1.5 / 1.3), 0.125);
    EXPECT_EQ(spacing(1.5 / 2.5), 0.0625);
    // A perspective view: lines on the cap only, about the same share of it.
    const Drawn p =
        Draw(ctx, Scene("view eye vrp 0 0 0 vup 0 1 0 cop 0.9 -0.6 -4 whh 1.5;"), section);
    int cap = 0, lines = 0;
    for (std::size_t i = 0; i < p.plain.pixels.size(); ++i) {
        const bool changed = p.plain.pixels[i] != p.hatched.pixels[i];
        const bool onCap = p.frame.surface[i] == ctx.Flat().sectionHalfSpace;
        EXPECT_TRUE(onCap || !changed);
        cap += onCap;
        lines += changed;
    }
    EXPECT_GT(cap, 5000);
    EXPECT_GT(lines, cap / 20);
    EXPECT_LT(lines, cap / 3);
    // Shading some rows (sort-first) gives those rows the same bits.
    ShadeOptions so;
    so.hatch = true;
    const Image whole = ctx.Shade(p.frame, so);
    const Image part = ShadeRows(p.frame, ctx.Flat(), so, {{20, 70}});
    for (int y = 20; y < 70; ++y)
        for (int x = 0; x < kWidth; ++x) ASSERT_EQ(*whole.At(x, y), *part.At(x, y)) << x << y;
}

TEST(SectionHatch, NothingWithoutASection) {
    RenderContext ctx;
    Frame frame;
    Diagnostics diags;
    InputRequest in;
    in.text = Scene("");
    ASSERT_TRUE(testing::RenderToFrame(ctx, in, 32, 24, frame, diags));
    EXPECT_FALSE(SectionHatchOf(ctx.Flat(), kHatchSpacingPixels));
    ShadeOptions so;
    so.hatch = true;
    Image image = ctx.Shade(frame, so);
    EXPECT_EQ(image.pixels, ctx.Shade(frame, {}).pixels);
    EXPECT_EQ(HatchSection(frame, ctx.Flat(), so, image), 0u);
}

}  // namespace
}  // namespace quadrix
