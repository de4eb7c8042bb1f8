// OpenSCAD polygonal solids; the constructions are derived in polygon_solids.h.
#include "quadrix/import/openscad/polygon_solids.h"

#include <algorithm>
#include <cmath>

#include "quadrix/import/shapes/mesh_solid.h"

namespace quadrix::import::scad {

namespace {

ShapeHalfSpace PlaneHs(double a, double b, double c, double d) {
    ShapeHalfSpace h;
    h.isPlane = true;
    h.plane = Plane{a, b, c, d};
    return h;
}

// x² + y² − (α z + β)² scaled by `sign` (−1: the complement).
ShapeHalfSpace RadialQuadric(double alpha, double beta, double sign) {
    Mat4 q = Mat4::Zero();
    q.m[0][0] = q.m[1][1] = sign;
    q.m[2][2] = -sign * alpha * alpha;
    q.m[2][3] = q.m[3][2] = -sign * alpha * beta;
    q.m[3][3] = -sign * beta * beta;
    ShapeHalfSpace h;
    h.isPlane = false;
    h.quadric = Quadric::FromMatrix(q);
    return h;
}

struct Edge {
    Pt2 a, b;  // a.y < b.y
};

}  // namespace

int Fragments(double r, const Specials& s) {
    if (r < 1e-5) return 3;
    // Clamped before the conversion: $fn = 1e80 (or a huge r / $fs) is far past any polygon
    // (kMaxPolygonSides) and must not overflow the int (fuzz_openscad finding).
    constexpr double kMaxFragments = 1e9;
    if (s.fn > 0) return std::max(static_cast<int>(std::min(s.fn, kMaxFragments)), 3);
    const double fa = s.fa > 0 ? s.fa : 12, fs = s.fs > 0 ? s.fs : 2;
    const double n = std::ceil(std::max(std::min(360.0 / fa, r * 2 * M_PI / fs), 5.0));
    return static_cast<int>(std::min(n, kMaxFragments));
}

std::optional<int> PolygonSides(double r, const Specials& s) {
    const bool asked = s.fn > 0 || s.fa != 12 || s.fs != 2;
    const int n = Fragments(r, s);
    if (!asked || n > kMaxPolygonSides) return std::nullopt;
    return n;
}

Ring RegularPolygon(double r, int n) {
    Ring ring;
    for (int i = 0; i < n; ++i) {
        double sn = 0, cs = 1;
        SinCosDegrees(360.0 * i / n, sn, cs);
        ring.push_back({r * cs, r * sn});
    }
    return ring;
}

std::vector<Trapezoid> Trapezoids(const std::vector<Ring>& rings) {
    std::vector<Edge> edges;
    std::vector<double> ys;
    for (const Ring& ring : rings)
        for (std::size_t i = 0; i < ring.size(); ++i) {
            Pt2 a = ring[i], b = ring[(i + 1) % ring.size()];
            ys.push_back(a.y);
            if (a.y == b.y) continue;  // horizontal edges bound no slab interior
            if (a.y > b.y) std::swap(a, b);
            edges.push_back({a, b});
        }
    // Crossings of edges (self-intersecting or overlapping outlines) become slab cuts too.
    for (std::size_t i = 0; i < edges.size(); ++i)
        for (std::size_t j = i + 1; j < edges.size(); ++j) {
            const Edge &e = edges[i], &f = edges[j];
            const double dx1 = e.b.x - e.a.x, dy1 = e.b.y - e.a.y;
            const double dx2 = f.b.x - f.a.x, dy2 = f.b.y - f.a.y;
            const double den = dx1 * dy2 - dy1 * dx2;
            if (den == 0) continue;
            const double t = ((f.a.x - e.a.x) * dy2 - (f.a.y - e.a.y) * dx2) / den;
            const double u = ((f.a.x - e.a.x) * dy1 - (f.a.y - e.a.y) * dx1) / den;
            if (t > 0 && t < 1 && u > 0 && u < 1) ys.push_back(e.a.y + t * dy1);
        }
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    std::vector<Trapezoid> out;
    for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
        const double y0 = ys[k], y1 = ys[k + 1], ym = 0.5 * (y0 + y1);
        // (x at the middle, p, q) of each edge spanning the slab.
        std::vector<std::array<double, 3>> span;
        for (const Edge& e : edges) {
            if (e.a.y > y0 || e.b.y < y1) continue;
            const double q = (e.b.x - e.a.x) / (e.b.y - e.a.y);
            const double p = e.a.x - q * e.a.y;
            span.push_back({p + q * ym, p, q});
        }
        std::sort(span.begin(), span.end());
        for (std::size_t i = 0; i + 1 < span.size(); i += 2)
            out.push_back({y0, y1, span[i][1], span[i][2], span[i + 1][1], span[i + 1][2]});
    }
    return out;
}

Shape PolygonalCylinder(double r1, double r2, double z0, double h, int n) {
    Shape s;
    const Ring bottom = RegularPolygon(r1, n), top = RegularPolygon(r2, n);
    ShapeBody body;
    body.push_back(PlaneHs(0, 0, -1, z0));        // z >= z0
    body.push_back(PlaneHs(0, 0, 1, -(z0 + h)));  // z <= z0 + h
    const double rmax = std::max(r1, r2);
    const Ring& wide = r1 >= r2 ? bottom : top;
    for (int i = 0; i < n; ++i) {
        // The side through edge i: its outward normal in the xy plane is the edge's bisector
        // direction; it leans with the change of radius (a frustum of similar polygons).
        const Pt2 a = wide[i], b = wide[(i + 1) % n];
        double nx = 0.5 * (a.x + b.x), ny = 0.5 * (a.y + b.y);
        const double apothem = std::hypot(nx, ny);  // distance of edge i from the axis at rmax
        nx /= apothem, ny /= apothem;
        // Points of the side: apothem·(r/rmax) at height z: n·x = apothem (r1 + (r2−r1) t)/rmax.
        const double k = apothem / rmax;
        const double slope = k * (r2 - r1) / h;  // d(n·x)/dz
        // n·x − slope (z − z0) − k r1 <= 0
        body.push_back(PlaneHs(nx, ny, -slope, slope * z0 - k * r1));
    }
    s.bodies.push_back(std::move(body));
    for (const Pt2& p : bottom) s.extent.push_back({{p.x, p.y, z0}, {}, {}, {}});
    for (const Pt2& p : top) s.extent.push_back({{p.x, p.y, z0 + h}, {}, {}, {}});
    return s;
}

std::optional<Shape> PolygonalSphere(double r, int n) {
    // OpenSCAD's sphere: (n + 1) / 2 rings at polar angles 180°(i + ½)/rings, each an n-gon.
    const int rings = (n + 1) / 2;
    std::vector<Vec3> v;
    for (int i = 0; i < rings; ++i) {
        double sp = 0, cp = 1;
        SinCosDegrees(180.0 * (i + 0.5) / rings, sp, cp);
        for (const Pt2& p : RegularPolygon(r * sp, n)) v.push_back({p.x, p.y, r * cp});
    }
    std::vector<std::vector<int>> faces;
    std::vector<int> cap0, cap1;
    for (int j = 0; j < n; ++j) cap0.push_back(j), cap1.push_back((rings - 1) * n + j);
    faces.push_back(cap0);
    faces.push_back(cap1);
    for (int i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < n; ++j) {
            const int j1 = (j + 1) % n;
            faces.push_back({i * n + j, (i + 1) * n + j, (i + 1) * n + j1, i * n + j1});
        }
    MeshSolid m = MeshToSolid(v, faces);
    if (!m.ok) return std::nullopt;
    return std::move(m.shape);
}

Shape LinearExtrude(const std::vector<Ring>& rings, double z0, double h, double scale) {
    Shape s;
    // σ(z) = kz·z + m0 (polygon_solids.h); every constant term c becomes c·σ(z).
    const double kz = (scale - 1) / h, m0 = 1 - kz * z0;
    auto plane = [&](double a, double b, double c) { return PlaneHs(a, b, c * kz, c * m0); };
    for (const Trapezoid& t : Trapezoids(rings)) {
        ShapeBody body;
        body.push_back(plane(0, -1, t.y0));           // y >= y0
        body.push_back(plane(0, 1, -t.y1));           // y <= y1
        body.push_back(plane(-1, t.ql, t.pl));        // x >= pl + ql y
        body.push_back(plane(1, -t.qr, -t.pr));       // x <= pr + qr y
        body.push_back(PlaneHs(0, 0, -1, z0));        // z >= z0
        body.push_back(PlaneHs(0, 0, 1, -(z0 + h)));  // z <= z0 + h
        s.bodies.push_back(std::move(body));
    }
    for (const Ring& ring : rings)
        for (const Pt2& p : ring) {
            s.extent.push_back({{p.x, p.y, z0}, {}, {}, {}});
            s.extent.push_back({{p.x * scale, p.y * scale, z0 + h}, {}, {}, {}});
        }
    return s;
}

std::optional<Shape> RotateExtrude(const std::vector<Ring>& rings, const Specials& specials,
                                   std::string* problem) {
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    for (const Ring& ring : rings)
        for (const Pt2& p : ring) {
            xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
            ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
        }
    if (!(xmax > xmin)) {
        if (problem) *problem = "the profile has no area";
        return std::nullopt;
    }
    std::vector<Ring> profile = rings;
    if (xmax <= 0) {  // all in x <= 0: OpenSCAD revolves the mirror image, the same solid
        for (Ring& ring : profile)
            for (Pt2& p : ring) p.x = -p.x;
        std::swap(xmin, xmax);
        xmin = -xmin, xmax = -xmax;
    } else if (xmin < 0) {
        if (problem)
            *problem =
                "the profile crosses the axis (points on both sides of x = 0), which "
                "OpenSCAD refuses too";
        return std::nullopt;
    }
    Shape s;
    if (const std::optional<int> n = PolygonSides(xmax, specials)) {
        // n wedges between the vertex angles θ_i = 180° + 360°·i/n; in wedge i the faces are
        // u = c·L(z) and u = c·M(z), u the coordinate along the wedge's bisector
        // (polygon_solids.h).
        double sh = 0, c = 1;
        SinCosDegrees(180.0 / *n, sh, c);
        for (const Trapezoid& t : Trapezoids(profile))
            for (int i = 0; i < *n; ++i) {
                double sa = 0, ca = 1, sb = 0, cb = 1, sm = 0, cm = 1;
                SinCosDegrees(180.0 + 360.0 * i / *n, sa, ca);
                SinCosDegrees(180.0 + 360.0 * (i + 1) / *n, sb, cb);
                SinCosDegrees(180.0 + 360.0 * (i + 0.5) / *n, sm, cm);
                ShapeBody body;
                body.push_back(PlaneHs(0, 0, -1, t.y0));                // z >= y0
                body.push_back(PlaneHs(0, 0, 1, -t.y1));                // z <= y1
                body.push_back(PlaneHs(sa, -ca, 0, 0));                 // counter-clockwise of θ_i
                body.push_back(PlaneHs(-sb, cb, 0, 0));                 // clockwise of θ_i+1
                body.push_back(PlaneHs(cm, sm, -c * t.qr, -c * t.pr));  // u <= c·L(z)
                if (t.pl != 0 || t.ql != 0)
                    body.push_back(PlaneHs(-cm, -sm, c * t.ql, c * t.pl));  // u >= c·M(z)
                s.bodies.push_back(std::move(body));
            }
        for (double z : {ymin, ymax})
            s.extent.push_back({{0, 0, z}, {xmax, 0, 0}, {0, xmax, 0}, {}});
        return s;
    }
    for (const Trapezoid& t : Trapezoids(profile)) {
        ShapeBody body;
        body.push_back(PlaneHs(0, 0, -1, t.y0));       // z >= y0
        body.push_back(PlaneHs(0, 0, 1, -t.y1));       // z <= y1
        body.push_back(RadialQuadric(t.qr, t.pr, 1));  // r <= L(z) = pr + qr z
        if (t.pl != 0 || t.ql != 0) body.push_back(RadialQuadric(t.ql, t.pl, -1));  // r >= M(z)
        s.bodies.push_back(std::move(body));
    }
    for (double z : {ymin, ymax}) s.extent.push_back({{0, 0, z}, {xmax, 0, 0}, {0, xmax, 0}, {}});
    return s;
}

}  // namespace quadrix::import::scad
