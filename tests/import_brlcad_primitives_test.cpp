// BRL-CAD primitives → half-spaces, checked against the primitives' own definitions
// (FORMAT.md §6.1) at random points: inside the BRL-CAD solid ⇔ inside the converted shape.
// Points within a small margin of the analytic boundary are skipped (the two computations round
// differently there), so every comparison is a strict one.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "quadrix/import/brlcad/primitives.h"

namespace quadrix::import::brlcad {
namespace {

// Signed "inside margin" of the analytic definition: > 0 inside, < 0 outside, in roughly
// millimetres; |margin| < kSkip counts as on the boundary.
using Analytic = std::function<double(const Vec3&)>;
constexpr double kSkip = 1e-3;

struct Case {
    std::string label;
    Primitive prim;
    Analytic margin;
    Box3 sampleBox;
};

// A random rotation (as three orthonormal columns) from a seeded generator.
void Frame(std::mt19937& rng, Vec3& e1, Vec3& e2, Vec3& e3) {
    std::normal_distribution<double> n(0, 1);
    e1 = Normalize(Vec3{n(rng), n(rng), n(rng)});
    Vec3 t = Normalize(Vec3{n(rng), n(rng), n(rng)});
    e2 = Normalize(Cross(e1, t));
    e3 = Cross(e1, e2);
}

// Counts agreements over `samples` random points; returns the number of points compared.
int Compare(const Case& c, int samples, std::mt19937& rng) {
    ConvertResult r = ConvertPrimitive(c.prim);
    EXPECT_EQ(r.status, ConvertResult::Status::kOk) << c.label << ": " << r.problem;
    if (r.status != ConvertResult::Status::kOk) return 0;
    std::uniform_real_distribution<double> u(0, 1);
    int compared = 0, inside = 0;
    for (int i = 0; i < samples; ++i) {
        Vec3 p;
        for (int k = 0; k < 3; ++k)
            p[k] = c.sampleBox.lo[k] + u(rng) * (c.sampleBox.hi[k] - c.sampleBox.lo[k]);
        double m = c.margin(p);
        if (std::fabs(m) < kSkip) continue;
        ++compared;
        bool want = m > 0;
        inside += want;
        EXPECT_EQ(ShapeContains(r.shape, p), want)
            << c.label << " at (" << p.x << " " << p.y << " " << p.z << "), margin " << m;
        if (::testing::Test::HasFailure()) return compared;
    }
    // The sample box is chosen so that both outcomes occur (at least 1 % each).
    EXPECT_GT(inside, compared / 100) << c.label;
    EXPECT_LT(inside, compared - compared / 100) << c.label;
    return compared;
}

Box3 Around(const Vec3& c, double r) { return {c - Vec3{r, r, r}, c + Vec3{r, r, r}}; }

TEST(ImportBrlcadPrimitives, EllipsoidMatchesDefinition) {
    std::mt19937 rng(1);
    Vec3 e1, e2, e3;
    Frame(rng, e1, e2, e3);
    Primitive p;
    p.type = "ell";
    p.V = {10, -5, 3};
    p.A = e1 * 7, p.B = e2 * 3, p.C = e3 * 1.5;
    Analytic m = [&](const Vec3& x) {
        Vec3 d = x - p.V;
        double s = 0;
        for (const Vec3* a : {&p.A, &p.B, &p.C}) {
            double t = Dot(d, *a) / Dot(*a, *a);
            s += t * t;
        }
        return 1 - s;
    };
    EXPECT_GT(Compare({"ell", p, m, Around(p.V, 8)}, 4000, rng), 3000);
}

// tgc forms: rcc, rec, trc, tec, a cone to a point, an oblique quadric tgc.
TEST(ImportBrlcadPrimitives, TgcFormsMatchDefinition) {
    std::mt19937 rng(2);
    struct Form {
        const char* label;
        double a, b, k;  // |A|, |B|, ratio |C|/|A| = |D|/|B|
        double shear;    // H tilted by this much along A (oblique)
    };
    const Form forms[] = {{"rcc", 2, 2, 1, 0},          {"rec", 3, 1.5, 1, 0},
                          {"trc", 2, 2, 0.4, 0},        {"tec", 3, 1.5, 0.5, 0},
                          {"cone", 2, 2, 0, 0},         {"inverted", 1, 1, 2.5, 0},
                          {"oblique", 2.5, 1, 0.6, 1.5}};
    for (const Form& f : forms) {
        Vec3 e1, e2, e3;
        Frame(rng, e1, e2, e3);
        Primitive p;
        p.type = "tgc";
        p.V = {1, 2, 3};
        p.A = e1 * f.a, p.B = e2 * f.b;
        p.C = p.A * f.k, p.D = p.B * f.k;
        p.H = e3 * 5 + e1 * f.shear;
        // Cross-section at height s (planes parallel to A, B): an ellipse centred at V + sH with
        // semi-axes |A| + s(|C| - |A|) and |B| + s(|D| - |B|).
        Analytic m = [p, f, e1, e2, e3](const Vec3& x) {
            Vec3 d = x - p.V;
            double s = Dot(d, e3) / Dot(p.H, e3);
            if (s < 0) return s * 5;
            if (s > 1) return (1 - s) * 5;
            Vec3 q = d - p.H * s;
            double ra = f.a * (1 + s * (f.k - 1)), rb = f.b * (1 + s * (f.k - 1));
            double u = Dot(q, e1) / ra, v = Dot(q, e2) / rb;
            double ell = ra > 0 ? 1 - std::sqrt(u * u + v * v) : -1;
            return std::min({ell * std::min(ra, rb), s * 5, (1 - s) * 5});
        };
        Compare({f.label, p, m, Around(p.V + p.H * 0.5, 4)}, 3000, rng);
    }
}

// The quartics in random frames: tor, eto and the general (non-similar) tgc, oblique included.
TEST(ImportBrlcadPrimitives, QuarticsMatchTheirDefinitions) {
    std::mt19937 rng(20);
    for (int trial = 0; trial < 4; ++trial) {
        Vec3 e1, e2, e3;
        Frame(rng, e1, e2, e3);
        const Vec3 v{3.0 * trial, -2, 1};
        {
            Primitive p;
            p.type = "tor";
            p.V = v, p.H = e3 * 3, p.r1 = 4, p.r2 = 1.5;
            Analytic m = [=](const Vec3& x) {
                const Vec3 d = x - v;
                const double z = Dot(d, e3), rho = Length(d - e3 * z);
                return 1.5 - std::hypot(rho - 4, z);
            };
            Compare({"tor", p, m, Around(v, 6)}, 3000, rng);
        }
        {
            // Meridian ellipse tilted in the (radius, axis) plane: C = 2·(cos 30°, sin 30°).
            const double cr = 2 * std::cos(0.5236), cz = 2 * std::sin(0.5236), rd = 0.8;
            Primitive p;
            p.type = "eto";
            p.V = v, p.N = e3, p.r = 5, p.C = e1 * cr + e3 * cz, p.rd = rd;
            Analytic m = [=](const Vec3& x) {
                const Vec3 d = x - v;
                const double z = Dot(d, e3), rho = Length(d - e3 * z);
                const double a = rho - 5;  // meridian coordinates about the ellipse's centre
                const double u = (a * cr + z * cz) / 2, w = (-a * cz + z * cr) / 2;
                return (1 - std::hypot(u / 2, w / rd)) * rd;
            };
            Compare({"eto", p, m, Around(v, 8)}, 3000, rng);
        }
        {
            // Semi-axes 2 → 0.5 along A and 1 → 1.5 along B; H oblique.
            Primitive p;
            p.type = "tgc";
            p.V = v, p.H = e3 * 4 + e1 * 1.0, p.A = e1 * 2, p.B = e2 * 1, p.C = e1 * 0.5,
            p.D = e2 * 1.5;
            ConvertResult r = ConvertPrimitive(p);
            EXPECT_EQ(r.censusName, "tgc (quartic)");
            Analytic m = [=](const Vec3& x) {
                const Vec3 d = x - v;
                const double s = Dot(d, e3) / 4;
                if (s < 0) return s * 4;
                if (s > 1) return (1 - s) * 4;
                const Vec3 q = d - p.H * s;
                const double ra = 2 - 1.5 * s, rb = 1 + 0.5 * s;
                const double u = Dot(q, e1) / ra, w = Dot(q, e2) / rb;
                return std::min({(1 - std::hypot(u, w)) * std::min(ra, rb), s * 4, (1 - s) * 4});
            };
            Compare({"tgc (quartic)", p, m, Around(v + p.H * 0.5, 4)}, 3000, rng);
        }
    }
}

// arb8 degeneracies as arb8 records with repeated vertices, against analytic membership and the
// analytic volume (estimated on a grid of 40³ cells: the error is O(surface/cell count), well
// under the 3 % allowed).
TEST(ImportBrlcadPrimitives, Arb8DegeneraciesMatchDefinitionAndVolume) {
    struct ArbCase {
        const char* label;
        std::array<Vec3, 8> pts;
        Analytic margin;
        double volume;
    };
    const Vec3 o{0, 0, 0}, x{4, 0, 0}, xy{4, 3, 0}, y{0, 3, 0};
    const Vec3 oz{0, 0, 2}, xz{4, 0, 2}, xyz{4, 3, 2}, yz{0, 3, 2};
    std::vector<ArbCase> cases = {
        {"box",
         {o, x, xy, y, oz, xz, xyz, yz},
         [](const Vec3& p) {
             return std::min({p.x, 4 - p.x, p.y, 3 - p.y, p.z, 2 - p.z});
         },
         24},
        // arb6-style wedge: the top edge along y at x = 0 (vertices 5=8 and 6=7 repeated).
        {"wedge",
         {o, x, xy, y, oz, oz + Vec3{0, 0, 0}, yz, yz},
         [](const Vec3& p) {
             // 0 <= y <= 3, z >= 0, x >= 0, x/4 + z/2 <= 1
             double slant = (1 - p.x / 4 - p.z / 2) / std::sqrt(1.0 / 16 + 1.0 / 4);
             return std::min({p.y, 3 - p.y, p.z, p.x, slant});
         },
         12},
        // arb5 pyramid: apex above the centre of the base (vertices 5..8 equal).
        {"pyramid",
         {o, x, xy, y, {2, 1.5, 2}, {2, 1.5, 2}, {2, 1.5, 2}, {2, 1.5, 2}},
         [](const Vec3& p) {
             // faces through the apex: x >= z, 4 - x >= z, y >= 0.75 z, 3 - y >= 0.75 z
             return std::min({p.z, (p.x - p.z) / std::sqrt(2.0), (4 - p.x - p.z) / std::sqrt(2.0),
                              (p.y - 0.75 * p.z) / 1.25, (3 - p.y - 0.75 * p.z) / 1.25});
         },
         8},
        // arb4 tetrahedron as arb8: 1 2 3 1 4 4 4 4.
        {"tetrahedron",
         {o, x, y, o, oz, oz, oz, oz},
         [](const Vec3& p) {
             double slant =
                 (1 - p.x / 4 - p.y / 3 - p.z / 2) / std::sqrt(1.0 / 16 + 1.0 / 9 + 1.0 / 4);
             return std::min({p.x, p.y, p.z, slant});
         },
         4},
    };
    std::mt19937 rng(3);
    for (const ArbCase& c : cases) {
        Primitive p;
        p.type = "arb8";
        p.pts = c.pts;
        Compare({c.label, p, c.margin, {{-1, -1, -1}, {5, 4, 3}}}, 3000, rng);
        ConvertResult r = ConvertPrimitive(p);
        ASSERT_EQ(r.status, ConvertResult::Status::kOk) << c.label;
        const int n = 40;
        int in = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                for (int k = 0; k < n; ++k)
                    in += ShapeContains(
                        r.shape, {4.0 * (i + 0.5) / n, 3.0 * (j + 0.5) / n, 2.0 * (k + 0.5) / n});
        double volume = 24.0 * in / (n * n * n);
        EXPECT_NEAR(volume, c.volume, 0.03 * c.volume) << c.label;
    }
}

TEST(ImportBrlcadPrimitives, HalfRpcRhcEpaEhyHypPart) {
    std::mt19937 rng(4);
    Vec3 e1, e2, e3;
    Frame(rng, e1, e2, e3);
    const Vec3 v{2, -1, 4};
    {
        Primitive p;
        p.type = "half";
        p.N = e1;
        p.d = 3;
        Compare({"half", p, [&](const Vec3& x) { return 3 - Dot(e1, x); }, Around(e1 * 3, 4)}, 2000,
                rng);
    }
    // rpc/rhc: b along B̂ = e1 (|B| = 3), y along Ĥ×B̂ (= e3 × e1 = e2), h along Ĥ = e3 (|H| = 4).
    const double lb = 3, lh = 4, r = 2, c = 1.5;
    {
        Primitive p;
        p.type = "rpc";
        p.V = v, p.H = e3 * lh, p.B = e1 * lb, p.r = r;
        Analytic m = [&](const Vec3& x) {
            Vec3 d = x - v;
            double b = Dot(d, e1), y = Dot(d, e2), h = Dot(d, e3);
            double para = r * std::sqrt(std::max(0.0, 1 - b / lb)) - std::fabs(y);
            if (b > lb) para = lb - b;
            return std::min({b, h, lh - h, para});
        };
        Compare({"rpc", p, m, Around(v + e3 * 2 + e1 * 1.5, 4)}, 3000, rng);
    }
    {
        Primitive p;
        p.type = "rhc";
        p.V = v, p.H = e3 * lh, p.B = e1 * lb, p.r = r, p.c = c;
        // Hyperbola in (b, y): centre at b0 = |B| + c, real semi-axis c along -b̂, passing through
        // (0, ±r): ((b0 - b)/c)² - (y/w)² = 1 with w = r / sqrt((b0/c)² - 1).
        Analytic m = [&](const Vec3& x) {
            Vec3 d = x - v;
            double b = Dot(d, e1), y = Dot(d, e2), h = Dot(d, e3);
            double b0 = lb + c, w = r / std::sqrt((b0 / c) * (b0 / c) - 1);
            double t = (b0 - b) / c;
            double hyp = b < lb ? w * std::sqrt(t * t - 1) - std::fabs(y) : lb - b;
            return std::min({b, h, lh - h, hyp});
        };
        Compare({"rhc", p, m, Around(v + e3 * 2 + e1 * 1.5, 4)}, 3000, rng);
    }
    // epa/ehy: A along e1 (r1 = 3), r2 = 2 along Ĥ×Â = e3×e1 = e2, H = 5 e3.
    const double r1 = 3, r2 = 2, lh2 = 5;
    {
        Primitive p;
        p.type = "epa";
        p.V = v, p.H = e3 * lh2, p.A = e1, p.r1 = r1, p.r2 = r2;
        Analytic m = [&](const Vec3& x) {
            Vec3 d = x - v;
            double a = Dot(d, e1) / r1, b = Dot(d, e2) / r2, h = Dot(d, e3) / lh2;
            if (h > 1) return 1 - h;
            return std::min(h * lh2, (std::sqrt(std::max(0.0, 1 - h)) - std::hypot(a, b)) * r2);
        };
        Compare({"epa", p, m, Around(v + e3 * 2.5, 4)}, 3000, rng);
    }
    {
        Primitive p;
        p.type = "ehy";
        p.V = v, p.H = e3 * lh2, p.A = e1, p.r1 = r1, p.r2 = r2, p.c = c;
        // Along the axis z ∈ [0, |H|]: the section is the base ellipse scaled by
        // s(z) = sqrt(((z0 - z)/c)² - 1) / sqrt((z0/c)² - 1), z0 = |H| + c.
        Analytic m = [&](const Vec3& x) {
            Vec3 d = x - v;
            double z = Dot(d, e3);
            if (z > lh2) return lh2 - z;
            double z0 = lh2 + c, t = (z0 - z) / c;
            double s = std::sqrt(std::max(0.0, t * t - 1)) / std::sqrt((z0 / c) * (z0 / c) - 1);
            double a = Dot(d, e1) / r1, b = Dot(d, e2) / r2;
            return std::min(z, (s - std::hypot(a, b)) * r2);
        };
        Compare({"ehy", p, m, Around(v + e3 * 2.5, 4)}, 3000, rng);
    }
    {
        // hyp: end semi-axes |A| = 3 (e1) and b = 2 (Ĥ×Â = e2), H = 6 e3, neck ratio 0.5.
        Primitive p;
        p.type = "hyp";
        p.V = v, p.H = e3 * 6, p.A = e1 * 3, p.b = 2, p.bnr = 0.5;
        Analytic m = [&](const Vec3& x) {
            Vec3 d = x - (v + e3 * 3);
            double z = Dot(d, e3) / 3;  // -1 .. 1 between the ends
            if (std::fabs(z) > 1) return (1 - std::fabs(z)) * 3;
            // Section scale relative to the neck: sqrt(1 + z² (1/bnr² - 1)).
            double s = 0.5 * std::sqrt(1 + z * z * 3);
            double a = Dot(d, e1) / 3, b = Dot(d, e2) / 2;
            return std::min((1 - std::fabs(z)) * 3, (s - std::hypot(a, b)) * 2);
        };
        Compare({"hyp", p, m, Around(v + e3 * 3, 4)}, 3000, rng);
    }
    {
        // part: the union of balls centred on V + tH with radius r_v + t(r_h - r_v), t ∈ [0, 1]
        // (the convex hull of the two end balls).
        Primitive p;
        p.type = "part";
        p.V = v, p.H = e3 * 4, p.rv = 2, p.rh = 0.8;
        Analytic m = [&](const Vec3& x) {
            double best = -1e9;
            for (int i = 0; i <= 4000; ++i) {
                double t = i / 4000.0;
                best = std::max(best, p.rv + t * (p.rh - p.rv) - Length(x - (v + p.H * t)));
            }
            return best;
        };
        // The sampled t grid has error below 4 mm/4000 · (1 + slope) < 2e-3 > kSkip, so points
        // closer than 5e-3 to the surface are skipped here.
        std::uniform_real_distribution<double> u(0, 1);
        ConvertResult cr = ConvertPrimitive(p);
        ASSERT_EQ(cr.status, ConvertResult::Status::kOk);
        Box3 box = Around(v + e3 * 2, 4);
        for (int i = 0; i < 1500; ++i) {
            Vec3 x;
            for (int k = 0; k < 3; ++k) x[k] = box.lo[k] + u(rng) * (box.hi[k] - box.lo[k]);
            double mm = m(x);
            if (std::fabs(mm) < 5e-3) continue;
            EXPECT_EQ(ShapeContains(cr.shape, x), mm > 0)
                << "part at " << x.x << " " << x.y << " " << x.z;
        }
    }
}

TEST(ImportBrlcadPrimitives, ExtentIsExactUnderAffineMaps) {
    // An ellipsoid's box under a rotation+scale equals the analytic one: c ± sqrt(Σ a_i²).
    Primitive p;
    p.type = "ell";
    p.V = {1, 2, 3};
    p.A = {3, 0, 0}, p.B = {0, 2, 0}, p.C = {0, 0, 1};
    ConvertResult r = ConvertPrimitive(p);
    ASSERT_EQ(r.shape.extent.size(), 1u);
    Mat4 m = Mat4::Identity();
    m.m[0][0] = 0, m.m[0][1] = -1, m.m[1][0] = 1, m.m[1][1] = 0;  // 90° about z
    Box3 b = PieceBox(r.shape.extent[0], m);
    EXPECT_NEAR(b.lo.x, -2 - 2, 1e-12);
    EXPECT_NEAR(b.hi.y, 1 + 3, 1e-12);
    EXPECT_NEAR(b.hi.z, 3 + 1, 1e-12);
}

}  // namespace
}  // namespace quadrix::import::brlcad

namespace quadrix::import::brlcad {
namespace {

// A twisted arb (top face rotated against the bottom, as arb8_showcase's TwistedCubeNonPlanar):
// the intersection of its six face planes runs far past the vertices, so it is bounded by the
// vertices' box; a convex arb gets no extra planes.
TEST(ImportBrlcadPrimitives, ConcaveArbIsBoundedByItsVertices) {
    Primitive p;
    p.type = "arb8";
    p.pts = {Vec3{0, 0, 0},      Vec3{1, 0, 0},     Vec3{1, 1, 0},     Vec3{0, 1, 0},
             Vec3{0.5, -0.2, 1}, Vec3{1.2, 0.5, 1}, Vec3{0.5, 1.2, 1}, Vec3{-0.2, 0.5, 1}};
    ConvertResult r = ConvertPrimitive(p);
    ASSERT_EQ(r.status, ConvertResult::Status::kOk);
    ASSERT_EQ(r.shape.bodies.size(), 1u);
    EXPECT_EQ(r.shape.bodies[0].size(), 12u);  // 6 faces + 6 box planes
    EXPECT_FALSE(ShapeContains(r.shape, {0.5, 0.5, 1.5}));
    EXPECT_FALSE(ShapeContains(r.shape, {0.5, 0.5, -0.5}));
    EXPECT_TRUE(ShapeContains(r.shape, {0.5, 0.5, 0.5}));
    Primitive box = p;
    box.pts = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0},
               Vec3{0, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 1, 1}, Vec3{0, 1, 1}};
    EXPECT_EQ(ConvertPrimitive(box).shape.bodies[0].size(), 6u);
}

}  // namespace
}  // namespace quadrix::import::brlcad
