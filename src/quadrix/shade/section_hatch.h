// Hatching of the section plane's cut faces (issue 18 §5): the pixels whose surface is the
// section plane's cap (FlatScene::sectionHalfSpace) get parallel lines over their shading, as a
// mechanical drawing hatches a section. Applied to the shaded Image from the Frame, after the
// anti-aliasing and before the edge lines (RenderContext::Shade, ShadeRows); never in an engine.
//
// The pattern belongs to the plane, not to the screen, so that it does not swim when the view
// orbits or pans:
//   - The plane's own axes. n = the section's WORLD unit normal (FlatScene::section, as given),
//     its sign chosen so that its largest-magnitude component is positive (the first of equal
//     ones), so that flipping the kept side keeps the pattern. a = the world axis least aligned
//     with n (the first of equal ones); e1 = the unit part of a orthogonal to n, e2 = n × e1.
//   - Lines at 45° to e1 (solids of even index) or 135° (odd index: adjacent parts of an
//     assembly are told apart, as drawings alternate the hatch direction). A point p of the
//     plane lies on a line when its hatch coordinate h = p·m (m = (e2 − e1)/√2 for 45°,
//     (e1 + e2)/√2 for 135°, unit vectors of the plane across the lines) is within w/2 of a
//     multiple of the spacing s. Moving the plane along its normal keeps the lines where they
//     were in the plane's directions (p·m does not change along n).
//   - The spacing s is world units: `spacingPixels` (ShadeOptions::hatchSpacing, 8) times the
//     world size of a pixel, rounded to the nearest power of two. A pixel's world size is that
//     of a one-pixel step across the screen at the point where the image centre's ray meets the
//     plane (the same everywhere in a parallel view). Orbiting a parallel view keeps s; zooming
//     changes it by factors of two only, and a line of spacing 2s is a line of spacing s: the
//     lines stay put and every other one goes as the view zooms out.
//   - The width w of a line is what keeps it kLineWidthPixels wide on the screen at that pixel:
//     w = kLineWidthPixels · |∇h| (∇h the change of h per pixel, from the screen-to-plane
//     homography), at most s/3 (a plane seen nearly edge-on gets a grey tone, not a solid fill).
//     Since the line is at least one pixel wide along both screen axes, every row and column it
//     crosses has a pixel centre on it: the lines are continuous.
// So a pixel's state is a function of its point on the plane, its solid, and of s and w (which
// depend on the view, not on the pixel, in a parallel view whose plane faces the viewer); it
// reads only its own Frame entry, so shading rows apart (sort-first) gives the same bits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/math/vec.h"
#include "quadrix/shade/shader.h"

namespace quadrix {

constexpr double kHatchSpacingPixels = 8;
constexpr double kLineWidthPixels = 1.25;

// The pattern of a flat scene's section (see the file comment); nullopt when the scene has no
// section, or its plane is seen edge-on (no cut face can show), or the pixel size is not finite.
struct SectionHatch {
    int halfSpace = -1;    // FlatScene::sectionHalfSpace
    Vec3 normal;           // canonical world unit normal
    Vec3 e1, e2;           // the plane's axes (world unit vectors)
    double spacing = 0;    // s, world units
    double pixelSize = 0;  // the world size of a pixel it was derived from
};
std::optional<SectionHatch> SectionHatchOf(const FlatScene& scene, double spacingPixels);

// The unit vector m across the lines of `solid`'s family, and a point's hatch coordinate.
Vec3 HatchAcross(const SectionHatch& hatch, int solid);
// Whether hatch coordinate h is on a line of width w (world units).
bool OnHatchLine(const SectionHatch& hatch, double h, double w);

// Paints the hatch lines of the section's cut faces in options.hatchColor (when options.hatch
// and the scene has a section); returns how many pixels. Only rows marked kRowShaded when `rows`
// is not empty (shade/row_shading.h).
std::size_t HatchSection(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                         Image& image);
std::size_t HatchSectionRowKinds(const Frame& frame, const FlatScene& scene,
                                 const ShadeOptions& options, Image& image,
                                 const std::vector<std::uint8_t>& rows);

}  // namespace quadrix
