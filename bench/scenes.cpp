#include "scenes.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace quadrix::bench {

namespace {

struct V {
    double x, y, z;
};
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator*(V a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double Dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V Unit(V a) { return a * (1.0 / std::sqrt(Dot(a, a))); }

std::string Sphere(const std::string& id, V c, double r) {
    // (x-c)² - r² <= 0
    return fmt::format("quadric {} <1 1 1 0 0 0 {:.9g} {:.9g} {:.9g} {:.9g}>;\n", id, -c.x, -c.y,
                       -c.z, Dot(c, c) - r * r);
}

// Infinite cylinder of radius r about the line through p with direction d:
// |x-p|² - ((x-p)·d)² - r² <= 0, i.e. matrix M = I - d dᵀ, linear part -M p, constant pᵀMp - r².
std::string Cylinder(const std::string& id, V p, V d, double r) {
    d = Unit(d);
    double m[3][3];
    double dv[3] = {d.x, d.y, d.z}, pv[3] = {p.x, p.y, p.z};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = (i == j ? 1.0 : 0.0) - dv[i] * dv[j];
    double mp[3];
    for (int i = 0; i < 3; ++i) mp[i] = m[i][0] * pv[0] + m[i][1] * pv[1] + m[i][2] * pv[2];
    double k = pv[0] * mp[0] + pv[1] * mp[1] + pv[2] * mp[2] - r * r;
    return fmt::format(
        "quadric {} <{:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g}>;\n", id,
        m[0][0], m[1][1], m[2][2], m[0][1], m[1][2], m[0][2], -mp[0], -mp[1], -mp[2], k);
}

// Plane through q with outward normal n: n·(x-q) <= 0.
std::string Plane(const std::string& id, V q, V n) {
    return fmt::format("plane {} <{:.9g} {:.9g} {:.9g} {:.9g}>;\n", id, n.x, n.y, n.z, -Dot(n, q));
}

const char* kLights = "light fill .25;\nlight key .8 .5 .9 -1;\n";

}  // namespace

BenchScene SpheresMinusCylinder(int n, bool distributed) {
    BenchScene s;
    s.name = distributed ? fmt::format("spheres{}_distributed", n) : fmt::format("spheres{}", n);
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    // Radius so that the spheres fill about 60 % of the cube's volume in total: they overlap.
    double r = std::cbrt(0.6 * 8000.0 / (n * 4.18879));
    std::ostringstream out;
    out << fmt::format("{{ {} spheres of radius {:.4g} unioned, minus a cylinder (issue 8) }}\n", n,
                       r);
    for (int i = 0; i < n; ++i) {
        out << Sphere(fmt::format("q{}", i), {u(rng), u(rng), u(rng)}, r);
        out << fmt::format("body s{} (q{});\n", i, i);
    }
    out << Cylinder("cyl", {0, 0, 0}, {1, 0.2, 0}, 4.0);
    out << "plane cl <-1 0 0 -13>;\nplane cr <1 0 0 -13>;\nbody drill (cyl cl cr);\n";
    if (distributed) {
        out << "csg balls (";
        for (int i = 0; i < n; ++i)
            out << (i ? " | " : "") << "(s" << i << " - drill)" << ((i % 16 == 15) ? "\n" : "");
        out << ") =c .9 .75 .55;\n";
    } else {
        out << "csg balls ((";
        for (int i = 0; i < n; ++i)
            out << (i ? " | " : "") << "s" << i << ((i % 16 == 15) ? "\n" : "");
        out << ") - drill) =c .9 .75 .55;\n";
    }
    out << kLights << "view v dop .4 .5 -1;\n";
    s.text = out.str();
    s.primitives = n + 3;
    return s;
}

BenchScene TwoCylinders(char op) {
    BenchScene s;
    s.name = op == '|'   ? "two_cyl_union"
             : op == '&' ? "two_cyl_intersection"
                         : "two_cyl_difference";
    std::ostringstream out;
    out << "quadric qa <1 0 1 0 0 0 0 0 0 -4>;\nplane at <0 1 0 -4>;\nplane ab <0 -1 0 -4>;\n"
           "quadric qb <0 1 1 0 0 0 0 0 0 -2.25>;\nplane br <1 0 0 -4>;\nplane bl <-1 0 0 -4>;\n"
           "body ca (qa at ab);\nbody cb (qb br bl);\n";
    out << fmt::format("csg both (ca {} cb) =c .7 .8 1;\n", op) << kLights
        << "view v dop .5 .6 -1;\n";
    s.text = out.str();
    s.primitives = 6;
    return s;
}

BenchScene MiteredKnot(int segments) {
    BenchScene s;
    s.name = fmt::format("knot{}", segments);
    std::vector<V> p(segments);
    for (int i = 0; i < segments; ++i) {
        double t = 2 * M_PI * i / segments;
        p[i] = {std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t),
                -std::sin(3 * t)};
        p[i] = p[i] * 3.0;
    }
    const double r = 0.6;
    std::ostringstream out;
    out << fmt::format("{{ a trefoil of {} mitered pipes with spheres at the joints }}\n",
                       segments);
    for (int i = 0; i < segments; ++i) {
        V a = p[i], b = p[(i + 1) % segments];
        V prev = p[(i + segments - 1) % segments], next = p[(i + 2) % segments];
        V d = Unit(b - a);
        V nStart = Unit(Unit(a - prev) + d);  // bisector at a: this pipe lies on its + side
        V nEnd = Unit(d + Unit(next - b));    // bisector at b: this pipe lies on its − side
        out << Cylinder(fmt::format("c{}", i), a, d, r);
        out << Plane(fmt::format("ps{}", i), a, nStart * -1.0);
        out << Plane(fmt::format("pe{}", i), b, nEnd);
        out << fmt::format("body pipe{} (c{} ps{} pe{}) =c .85 .6 .4;\n", i, i, i, i);
        out << Sphere(fmt::format("j{}", i), a, r * 1.25);
        out << fmt::format("body joint{} (j{}) =c .5 .6 .9;\n", i, i);
    }
    out << kLights << "view v dop .2 .3 -1;\n";
    s.text = out.str();
    s.primitives = segments * 4;
    return s;
}

BenchScene SumOfProductsExplosion(int pairs) {
    BenchScene s;
    s.name = fmt::format("sop{}", pairs);
    std::ostringstream out;
    out << fmt::format(
        "{{ A - B1&C1 - B2&C2 - ... with {} pairs: 2^{} products in sum-of-products "
        "form }}\n",
        pairs, pairs);
    out << "quadric big <1 1 1 0 0 0 0 0 0 -100>;\nbody A (big);\n";
    for (int i = 0; i < pairs; ++i) {
        double a = 2 * M_PI * i / pairs;
        V c = {8 * std::cos(a), 8 * std::sin(a), -6};
        out << Sphere(fmt::format("bq{}", i), c, 3.0);
        out << Sphere(fmt::format("cq{}", i), c + V{0.8, 0.8, -1.0}, 2.6);
        out << fmt::format("body B{} (bq{});\nbody C{} (cq{});\n", i, i, i, i);
    }
    out << "csg explode (A";
    for (int i = 0; i < pairs; ++i) out << fmt::format(" - (B{} & C{})", i, i);
    out << ") =c .8 .8 .7;\n" << kLights << "view v dop .1 .15 -1;\n";
    s.text = out.str();
    s.primitives = 1 + 2 * pairs;
    return s;
}

BenchScene FromFile(const std::string& name, const std::string& path) {
    BenchScene s;
    s.name = name;
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    s.text = ss.str();
    // Primitive count: statements starting with plane, quadric or solid (one primitive of the
    // language's library: a torus, a box, …); approximate for files (a word in a comment counts).
    std::istringstream lines(s.text);
    std::string word;
    while (lines >> word) s.primitives += word == "plane" || word == "quadric" || word == "solid";
    return s;
}

}  // namespace quadrix::bench
