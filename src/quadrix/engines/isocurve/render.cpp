#include "quadrix/engines/isocurve/render.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include "quadrix/engines/isocurve/counters.h"
#include "quadrix/util/parallel.h"
#include "quadrix/util/seconds_since.h"

namespace quadrix::isocurve {

namespace {

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
    ParallelFor(std::size_t{0}, drawables.size(), [&](std::size_t i) {
        ex[i] = ExtractFor(*drawables[i].surface, st.delta, options);
    });
    st.extractSeconds = SecondsSince(start);
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
    st.drawSeconds = SecondsSince(start);
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

const OptionSchema& IsocurveSchema() {
    using O = OptionSpec;
    static const OptionSchema kSchema{
        O::Number("delta", "", 0, HUGE_VAL, true,
                  "world tolerance between adjacent isocurves (default: from spacing)"),
        O::Number("spacing", "1", 0, 1000, true,
                  "screen gap between adjacent isocurves when delta is not given (pixels)"),
        O::Number("thickness", "", 0, 1000, true,
                  "curve width in pixels (default 1.5 x spacing + 0.25)"),
        O::Choice("direction", "auto", {"u", "v", "auto"},
                  "isocurves of constant u, constant v, or chosen per surface"),
        O::Int("min-level", "2", 0, 20, "subdivision levels always made"),
        O::Int("max-level", "24", 1, 50, "subdivision levels at most"),
        O::Int("base", "1", 1, 4096,
               "base intervals: 1 = Algorithm 1, auto = from the spacing, or N")
            .AllowingAuto(),
        O::Bool("uniform", "off", "uniformly spaced curves instead of adaptive ones"),
        O::Int("progressive", "1", 0, 8, "coarse levels drawn before the final one"),
        O::Bool("compare", "off",
                "also measure uniform curves and a polygon mesh (a comparison table)"),
    };
    return kSchema;
}

std::string CheckIsocurveOptions(const EngineOptions& options) {
    if (options.Int("min-level") > options.Int("max-level"))
        return "engine 'isocurve': min-level exceeds max-level";
    return {};
}

IsocurveOptions ReadIsocurveOptions(const EngineOptions& v) {
    IsocurveOptions o;
    if (v.Given("delta")) o.delta = v.Number("delta");
    o.pixelSpacing = v.Number("spacing");
    if (v.Given("thickness")) o.thickness = v.Number("thickness");
    const std::string& d = v.Choice("direction");
    o.direction = d == "u" ? Direction::kConstU : d == "v" ? Direction::kConstV : Direction::kAuto;
    o.minLevel = v.Int("min-level");
    o.maxLevel = v.Int("max-level");
    o.baseCount = v.Int("base");
    o.uniform = v.Bool("uniform");
    o.progressiveLevels = v.Int("progressive");
    o.compare = v.Bool("compare");
    return o;
}

std::string ParseIsocurveOptions(const std::map<std::string, std::string>& values,
                                 IsocurveOptions& o) {
    EngineOptions parsed;
    std::string error = ParseEngineOptions("isocurve", IsocurveSchema(), values, parsed);
    if (error.empty()) error = CheckIsocurveOptions(parsed);
    if (error.empty()) o = ReadIsocurveOptions(parsed);
    return error;
}

void FillRenderStats(const IsocurveStats& s, RenderStats& out) {
    out.seconds += s.extractSeconds + s.drawSeconds;
    CounterValues counters(kIsocurveCounters);
    counters.Set(kIsocurveSurfaces, s.surfaces);
    counters.Set(kIsocurveDelta, s.delta);
    counters.Set(kIsocurveThickness, s.thickness);
    counters.Set(kIsocurveCurves, s.curves);
    counters.Set(kIsocurveLength, s.length);
    counters.Set(kIsocurveCrossings, s.crossings);
    counters.Set(kIsocurveUnresolved, s.unresolved);
    counters.Set(kIsocurveSamples, static_cast<double>(s.raster.samples));
    counters.Set(kIsocurvePixelsDrawn, static_cast<double>(s.raster.pixelsDrawn));
    counters.Set(kIsocurvePixelsDistinct, static_cast<double>(s.raster.distinctPixels));
    counters.Set(kIsocurvePixelsMultiple, static_cast<double>(s.raster.multiplyDrawn));
    counters.Set(kIsocurveRedundancy, s.raster.Redundancy());
    counters.Set(kIsocurveExtractSeconds, s.extractSeconds);
    counters.Set(kIsocurveDrawSeconds, s.drawSeconds);
    counters.AppendTo(out.counters);
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
