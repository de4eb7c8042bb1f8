// Polygon meshes of freeform surfaces at a given tolerance, and their scan conversion: the
// polygonal baseline of seed 002 §1 (item 5 of issue 6) and the dense reference render used to
// look for holes.
//
// Each Bézier patch is sampled on a uniform nu × nv grid and split into triangles. The grid comes
// from the bound of Filip, Magedson & Markot ("Surface algorithms using bounds on derivatives",
// CAGD 3, 1986) on the distance between a C² surface and its piecewise-linear interpolant over
// cells of size hu × hv:
//     ε ≤ (hu² M_uu + 2 hu hv M_uv + hv² M_vv) / 8,   M_xy = sup |∂²S/∂x∂y|,
// and since 2 hu hv ≤ hu² + hv², choosing hu² (M_uu + M_uv) ≤ 4ε and hv² (M_vv + M_uv) ≤ 4ε
// guarantees the tolerance ε. For a polynomial patch the suprema are bounded by the second
// differences of the control net (p(p−1) max |Δ²_u P|, p q max |Δ_u Δ_v P|, ...); for a rational
// patch they are estimated from finite differences on a 9×9 grid, times 1.5.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

struct PolygonMesh {
    std::vector<Vec3> vertices;  // world
    std::vector<std::array<std::uint32_t, 3>> triangles;
    int patches = 0;
};

// Grid size (nu, nv) for one patch at tolerance `tolerance` (world), each at most `maxCells`.
std::pair<int, int> GridForTolerance(const freeform::BezierSurface& patch, double tolerance,
                                     int maxCells = 2048);

PolygonMesh MeshForTolerance(const freeform::Surface& surface, double tolerance);

// Scan conversion of triangles in device space (pixel centres, top-left fill rule, so triangles
// sharing an edge never both take a pixel on it). Counts per pixel how many triangles drew it.
class TriangleCoverage {
  public:
    TriangleCoverage(int width, int height);
    void Add(const PolygonMesh& mesh, const Projection& projection);
    const std::vector<std::uint16_t>& Counts() const { return count_; }
    long long PixelsDrawn() const { return pixelsDrawn_; }
    long long Triangles() const { return triangles_; }

  private:
    void Triangle(const Vec3& a, const Vec3& b, const Vec3& c);
    int width_, height_;
    std::vector<std::uint16_t> count_;
    long long pixelsDrawn_ = 0, triangles_ = 0;
};

}  // namespace quadrix::isocurve
