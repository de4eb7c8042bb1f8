// The Renderer's row and span loop (seed 001 §5.1): per band of rows, the phases of renderer.h
// composed — per row pass one and two (vertex_processing.h, edge_list.h), the row's bodies
// (row_bodies.h), S0 and pass three's walk (face_stack.h) with spans between crossings; per span
// its faces (span_shader.h: the face stack's and those of bodies evaluated at the sample pixel)
// and its CSG units (csg_spans.h), then per pixel the nearest of them.
#include "quadrix/engines/scanline/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <utility>

#include "quadrix/engines/scanline/csg_spans.h"
#include "quadrix/engines/scanline/csg_spans_inline.h"
#include "quadrix/engines/scanline/edge_list.h"
#include "quadrix/engines/scanline/face_stack.h"
#include "quadrix/engines/scanline/row_bodies.h"
#include "quadrix/engines/scanline/scan_context.h"
#include "quadrix/engines/scanline/span_shader.h"
#include "quadrix/engines/scanline/stack_verifier.h"
#include "quadrix/engines/scanline/vertex_processing.h"
#include "quadrix/engines/scanline/vertex_table.h"
#include "quadrix/util/parallel.h"

namespace quadrix::scanline {

ScanContext::ScanContext(const FlatScene& scene_, std::vector<ShowEdge>& edges_,
                         const std::vector<ShowFace>& faces_, const std::vector<Unit>& units_,
                         const std::vector<bool>& pixelBody_, const std::vector<bool>& stackBody,
                         const VertexTable& vt_, const RenderSettings& settings_, Frame& frame_,
                         RendererCounters& c_)
    : scene(scene_),
      vt(vt_),
      edges(edges_),
      faces(faces_),
      units(units_),
      pixelBody(pixelBody_),
      settings(settings_),
      frame(frame_),
      c(c_),
      eval(scene_) {
    const std::size_t nb = scene.bodies.size();
    bodyUnit.assign(nb, -1);
    bodyFaces.assign(nb, {});
    useStack.assign(nb, 0);
    for (std::size_t u = 0; u < units.size(); ++u) {
        const Unit& unit = units[u];
        if (unit.kind != Unit::Kind::kBody) continue;
        auto b = static_cast<std::size_t>(unit.body);
        bodyUnit[b] = static_cast<int>(u);
        useStack[b] = settings.faceStacks && b < stackBody.size() && stackBody[b] && !pixelBody[b];
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
        auto b = static_cast<std::size_t>(faces[f].body);
        if (b < nb) bodyFaces[b].push_back(static_cast<int>(f));
    }
    for (char u : useStack) stackOn = stackOn || u;
}

namespace {

// One band of rows: the phases, each with its own state, sharing the context.
class ScanRenderer {
  public:
    ScanRenderer(const FlatScene& scene, std::vector<ShowEdge>& edges,
                 const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                 const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                 const VertexTable& vt, const RenderSettings& settings, Frame& frame,
                 RendererCounters& c)
        : ctx_(scene, edges, faces, units, pixelBody, stackBody, vt, settings, frame, c),
          order_(ctx_),
          verifier_(ctx_, order_),
          ael_(ctx_),
          stacks_(ctx_, order_, verifier_, ael_.Edges()),
          passOne_(ctx_, ael_, stacks_),
          row_(ctx_),
          csg_(ctx_, row_),
          shader_(ctx_),
          unitStamp_(units.size(), 0) {}

    // Rows [j0, j1): a band. Bands are independent (each starts its AEL from the ESL), so they
    // run in parallel; results do not depend on the thread count, only on the fixed band size.
    void Run(const EdgeStartList& esl, int j0, int j1) {
        const int w = ctx_.frame.width, h = ctx_.frame.height;
        if (w <= 0 || h <= 0) return;
        ael_.SetEsl(&esl);
        for (int j = j0; j < j1; ++j) Row(j, j == j0);
    }

  private:
    void Row(int j, bool bandStart);
    void Span(int i0, int i1, int j);
    // The span's candidates from body b: its face (a body drawn on its own) or its CSG leaves.
    void AddSpanBody(int b, int i0, int sample, int j);
    void ShadeSpan(int i0, int i1, int j);
    bool EvaluateUnit(int u, double x, double y, eval::RayEvaluator::Hit& hit);
    void ExactPixel(int i, int j);

    ScanContext ctx_;
    FaceOrder order_;
    StackVerifier verifier_;
    ActiveEdgeList ael_;
    FaceStacks stacks_;
    VertexPass passOne_;
    RowBodies row_;
    CsgSpans csg_;
    SpanShader shader_;
    // The span's units evaluated per pixel (refused bodies; CSG units with csg=pixels, stamped
    // per span in unitStamp_ so each enters once).
    std::vector<int> perPixel_;
    std::vector<std::uint32_t> unitStamp_;
    std::uint32_t spanGen_ = 0;
};

void ScanRenderer::Row(int j, bool bandStart) {
    const double yc = j + 0.5;
    const bool stackOn = ctx_.stackOn;
    stacks_.SetBandStart(bandStart);
    // Pass one (the vertices of the CSL, §5.4: finishing edges leave, starting stack edges enter
    // with their stacks) and pass two (x on the CSL, x order by adjacent swaps), with the face
    // stacks carried through both; then the other starting edges.
    if (stackOn && !bandStart)
        passOne_.Run(j);
    else
        ael_.DropFinishingEdges(j);
    ael_.TraceAndSort(j, stacks_);
    ael_.MergeStartingEdges(j, bandStart);
    row_.BuildRow(j, ael_.Edges());
    if (stackOn) stacks_.SeedStack(row_.ActiveUnits(), yc);
    // Pass three: spans between crossings.
    const int w = ctx_.frame.width;
    int i = 0;
    while (i < w) {
        const double xc = i + 0.5;
        const bool straddle = stackOn && stacks_.ApplyEdgesBefore(xc, yc);
        const double next = row_.PassCrossingsBefore(xc);
        if (straddle || next <= xc + kOnEdge) {
            ExactPixel(i, j);
            ++i;
            continue;
        }
        int end = w - 1;
        if (std::isfinite(next)) {
            // Clamped before the cast: a crossing may lie far outside the image.
            end = static_cast<int>(std::ceil(std::min(next, w + 1.0) - kOnEdge - 0.5)) - 1;
            end = std::min(w - 1, end);
        }
        end = std::max(end, i);
        Span(i, end, j);
        i = end + 1;
    }
    // The walk goes on past the image's right side: every stack must be consistent (and
    // verified) before it is carried to the next row.
    if (stackOn) stacks_.ApplyEdgesBefore(HUGE_VAL, yc);
}

void ScanRenderer::Span(int i0, int i1, int j) {
    ++ctx_.c.spans;
    const double y = j + 0.5;
    shader_.BeginSpan();
    perPixel_.clear();
    csg_.BeginSpan();
    const int sample = (i0 + i1) / 2;
    // The bodies whose x range meets the span, from the row's sweep (not all bodies).
    row_.SweepTo(i0, i1);
    if (++spanGen_ == 0) {
        std::fill(unitStamp_.begin(), unitStamp_.end(), 0);
        spanGen_ = 1;
    }
    for (int b : row_.SpanBodies()) AddSpanBody(b, i0, sample, j);
    // Per CSG unit present: its tree pruned to the leaves present.
    csg_.PruneSpanUnits();
    if (ctx_.stackOn) {
        shader_.TakeStackFaces(stacks_.Shown(), sample, y);
        if (ctx_.settings.verify)
            verifier_.VerifySpan(row_.ActiveUnits(), stacks_.Shown(), shader_.Faces(), sample, y);
    }
    if (shader_.Faces().empty() && perPixel_.empty() && csg_.Units().empty()) {
        ++ctx_.c.emptySpans;
        return;
    }
    ShadeSpan(i0, i1, j);
}

void ScanRenderer::AddSpanBody(int b, int i0, int sample, int j) {
    const double y = j + 0.5;
    const auto k = static_cast<std::size_t>(b);
    const int u = ctx_.bodyUnit[k];
    if (u >= 0 && ctx_.RowActive(u, j)) {  // a body drawn on its own
        if (ctx_.pixelBody[k]) {
            perPixel_.push_back(u);
        } else if (!ctx_.useStack[k]) {  // stack bodies: TakeStackFaces
            eval::RayEvaluator::Hit hit;
            ++ctx_.c.sampleEvaluations;
            if (ctx_.eval.Body(b, sample + 0.5, y, hit)) shader_.AddExactFace(hit, u, sample, y);
        }
    }
    int tmpl = -2;  // one template per body and span, built when a CSG leaf needs it
    for (auto [lu, leaf] : csg_.BodyLeaves(b)) {
        if (!ctx_.RowActive(lu, j)) continue;
        if (!ctx_.settings.csgTemplates) {  // csg=pixels: the whole tree per pixel
            if (unitStamp_[static_cast<std::size_t>(lu)] != spanGen_) {
                unitStamp_[static_cast<std::size_t>(lu)] = spanGen_;
                perPixel_.push_back(lu);
            }
            continue;
        }
        if (tmpl == -2) tmpl = csg_.BuildTemplate(b, i0, sample, y);
        csg_.AddSpanLeaf(lu, leaf, tmpl);
    }
}

// Per pixel of the span: the nearest of the span's faces (their depths by differences), the
// units evaluated per pixel and the CSG units; a face without a root sends the pixel to the
// exact evaluation.
void ScanRenderer::ShadeSpan(int i0, int i1, int j) {
    const double y = j + 0.5;
    shader_.Seek(i0, y);
    const int delta = std::max(1, std::min((i1 - i0) / 16 + 1, ctx_.settings.shadeInterval));
    for (int i = i0; i <= i1; ++i) {
        int best = -1;
        double bestT = HUGE_VAL;
        bool fallback = false;
        shader_.NearestFace(i + 0.5, y, best, bestT, fallback);
        if (ctx_.stackOn && shader_.StackHead() == 0 && best > 0) ++ctx_.c.interpenetrationPixels;
        if (fallback) {
            ++ctx_.c.rootFallbackPixels;
            ExactPixel(i, j);
        } else {
            // Units evaluated per pixel (refused bodies, CSG solids) compete with the stack.
            // (Their order is kept: ties between equal depths of one solid go to the first.)
            eval::RayEvaluator::Hit ph;
            int phSolid = -1, phUnit = -1;
            for (int u : perPixel_) {
                const Unit& unit = ctx_.UnitOf(u);
                if (i < unit.x0 || i > unit.x1) continue;
                ++ctx_.c.perPixelUnitPixels;
                eval::RayEvaluator::Hit hit;
                if (EvaluateUnit(u, i + 0.5, y, hit) &&
                    (hit.t < ph.t ||
                     (hit.t == ph.t && ctx_.UnitWinsTie(u, hit.halfSpace, phUnit, ph.halfSpace,
                                                        i + 0.5, y, hit.t)))) {
                    ph = hit;
                    phSolid = unit.solid;
                    phUnit = u;
                }
            }
            if (csg_.Active()) csg_.OfferPixel(i, y, ph, phSolid, phUnit);
            std::vector<StackFace>& faces = shader_.Faces();
            if (ph.halfSpace >= 0 &&
                (best < 0 || ph.t < bestT ||
                 (ph.t == bestT &&
                  ctx_.UnitWinsTie(phUnit, ph.halfSpace, faces[static_cast<std::size_t>(best)].unit,
                                   faces[static_cast<std::size_t>(best)].halfSpace, i + 0.5, y,
                                   ph.t)))) {
                shader_.Write(i, j, ph.t, shader_.Normal(ph.halfSpace, i + 0.5, y, ph.t),
                              ph.halfSpace, ph.body);
            } else if (best >= 0) {
                StackFace& f = faces[static_cast<std::size_t>(best)];
                shader_.Write(i, j, bestT, shader_.ShadedNormal(f, i, i0, i1, delta, y, bestT),
                              f.halfSpace, f.body);
            }
        }
        shader_.Advance();
        csg_.AdvanceTemplates();
    }
}

bool ScanRenderer::EvaluateUnit(int u, double x, double y, eval::RayEvaluator::Hit& hit) {
    const Unit& unit = ctx_.UnitOf(u);
    if (unit.kind != Unit::Kind::kCsg) return ctx_.eval.Body(unit.body, x, y, hit);
    if (!ctx_.settings.csgTemplates) return ctx_.eval.Node(unit.node, x, y, hit);  // csg=pixels
    return csg_.EvaluateExact(u, x, y, hit);
}

// A pixel within kOnEdge of a crossing (or where a face has no root): every unit active there
// evaluated exactly; the nearest wins, exact ties by raycast's rule (ScanContext::UnitWinsTie).
void ScanRenderer::ExactPixel(int i, int j) {
    ++ctx_.c.exactPixels;
    const double x = i + 0.5, y = j + 0.5;
    eval::RayEvaluator::Hit best;
    int bestUnit = -1;
    for (int u : row_.ActiveUnits()) {
        const Unit& unit = ctx_.UnitOf(u);
        if (i < unit.x0 || i > unit.x1) continue;
        eval::RayEvaluator::Hit hit;
        if (EvaluateUnit(u, x, y, hit) &&
            (hit.t < best.t ||
             (hit.t == best.t &&
              ctx_.UnitWinsTie(u, hit.halfSpace, bestUnit, best.halfSpace, x, y, hit.t)))) {
            best = hit;
            bestUnit = u;
        }
    }
    if (best.halfSpace < 0) return;
    shader_.Write(i, j, best.t, ctx_.scene.WorldNormal(best.halfSpace, {x, y, best.t}),
                  best.halfSpace, best.body);
}

}  // namespace

void RendererCounters::Add(const RendererCounters& o) {
    edgesStarted += o.edgesStarted;
    edgeSwaps += o.edgeSwaps;
    spans += o.spans;
    emptySpans += o.emptySpans;
    faceInserts += o.faceInserts;
    depthCalcs += o.depthCalcs;
    sampleEvaluations += o.sampleEvaluations;
    sideEvaluations += o.sideEvaluations;
    exactPixels += o.exactPixels;
    perPixelUnitPixels += o.perPixelUnitPixels;
    normals += o.normals;
    covered += o.covered;
    tieBreaks += o.tieBreaks;
    csgPixels += o.csgPixels;
    csgTemplateBodies += o.csgTemplateBodies;
    csgFallbackPixels += o.csgFallbackPixels;
    csgTemplateReuses += o.csgTemplateReuses;
    rootFallbackPixels += o.rootFallbackPixels;
    stackInserts += o.stackInserts;
    stackDeletes += o.stackDeletes;
    stackMaxDepth = std::max(stackMaxDepth, o.stackMaxDepth);
    stackDepthSum += o.stackDepthSum;
    stackSpans += o.stackSpans;
    stackSeedEvaluations += o.stackSeedEvaluations;
    stackTieBreaks += o.stackTieBreaks;
    stackCorrections += o.stackCorrections;
    stackRepairs += o.stackRepairs;
    closedRowFaces += o.closedRowFaces;
    stackOrderCorrections += o.stackOrderCorrections;
    stackSwapUpdates += o.stackSwapUpdates;
    stackDerivations += o.stackDerivations;
    stackDerivationsChanged += o.stackDerivationsChanged;
    stackDeriveInserts += o.stackDeriveInserts;
    stackDeriveDeletes += o.stackDeriveDeletes;
    stackVertices += o.stackVertices;
    stackVertexRecursions += o.stackVertexRecursions;
    stackDeletionSwaps += o.stackDeletionSwaps;
    stackVertexFallbacks += o.stackVertexFallbacks;
    stackRebuilds += o.stackRebuilds;
    interpenetrationPixels += o.interpenetrationPixels;
    verifySpans += o.verifySpans;
    verifyMismatchSpans += o.verifyMismatchSpans;
    verifyBodies += o.verifyBodies;
    verifyBodyMismatches += o.verifyBodyMismatches;
}

void RenderScanlines(const FlatScene& scene, std::vector<ShowEdge>& edges,
                     const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                     const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                     const RenderSettings& settings, Frame& frame, RendererCounters& counters) {
    const int h = frame.height;
    if (frame.width <= 0 || h <= 0) return;
    const auto esl = BuildEsl(edges, h);
    // Bodies drawn from face stacks (as ScanContext::useStack): their edges make §5.4's
    // vertices.
    std::vector<char> stack(scene.bodies.size(), 0);
    for (const Unit& unit : units) {
        if (unit.kind != Unit::Kind::kBody || unit.body < 0) continue;
        const auto b = static_cast<std::size_t>(unit.body);
        stack[b] = settings.faceStacks && b < stackBody.size() && stackBody[b] && !pixelBody[b];
    }
    const VertexTable vt = BuildVertices(edges, stack, h);
    constexpr int kBand = 32;  // rows per task; fixed, so results never depend on threads
    const int bands = (h + kBand - 1) / kBand;
    std::mutex mutex;
    // Bands run in the caller's arena (Engine::Render, the render context).
    ParallelFor(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& r) {
        for (int b = r.begin(); b < r.end(); ++b) {
            RendererCounters local;
            ScanRenderer(scene, edges, faces, units, pixelBody, stackBody, vt, settings, frame,
                         local)
                .Run(esl, b * kBand, std::min(h, (b + 1) * kBand));
            std::lock_guard<std::mutex> lock(mutex);
            counters.Add(local);
        }
    });
}

}  // namespace quadrix::scanline
