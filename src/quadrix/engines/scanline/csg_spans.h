// CSG solids in engine `scanline` (anything but a union of bodies) by per-span BODY TEMPLATES,
// seed 001 §5.2–5.3's spans turned to CSG (DESIGN.md "Engines in more detail"). In a span, each
// operand body's interval list along the ray has a constant structure (which show-faces bound
// which intervals, in which order), because all of its own face boundaries are breakpoints. The
// structure is read once per span at the sample pixel; at every pixel the endpoints' depths come
// from the span shader's incremental conics (span_shader.h), and the lists are combined by the
// interval CSG of the tree (union/intersection/difference of sorted lists, as raycast). Operand
// surfaces of DIFFERENT bodies may cross inside a span (their intersection curves are quartic in
// general and are not show-edges), which is exactly why the CSG combination is redone per pixel.
// A template endpoint without a root at some pixel falls back to exact evaluation of the tree
// there. The tree is PRUNED per span to the operands whose x range meets the span (an absent
// operand is ∅: dropped from unions and subtrahends, emptying intersections and differences whose
// minuend it is), so a union of 10,000 spheres costs per span the few spheres there. An operand's
// template holds between two of its own crossings, so it is read once there and reused
// (re-seeked) by the spans in between, which other bodies' crossings cut.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "quadrix/engines/scanline/row_bodies.h"
#include "quadrix/engines/scanline/scan_context.h"
#include "quadrix/engines/scanline/span_shader.h"
#include "quadrix/math/interval_list.h"
#include "quadrix/math/quadratic.h"

namespace quadrix::scanline {

// A CSG unit present in a span, with its tree pruned to the operands present there.
struct CsgSpanUnit {
    int unit = -1;
    int root = -1;  // its pruned tree (a PNode)
};

class CsgSpans {
  public:
    CsgSpans(ScanContext& ctx, const RowBodies& row);

    // Per body: its leaves (unit, tree node) in the CSG units' trees.
    const std::vector<std::pair<int, int>>& BodyLeaves(int body) const {
        return bodyLeaves_[static_cast<std::size_t>(body)];
    }

    // ---- per span ----
    void BeginSpan();
    // The template of CSG operand `body` in the span starting at pixel i0 (read at `sample`, or
    // kept from an earlier span of the row); its index.
    int BuildTemplate(int body, int i0, int sample, double y);
    // Leaf `leaf` of CSG unit `unit` is present in the span with template `tmpl`.
    void AddSpanLeaf(int unit, int leaf, int tmpl) { spanLeaves_.push_back({unit, leaf, tmpl}); }
    // Per CSG unit present: its tree pruned to the leaves added (Units()).
    void PruneSpanUnits();
    const std::vector<CsgSpanUnit>& Units() const { return units_; }

    // ---- per pixel of the span ----
    // Some CSG unit or template face is present in the span.
    bool Active() const { return !units_.empty() || !tFaces_.empty(); }
    // At pixel i: the template faces' depths from their conics, then each CSG unit's visible
    // point offered to (hit, solid, unit): taken when strictly nearer, or as near and winning
    // raycast's tie rule (ScanContext::UnitWinsTie).
    inline void OfferPixel(int i, double y, eval::RayEvaluator::Hit& hit, int& solid,
                           int& unit);  // (_inline.h)
    void AdvanceTemplates() {
        for (StackFace& f : tFaces_) AdvanceFace(f);
    }

    // An exact pixel (x, y): CSG unit u's tree pruned to the operands whose x range on this row
    // holds x, each evaluated exactly.
    bool EvaluateExact(int u, double x, double y, eval::RayEvaluator::Hit& hit);

  private:
    // (The functions declared inline here are defined in csg_spans_inline.h: the per-pixel path.)
    struct TemplateInterval {
        int lo = -1, hi = -1;        // indices of endpoint faces; −1 = infinite end
        int loTag = -1, hiTag = -1;  // the evaluator's tags of the endpoints
    };
    struct BodyTemplate {
        int body = -1;
        bool exact = false;  // refused body: evaluated per pixel
        std::size_t first = 0, count = 0;
    };
    // A node of a pruned CSG tree: a leaf (body, template index or −1 = exact) or an operation on
    // pKids_[first, first + count).
    struct PNode {
        bool leaf = false;
        int body = -1, tmpl = -1;
        scene::CsgOp op = scene::CsgOp::kUnion;
        std::size_t first = 0, count = 0;
    };
    // A CSG operand's template kept across spans: per interval its two ends (the evaluator's tag,
    // −1 for an infinite end, and the sheet), valid on row `row` while `passed` own crossings lie
    // left.
    struct CachedEnd {
        int tag = -1, sheet = 0;
    };
    struct CachedTemplate {
        int row = -1, passed = -1;
        std::vector<std::array<CachedEnd, 2>> ends;
    };
    struct SpanLeaf {
        int unit = -1, leaf = -1, tmpl = -1;
    };

    // The template faces' depths at the current pixel (two sheets of one quadric share a solve).
    inline void UpdateTemplateDepths();
    // The CSG unit's visible point at pixel i from its pruned tree and templates; false when
    // nothing is visible. Where a template does not hold, the pruned tree is evaluated exactly.
    inline bool CsgPixel(const CsgSpanUnit& cu, int i, double y, eval::RayEvaluator::Hit& hit);
    // BuildTemplate's read at the sample pixel: the ends of the body's intervals into `cache`.
    void ReadTemplate(int body, int sample, double y, CachedTemplate& cache);
    // The set of template t at the current pixel (depths from the span shader's conics).
    // `broken` when the template does not hold here (a root vanished, the order changed).
    inline void TemplateSet(int tmpl, IntervalList& out, bool& broken);
    int BuildPruned(int root, const std::vector<std::pair<int, int>>& leaves);
    int Assemble(int node);
    inline void EvalPruned(int pn, std::size_t depth, double x, double y, IntervalList& out,
                           bool& broken, bool exact);
    IntervalList& Pool(std::size_t i) { return pool_[i]; }

    ScanContext& ctx_;
    const RowBodies& row_;
    // Tree parents and child positions, per body its leaves (unit, node); pruned trees
    // (BuildPruned) and their scratch.
    std::vector<int> parent_, childPos_;
    std::vector<std::vector<std::pair<int, int>>> bodyLeaves_;
    std::vector<std::uint32_t> touchGen_;
    std::uint32_t pruneGen_ = 0;
    std::vector<int> leafPNode_;
    std::vector<std::vector<int>> touchedKids_;
    std::vector<PNode> pNodes_;
    std::vector<int> pKids_;
    std::vector<SpanLeaf> spanLeaves_;
    std::vector<std::pair<int, int>> pruneLeaves_;  // (leaf node, template index or −1)
    std::vector<IntervalList> pool_;
    std::vector<CachedTemplate> tmplCache_;  // per CSG operand body (BuildTemplate)
    std::vector<CsgSpanUnit> units_;
    std::vector<BodyTemplate> templates_;
    std::vector<TemplateInterval> tIntervals_;
    std::vector<StackFace> tFaces_;
    QuadraticRoots lastRoots_;  // UpdateTemplateDepths: roots shared by consecutive faces
};

}  // namespace quadrix::scanline
