#include "quadrix/engines/scanline/scanline_engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "quadrix/engines/scanline/counters.h"
#include "quadrix/engines/scanline/overlap_guard.h"
#include "quadrix/engines/scanline/pixel_range.h"
#include "quadrix/engines/scanline/renderer.h"
#include "quadrix/engines/scanline/resolver.h"

namespace quadrix {
namespace scanline {
namespace {

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

Unit MakeUnit(const FlatScene& scene, int solid, const Box3& bounds) {
    Unit u;
    u.solid = solid;
    if (bounds.Empty()) return u;  // x1 < x0: never active
    PixelRange(bounds.lo.x, bounds.hi.x, scene.width, u.x0, u.x1);
    PixelRange(bounds.lo.y, bounds.hi.y, scene.height, u.y0, u.y1);
    return u;
}

class ScanlineEngine final : public Engine {
  public:
    std::string_view Name() const override { return "scanline"; }

    const OptionSchema& Schema() const override {
        using O = OptionSpec;
        static const OptionSchema kSchema{
            O::Int("sd", "1", 1, 1e9, "shading interval in pixels (seed 001 §6.2; 1 = exact)"),
            O::Choice("shade", "exact", {"exact", "fast"},
                      "span normals exact per pixel, or fast (flat per span)"),
            O::Choice("csg", "spans", {"spans", "pixels"},
                      "CSG by span templates, or the whole tree per pixel"),
            O::Choice("render", "stacks", {"stacks", "exact"},
                      "face stacks carried along the row (seed 001 ch. 5), or exact per span"),
            O::Bool("check", "on", "verify the carried face stacks (off: trust them, to measure)"),
            O::Bool("verify", "off", "count spans whose stack head differs from exact evaluation"),
            O::Int("max-literals", "256", 1, 1e9,
                   "literals of one body above which its solid is drawn by raycast (the Resolver "
                   "intersects every pair and triple of a body's half-spaces; overlap_guard.h)"),
            O::Int("max-overlap", "64", 0, 1e9,
                   "bodies overlapping one 8x8-pixel cell above which their solids are drawn by "
                   "raycast (face stacks cost ~k^3; overlap_guard.h)"),
        };
        return kSchema;
    }

  protected:
    RenderStats Draw(const FlatScene& scene, const EngineOptions& options, Frame& frame) override {
        const auto t0 = Clock::now();
        RenderSettings settings;
        settings.shadeInterval = options.Int("sd");
        settings.fastShading = options.Choice("shade") == "fast";
        settings.csgTemplates = options.Choice("csg") == "spans";
        settings.faceStacks = options.Choice("render") == "stacks";
        settings.verify = options.Bool("verify");
        settings.checkStacks = options.Bool("check");
        const int width = std::max(scene.width, 0), height = std::max(scene.height, 0);
        frame.Reset(width, height);

        // Units: bodies of single-body solids and of unions of bodies; other solids as CSG units.
        std::vector<Unit> units;
        std::vector<int> bodiesToResolve;
        std::vector<char> inCsg(scene.bodies.size(), 0);
        std::uint64_t csgUnits = 0;
        for (std::size_t s = 0; s < scene.solids.size(); ++s) {
            const FlatSolid& solid = scene.solids[s];
            if (solid.root < 0 || static_cast<std::size_t>(solid.root) >= scene.nodes.size())
                continue;
            const FlatCsgNode& root = scene.nodes[static_cast<std::size_t>(solid.root)];
            std::vector<int> leaves;
            bool bodiesOnly = root.isLeaf;
            if (root.isLeaf) {
                leaves.push_back(root.body);
            } else if (root.op == scene::CsgOp::kUnion) {
                bodiesOnly = true;
                for (int c : root.children) {
                    const FlatCsgNode& n = scene.nodes[static_cast<std::size_t>(c)];
                    if (!n.isLeaf) bodiesOnly = false;
                    leaves.push_back(n.body);
                }
            }
            auto validBody = [&](int b) {
                return b >= 0 && static_cast<std::size_t>(b) < scene.bodies.size();
            };
            if (bodiesOnly) {
                for (int b : leaves) {
                    if (!validBody(b)) continue;
                    Unit u = MakeUnit(
                        scene, static_cast<int>(s),
                        scene.bodies[static_cast<std::size_t>(b)].bounds.Intersected(solid.bounds));
                    u.body = b;
                    units.push_back(u);
                    bodiesToResolve.push_back(b);
                }
            } else {
                Unit u = MakeUnit(scene, static_cast<int>(s), solid.bounds);
                u.kind = Unit::Kind::kCsg;
                u.node = solid.root;
                std::vector<int> stack{solid.root};
                while (!stack.empty()) {
                    const FlatCsgNode& n = scene.nodes[static_cast<std::size_t>(stack.back())];
                    stack.pop_back();
                    if (n.isLeaf) {
                        if (validBody(n.body)) {
                            u.bodies.push_back(n.body);
                            bodiesToResolve.push_back(n.body);
                            inCsg[static_cast<std::size_t>(n.body)] = 1;
                        }
                    } else {
                        for (int c : n.children) stack.push_back(c);
                    }
                }
                units.push_back(u);
                ++csgUnits;
            }
        }

        // The complexity guard (overlap_guard.h): solids in cells of too many overlapping
        // bodies go to raycast through the render context.
        RenderStats stats;
        const OverlapReport overlap =
            OverloadedSolids(units, width, height, static_cast<int>(options.Int("max-overlap")));
        const std::size_t maxLiterals = static_cast<std::size_t>(options.Int("max-literals"));
        std::vector<char> drop(scene.solids.size(), 0);
        for (const Unit& u : units) {
            std::size_t most = 0;
            if (u.kind == Unit::Kind::kBody)
                most = scene.bodies[static_cast<std::size_t>(u.body)].literals.size();
            else
                for (int b : u.bodies)
                    most =
                        std::max(most, scene.bodies[static_cast<std::size_t>(b)].literals.size());
            if (most <= maxLiterals || drop[static_cast<std::size_t>(u.solid)]) continue;
            drop[static_cast<std::size_t>(u.solid)] = 1;
            stats.undrawn.push_back(
                {u.solid, fmt::format("a body of {} literals (max-literals={}: the Resolver's "
                                      "i-vertices cost ~literals^3)",
                                      most, maxLiterals)});
        }
        for (int s : overlap.solids) {
            if (drop[static_cast<std::size_t>(s)]) continue;
            drop[static_cast<std::size_t>(s)] = 1;
            stats.undrawn.push_back(
                {s, fmt::format("bodies overlapping up to {} deep in one 8x8-pixel cell "
                                "(max-overlap={}: the face stacks cost ~depth^3)",
                                overlap.maxDepth, options.Int("max-overlap"))});
        }
        if (!stats.undrawn.empty()) {
            std::vector<Unit> kept;
            bodiesToResolve.clear();
            for (Unit& u : units) {
                if (drop[static_cast<std::size_t>(u.solid)]) continue;
                if (u.kind == Unit::Kind::kBody)
                    bodiesToResolve.push_back(u.body);
                else
                    bodiesToResolve.insert(bodiesToResolve.end(), u.bodies.begin(), u.bodies.end());
                kept.push_back(std::move(u));
            }
            units = std::move(kept);
        }

        // Resolver.
        ResolverCounters rc;
        std::vector<ShowFace> faces;
        std::vector<ShowEdge> edges;
        std::vector<ResolvedBody> resolved(scene.bodies.size());
        std::vector<bool> done(scene.bodies.size(), false), pixelBody(scene.bodies.size(), false);
        for (int b : bodiesToResolve) {
            auto k = static_cast<std::size_t>(b);
            if (done[k]) continue;
            done[k] = true;
            ResolveBody(scene, b, 0.0, static_cast<double>(height), inCsg[k] != 0, resolved[k],
                        faces, edges, rc);
            pixelBody[k] = resolved[k].perPixel;
        }
        const auto t1 = Clock::now();

        // Face-stack bodies: those drawn on their own (not CSG operands) and not refused.
        std::vector<bool> stackBody(scene.bodies.size(), false);
        std::uint64_t stackBodies = 0;
        for (const Unit& u : units) {
            if (u.kind != Unit::Kind::kBody) continue;
            auto k = static_cast<std::size_t>(u.body);
            if (pixelBody[k] || inCsg[k] || stackBody[k]) continue;
            stackBody[k] = true;
            ++stackBodies;
        }
        RendererCounters c;
        RenderScanlines(scene, edges, faces, units, pixelBody, stackBody, settings, frame, c);
        const auto t2 = Clock::now();

        stats.seconds = Seconds(t0, t2);
        CounterValues counters(kScanlineCounters);
        std::uint64_t perPixelBodies = 0;
        for (std::size_t b = 0; b < pixelBody.size(); ++b) perPixelBodies += pixelBody[b];
        counters.Set(kBodies, static_cast<double>(bodiesToResolve.size()));
        counters.Set(kHsbsPlanar, static_cast<double>(rc.planarHsbs));
        counters.Set(kHsbsQuadric, static_cast<double>(rc.quadricHsbs));
        counters.Set(kShowFaces, static_cast<double>(rc.faces));
        for (std::size_t t = 0; t < 6; ++t) counters.Set(kIlinesNoexist + t, rc.ilines[t]);
        counters.Set(kIverticesCalculated, static_cast<double>(rc.verticesCalculated));
        counters.Set(kIverticesKept, static_cast<double>(rc.verticesKept));
        for (std::size_t t = 0; t < 4; ++t)
            counters.Set(kIverticesHextrm + t, rc.verticesByType[t]);
        counters.Set(kShowEdgesLinear, static_cast<double>(rc.edgesLinear));
        counters.Set(kShowEdgesHorizontal, static_cast<double>(rc.edgesHorizontal));
        counters.Set(kShowEdgesConic, static_cast<double>(rc.edgesConic));
        counters.Set(kPerPixelBodies, static_cast<double>(perPixelBodies));
        counters.Set(kCsgSolids, static_cast<double>(csgUnits));
        counters.Set(kCsgPixels, static_cast<double>(c.csgPixels));
        counters.Set(kCsgTemplateBodies, static_cast<double>(c.csgTemplateBodies));
        counters.Set(kCsgTemplateReuses, static_cast<double>(c.csgTemplateReuses));
        counters.Set(kCsgExactFallbackPixels, static_cast<double>(c.csgFallbackPixels));
        counters.Set(kEdgesStarted, static_cast<double>(c.edgesStarted));
        counters.Set(kEdgeSwaps, static_cast<double>(c.edgeSwaps));
        counters.Set(kSpans, static_cast<double>(c.spans));
        counters.Set(kEmptySpans, static_cast<double>(c.emptySpans));
        counters.Set(kFaceInserts, static_cast<double>(c.faceInserts));
        counters.Set(kDepthCalculations, static_cast<double>(c.depthCalcs));
        counters.Set(kTieBreaks, static_cast<double>(c.tieBreaks));
        counters.Set(kSpanSampleEvaluations, static_cast<double>(c.sampleEvaluations));
        counters.Set(kRowSideEvaluations, static_cast<double>(c.sideEvaluations));
        counters.Set(kExactPixels, static_cast<double>(c.exactPixels));
        counters.Set(kRootFallbackPixels, static_cast<double>(c.rootFallbackPixels));
        counters.Set(kPerPixelUnitEvaluations, static_cast<double>(c.perPixelUnitPixels));
        counters.Set(kIntensityCalculations, static_cast<double>(c.normals));
        counters.Set(kPixels, static_cast<double>(width) * height);
        counters.Set(kCoveredPixels, static_cast<double>(c.covered));
        counters.Set(kFaceStackBodies, static_cast<double>(settings.faceStacks ? stackBodies : 0));
        counters.Set(kFaceStackInserts, static_cast<double>(c.stackInserts));
        counters.Set(kFaceStackDeletes, static_cast<double>(c.stackDeletes));
        counters.Set(kFaceStackMaxDepth, static_cast<double>(c.stackMaxDepth));
        counters.Set(kFaceStackMeanDepth,
                     c.stackSpans ? static_cast<double>(c.stackDepthSum) / c.stackSpans : 0.0);
        counters.Set(kFaceStackSpans, static_cast<double>(c.stackSpans));
        counters.Set(kFaceStackSeedEvaluations, static_cast<double>(c.stackSeedEvaluations));
        counters.Set(kFaceStackTieBreaks, static_cast<double>(c.stackTieBreaks));
        counters.Set(kFaceStackCorrections, static_cast<double>(c.stackCorrections));
        counters.Set(kFaceStackRepairs, static_cast<double>(c.stackRepairs));
        counters.Set(kFaceStackClosedRowFaces, static_cast<double>(c.closedRowFaces));
        counters.Set(kFaceStackOrderCorrections, static_cast<double>(c.stackOrderCorrections));
        counters.Set(kFaceStackSwapUpdates, static_cast<double>(c.stackSwapUpdates));
        counters.Set(kFaceStackDerivations, static_cast<double>(c.stackDerivations));
        counters.Set(kFaceStackDerivationsChanged, static_cast<double>(c.stackDerivationsChanged));
        counters.Set(kFaceStackDeriveInserts, static_cast<double>(c.stackDeriveInserts));
        counters.Set(kFaceStackDeriveDeletes, static_cast<double>(c.stackDeriveDeletes));
        counters.Set(kFaceStackVertices, static_cast<double>(c.stackVertices));
        counters.Set(kFaceStackVertexRecursions, static_cast<double>(c.stackVertexRecursions));
        counters.Set(kFaceStackDeletionSwaps, static_cast<double>(c.stackDeletionSwaps));
        counters.Set(kFaceStackVertexFallbacks, static_cast<double>(c.stackVertexFallbacks));
        counters.Set(kFaceStackRebuilds, static_cast<double>(c.stackRebuilds));
        counters.Set(kInterpenetrationPixels, static_cast<double>(c.interpenetrationPixels));
        counters.Set(kOverlapMaxDepth, static_cast<double>(overlap.maxDepth));
        counters.Set(kOverlapSolidsToRaycast, static_cast<double>(overlap.solids.size()));
        counters.Set(kSolidsToRaycast, static_cast<double>(stats.undrawn.size()));
        if (settings.verify) {
            counters.Set(kVerifySpans, static_cast<double>(c.verifySpans));
            counters.Set(kVerifyMismatchSpans, static_cast<double>(c.verifyMismatchSpans));
            counters.Set(kVerifyBodyFaces, static_cast<double>(c.verifyBodies));
            counters.Set(kVerifyBodyFaceMismatches, static_cast<double>(c.verifyBodyMismatches));
        }
        counters.Set(kResolverSeconds, Seconds(t0, t1));
        counters.Set(kRendererShaderSeconds, Seconds(t1, t2));
        counters.AppendTo(stats.counters);

        // The paper's tables (7.1–7.3), one row for this image; the report formats them.
        using C = StatsCell;
        StatsTable resolver{
            "Table 7.1 - Resolver statistics",
            {"Bodies", "HSBs\nplanar", "HSBs\nquadric", "Ivertices\ncalc", "Ivertices\nkept",
             "ShowEdges\nlinear", "ShowEdges\nconic"},
            {{C::Integer(bodiesToResolve.size()), C::Integer(rc.planarHsbs),
              C::Integer(rc.quadricHsbs), C::Integer(rc.verticesCalculated),
              C::Integer(rc.verticesKept), C::Integer(rc.edgesLinear), C::Integer(rc.edgesConic)}},
            {}};
        // Face inserts: into the edges' carried face stacks (§5.3, §5.4: at vertices, after
        // swaps, and the verifier's corrections) plus the per-span inserts of bodies evaluated
        // exactly (render=exact, CSG operands, refused bodies); deletes from the carried stacks.
        StatsTable renderer{
            "Table 7.2 - Renderer statistics",
            {"DepthCalc", "FaceInsert", "FaceDelete", "EdgeSwaps", "Spans", "MaxStack", "MeanStack",
             "Intensities", "Pixels(k)"},
            {{C::Integer(c.depthCalcs), C::Integer(c.stackDeriveInserts + c.faceInserts),
              C::Integer(c.stackDeriveDeletes), C::Integer(c.edgeSwaps), C::Integer(c.spans),
              C::Integer(c.stackMaxDepth),
              C::Real(c.stackSpans ? static_cast<double>(c.stackDepthSum) / c.stackSpans : 0.0, 2),
              C::Integer(c.normals), C::Real(width * static_cast<double>(height) / 1000, 1)}},
            {}};
        StatsTable times{"Table 7.3 - Run times (seconds)",
                         {"Resolver", "Renderer+Shader", "Total"},
                         {{C::Real(Seconds(t0, t1), 4), C::Real(Seconds(t1, t2), 4),
                           C::Real(Seconds(t0, t2), 4)}},
                         {}};
        stats.tables = {std::move(resolver), std::move(renderer), std::move(times)};
        return stats;
    }
};

}  // namespace
}  // namespace scanline

std::unique_ptr<Engine> MakeScanlineEngine() {
    return std::make_unique<scanline::ScanlineEngine>();
}

}  // namespace quadrix
