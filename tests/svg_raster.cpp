#include "svg_raster.h"

#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>

namespace quadrix::testing {

namespace {

double Attr(const std::string& element, const std::string& name, bool& ok) {
    const std::regex re("\\s" + name + "=\"([^\"]*)\"");
    std::smatch m;
    if (!std::regex_search(element, m, re)) {
        ok = false;
        return 0;
    }
    return std::strtod(m[1].str().c_str(), nullptr);
}

std::string AttrText(const std::string& element, const std::string& name) {
    const std::regex re("\\s" + name + "=\"([^\"]*)\"");
    std::smatch m;
    return std::regex_search(element, m, re) ? m[1].str() : std::string();
}

// SVG 1.1 F.6.5 (with F.6.6's scaling of radii that are too small).
SvgOp ArcOp(double x1, double y1, double rx, double ry, double phiDeg, bool large, bool sweep,
            double x2, double y2) {
    SvgOp op;
    op.kind = SvgOp::kArc;
    const double phi = phiDeg * M_PI / 180, c = std::cos(phi), s = std::sin(phi);
    rx = std::fabs(rx);
    ry = std::fabs(ry);
    const double dx = (x1 - x2) / 2, dy = (y1 - y2) / 2;
    const double x1p = c * dx + s * dy, y1p = -s * dx + c * dy;
    const double lambda = x1p * x1p / (rx * rx) + y1p * y1p / (ry * ry);
    if (lambda > 1) {
        rx *= std::sqrt(lambda);
        ry *= std::sqrt(lambda);
    }
    const double num =
        std::fmax(0.0, rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p);
    const double den = rx * rx * y1p * y1p + ry * ry * x1p * x1p;
    double k = den > 0 ? std::sqrt(num / den) : 0;
    if (large == sweep) k = -k;
    const double cxp = k * rx * y1p / ry, cyp = -k * ry * x1p / rx;
    op.cx = c * cxp - s * cyp + (x1 + x2) / 2;
    op.cy = s * cxp + c * cyp + (y1 + y2) / 2;
    auto angle = [](double ux, double uy, double vx, double vy) {
        return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    };
    op.theta1 = angle(1, 0, (x1p - cxp) / rx, (y1p - cyp) / ry);
    double dt = angle((x1p - cxp) / rx, (y1p - cyp) / ry, (-x1p - cxp) / rx, (-y1p - cyp) / ry);
    if (!sweep && dt > 0) dt -= 2 * M_PI;
    if (sweep && dt < 0) dt += 2 * M_PI;
    op.dtheta = dt;
    op.rx = rx;
    op.ry = ry;
    op.phi = phi;
    op.p[0] = {x2, y2};
    return op;
}

bool ParsePath(const std::string& d, std::vector<SvgOp>& ops) {
    std::istringstream in(d);
    std::string cmd;
    SvgPoint cur;
    auto num = [&](double& v) { return static_cast<bool>(in >> v); };
    while (in >> cmd) {
        if (cmd == "M" || cmd == "L") {
            SvgOp op;
            op.kind = cmd == "M" ? SvgOp::kMove : SvgOp::kLine;
            if (!num(op.p[0].x) || !num(op.p[0].y)) return false;
            cur = op.p[0];
            ops.push_back(op);
        } else if (cmd == "C") {
            SvgOp op;
            op.kind = SvgOp::kCubic;
            for (SvgPoint& p : op.p)
                if (!num(p.x) || !num(p.y)) return false;
            cur = op.p[2];
            ops.push_back(op);
        } else if (cmd == "Q") {
            // Degree elevation (exact): controls p0 + 2/3 (q − p0) and p1 + 2/3 (q − p1).
            SvgPoint q, e;
            if (!num(q.x) || !num(q.y) || !num(e.x) || !num(e.y)) return false;
            SvgOp op;
            op.kind = SvgOp::kCubic;
            op.p[0] = {cur.x + 2 * (q.x - cur.x) / 3, cur.y + 2 * (q.y - cur.y) / 3};
            op.p[1] = {e.x + 2 * (q.x - e.x) / 3, e.y + 2 * (q.y - e.y) / 3};
            op.p[2] = e;
            cur = e;
            ops.push_back(op);
        } else if (cmd == "A") {
            double rx, ry, rot, large, sweep, x, y;
            if (!num(rx) || !num(ry) || !num(rot) || !num(large) || !num(sweep) || !num(x) ||
                !num(y))
                return false;
            ops.push_back(ArcOp(cur.x, cur.y, rx, ry, rot, large != 0, sweep != 0, x, y));
            cur = {x, y};
        } else {
            return false;
        }
    }
    return true;
}

}  // namespace

SvgDrawing ReadSvgDrawing(const std::string& svg) {
    SvgDrawing out;
    std::smatch m;
    if (std::regex_search(svg, m, std::regex(R"re(viewBox="0 0 ([^ ]+) ([^"]+)")re"))) {
        out.width = std::stod(m[1]);
        out.height = std::stod(m[2]);
    } else {
        out.errors.push_back("no viewBox");
    }
    const std::regex width(R"re(\.(\w+) \{ stroke-width: ([0-9.e+-]+);)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), width);
         it != std::sregex_iterator(); ++it)
        out.strokeWidth[(*it)[1]] = std::stod((*it)[2]);
    // Elements in document order, with the group they are in.
    const std::regex element(R"re(<(g|/g|ellipse|path|line)\b[^>]*>)re");
    std::string group;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), element);
         it != std::sregex_iterator(); ++it) {
        const std::string e = (*it)[0], tag = (*it)[1];
        if (tag == "g") {
            group = AttrText(e, "id");
            continue;
        }
        if (tag == "/g") {
            group.clear();
            continue;
        }
        SvgShape s;
        s.group = group;
        s.cls = AttrText(e, "class");
        bool ok = true;
        if (tag == "ellipse") {
            const double cx = Attr(e, "cx", ok), cy = Attr(e, "cy", ok);
            SvgOp arc;
            arc.kind = SvgOp::kArc;
            arc.cx = cx;
            arc.cy = cy;
            arc.rx = Attr(e, "rx", ok);
            arc.ry = Attr(e, "ry", ok);
            const std::string tr = AttrText(e, "transform");
            std::smatch r;
            if (std::regex_search(tr, r, std::regex(R"re(rotate\(([^ ]+) ([^ ]+) ([^)]+)\))re"))) {
                // rotate(a cx cy) about the ellipse's own centre: the axes turn by a.
                if (std::stod(r[2]) != cx || std::stod(r[3]) != cy)
                    out.errors.push_back("ellipse rotated about another point: " + e);
                arc.phi = std::stod(r[1]) * M_PI / 180;
            } else if (!tr.empty()) {
                out.errors.push_back("unknown transform: " + e);
            }
            arc.theta1 = 0;
            arc.dtheta = 2 * M_PI;
            SvgOp move;
            move.kind = SvgOp::kMove;
            move.p[0] = {cx + arc.rx * std::cos(arc.phi), cy + arc.rx * std::sin(arc.phi)};
            s.ops = {move, arc};
        } else if (tag == "path") {
            ok = ParsePath(AttrText(e, "d"), s.ops);
        } else {
            SvgOp a, b;
            a.kind = SvgOp::kMove;
            b.kind = SvgOp::kLine;
            a.p[0] = {Attr(e, "x1", ok), Attr(e, "y1", ok)};
            b.p[0] = {Attr(e, "x2", ok), Attr(e, "y2", ok)};
            s.ops = {a, b};
        }
        if (!ok) {
            out.errors.push_back("cannot read " + e);
            continue;
        }
        out.shapes.push_back(std::move(s));
    }
    return out;
}

void AppendToCairo(cairo_t* cr, const SvgShape& shape) {
    for (const SvgOp& op : shape.ops) {
        switch (op.kind) {
            case SvgOp::kMove:
                cairo_move_to(cr, op.p[0].x, op.p[0].y);
                break;
            case SvgOp::kLine:
                cairo_line_to(cr, op.p[0].x, op.p[0].y);
                break;
            case SvgOp::kCubic:
                cairo_curve_to(cr, op.p[0].x, op.p[0].y, op.p[1].x, op.p[1].y, op.p[2].x,
                               op.p[2].y);
                break;
            case SvgOp::kArc: {
                cairo_matrix_t saved;
                cairo_get_matrix(cr, &saved);
                cairo_translate(cr, op.cx, op.cy);
                cairo_rotate(cr, op.phi);
                cairo_scale(cr, op.rx, op.ry);
                if (op.dtheta >= 0)
                    cairo_arc(cr, 0, 0, 1, op.theta1, op.theta1 + op.dtheta);
                else
                    cairo_arc_negative(cr, 0, 0, 1, op.theta1, op.theta1 + op.dtheta);
                cairo_set_matrix(cr, &saved);
                break;
            }
        }
    }
}

std::vector<std::vector<SvgPoint>> FlattenShape(const SvgShape& shape, double tolerance) {
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t* cr = cairo_create(surface);
    cairo_set_tolerance(cr, tolerance);
    AppendToCairo(cr, shape);
    cairo_path_t* path = cairo_copy_path_flat(cr);
    std::vector<std::vector<SvgPoint>> out;
    for (int i = 0; i < path->num_data; i += path->data[i].header.length) {
        const cairo_path_data_t* d = &path->data[i];
        if (d->header.type == CAIRO_PATH_MOVE_TO) out.emplace_back();
        if (d->header.type == CAIRO_PATH_MOVE_TO || d->header.type == CAIRO_PATH_LINE_TO) {
            if (out.empty()) out.emplace_back();
            out.back().push_back({d[1].point.x, d[1].point.y});
        }
    }
    cairo_path_destroy(path);
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
    return out;
}

std::vector<double> RasteriseSelected(const SvgDrawing& d, int width, int height,
                                      const std::vector<const SvgShape*>& shapes) {
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_A8, width, height);
    cairo_t* cr = cairo_create(surface);
    // The viewBox mapped onto the image (the identity when they have the same size).
    if (d.width > 0 && d.height > 0) cairo_scale(cr, width / d.width, height / d.height);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_source_rgba(cr, 0, 0, 0, 1);
    for (const SvgShape* s : shapes) {
        const auto w = d.strokeWidth.find(s->cls);
        cairo_set_line_width(cr, w == d.strokeWidth.end() ? 1.0 : w->second);
        cairo_new_path(cr);
        AppendToCairo(cr, *s);
        cairo_stroke(cr);
    }
    cairo_surface_flush(surface);
    std::vector<double> alpha(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i)
            alpha[static_cast<std::size_t>(j * width + i)] = data[j * stride + i] / 255.0;
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
    return alpha;
}

}  // namespace quadrix::testing
