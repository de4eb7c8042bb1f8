// The SVG writer's elliptical arcs (svg_writer.h), checked the way an SVG renderer reads them:
// each `A` command is converted back to its centre and angles with the endpoint-to-centre
// conversion of the SVG specification (SVG 1.1 Appendix F.6.5), and must give the stroke's
// ellipse: the same centre, and the midpoint of every command on the stroke's arc (so the
// large-arc and sweep flags are right too).
#include "quadrix/draw/svg_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <regex>

namespace quadrix::draw {
namespace {

struct Centre {
    double cx, cy, theta1, dtheta;
};

// SVG 1.1 F.6.5, with rx, ry as written (they are exact, so no scaling-up is needed).
Centre EndpointToCentre(double x1, double y1, double x2, double y2, double rx, double ry,
                        double phiDeg, bool large, bool sweep) {
    const double phi = phiDeg * M_PI / 180, c = std::cos(phi), s = std::sin(phi);
    const double dx = (x1 - x2) / 2, dy = (y1 - y2) / 2;
    const double x1p = c * dx + s * dy, y1p = -s * dx + c * dy;
    double num = rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p;
    num = std::fmax(num, 0.0);
    double k = std::sqrt(num / (rx * rx * y1p * y1p + ry * ry * x1p * x1p));
    if (large == sweep) k = -k;
    const double cxp = k * rx * y1p / ry, cyp = -k * ry * x1p / rx;
    Centre out;
    out.cx = c * cxp - s * cyp + (x1 + x2) / 2;
    out.cy = s * cxp + c * cyp + (y1 + y2) / 2;
    auto angle = [](double ux, double uy, double vx, double vy) {
        return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    };
    out.theta1 = angle(1, 0, (x1p - cxp) / rx, (y1p - cyp) / ry);
    double dt = angle((x1p - cxp) / rx, (y1p - cyp) / ry, (-x1p - cxp) / rx, (-y1p - cyp) / ry);
    if (!sweep && dt > 0) dt -= 2 * M_PI;
    if (sweep && dt < 0) dt += 2 * M_PI;
    out.dtheta = dt;
    return out;
}

TEST(SvgWriter, ArcsReadBackAsTheStrokesEllipse) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-50, 50), a(0, 2 * M_PI), span(0.05, 2 * M_PI - 0.05);
    for (int trial = 0; trial < 200; ++trial) {
        Stroke s;
        s.kind = StrokeKind::kEllipseArc;
        s.c = {200 + u(rng), 150 + u(rng)};
        s.U = {u(rng), u(rng)};
        s.V = {u(rng), u(rng)};
        const double det = s.U.x * s.V.y - s.U.y * s.V.x;
        if (std::fabs(det) < 100) continue;  // nearly flat ellipses are segments, not arcs
        s.a0 = a(rng);
        s.a1 = s.a0 + span(rng);
        Page page;
        page.width = 400;
        page.height = 300;
        page.strokes = {s};
        const std::string svg = SvgDocument(page);
        const std::regex move(R"(d="M ([-0-9.e]+) ([-0-9.e]+))");
        std::smatch m;
        ASSERT_TRUE(std::regex_search(svg, m, move));
        double x = std::stod(m[1]), y = std::stod(m[2]);
        const std::regex arc(
            R"(A ([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+) 0 ([01]) ([-0-9.e]+) ([-0-9.e]+))");
        const auto begin = std::sregex_iterator(svg.begin(), svg.end(), arc);
        const int n = static_cast<int>(std::distance(begin, std::sregex_iterator()));
        ASSERT_GE(n, 1);
        int i = 0;
        for (auto it = begin; it != std::sregex_iterator(); ++it, ++i) {
            const double rx = std::stod((*it)[1]), ry = std::stod((*it)[2]);
            const double rot = std::stod((*it)[3]);
            const bool sweep = (*it)[4] == "1";
            const double x2 = std::stod((*it)[5]), y2 = std::stod((*it)[6]);
            const Centre c = EndpointToCentre(x, y, x2, y2, rx, ry, rot, false, sweep);
            const double scale = std::hypot(rx, ry);
            EXPECT_NEAR(c.cx, s.c.x, 1e-7 * scale);
            EXPECT_NEAR(c.cy, s.c.y, 1e-7 * scale);
            // The command's midpoint is the stroke's point halfway through this command.
            const double tm = c.theta1 + c.dtheta / 2, phi = rot * M_PI / 180;
            const double mx =
                c.cx + rx * std::cos(tm) * std::cos(phi) - ry * std::sin(tm) * std::sin(phi);
            const double my =
                c.cy + rx * std::cos(tm) * std::sin(phi) + ry * std::sin(tm) * std::cos(phi);
            const double t0 = s.a0 + (s.a1 - s.a0) * i / n, t1 = s.a0 + (s.a1 - s.a0) * (i + 1) / n;
            const Point2 want = s.ArcPoint(0.5 * (t0 + t1));
            EXPECT_NEAR(mx, want.x, 1e-6 * scale) << trial;
            EXPECT_NEAR(my, want.y, 1e-6 * scale) << trial;
            x = x2;
            y = y2;
        }
    }
}

}  // namespace
}  // namespace quadrix::draw
