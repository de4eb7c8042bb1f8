#include "quadrix/engines/isocurve/polygon_mesh.h"

#include <algorithm>
#include <cmath>

#include "quadrix/freeform/power_form.h"

namespace quadrix::isocurve {

using freeform::BezierSurface;

namespace {

Vec3 EuclideanPoint(const BezierSurface& p, double u, double v) {
    double out[4] = {0, 0, 0, 1};
    p.Evaluate(u, v, out);
    return p.Dim() == 4 ? Vec3{out[0] / out[3], out[1] / out[3], out[2] / out[3]}
                        : Vec3{out[0], out[1], out[2]};
}

Vec3 Cp(const BezierSurface& p, int i, int j) {
    const double* c = p.Point(i, j);
    return {c[0], c[1], c[2]};
}

// Second-derivative bounds (M_uu, M_uv, M_vv) with respect to the patch's own parameters.
std::array<double, 3> SecondDerivativeBounds(const BezierSurface& p) {
    int m = p.DegreeU(), n = p.DegreeV();
    double du = p.U1() - p.U0(), dv = p.V1() - p.V0();
    std::array<double, 3> b{0, 0, 0};
    if (p.Dim() == 3) {
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i + 2 <= m; ++i)
                b[0] = std::max(b[0], Length(Cp(p, i + 2, j) - 2 * Cp(p, i + 1, j) + Cp(p, i, j)));
        for (int j = 0; j + 1 <= n; ++j)
            for (int i = 0; i + 1 <= m; ++i)
                b[1] = std::max(b[1], Length(Cp(p, i + 1, j + 1) - Cp(p, i + 1, j) -
                                             Cp(p, i, j + 1) + Cp(p, i, j)));
        for (int j = 0; j + 2 <= n; ++j)
            for (int i = 0; i <= m; ++i)
                b[2] = std::max(b[2], Length(Cp(p, i, j + 2) - 2 * Cp(p, i, j + 1) + Cp(p, i, j)));
        b[0] *= m * (m - 1) / (du * du);
        b[1] *= m * n / (du * dv);
        b[2] *= n * (n - 1) / (dv * dv);
        return b;
    }
    // Rational: central differences on a 9×9 grid of interior points, with a 1.5 margin.
    double hu = 1e-3 * du, hv = 1e-3 * dv;
    for (int j = 0; j <= 8; ++j)
        for (int i = 0; i <= 8; ++i) {
            double u = p.U0() + du * (0.01 + 0.98 * i / 8), v = p.V0() + dv * (0.01 + 0.98 * j / 8);
            Vec3 c = EuclideanPoint(p, u, v);
            Vec3 suu = (EuclideanPoint(p, u + hu, v) - 2 * c + EuclideanPoint(p, u - hu, v)) *
                       (1 / (hu * hu));
            Vec3 svv = (EuclideanPoint(p, u, v + hv) - 2 * c + EuclideanPoint(p, u, v - hv)) *
                       (1 / (hv * hv));
            Vec3 suv = (EuclideanPoint(p, u + hu, v + hv) - EuclideanPoint(p, u + hu, v - hv) -
                        EuclideanPoint(p, u - hu, v + hv) + EuclideanPoint(p, u - hu, v - hv)) *
                       (1 / (4 * hu * hv));
            b[0] = std::max(b[0], 1.5 * Length(suu));
            b[1] = std::max(b[1], 1.5 * Length(suv));
            b[2] = std::max(b[2], 1.5 * Length(svv));
        }
    return b;
}

}  // namespace

std::pair<int, int> GridForTolerance(const BezierSurface& patch, double tolerance, int maxCells) {
    auto b = SecondDerivativeBounds(patch);
    double du = patch.U1() - patch.U0(), dv = patch.V1() - patch.V0();
    // hu = du / nu with hu² (M_uu + M_uv) <= 4 ε.
    auto cells = [&](double m, double extent) {
        if (!(m > 0)) return 1;
        double n = std::ceil(extent * std::sqrt(m / (4 * tolerance)));
        return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(maxCells)));
    };
    return {cells(b[0] + b[1], du), cells(b[2] + b[1], dv)};
}

PolygonMesh MeshForTolerance(const freeform::Surface& surface, double tolerance) {
    PolygonMesh mesh;
    for (const BezierSurface& p : surface.Patches().Patches()) {
        const auto [nu, nv] = GridForTolerance(p, tolerance);
        const int columns = nu + 1;  // a lambda may not capture a structured binding (clang 14)
        std::uint32_t base = static_cast<std::uint32_t>(mesh.vertices.size());
        for (int j = 0; j <= nv; ++j) {
            // One isocurve per grid row, evaluated along u in power form (dense reference meshes
            // have many vertices).
            freeform::PowerForm row(p.IsoCurveAtV(p.V0() + (p.V1() - p.V0()) * j / nv));
            for (int i = 0; i <= nu; ++i) {
                double c[4] = {0, 0, 0, 1};
                row.Evaluate(p.U0() + (p.U1() - p.U0()) * i / nu, c);
                mesh.vertices.push_back(p.Dim() == 4 ? Vec3{c[0] / c[3], c[1] / c[3], c[2] / c[3]}
                                                     : Vec3{c[0], c[1], c[2]});
            }
        }
        auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * columns + i); };
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        ++mesh.patches;
    }
    return mesh;
}

TriangleCoverage::TriangleCoverage(int width, int height)
    : width_(width), height_(height), count_(static_cast<std::size_t>(width) * height, 0) {}

void TriangleCoverage::Add(const PolygonMesh& mesh, const Projection& projection) {
    const Mat4& m = projection.deviceFromWorld.Matrix();
    std::vector<Vec3> device;
    std::vector<bool> ok;
    for (const Vec3& v : mesh.vertices) {
        Vec4 h = m * Vec4(v, 1.0);
        ok.push_back(h.w > 0);
        device.push_back(h.w > 0 ? Dehomogenize(h) : Vec3{});
    }
    for (const auto& t : mesh.triangles) {
        if (!ok[t[0]] || !ok[t[1]] || !ok[t[2]]) continue;
        Triangle(device[t[0]], device[t[1]], device[t[2]]);
    }
}

void TriangleCoverage::Triangle(const Vec3& a0, const Vec3& b0, const Vec3& c0) {
    ++triangles_;
    Vec3 a = a0, b = b0, c = c0;
    double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0) return;  // seen edge-on: no pixel centre strictly inside
    if (area < 0) std::swap(b, c);
    int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
    int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
    int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
    // Edge function of p against edge (p0 → p1), positive inside for the orientation chosen.
    // Top-left rule (y grows downward): a pixel centre exactly on an edge belongs to the
    // triangle when the edge is a "top" edge (horizontal, interior below) or a "left" edge.
    auto edge = [](const Vec3& p0, const Vec3& p1, double x, double y) {
        return (p1.x - p0.x) * (y - p0.y) - (p1.y - p0.y) * (x - p0.x);
    };
    auto topLeft = [](const Vec3& p0, const Vec3& p1) {
        double dx = p1.x - p0.x, dy = p1.y - p0.y;
        return (dy == 0 && dx > 0) || dy < 0;
    };
    bool tl[3] = {topLeft(a, b), topLeft(b, c), topLeft(c, a)};
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            double px = x + 0.5, py = y + 0.5;
            double e[3] = {edge(a, b, px, py), edge(b, c, px, py), edge(c, a, px, py)};
            bool inside = true;
            for (int k = 0; k < 3 && inside; ++k) inside = e[k] > 0 || (e[k] == 0 && tl[k]);
            if (!inside) continue;
            std::uint16_t& n = count_[static_cast<std::size_t>(y) * width_ + x];
            if (n < UINT16_MAX) ++n;
            ++pixelsDrawn_;
        }
}

}  // namespace quadrix::isocurve
