#include "quadrix/draw/cairo_writer.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "quadrix/draw/cairo_module.h"
#include "quadrix/io/output_file.h"
#include "quadrix/util/module_loader.h"

// Null unless the module's source is linked into this target (quadrix_modules_linked); the
// program loads quadrix-cairo.so instead (util/module_loader.h).
#pragma weak quadrix_cairo_module

namespace quadrix::draw {

namespace {

using Op = CairoCommand::Op;

struct JobBuilder {
    CairoJob& job;
    void Add(Op op, std::initializer_list<double> v = {}) {
        CairoCommand c;
        c.op = op;
        int i = 0;
        for (double x : v) c.v[i++] = x;
        job.commands.push_back(c);
    }
    void Point(Op op, Point2 p) { Add(op, {p.x, p.y}); }

    void StrokePath(const Stroke& s, double tolerance) {
        Add(Op::kNewPath);
        if (s.kind == StrokeKind::kParabolaArc) {
            // The exact quadratic Bézier (svg_writer.cpp), raised to a cubic (exact too).
            const Point2 p0 = s.ArcPoint(s.a0), p1 = s.ArcPoint(s.a1), d0 = s.ArcTangent(s.a0);
            const double h = 0.5 * (s.a1 - s.a0);
            const Point2 q{p0.x + h * d0.x, p0.y + h * d0.y};
            Point(Op::kMoveTo, p0);
            Add(Op::kCurveTo,
                {p0.x + 2 * (q.x - p0.x) / 3, p0.y + 2 * (q.y - p0.y) / 3,
                 p1.x + 2 * (q.x - p1.x) / 3, p1.y + 2 * (q.y - p1.y) / 3, p1.x, p1.y});
        } else if (s.kind == StrokeKind::kHyperbolaArc) {
            const std::vector<Point2> p = ConicToCubics(s, tolerance);
            Point(Op::kMoveTo, p[0]);
            for (std::size_t i = 1; i + 2 < p.size(); i += 3)
                Add(Op::kCurveTo, {p[i].x, p[i].y, p[i + 1].x, p[i + 1].y, p[i + 2].x, p[i + 2].y});
        } else if (s.kind == StrokeKind::kEllipseArc) {
            // Cairo approximates the arc by cubic Béziers within its tolerance (0.001 here).
            Add(Op::kEllipseArc, {s.U.x, s.U.y, s.V.x, s.V.y, s.c.x, s.c.y, s.a0, s.a1});
        } else {
            for (std::size_t i = 0; i < s.points.size(); ++i)
                Point(i == 0 ? Op::kMoveTo : Op::kLineTo, s.points[i]);
        }
        Add(Op::kStroke);
    }

    // Hidden lines first (dashed, gray), then thin tangent edges, edges and silhouettes (the
    // order of svg_writer.cpp), then the sheet's frame and texts.
    void Paint(const Page& page) {
        const LineStyle& st = page.style;
        Add(Op::kDash, {st.dash, st.gap});
        Add(Op::kLineWidth, {st.hidden});
        Add(Op::kGray, {0.27});
        for (const Stroke& s : page.strokes)
            if (!s.visible) StrokePath(s, page.tolerance);
        Add(Op::kSolid);
        Add(Op::kGray, {0});
        for (int pass = 0; pass < 3; ++pass) {
            const CurveRole role = pass < 2 ? CurveRole::kEdge : CurveRole::kSilhouette;
            Add(Op::kLineWidth, {pass == 0 ? st.tangent : (pass == 1 ? st.edge : st.silhouette)});
            for (const Stroke& s : page.strokes) {
                if (!s.visible || s.role != role ||
                    (role == CurveRole::kEdge && s.tangent != (pass == 0)))
                    continue;
                StrokePath(s, page.tolerance);
            }
        }
        Add(Op::kLineWidth, {st.frame});
        for (const PageLine& l : page.frameLines) {
            Add(Op::kNewPath);
            Point(Op::kMoveTo, l.a);
            Point(Op::kLineTo, l.b);
            Add(Op::kStroke);
        }
        for (const PageText& t : page.texts) {
            Add(Op::kText, {t.x, t.y, t.size});
            job.commands.back().index = static_cast<std::uint32_t>(job.texts.size());
            job.texts.push_back(t.text);
        }
    }
};

const CairoModule* Module(std::string* error) {
    if (quadrix_cairo_module) return quadrix_cairo_module();
    const auto entry = reinterpret_cast<const CairoModule* (*)()>(
        LoadModuleSymbol("quadrix-cairo.so", "quadrix_cairo_module", error));
    if (!entry) return nullptr;
    const CairoModule* m = entry();
    if (m->abi != kCairoModuleAbi || !m->render) {
        *error = "quadrix-cairo.so is from another build of Quadrix (interface " +
                 std::to_string(m->abi) + ", this program's " + std::to_string(kCairoModuleAbi) +
                 ")";
        return nullptr;
    }
    return m;
}

}  // namespace

std::string WriteCairo(const std::string& path, const Page& page, CairoFormat format) {
    const double toPt = page.unit == "mm" ? 72.0 / 25.4 : 1.0;
    const double w = page.width * toPt, h = page.height * toPt;
    if (!(w > 0 && h > 0)) return "empty page";
    CairoJob job;
    if (format == CairoFormat::kPng) {
        const double k = page.unit == "mm" ? 4.0 : 1.0;
        job.format = CairoJob::Format::kPng;
        job.pixelsPerUnit = k;
        job.pixelWidth = static_cast<int>(std::ceil(page.width * k));
        job.pixelHeight = static_cast<int>(std::ceil(page.height * k));
        if (job.pixelWidth > 16384 || job.pixelHeight > 16384)
            return "page too large for a PNG preview";
    } else {
        job.format = format == CairoFormat::kPdf ? CairoJob::Format::kPdf : CairoJob::Format::kEps;
        job.widthPt = w;
        job.heightPt = h;
        job.pointsPerUnit = toPt;
        job.title = page.title;
    }
    JobBuilder{job}.Paint(page);
    std::string error;
    const CairoModule* m = Module(&error);
    if (!m) return "cannot write " + path + ": PDF, EPS and PNG drawings need Cairo: " + error;
    std::string bytes;
    if (!m->render(job, &bytes, &error)) return "cannot write " + path + ": " + error;
    return WriteOutputFile(path, bytes);
}

}  // namespace quadrix::draw
