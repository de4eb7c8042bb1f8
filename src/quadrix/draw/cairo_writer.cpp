#include "quadrix/draw/cairo_writer.h"

#include <cairo-pdf.h>
#include <cairo-ps.h>
#include <cairo.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace quadrix::draw {

namespace {

void StrokePath(cairo_t* cr, const Stroke& s, double tolerance) {
    cairo_new_path(cr);
    if (s.kind == StrokeKind::kParabolaArc) {
        // The exact quadratic Bézier (svg_writer.cpp), raised to a cubic (exact too).
        const Point2 p0 = s.ArcPoint(s.a0), p1 = s.ArcPoint(s.a1), d0 = s.ArcTangent(s.a0);
        const double h = 0.5 * (s.a1 - s.a0);
        const Point2 q{p0.x + h * d0.x, p0.y + h * d0.y};
        cairo_move_to(cr, p0.x, p0.y);
        cairo_curve_to(cr, p0.x + 2 * (q.x - p0.x) / 3, p0.y + 2 * (q.y - p0.y) / 3,
                       p1.x + 2 * (q.x - p1.x) / 3, p1.y + 2 * (q.y - p1.y) / 3, p1.x, p1.y);
    } else if (s.kind == StrokeKind::kHyperbolaArc) {
        const std::vector<Point2> p = ConicToCubics(s, tolerance);
        cairo_move_to(cr, p[0].x, p[0].y);
        for (std::size_t i = 1; i + 2 < p.size(); i += 3)
            cairo_curve_to(cr, p[i].x, p[i].y, p[i + 1].x, p[i + 1].y, p[i + 2].x, p[i + 2].y);
    } else if (s.kind == StrokeKind::kEllipseArc) {
        cairo_save(cr);
        cairo_matrix_t m;
        cairo_matrix_init(&m, s.U.x, s.U.y, s.V.x, s.V.y, s.c.x, s.c.y);
        cairo_transform(cr, &m);
        // cairo_arc runs toward increasing angle in user space, i.e. increasing θ here.
        cairo_arc(cr, 0, 0, 1, s.a0, s.a1);
        cairo_restore(cr);
    } else {
        for (std::size_t i = 0; i < s.points.size(); ++i) {
            if (i == 0)
                cairo_move_to(cr, s.points[i].x, s.points[i].y);
            else
                cairo_line_to(cr, s.points[i].x, s.points[i].y);
        }
    }
}

void Paint(cairo_t* cr, const Page& page, bool visibleOnly) {
    const LineStyle& st = page.style;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_tolerance(cr, 0.001);
    if (!visibleOnly) {
        const double dashes[2] = {st.dash, st.gap};
        cairo_set_dash(cr, dashes, 2, 0);
        cairo_set_line_width(cr, st.hidden);
        cairo_set_source_rgb(cr, 0.27, 0.27, 0.27);
        for (const Stroke& s : page.strokes) {
            if (s.visible) continue;
            StrokePath(cr, s, page.tolerance);
            cairo_stroke(cr);
        }
        cairo_set_dash(cr, nullptr, 0, 0);
        cairo_set_source_rgb(cr, 0, 0, 0);
    }
    // Thin tangent edges, then edges, then silhouettes (the order of svg_writer.cpp).
    for (int pass = 0; pass < 3; ++pass) {
        const CurveRole role = pass < 2 ? CurveRole::kEdge : CurveRole::kSilhouette;
        cairo_set_line_width(cr, pass == 0 ? st.tangent : (pass == 1 ? st.edge : st.silhouette));
        for (const Stroke& s : page.strokes) {
            if (!s.visible || s.role != role ||
                (role == CurveRole::kEdge && s.tangent != (pass == 0)))
                continue;
            StrokePath(cr, s, page.tolerance);
            cairo_stroke(cr);
        }
    }
    if (visibleOnly) return;
    cairo_set_line_width(cr, st.frame);
    for (const PageLine& l : page.frameLines) {
        cairo_move_to(cr, l.a.x, l.a.y);
        cairo_line_to(cr, l.b.x, l.b.y);
        cairo_stroke(cr);
    }
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    for (const PageText& t : page.texts) {
        cairo_set_font_size(cr, t.size);
        cairo_move_to(cr, t.x, t.y);
        cairo_show_text(cr, t.text.c_str());
    }
}

}  // namespace

std::string WriteCairo(const std::string& path, const Page& page, CairoFormat format) {
    const double toPt = page.unit == "mm" ? 72.0 / 25.4 : 1.0;
    const double w = page.width * toPt, h = page.height * toPt;
    if (!(w > 0 && h > 0)) return "empty page";
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    if (format == CairoFormat::kPng) {
        const double k = page.unit == "mm" ? 4.0 : 1.0;
        const int pw = static_cast<int>(std::ceil(page.width * k));
        const int ph = static_cast<int>(std::ceil(page.height * k));
        if (pw > 16384 || ph > 16384) return "page too large for a PNG preview";
        cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, pw, ph);
        cairo_t* cr = cairo_create(img);
        cairo_scale(cr, k, k);
        Paint(cr, page, false);
        cairo_destroy(cr);
        const cairo_status_t st = cairo_surface_write_to_png(img, tmp.c_str());
        cairo_surface_destroy(img);
        if (st != CAIRO_STATUS_SUCCESS || std::rename(tmp.c_str(), path.c_str()) != 0) {
            std::remove(tmp.c_str());
            return "cannot write " + path;
        }
        return {};
    }
    cairo_surface_t* surface = format == CairoFormat::kPdf
                                   ? cairo_pdf_surface_create(tmp.c_str(), w, h)
                                   : cairo_ps_surface_create(tmp.c_str(), w, h);
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
        const std::string e = cairo_status_to_string(cairo_surface_status(surface));
        cairo_surface_destroy(surface);
        std::remove(tmp.c_str());
        return "cannot write " + path + ": " + e;
    }
    if (format == CairoFormat::kEps) cairo_ps_surface_set_eps(surface, 1);
    if (format == CairoFormat::kPdf && !page.title.empty())
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, page.title.c_str());
    cairo_t* cr = cairo_create(surface);
    cairo_scale(cr, toPt, toPt);
    Paint(cr, page, false);
    cairo_show_page(cr);
    const cairo_status_t status = cairo_status(cr);
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    const cairo_status_t fstatus = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS || fstatus != CAIRO_STATUS_SUCCESS) {
        std::remove(tmp.c_str());
        return "cannot write " + path + ": " +
               cairo_status_to_string(status != CAIRO_STATUS_SUCCESS ? status : fstatus);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        return "cannot write " + path;
    }
    return {};
}

}  // namespace quadrix::draw
