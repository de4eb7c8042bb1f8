#include "quadrix/engines/patch/host_setup.h"

#include <algorithm>
#include <cmath>

#include "quadrix/math/quadratic.h"

namespace quadrix::patch {
namespace {

// Pixel centres of the window, as a closed rectangle of device coordinates.
struct CentreRect {
    double x0, x1, y0, y1;
};
CentreRect CentresOf(const PixelWindow& w) {
    return {w.x0 + 0.5, w.x1 - 0.5, w.y0 + 0.5, w.y1 - 0.5};
}

// Share of a word's range the host fills, leaving room for the forward-differencing drift.
constexpr double kFill = 0.75;
// A plane whose cut moves by at most this many pixels over the patch's depth range is loaded as
// perpendicular.
constexpr double kPerpendicularPixels = 1.0 / 16;

void Extend(Range& r, const Range& o) {
    r.lo = std::min(r.lo, o.lo);
    r.hi = std::max(r.hi, o.hi);
}

bool FitsWord(std::int64_t v, int bits) { return v >= MinWord(bits) && v <= MaxWord(bits); }

// EP1 words for l(x, y) · scale - offset over a window of w × h pixels starting at the pixel
// centre (x0, y0). The rounded steps drift by i·δx + j·δy at pixel (i, j); the start word is
// moved by the middle of that drift's range over the window, which halves the worst error.
std::optional<Ep1Program> Ep1Words(const Linear2& l, double x0, double y0, double scale,
                                   double offset, int bits, int w, int h) {
    const auto sx = Quantize(l.a * scale), sy = Quantize(l.b * scale);
    if (!sx || !sy) return std::nullopt;
    const double dx = static_cast<double>(*sx) - l.a * scale;
    const double dy = static_cast<double>(*sy) - l.b * scale;
    const double mid = 0.5 * (dx * (w - 1) + dy * (h - 1));
    const auto start = Quantize(l(x0, y0) * scale - offset - mid);
    if (!start) return std::nullopt;
    if (!FitsWord(*start, bits) || !FitsWord(*sx, bits) || !FitsWord(*sy, bits))
        return std::nullopt;
    return Ep1Program{*start, *sx, *sy};
}

}  // namespace

std::optional<std::int64_t> Quantize(double value) {
    if (!std::isfinite(value) || std::fabs(value) > 4.6e18) return std::nullopt;
    return static_cast<std::int64_t>(std::llround(value));
}

HostAnalysis AnalyzePatch(const QuadricPatch& patch) {
    HostAnalysis a;
    a.poly = PolynomialsOf(patch);
    const CentreRect r = CentresOf(patch.window);
    const Range f2 = RangeOnRectangle(a.poly.f2, r.x0, r.x1, r.y0, r.y1);
    const Range f1 = RangeOnRectangle(a.poly.f1, r.x0, r.x1, r.y0, r.y1);
    if (patch.window.Empty() || !(f2.hi >= 0) || !std::isfinite(f1.lo) || !std::isfinite(f1.hi)) {
        a.empty = true;
        return a;
    }
    a.sqrtMaxAbsF2 = std::sqrt(std::max(std::fabs(f2.lo), std::fabs(f2.hi)));
    const double rootSpread = std::sqrt(f2.hi);
    a.rootDepths = {f1.lo - rootSpread, f1.hi + rootSpread};
    a.depthWords = f1;
    Extend(a.depthWords, a.rootDepths);

    // Prepare the planes (host_setup.h): drop, make perpendicular, or find the patch empty.
    PatchPolynomials& p = a.poly;
    int kept = 0;
    const double zMid = 0.5 * (a.rootDepths.lo + a.rootDepths.hi);
    const double zSpan = a.rootDepths.hi - a.rootDepths.lo;
    for (int k = 0; k < p.planeCount; ++k) {
        const Plane& pl = patch.planes[static_cast<std::size_t>(k)].plane;
        PlaneKind kind = p.kind[static_cast<std::size_t>(k)];
        Linear2 zp = p.zp[static_cast<std::size_t>(k)];
        if (kind != PlaneKind::kPerpendicular &&
            std::fabs(pl.c) * zSpan <= std::hypot(pl.a, pl.b) * kPerpendicularPixels) {
            kind = PlaneKind::kPerpendicular;
            zp = {-pl.a, -pl.b, -(pl.d + pl.c * zMid)};
            ++a.planesMadePerpendicular;
        }
        const Range z = RangeOnRectangle(zp, r.x0, r.x1, r.y0, r.y1);
        bool never = false, always = false;
        switch (kind) {
            case PlaneKind::kPerpendicular:
                never = z.lo >= 0;
                always = z.hi < 0;
                break;
            case PlaneKind::kFront:  // keeps z >= ZP
                never = z.hi <= a.rootDepths.lo;
                always = z.lo > a.rootDepths.hi;
                break;
            case PlaneKind::kBack:  // keeps z <= ZP
                never = z.lo >= a.rootDepths.hi;
                always = z.hi < a.rootDepths.lo;
                break;
        }
        if (always) {
            a.empty = true;
            return a;
        }
        if (never) {
            ++a.planesDropped;
            continue;
        }
        if (kind != PlaneKind::kPerpendicular) Extend(a.depthWords, z);
        p.kind[static_cast<std::size_t>(kept)] = kind;
        p.zp[static_cast<std::size_t>(kept)] = zp;
        ++kept;
    }
    p.planeCount = kept;
    return a;
}

void DepthFormatBuilder::Add(const HostAnalysis& analysis) {
    if (analysis.empty) return;
    lo_ = std::min(lo_, analysis.depthWords.lo);
    hi_ = std::max(hi_, analysis.depthWords.hi);
    halfF2_ = std::max(halfF2_, analysis.sqrtMaxAbsF2);
}

DepthFormat DepthFormatBuilder::Build(const DatapathWidths& widths) const {
    double lo = lo_, hi = hi_;
    if (!(lo <= hi)) lo = 0, hi = 1;
    DepthFormat f;
    f.bits = widths.depthBits;
    f.origin = 0.5 * (lo + hi);
    double half = std::max(0.5 * (hi - lo), halfF2_);
    half = std::max(half, 1e-9 * std::max(1.0, std::fabs(f.origin)));
    f.ulp = half / (kFill * std::ldexp(1.0, widths.depthBits - 2));
    return f;
}

std::optional<HostPatch> PrepareFixedPatch(const QuadricPatch& patch, const HostAnalysis& analysis,
                                           const DepthFormat& format,
                                           const DatapathWidths& widths) {
    const int d = widths.depthBits, n = widths.normalBits, s = widths.NormalGuardBits();
    const int w2 = widths.Ep2Bits();
    const PatchPolynomials& p = analysis.poly;
    const double X0 = patch.window.x0 + 0.5, Y0 = patch.window.y0 + 0.5;
    const double ulp = format.ulp, u2 = ulp * ulp;
    const int W = patch.window.Width(), H = patch.window.Height();
    HostPatch hp;
    FixedPatch& fp = hp.program;
    fp.window = patch.window;

    // F1 and F2 at the first pixel centre from the direct forms (no cancellation), the
    // differences from eq. 1.3's coefficients.
    const Quadric& q = patch.quadric;
    const double hb = q.F() * X0 + q.E() * Y0 + q.J();
    const double a0 = q.A() * X0 * X0 + q.B() * Y0 * Y0 + 2 * q.D() * X0 * Y0 + 2 * q.G() * X0 +
                      2 * q.H() * Y0 + q.K();
    const double f1Start = -hb / q.C();
    const double f2Start = DifferenceOfProducts(hb, hb, q.C(), a0) / (q.C() * q.C());
    {
        // The start from the direct form, the steps from eq. 1.3.
        const Linear2 f1{p.f1.a, p.f1.b, f1Start - p.f1.a * X0 - p.f1.b * Y0};
        const auto words = Ep1Words(f1, X0, Y0, 1 / ulp, format.origin / ulp, d, W, H);
        if (!words) return std::nullopt;
        fp.f1 = *words;
    }
    {
        // Local polynomial F(u, v) = a u² + b v² + c uv + d u + e v + f around (X0, Y0).
        const Quadratic2& g = p.f2;
        const double la = g.xx, lb = g.yy, lc = g.xy;
        const double ld = 2 * g.xx * X0 + g.xy * Y0 + g.x;
        const double le = 2 * g.yy * Y0 + g.xy * X0 + g.y;
        const auto r0 = Quantize((le - lb) / u2), s0 = Quantize((ld - la) / u2),
                   twoA = Quantize(2 * la / u2), twoB = Quantize(2 * lb / u2),
                   c = Quantize(lc / u2);
        if (!r0 || !s0 || !twoA || !twoB || !c) return std::nullopt;
        // Drift of the rounded differences at pixel (i, j), as a polynomial (integer_reference.h
        // form); the start word is moved by the middle of its range over the window.
        const double er0 = *r0 - (le - lb) / u2, es0 = *s0 - (ld - la) / u2,
                     e2a = *twoA - 2 * la / u2, e2b = *twoB - 2 * lb / u2, ec = *c - lc / u2;
        const Quadratic2 drift{e2a / 2, e2b / 2, ec, es0 + e2a / 2, er0 + e2b / 2, 0};
        const Range dr = RangeOnRectangle(drift, 0, W - 1, 0, H - 1);
        const auto q0 = Quantize(f2Start / u2 - 0.5 * (dr.lo + dr.hi));
        if (!q0) return std::nullopt;
        for (const auto& w : {q0, r0, s0, twoA, twoB, c})
            if (!FitsWord(*w, w2)) return std::nullopt;
        fp.f2 = {*q0, *r0, *s0, *twoA, *twoB, *c};
    }

    // Plane units.
    const CentreRect r = CentresOf(patch.window);
    for (int k = 0; k < kMaxPlanes; ++k) {
        PlaneUnitProgram& unit = fp.planes[static_cast<std::size_t>(k)];
        if (k >= p.planeCount) {
            unit = {};  // perpendicular, ZP = 0: never cuts
            continue;
        }
        const Linear2& zp = p.zp[static_cast<std::size_t>(k)];
        const PlaneKind kind = p.kind[static_cast<std::size_t>(k)];
        unit.perpendicular = kind == PlaneKind::kPerpendicular;
        unit.sgnCp = kind == PlaneKind::kFront;
        std::optional<Ep1Program> words;
        if (unit.perpendicular) {
            // Only the sign matters: scale the plane's function to fill the word.
            const Range z = RangeOnRectangle(zp, r.x0, r.x1, r.y0, r.y1);
            const double m = std::max(std::fabs(z.lo), std::fabs(z.hi));
            const double scale = m > 0 ? kFill * std::ldexp(1.0, d - 2) / m : 1.0;
            words = Ep1Words(zp, X0, Y0, scale, 0, d, W, H);
        } else {
            words = Ep1Words(zp, X0, Y0, 1 / ulp, format.origin / ulp, d, W, H);
        }
        if (!words) return std::nullopt;
        unit.zp = *words;
    }

    // Normals: one unit per patch. NX = NXBASE' + e (Z'·ulp) with NXBASE' = NXBASE + e·origin.
    const Linear2 nxB{p.nxBase.a, p.nxBase.b, p.nxBase.c + p.e * format.origin};
    const Linear2 nyB{p.nyBase.a, p.nyBase.b, p.nyBase.c + p.f * format.origin};
    const Linear2 nzB{p.nzBase.a, p.nzBase.b, p.nzBase.c + p.twoC * format.origin};
    double nMax = 0;
    for (double x : {r.x0, r.x1})
        for (double y : {r.y0, r.y1})
            for (double z : {analysis.rootDepths.lo, analysis.rootDepths.hi, format.origin}) {
                const double dz = z - format.origin;
                nMax =
                    std::max({nMax, std::fabs(nxB(x, y) + p.e * dz),
                              std::fabs(nyB(x, y) + p.f * dz), std::fabs(nzB(x, y) + p.twoC * dz),
                              std::fabs(nxB(x, y)), std::fabs(nyB(x, y)), std::fabs(nzB(x, y))});
            }
    const double coefMax = std::max({std::fabs(p.e), std::fabs(p.f), std::fabs(p.twoC)});
    const double room = kFill * std::ldexp(1.0, n - 1);
    const double coefScale = ulp * std::ldexp(1.0, d);  // word = coef · coefScale / unit
    double unit = std::max(nMax / room, coefMax * coefScale / room);
    if (!(unit > 0) || !std::isfinite(unit)) unit = 1;
    hp.normalUnit = unit;
    const double guard = std::ldexp(1.0, s);
    const auto nx = Ep1Words(nxB, X0, Y0, guard / unit, 0, d, W, H);
    const auto ny = Ep1Words(nyB, X0, Y0, guard / unit, 0, d, W, H);
    const auto nz = Ep1Words(nzB, X0, Y0, guard / unit, 0, d, W, H);
    const auto e = Quantize(p.e * coefScale / unit), f = Quantize(p.f * coefScale / unit),
               twoC = Quantize(p.twoC * coefScale / unit);
    if (!nx || !ny || !nz || !e || !f || !twoC) return std::nullopt;
    if (!FitsWord(*e, n) || !FitsWord(*f, n) || !FitsWord(*twoC, n)) return std::nullopt;
    fp.nxBase = *nx;
    fp.nyBase = *ny;
    fp.nzBase = *nz;
    fp.e = *e;
    fp.f = *f;
    fp.twoC = *twoC;
    return hp;
}

double DepthErrorBoundLsb(const PixelWindow& window) {
    const double i = std::max(0, window.Width() - 1), j = std::max(0, window.Height() - 1);
    const double f1 = 0.5 + 0.25 * (i + j);  // centred drift: half of |δx| i + |δy| j
    const double f2 = 0.5 * (1 + j + j * (j + 1) / 2 + i + i * j + i * (i + 1) / 2);
    return f1 + std::sqrt(f2) + 1;
}

}  // namespace quadrix::patch
