// The per-pixel path of engine `scanline`'s CSG spans (csg_spans.h), defined inline here so that
// the span loop (renderer.cpp) and csg_spans.cpp compile it in place, as when the renderer was one
// class: the template faces' depths, the templates' sets, the pruned trees' evaluation and the
// offer of each CSG unit's visible point, per pixel. Include it only from those two files.
#pragma once

#include <cmath>

#include "quadrix/engines/scanline/csg_spans.h"

namespace quadrix::scanline {

// Template faces: the two ends of an operand's interval are often the two sheets of one quadric,
// with the same incremental state: one solve for both.
inline void CsgSpans::UpdateTemplateDepths() {
    for (std::size_t k = 0; k < tFaces_.size(); ++k) {
        StackFace& f = tFaces_[k];
        if (f.ray->isPlane) {
            f.depth = FaceDepth(f, ctx_.c);
            continue;
        }
        const StackFace* g = k > 0 ? &tFaces_[k - 1] : nullptr;
        if (!(g && g->ray == f.ray && g->h == f.h && g->k == f.k))
            lastRoots_ = SolveQuadratic(f.ray->c, f.h, f.k);
        ++ctx_.c.depthCalcs;
        f.depth = SheetDepth(f, lastRoots_);
    }
}

inline void CsgSpans::OfferPixel(int i, double y, eval::RayEvaluator::Hit& hit, int& solid,
                                 int& unit) {
    UpdateTemplateDepths();
    for (const CsgSpanUnit& cu : units_) {
        eval::RayEvaluator::Hit h;
        if (!CsgPixel(cu, i, y, h)) continue;
        if (h.t < hit.t || (h.t == hit.t && ctx_.UnitWinsTie(cu.unit, h.halfSpace, unit,
                                                             hit.halfSpace, i + 0.5, y, h.t))) {
            hit = h;
            solid = ctx_.UnitOf(cu.unit).solid;
            unit = cu.unit;
        }
    }
}

inline void CsgSpans::TemplateSet(int tmpl, IntervalList& out, bool& broken) {
    out.clear();
    const BodyTemplate& t = templates_[static_cast<std::size_t>(tmpl)];
    double prevLo = -HUGE_VAL;
    for (std::size_t k = t.first; k < t.first + t.count; ++k) {
        const TemplateInterval& ti = tIntervals_[k];
        double lo = ti.lo < 0 ? -HUGE_VAL : tFaces_[static_cast<std::size_t>(ti.lo)].depth;
        double hi = ti.hi < 0 ? HUGE_VAL : tFaces_[static_cast<std::size_t>(ti.hi)].depth;
        if (std::isnan(lo) || std::isnan(hi) || lo < prevLo) {
            broken = true;
            return;
        }
        prevLo = lo;
        out.Append(lo, ti.lo < 0 ? Interval::kNoId : ti.loTag, hi,
                   ti.hi < 0 ? Interval::kNoId : ti.hiTag);
    }
}

// The set of pruned node pn on the ray through (x, y): template leaves from the span's
// templates (exact leaves, or all leaves with `exact`, by the interval code of raycast),
// combined as eval::RayEvaluator::TreeSet does. Scratch lists come from pool_ by depth.
inline void CsgSpans::EvalPruned(int pn, std::size_t depth, double x, double y, IntervalList& out,
                                 bool& broken, bool exact) {
    const PNode& p = pNodes_[static_cast<std::size_t>(pn)];
    if (p.leaf) {
        if (exact || p.tmpl < 0)
            ctx_.eval.BodySet(p.body, x, y, out);
        else
            TemplateSet(p.tmpl, out, broken);
        return;
    }
    out.clear();
    IntervalList& operand = Pool(2 * depth);
    IntervalList& tmp = Pool(2 * depth + 1);
    for (std::size_t i = 0; i < p.count; ++i) {
        if (i > 0 && out.empty() && p.op != scene::CsgOp::kUnion) return;
        const int kid = pKids_[p.first + i];
        if (i == 0) {
            EvalPruned(kid, depth + 1, x, y, out, broken, exact);
            if (broken) return;
            continue;
        }
        EvalPruned(kid, depth + 1, x, y, operand, broken, exact);
        if (broken) return;
        eval::CombineOperand(p.op, out, operand, tmp);
    }
}

inline bool CsgSpans::CsgPixel(const CsgSpanUnit& cu, int i, double y,
                               eval::RayEvaluator::Hit& hit) {
    ++ctx_.c.csgPixels;
    bool broken = false;
    IntervalList& l = Pool(0);
    EvalPruned(cu.root, 1, i + 0.5, y, l, broken, false);
    if (broken) {
        ++ctx_.c.csgFallbackPixels;
        broken = false;
        EvalPruned(cu.root, 1, i + 0.5, y, l, broken, true);
    }
    return ctx_.eval.First(l, hit);
}

}  // namespace quadrix::scanline
