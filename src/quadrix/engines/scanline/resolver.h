// The Resolver of engine `scanline` (seed 001 chapter 4): per body an i-line table, i-vertices,
// show-faces and show-edges, in device space (DESIGN.md: x column, y row, rays along +z).
//
// Design (what is the paper's and what is ours):
//  - HSBs: the body's literals, complemented ones negated, so every HSB is "value <= 0 inside".
//  - Show-faces (§4.3): one per opaque plane that is not edge-on (zero test (1)), front and back
//    sheets per opaque quadric that is not a cylinder along the view axis (zero test (2)).
//  - I-line table (§4.2, §4.3): lower-triangular, i-line(i, j) for i > j is the intersection of
//    HSB_i and HSB_j, i-line(k, k) the limb of HSB_k. Types POINT, LINEAR, CONIC, EDGE, NOEXIST as
//    in the paper, plus QUARTIC for two quadrics whose surfaces may meet (the paper's "future
//    work"; see below). A limb of a quadric with C = 0 but z-dependent (a paraboloid or cone with
//    one ruling along the view) is the LINEAR i-line F x + E y + J = 0 where its one root runs to
//    infinity.
//  - I-vertices (§4.5.8–4.5.12): ISECT (three planes; plane–plane–quadric), LIMB (plane ∩ limb
//    plane ∩ quadric, and EDGE lines ∩ limb conic), HEXTRM and VEXTRM, inserted in the left/right
//    (CONIC) or single (LINEAR, EDGE) list by the insert line (4.22) on ascending y. Coincident
//    i-vertices merge (zero test (5)); a tangent touch creates none (zero test (3)).
//  - Show-edges (§4.4): consecutive i-vertices of a list (plus the window rows 0 and H, since the
//    device image is the scene box here) bound a piece of one leg. A piece becomes a show-edge when
//    its midpoint satisfies every HSI whose crossings with the i-line were computed in closed form
//    (zero test (4), conservative). This replaces the paper's bottom/top walking rule, which relies
//    on exact ISECT/LIMB typing; testing the midpoint keeps every piece that can bound a face, so
//    the renderer's breakpoints are a superset of the true face boundaries. The zero test accepts
//    a midpoint lying ON a third HSB's surface, which happens along whole pieces where three or
//    more HSBs share a line (every bisecting plane of a tube at a mitred joint of several tubes
//    contains the joint's normal line); there a WEDGE TEST keeps the piece only when its two
//    surfaces bound the body's local wedge (no third surface through the point cuts the cone of
//    their two boundary rays, linearised at the midpoint). Without it such pieces toggled faces
//    that do not change sides (4388 face-test corrections on the gallery's triangles at 512²).
//    Face pointers follow the table of §4.4 (normal z of the quadric at the midpoint, existence
//    of the limb).
//  - Two quadrics in one body: when the pencil test below proves their surfaces disjoint (the
//    tube: coaxial cylinders), the i-line is NOEXIST; otherwise it is QUARTIC and the body is
//    marked perPixel: the renderer evaluates it exactly at every pixel of its spans (documented
//    refusal, issue 3 item 4). Crossings of conic i-lines with a *second* quadric are not computed
//    (quartic); such pieces are kept unfiltered against that quadric (still a superset).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "quadrix/engines/scanline/coefficients.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/plane_or_quadric.h"

namespace quadrix::scanline {

enum class ILineType : std::uint8_t { kNoExist, kPoint, kLinear, kConic, kEdge, kQuartic };
enum class IVertexType : std::uint8_t { kHextrm, kVextrm, kLimb, kIsect };
enum class Sheet : std::uint8_t { kPlane, kFront, kBack };

const char* ToString(ILineType t);
const char* ToString(IVertexType t);

// The surface (PlaneOrQuadric) is oriented: the complement is applied.
struct Hsb : PlaneOrQuadric {
    int halfSpace = -1;
    bool opaque = true;
    bool edgeOn = false;        // plane perpendicular to the view plane (zero test (1))
    bool viewCylinder = false;  // quadric independent of z (zero test (2))
    int face[2] = {-1, -1};     // show-faces: plane → face[0]; quadric → front, back

    bool Satisfied(const Vec3& p, double pointError) const {
        return isPlane ? SatisfiesPlane(plane, p, pointError)
                       : SatisfiesQuadric(quadric, p, pointError);
    }
};

struct ShowFace {
    int body = -1;
    int hsb = -1;        // index in its body's HSB list
    int halfSpace = -1;  // FlatScene index
    Sheet sheet = Sheet::kPlane;
};

struct IVertex {
    IVertexType type = IVertexType::kIsect;
    double x = 0, y = 0, z = 0;
};

struct ILine {
    ILineType type = ILineType::kNoExist;
    int i = -1, j = -1;  // HSB indices; i == j for a limb
    bool limb = false;
    bool conicShape =
        false;  // shape is `conic` (CONIC); otherwise `line` (LINEAR, EDGE, limb line)
    Line2 line;
    Conic2 conic;
    Line2 insert;                   // (4.22) for CONIC
    std::vector<IVertex> lists[2];  // CONIC: left (insert < 0), right; LINEAR/EDGE: lists[0]
    bool filteredByAllHsbs = true;  // false when crossings with some quadric were not computed
};

// A show-edge: a piece of one leg of an i-line, single-valued in x and y, y in [yBottom, yTop].
struct ShowEdge {
    int body = -1;
    int iline = -1;  // index in the body's table
    bool conic = false;
    Line2 line;    // linear: x = −(b y + c)/a
    Conic2 shape;  // conic: root of (4.17) on the side `leg` of the insert line
    int leg = -1;  // −1: 2 a x + c y + d <= 0 (left when a > 0), +1 the other side
    double yBottom = 0, yTop = 0;
    int faces[2] = {-1, -1};  // global show-face indices (−1 = none)
    // A HORIZONTAL edge (a LINEAR i-line along a row: x = −(b y + c)/a is undefined): it is
    // crossed by no row centre, so it never enters the AEL; it only links its two end vertices
    // for pass one's recursion (§5.4). Its ends are (xBottom, yBottom) and (xTop, yTop).
    bool horizontal = false;
    double xBottom = 0, xTop = 0;

    // x of the edge at row y (NaN when the leg does not exist there).
    double XAt(double y) const;
};

struct ResolverCounters {
    std::uint64_t planarHsbs = 0, quadricHsbs = 0;
    std::uint64_t ilines[6] = {0, 0, 0, 0, 0, 0};  // by ILineType
    std::uint64_t verticesCalculated = 0, verticesKept = 0;
    std::uint64_t verticesByType[4] = {0, 0, 0, 0};  // kept, by IVertexType
    std::uint64_t piecesTested = 0;
    std::uint64_t edgesLinear = 0, edgesConic = 0;
    std::uint64_t edgesHorizontal = 0;  // ShowEdge::horizontal (not in edgesLinear)
    std::uint64_t faces = 0;
    std::uint64_t perPixelBodies = 0;
};

struct ResolvedBody {
    int body = -1;
    std::vector<Hsb> hsbs;
    std::vector<ILine> table;  // n × n, row-major; entries (i, j) with i >= j are used
    bool perPixel = false;     // QUARTIC i-line or invalid literal: rendered per pixel
    std::string reason;
    const ILine& At(int i, int j) const {
        return table[static_cast<std::size_t>(i) * hsbs.size() + static_cast<std::size_t>(j)];
    }
};

// Resolves one body: builds its HSBs, show-faces (appended to `faces`), i-line table, i-vertices
// and show-edges (appended to `edges`) for rows y in [yLo, yHi]. With `allBoundaries` (operands
// of CSG solids) i-lines and limbs are made for transparent HSBs too, since there every interval
// endpoint matters, not only the visible ones.
void ResolveBody(const FlatScene& scene, int body, double yLo, double yHi, bool allBoundaries,
                 ResolvedBody& out, std::vector<ShowFace>& faces, std::vector<ShowEdge>& edges,
                 ResolverCounters& counters);

// Pencil test: true when the surfaces q1 = 0 and q2 = 0 provably have no common point, i.e. some
// M = q2 − λ q1 has M(x, 1) < 0 for all x or > 0 for all x (then q2 has one sign on q1 = 0).
bool QuadricSurfacesDisjoint(const Quadric& q1, const Quadric& q2);

}  // namespace quadrix::scanline
