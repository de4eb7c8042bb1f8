#include "quadrix/draw/svg_writer.h"

#include <fmt/format.h>

#include <cmath>

#include "quadrix/io/writers.h"

namespace quadrix::draw {

namespace {

std::string Escape(const std::string& s) {
    std::string out;
    for (char ch : s) {
        switch (ch) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += ch;
        }
    }
    return out;
}

std::string Num(double v) { return fmt::format("{:.17g}", v == 0 ? 0.0 : v); }

void ArcPath(const Stroke& s, std::string& out) {
    const EllipseAxes ax = AxesOf(s.U, s.V);
    const double rot = ax.rotation * 180 / M_PI;
    const double span = s.a1 - s.a0;
    const int n = span > 0.9 * M_PI ? static_cast<int>(std::ceil(span / (2 * M_PI / 3))) : 1;
    const Point2 p0 = s.ArcPoint(s.a0);
    out += fmt::format("M {} {}", Num(p0.x), Num(p0.y));
    for (int i = 1; i <= n; ++i) {
        const double t = i == n ? s.a1 : s.a0 + span * i / n;
        const Point2 p = s.ArcPoint(t);
        out += fmt::format(" A {} {} {} 0 {} {} {}", Num(ax.rx), Num(ax.ry), Num(rot),
                           ax.positive ? 1 : 0, Num(p.x), Num(p.y));
    }
}

// A parabolic arc is a quadratic polynomial: exactly one quadratic Bézier, whose control point
// is where the end tangents meet, P(a0) + (a1 − a0)/2 · P'(a0).
void ParabolaPath(const Stroke& s, std::string& out) {
    const Point2 p0 = s.ArcPoint(s.a0), p1 = s.ArcPoint(s.a1), d0 = s.ArcTangent(s.a0);
    const double h = 0.5 * (s.a1 - s.a0);
    out += fmt::format("M {} {} Q {} {} {} {}", Num(p0.x), Num(p0.y), Num(p0.x + h * d0.x),
                       Num(p0.y + h * d0.y), Num(p1.x), Num(p1.y));
}

void CubicsPath(const std::vector<Point2>& p, std::string& out) {
    out += fmt::format("M {} {}", Num(p[0].x), Num(p[0].y));
    for (std::size_t i = 1; i + 2 < p.size(); i += 3)
        out += fmt::format(" C {} {} {} {} {} {}", Num(p[i].x), Num(p[i].y), Num(p[i + 1].x),
                           Num(p[i + 1].y), Num(p[i + 2].x), Num(p[i + 2].y));
}

void StrokeElement(const Stroke& s, const char* cls, double tolerance, std::string& out) {
    if (s.kind == StrokeKind::kEllipseArc && s.a1 - s.a0 >= 2 * M_PI * (1 - 1e-12)) {
        const EllipseAxes ax = AxesOf(s.U, s.V);
        out += fmt::format(
            "<ellipse class=\"{}\" cx=\"{}\" cy=\"{}\" rx=\"{}\" ry=\"{}\" "
            "transform=\"rotate({} {} {})\"/>\n",
            cls, Num(s.c.x), Num(s.c.y), Num(ax.rx), Num(ax.ry), Num(ax.rotation * 180 / M_PI),
            Num(s.c.x), Num(s.c.y));
        return;
    }
    std::string d;
    if (s.kind == StrokeKind::kEllipseArc) {
        ArcPath(s, d);
    } else if (s.kind == StrokeKind::kParabolaArc) {
        ParabolaPath(s, d);
    } else if (s.kind == StrokeKind::kHyperbolaArc) {
        CubicsPath(ConicToCubics(s, tolerance), d);
    } else {
        for (std::size_t i = 0; i < s.points.size(); ++i)
            d += fmt::format("{}{} {}", i == 0 ? "M " : " L ", Num(s.points[i].x),
                             Num(s.points[i].y));
    }
    if (d.empty()) return;
    out += fmt::format("<path class=\"{}\" d=\"{}\"/>\n", cls, d);
}

}  // namespace

EllipseAxes AxesOf(const Point2& U, const Point2& V) {
    // M = [[U.x V.x] [U.y V.y]] = R(φ) diag(s1, s2) R(θ) (Blinn's closed-form 2×2 SVD).
    const double m00 = U.x, m01 = V.x, m10 = U.y, m11 = V.y;
    const double e = 0.5 * (m00 + m11), f = 0.5 * (m00 - m11);
    const double g = 0.5 * (m10 + m01), h = 0.5 * (m10 - m01);
    const double q = std::hypot(e, h), r = std::hypot(f, g);
    const double a1 = std::atan2(g, f), a2 = std::atan2(h, e);
    EllipseAxes ax;
    ax.rx = q + r;
    ax.ry = std::fabs(q - r);
    ax.rotation = 0.5 * (a2 + a1);
    ax.positive = m00 * m11 - m01 * m10 > 0;
    return ax;
}

std::string SvgDocument(const Page& page) {
    const LineStyle& st = page.style;
    const std::string u = page.unit == "mm" ? "mm" : "";
    std::string out;
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}{}\" height=\"{}{}\" "
        "viewBox=\"0 0 {} {}\">\n",
        Num(page.width), u, Num(page.height), u, Num(page.width), Num(page.height));
    if (!page.title.empty()) out += fmt::format("<title>{}</title>\n", Escape(page.title));
    out += "<style>\n";
    out +=
        "  path, ellipse, line { fill: none; stroke: black; stroke-linecap: round; "
        "stroke-linejoin: round; }\n";
    out += fmt::format("  .silhouette {{ stroke-width: {}; }}\n", Num(st.silhouette));
    out += fmt::format("  .edge {{ stroke-width: {}; }}\n", Num(st.edge));
    out += fmt::format("  .tangent {{ stroke-width: {}; }}\n", Num(st.tangent));
    out += fmt::format("  .hidden {{ stroke-width: {}; stroke-dasharray: {} {}; stroke: #444; }}\n",
                       Num(st.hidden), Num(st.dash), Num(st.gap));
    out += fmt::format("  .frame {{ stroke-width: {}; }}\n", Num(st.frame));
    out += "  text { font-family: sans-serif; fill: black; }\n";
    out += "</style>\n";
    out += fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"white\"/>\n", Num(page.width),
                       Num(page.height));
    out += "<g id=\"hidden\">\n";
    for (const Stroke& s : page.strokes)
        if (!s.visible) StrokeElement(s, "hidden", page.tolerance, out);
    out += "</g>\n<g id=\"edges\">\n";
    for (const Stroke& s : page.strokes)
        if (s.visible && s.role == CurveRole::kEdge)
            StrokeElement(s, s.tangent ? "tangent" : "edge", page.tolerance, out);
    out += "</g>\n<g id=\"silhouettes\">\n";
    for (const Stroke& s : page.strokes)
        if (s.visible && s.role == CurveRole::kSilhouette)
            StrokeElement(s, "silhouette", page.tolerance, out);
    out += "</g>\n";
    if (!page.frameLines.empty() || !page.texts.empty()) {
        out += "<g id=\"sheet\">\n";
        for (const PageLine& l : page.frameLines)
            out += fmt::format("<line class=\"frame\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>\n",
                               Num(l.a.x), Num(l.a.y), Num(l.b.x), Num(l.b.y));
        for (const PageText& t : page.texts)
            out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\">{}</text>\n", Num(t.x),
                               Num(t.y), Num(t.size), Escape(t.text));
        out += "</g>\n";
    }
    out += "</svg>\n";
    return out;
}

std::string WriteSvg(const std::string& path, const Page& page) {
    return WriteFileAtomically(path, SvgDocument(page));
}

}  // namespace quadrix::draw
