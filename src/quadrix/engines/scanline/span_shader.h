// The span shader of engine `scanline`, seed 001 chapter 6 ("Shader"), writing the Frame (depth,
// normal, surface, body, solid):
//  - quadric depth along a span from the span's conic in (x, z) (§6.3 "Quadric Z"): h(x) and k(x)
//    of c z² + 2 h z + k = 0 updated by differences (h += F, k += Δk, Δk += 2A), root by sheet;
//    planes by one difference;
//  - normals (the Frame's "intensity" input) exactly per pixel when Δmax = 1, else at the span
//    ends and every Δ = min((x_r − x_l)/16 + 1, Δmax) pixels (6.9, §6.5.1 "Non-Unit Shading
//    Increments") with linear interpolation of the unit normal between; "fast" shading uses one
//    normal per face and span.
// The span's faces (SpanShader::Faces) are each stack body's first face on the span's face stack
// (face_stack.h, TakeStackFaces) and the visible faces of the bodies evaluated exactly at the
// span's sample pixel, in depth order (§5.5.1, InsertFace); per pixel the nearest of them wins.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "quadrix/engines/scanline/scan_context.h"
#include "quadrix/eval/ray_literal.h"
#include "quadrix/math/quadratic.h"

namespace quadrix::scanline {

// One show-face on a span's stack, with its incremental state along the span.
struct StackFace {
    int unit = -1;
    int halfSpace = -1, body = -1, solid = -1;
    int sheet = 0;
    const eval::RayHalfSpace* ray = nullptr;
    double h = 0, k = 0, dk = 0;  // quadric: c z'² + 2 h z' + k = 0 at the current pixel
    double planeE = 0;            // plane: px x + py y + pd at the current pixel
    double depth = HUGE_VAL;      // at the current pixel (NaN: no root)
    Vec3 fastNormal;
    int g0 = -1, g1 = -1;  // shading interval cache
    Vec3 n0, n1;
};

// A show-face from an interval endpoint at depth t found on the ray through (x, y): its sheet is
// the root nearer to t.
inline StackFace MakeFaceAt(const eval::RayEvaluator& eval, int halfSpace, double t, double x,
                            double y) {
    StackFace f;
    f.halfSpace = halfSpace;
    f.ray = &eval.Ray(halfSpace);
    f.sheet = eval.SheetOf(halfSpace, t, x, y);
    return f;
}

// The face state at pixel i (x = i + ½) on row y.
inline void SeekFace(StackFace& f, int i, double y) {
    const eval::RayHalfSpace& r = *f.ray;
    const double x = i + 0.5;
    if (r.isPlane) {
        f.planeE = r.px * x + r.py * y + r.pd;
        return;
    }
    const double dx = x - r.x0, dy = y - r.y0;
    f.h = r.hx * dx + r.hy * dy + r.h0;
    f.k = dx * (r.axx * dx + r.axy * dy + r.ax) + dy * (r.byy * dy + r.by) + r.k0;
    f.dk = r.axx * (2 * dx + 1) + r.axy * dy + r.ax;
}
// One pixel on along the row: the conic's differences (6.3).
inline void AdvanceFace(StackFace& f) {
    const eval::RayHalfSpace& r = *f.ray;
    if (r.isPlane) {
        f.planeE += r.px;
        return;
    }
    f.h += r.hx;
    f.k += f.dk;
    f.dk += 2 * r.axx;
}

// The depth of f's sheet from the roots of its quadric on the current ray.
[[gnu::always_inline]] inline double SheetDepth(const StackFace& f, const QuadraticRoots& roots) {
    const eval::RayHalfSpace& r = *f.ray;
    switch (roots.kind) {
        case RootKind::kTwo:
            return r.z0 + (f.sheet == 1 ? roots.t1 : roots.t0);
        case RootKind::kSingle:
        case RootKind::kDouble:
            return r.z0 + roots.t0;
        default:
            return std::numeric_limits<double>::quiet_NaN();
    }
}

// Depth from the current state (NaN when the sheet has no point here). (always_inline: the span
// loop is large enough that GCC stops inlining these per-pixel helpers there.)
[[gnu::always_inline]] inline double FaceDepth(const StackFace& f, RendererCounters& c) {
    ++c.depthCalcs;
    const eval::RayHalfSpace& r = *f.ray;
    if (r.isPlane) return r.c != 0 ? -f.planeE / r.c : std::numeric_limits<double>::quiet_NaN();
    return SheetDepth(f, SolveQuadratic(r.c, f.h, f.k));
}

class SpanShader {
  public:
    explicit SpanShader(ScanContext& ctx) : ctx_(ctx), bodyTaken_(ctx.scene.bodies.size(), 0) {}

    // The span's faces, nearest first at the sample pixel.
    std::vector<StackFace>& Faces() { return faces_; }
    const std::vector<StackFace>& Faces() const { return faces_; }
    void BeginSpan() { faces_.clear(); }
    // Index of the stack head in Faces() (−1: mixed with exactly evaluated bodies).
    int StackHead() const { return stackHead_; }

    // The visible face of a body evaluated exactly at the sample pixel joins the span's faces.
    void AddExactFace(const eval::RayEvaluator::Hit& hit, int unit, int sample, double y);
    // The span's faces from the face stack `shown`: per stack body its first (nearest) face, in
    // stack order, so Faces()[0] is the head when no exactly evaluated unit shares the span.
    void TakeStackFaces(const std::vector<int>& shown, int sample, double y);

    // Per pixel: every face's depth from its state; the nearest (exact ties to the lower solid,
    // by raycast's rule) into best / bestT; `fallback` when some face has no root here. (x, y)
    // is the pixel centre.
    void NearestFace(double x, double y, int& best, double& bestT, bool& fallback) {
        for (std::size_t s = 0; s < faces_.size(); ++s) {
            StackFace& f = faces_[s];
            f.depth = FaceDepth(f, ctx_.c);
            if (std::isnan(f.depth)) {
                fallback = true;
                continue;
            }
            // Strictly nearer wins; exact ties by raycast's rule (ScanContext::UnitWinsTie).
            if (f.depth < bestT ||
                (f.depth == bestT && best >= 0 &&
                 ctx_.UnitWinsTie(f.unit, f.halfSpace, faces_[static_cast<std::size_t>(best)].unit,
                                  faces_[static_cast<std::size_t>(best)].halfSpace, x, y,
                                  f.depth))) {
                best = static_cast<int>(s);
                bestT = f.depth;
            }
        }
    }
    void Seek(int i0, double y) {
        for (StackFace& f : faces_) SeekFace(f, i0, y);
    }
    void Advance() {
        for (StackFace& f : faces_) AdvanceFace(f);
    }

    // The world normal of half-space hs at (x, y, t).
    Vec3 Normal(int hs, double x, double y, double t) {
        ++ctx_.c.normals;
        return ctx_.scene.WorldNormal(hs, {x, y, t});
    }
    // The normal of face f at pixel i of the span [i0, i1] (shading interval `delta`, (6.9)).
    Vec3 ShadedNormal(StackFace& f, int i, int i0, int i1, int delta, double y, double t);
    [[gnu::always_inline]] void Write(int i, int j, double t, const Vec3& n, int hs, int body) {
        std::size_t idx = ctx_.frame.Index(i, j);
        ctx_.frame.depth[idx] = t;
        ctx_.frame.normal[idx] = n;
        ctx_.frame.surface[idx] = hs;
        ctx_.frame.body[idx] = body;
        ++ctx_.c.covered;
    }

  private:
    // Exact depth of the face at pixel i (for the shading-interval grid).
    double FaceDepthAt(const StackFace& f, int i, double y) {
        StackFace g = f;
        SeekFace(g, i, y);
        return FaceDepth(g, ctx_.c);
    }
    // Face stack insertion in depth order with the §5.5.1 tie-breaks.
    inline void InsertFace(const StackFace& f, double x, double y);

    ScanContext& ctx_;
    std::vector<StackFace> faces_;
    std::vector<char> bodyTaken_;  // TakeStackFaces: bodies whose first face is taken
    std::vector<int> taken_;
    int stackHead_ = -1;
};

// Per pixel, so defined here (inlined into the span loop, renderer.cpp).
inline Vec3 SpanShader::ShadedNormal(StackFace& f, int i, int i0, int i1, int delta, double y,
                                     double t) {
    if (ctx_.settings.fastShading) return f.fastNormal;
    if (delta <= 1) return Normal(f.halfSpace, i + 0.5, y, t);
    int g0 = i0 + ((i - i0) / delta) * delta, g1 = std::min(g0 + delta, i1);
    if (g1 == g0) return Normal(f.halfSpace, i + 0.5, y, t);
    if (f.g0 != g0 || f.g1 != g1) {
        // Moving on by one interval: the old right end is the new left end.
        bool reuse = f.g1 == g0;
        double t0 = reuse ? 0 : FaceDepthAt(f, g0, y), t1 = FaceDepthAt(f, g1, y);
        if (!std::isfinite(t0) || !std::isfinite(t1)) return Normal(f.halfSpace, i + 0.5, y, t);
        f.n0 = reuse ? f.n1 : Normal(f.halfSpace, g0 + 0.5, y, t0);
        f.n1 = Normal(f.halfSpace, g1 + 0.5, y, t1);
        f.g0 = g0;
        f.g1 = g1;
    }
    if (i == g0) return f.n0;
    double s = static_cast<double>(i - g0) / (g1 - g0);
    Vec3 n = f.n0 * (1 - s) + f.n1 * s;
    double len = Length(n);
    return len > 0 ? n / len : f.n0;
}

}  // namespace quadrix::scanline
