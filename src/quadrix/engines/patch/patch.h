// The quadric patch of seed 000 (Laporte et al., "Direct Visualization of Quadrics", §1.2.2): a
// quadric surface bounded by up to four planes, and its construction from a FlatBody.
//
// Notation of the module (used by every file of engines/patch/). The paper writes the quadric as
//   a x² + b y² + c z² + d xy + e xz + f yz + g x + h y + i z + j = 0          (seed 000 eq. 1.1)
// Quadrix stores UniQuadrix coefficients <A B C D E F G H J K> with the factor 2 on cross and
// linear terms (DESIGN.md), so the paper's letters are
//   a = A, b = B, c = C, d = 2D, e = 2F, f = 2E, g = 2G, h = 2H, i = 2J, j = K.
// All coordinates are device space: x = column, y = row, pixel centres at (i+½, j+½), rays along
// +z, z grows away from the viewer; ZF (front) < ZB (back).
//
// What a patch draws. Along the ray of a pixel the quadric has at most two roots ZF <= ZB. A
// bounding plane keeps the closed half-space A x + B y + C z + D <= 0 (Quadrix's convention, the
// paper's CP is C). The patch shows the first root that every plane keeps (§1.3.2). That is
// exactly what `raycast` draws for a body made of an opaque quadric and transparent planes: the
// body's interval endpoints along the ray are the roots lying inside the planes' slab, and the
// first of them that lies on an opaque surface is the visible point. Planes are bounds, never
// faces: the patch processor cannot draw a plane.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"

namespace quadrix::patch {

// The processor has four plane units (seed 000 §1.2.2: tetrahedral Bézier cells need four).
inline constexpr int kMaxPlanes = 4;

// A half-open rectangle of pixels [x0, x1) × [y0, y1): the window the processor scans
// (§1.3: "the projection of the patch is displayed inside the projection of the bounding box").
struct PixelWindow {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    bool Empty() const { return x1 <= x0 || y1 <= y0; }
    int Width() const { return Empty() ? 0 : x1 - x0; }
    int Height() const { return Empty() ? 0 : y1 - y0; }
    std::int64_t Pixels() const {
        return static_cast<std::int64_t>(Width()) * static_cast<std::int64_t>(Height());
    }
};

// The pixels of a width × height image whose centres (i+½, j+½) lie in the x-y projection of
// `box` (closed). Infinite sides extend to the image border; an empty box gives an empty window.
PixelWindow WindowOfBox(const Box3& box, int width, int height);

// A bounding plane, device space, oriented so that the kept side is A x + B y + C z + D <= 0 (a
// complemented literal is already negated).
struct BoundingPlane {
    Plane plane;
    int halfSpace = -1;  // FlatScene half-space index, for diagnostics
};

struct QuadricPatch {
    // Device space, scaled by ±1 so that C > 0: the normal orientation rule of §1.4.3 (negate the
    // normal of the back sheet) makes normals face the viewer only when c > 0, since the gradient's
    // z component is -2c·sqrt(F2) at ZF and +2c·sqrt(F2) at ZB. The surface Q = 0 is unchanged.
    Quadric quadric;
    int planeCount = 0;
    std::array<BoundingPlane, kMaxPlanes> planes{};
    PixelWindow window;
    Box3 box;  // the device-space box whose projection is the window
    // Frame ids of what the patch draws.
    int surface = -1;  // the quadric's half-space
    int body = -1;
    int solid = -1;
};

// Why a body is not drawn as a patch.
enum class Rejection : std::uint8_t {
    kNone,              // converted
    kEmpty,             // provably empty (empty bounds or window): nothing to draw, not an error
    kInvisible,         // the quadric is transparent and no plane shows a face: nothing to draw
    kNoQuadric,         // only planes: a polyhedron, not a patch
    kSeveralQuadrics,   // the processor has one square-root datapath
    kTooManyPlanes,     // more than four planes cut the body
    kOpaquePlaneFace,   // an opaque plane cuts the body, so one of its faces would be visible
    kViewAlongSurface,  // C = 0: the ray meets the quadric at most once (§1.2.1 needs c != 0)
    kNotFinite,         // NaN or infinite coefficients
    kMalformed,         // a literal names no half-space
};
std::string_view RejectionName(Rejection why);

// How bodies with opaque planes that cut them are treated.
enum class CapPolicy : std::uint8_t {
    kSkip,  // not drawable: report them (a patch cannot draw the plane faces)
    kOpen,  // draw the quadric part with every plane as a bound (the faces are missing)
};

struct Conversion {
    std::optional<QuadricPatch> patch;
    Rejection why = Rejection::kNone;
    bool drawnOpen = false;  // kOpen applied: opaque plane faces are missing from the picture
    int planesDropped = 0;   // plane literals found redundant over the body's box
};

// Converts body `bodyIndex` of `scene` (its Frame ids: surface = the quadric's half-space, body,
// solid = body.solid). Plane literals whose plane lies strictly outside the body's box on the kept
// side are redundant and dropped (this is how the Flattener's clipping planes usually go), which
// keeps more bodies within four planes. Never throws.
Conversion ConvertBody(const FlatScene& scene, int bodyIndex, CapPolicy caps);

// World-space unit normal from a device-space gradient g = (NX, NY, NZ) of the quadric at the
// device point p, mapped as FlatScene::WorldNormal maps normals (the covector pull-back
// n = Mᵀ (g, g_w) with M = deviceFromWorld). The homogeneous component is g_w = -p·g because p
// lies on the surface ((p,1)ᵀ Q (p,1) = p·(Qp)_xyz + (Qp)_w = 0), so the emulated normals of the
// fixed-point mode map exactly like exact ones. The orientation is kept as given (the patch
// algorithm already turns the back sheet's normal toward the viewer).
Vec3 WorldNormalFromDeviceGradient(const FlatScene& scene, const Vec3& p, const Vec3& g);

}  // namespace quadrix::patch
