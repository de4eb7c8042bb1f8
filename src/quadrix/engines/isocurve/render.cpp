#include "quadrix/engines/isocurve/render.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

namespace quadrix::isocurve {

namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Largest singular value of the 2×3 block of rows 0, 1: the spectral norm of the xy part of a
// linear map, from the eigenvalues of the 2×2 matrix A Aᵀ.
double XyNorm(double a0, double a1, double a2, double b0, double b1, double b2) {
    double p = a0 * a0 + a1 * a1 + a2 * a2, q = b0 * b0 + b1 * b1 + b2 * b2;
    double r = a0 * b0 + a1 * b1 + a2 * b2;
    double mean = 0.5 * (p + q), diff = 0.5 * (p - q);
    return std::sqrt(mean + std::sqrt(diff * diff + r * r));
}

}  // namespace

double PixelsPerWorldUnit(const std::vector<FreeformDrawable>& drawables,
                          const Projection& projection) {
    const Mat4& m = projection.deviceFromWorld.Matrix();
    if (!projection.perspective && m(3, 0) == 0 && m(3, 1) == 0 && m(3, 2) == 0)
        return XyNorm(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2)) / m(3, 3);
    // Perspective: the Jacobian of (x/w, y/w) is (M_xy − (x', y') M_w) / w at each point; sample.
    double best = 0;
    for (const FreeformDrawable& d : drawables)
        for (const freeform::BezierSurface& patch : d.surface->Patches().Patches())
            for (int j = 0; j <= 16; ++j)
                for (int i = 0; i <= 16; ++i) {
                    double u = patch.U0() + (patch.U1() - patch.U0()) * i / 16;
                    double v = patch.V0() + (patch.V1() - patch.V0()) * j / 16;
                    Vec4 h = m * Vec4(d.surface->Point(u, v), 1.0);
                    if (!(h.w > 0)) continue;
                    double x = h.x / h.w, y = h.y / h.w;
                    double a[3], b[3];
                    for (int k = 0; k < 3; ++k) {
                        a[k] = (m(0, k) - x * m(3, k)) / h.w;
                        b[k] = (m(1, k) - y * m(3, k)) / h.w;
                    }
                    best = std::max(best, XyNorm(a[0], a[1], a[2], b[0], b[1], b[2]));
                }
    return 1.1 * best;
}

double DeltaForImage(const std::vector<FreeformDrawable>& drawables, const Projection& projection,
                     double pixelSpacing) {
    double s = PixelsPerWorldUnit(drawables, projection);
    return s > 0 ? pixelSpacing / s : 0;
}

Extraction ExtractFor(const freeform::Surface& surface, double delta,
                      const IsocurveOptions& options, bool keepStrips) {
    ExtractOptions eo;
    eo.direction = options.direction;
    eo.minLevel = options.minLevel;
    eo.maxLevel = options.maxLevel;
    eo.baseCount = options.baseCount;
    eo.keepStrips = keepStrips;
    return options.uniform ? ExtractUniform(surface, delta, eo)
                           : ExtractAdaptive(surface, delta, eo);
}

RasterCounts DrawExtractions(const std::vector<FreeformDrawable>& drawables,
                             const std::vector<Extraction>& extractions,
                             const Projection& projection, double thickness, Frame& frame) {
    CurveRasterizer raster(frame, projection, 0.5 * thickness);
    for (std::size_t i = 0; i < drawables.size(); ++i) {
        const Extraction& e = extractions[i];
        IsoFamily family(*drawables[i].surface, e.constant);
        bool transposed = e.constant == Constant::kU;
        for (const Isocurve& c : e.curves) {
            raster.BeginCurve();
            std::vector<freeform::BezierCurve> pos = family.Pieces(c.fixed, c.t0, c.t1);
            std::vector<freeform::BezierCurve> nor = family.NormalPieces(c.fixed, c.t0, c.t1);
            for (std::size_t k = 0; k < pos.size() && k < nor.size(); ++k)
                raster.DrawSegment(pos[k], nor[k], *drawables[i].surface, c.fixed, transposed,
                                   drawables[i].ids);
            family.ClearCache();
        }
    }
    return raster.Counts();
}

IsocurveStats RenderFreeform(const std::vector<FreeformDrawable>& drawables,
                             const Projection& projection, const IsocurveOptions& options,
                             Frame& frame) {
    IsocurveStats st;
    st.surfaces = static_cast<int>(drawables.size());
    st.delta = options.delta > 0 ? options.delta
                                 : DeltaForImage(drawables, projection, options.pixelSpacing);
    st.thickness = options.thickness > 0 ? options.thickness : 1.5 * options.pixelSpacing + 0.25;
    if (!(st.delta > 0) || drawables.empty()) return st;

    auto start = std::chrono::steady_clock::now();
    std::vector<Extraction> ex(drawables.size());
    // Surfaces are independent: extract them in parallel (the drawing below is sequential, so
    // the Frame and the statistics are the same for any number of threads).
    tbb::parallel_for(std::size_t{0}, drawables.size(), [&](std::size_t i) {
        ex[i] = ExtractFor(*drawables[i].surface, st.delta, options);
    });
    st.extractSeconds = Seconds(start);
    for (const Extraction& e : ex) {
        st.curves += e.stats.curves;
        st.length += e.stats.length;
        st.pairs += e.stats.pairs;
        st.crossings += e.stats.crossings;
        st.unresolved += e.stats.unresolved;
        st.deepestLevel = std::max(st.deepestLevel, e.stats.deepestLevel);
    }
    start = std::chrono::steady_clock::now();
    st.raster = DrawExtractions(drawables, ex, projection, st.thickness, frame);
    st.drawSeconds = Seconds(start);
    return st;
}

void RenderFreeformProgressive(
    const std::vector<FreeformDrawable>& drawables, const Projection& projection,
    const IsocurveOptions& options, const Frame& base,
    const std::function<void(int, int, const Frame&, const IsocurveStats&)>& show) {
    int levels = std::max(options.progressiveLevels, 0) + 1;
    double delta = options.delta > 0 ? options.delta
                                     : DeltaForImage(drawables, projection, options.pixelSpacing);
    double thickness =
        options.thickness > 0 ? options.thickness : 1.5 * options.pixelSpacing + 0.25;
    for (int k = 0; k < levels; ++k) {
        double f = std::ldexp(1.0, levels - 1 - k);
        IsocurveOptions o = options;
        o.delta = delta * f;
        o.thickness = thickness * f;
        Frame frame = base;
        IsocurveStats st = RenderFreeform(drawables, projection, o, frame);
        show(k, levels, frame, st);
    }
}

namespace {

bool ParseDouble(const std::string& s, double& out) {
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return !s.empty() && end == s.c_str() + s.size() && std::isfinite(out);
}

bool ParseInt(const std::string& s, int& out) {
    char* end = nullptr;
    long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || end != s.c_str() + s.size() || v < -1000000 || v > 1000000) return false;
    out = static_cast<int>(v);
    return true;
}

}  // namespace

std::string ParseIsocurveOptions(const std::map<std::string, std::string>& values,
                                 IsocurveOptions& o) {
    for (const auto& [key, value] : values) {
        auto bad = [&](const char* what) {
            return fmt::format("isocurve option '{}': expected {}, got '{}'", key, what, value);
        };
        double d = 0;
        int n = 0;
        if (key == "delta") {
            if (!ParseDouble(value, d) || !(d > 0)) return bad("a positive world distance");
            o.delta = d;
        } else if (key == "spacing") {
            if (!ParseDouble(value, d) || !(d > 0) || d > 1000) return bad("pixels in (0, 1000]");
            o.pixelSpacing = d;
        } else if (key == "thickness") {
            if (!ParseDouble(value, d) || !(d > 0) || d > 1000) return bad("pixels in (0, 1000]");
            o.thickness = d;
        } else if (key == "direction") {
            if (value == "u")
                o.direction = Direction::kConstU;
            else if (value == "v")
                o.direction = Direction::kConstV;
            else if (value == "auto")
                o.direction = Direction::kAuto;
            else
                return bad("u, v or auto");
        } else if (key == "min-level") {
            if (!ParseInt(value, n) || n < 0 || n > 20) return bad("an integer in 0..20");
            o.minLevel = n;
        } else if (key == "max-level") {
            if (!ParseInt(value, n) || n < 1 || n > 50) return bad("an integer in 1..50");
            o.maxLevel = n;
        } else if (key == "base") {
            if (value == "auto") {
                o.baseCount = 0;
            } else if (!ParseInt(value, n) || n < 1 || n > 4096) {
                return bad("auto or a number of intervals in 1..4096");
            } else {
                o.baseCount = n;
            }
        } else if (key == "uniform" || key == "compare") {
            if (value != "0" && value != "1") return bad("0 or 1");
            (key == "uniform" ? o.uniform : o.compare) = value == "1";
        } else if (key == "progressive") {
            if (!ParseInt(value, n) || n < 0 || n > 8) return bad("a number of levels in 0..8");
            o.progressiveLevels = n;
        } else {
            return fmt::format(
                "engine 'isocurve' has no option '{}' (known: delta, spacing, "
                "thickness, direction, min-level, max-level, base, uniform, "
                "progressive, compare)",
                key);
        }
    }
    if (o.minLevel > o.maxLevel) return "isocurve options: min-level exceeds max-level";
    return {};
}

void FillRenderStats(const IsocurveStats& s, RenderStats& out) {
    out.seconds += s.extractSeconds + s.drawSeconds;
    auto add = [&](const char* name, double v) { out.counters.emplace_back(name, v); };
    add("isocurve.surfaces", s.surfaces);
    add("isocurve.delta", s.delta);
    add("isocurve.thickness", s.thickness);
    add("isocurve.curves", s.curves);
    add("isocurve.length", s.length);
    add("isocurve.crossings", s.crossings);
    add("isocurve.unresolved", s.unresolved);
    add("isocurve.samples", static_cast<double>(s.raster.samples));
    add("isocurve.pixels_drawn", static_cast<double>(s.raster.pixelsDrawn));
    add("isocurve.pixels_distinct", static_cast<double>(s.raster.distinctPixels));
    add("isocurve.pixels_multiple", static_cast<double>(s.raster.multiplyDrawn));
    add("isocurve.redundancy", s.raster.Redundancy());
    add("isocurve.extract_seconds", s.extractSeconds);
    add("isocurve.draw_seconds", s.drawSeconds);
    out.report += FormatIsocurveStats(s);
}

std::string FormatIsocurveStats(const IsocurveStats& s) {
    return fmt::format(
        "isocurve: {} surfaces, delta {:.6g} (world), curves {:.3g} px wide\n"
        "  curves {}  total length {:.6g}  pairs {}  crossings {}  deepest level {}  "
        "unresolved {}\n"
        "  samples {}  pixels drawn {}  distinct {}  drawn more than once {}  redundancy {:.3f}\n"
        "  extraction {:.3f} s  drawing {:.3f} s\n",
        s.surfaces, s.delta, s.thickness, s.curves, s.length, s.pairs, s.crossings, s.deepestLevel,
        s.unresolved, s.raster.samples, s.raster.pixelsDrawn, s.raster.distinctPixels,
        s.raster.multiplyDrawn, s.raster.Redundancy(), s.extractSeconds, s.drawSeconds);
}

}  // namespace quadrix::isocurve
