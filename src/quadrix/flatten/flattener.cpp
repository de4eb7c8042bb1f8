// The Flattener (seed 001 §3.3); the steps are listed in flattener.h. The pieces:
//   view_setup.{h,cpp}  the view → provisional device space (projection matrices, clip planes)
//   hierarchy.{h,cpp}   definitions, instances, arrays and CSG → FlatSolids (explosion guard)
//   bounds.{h,cpp}      conservative boxes of bodies, CSG nodes and solids
// This file strings them together: walk in provisional device space, add the clip planes,
// bound, fit the window (auto-fit where whh/whw are missing), map to device space with a
// uniform scale and a translation, cull solids that cannot reach the image.
//
// Window fit (window_fit.h). In provisional space x and y are view-plane coordinates centred on
// vrp (y down). whh or whw, alone or together, give the scale and centre the window on vrp; with
// neither, the bounded part of the scene's extent fills the image less autoFitMargin per side,
// and unbounded solids are drawn clipped to that window. Pixels are square. The extent ignores
// fbp (seed 001 §2.1.6: "It has no effect on auto-scaling"). Where a box came from the search,
// the fit takes a second look in its own device space (RefineFit), where the bounds are tightest.
//
// Device map: x_dev = k x + ox, y_dev = k y + oy, z_dev = k z (the same k for depth, so for
// parallel views device space is a similarity of view space up to the reflection of y, and for
// perspective dz/dn_e = k at the view plane).
//
// depthTolerance = 1e-9 × the scene's depth extent in device units (the finite z-range of all
// solids, at least max(width, height) and, for perspective, k·d, the depth from the view plane to
// infinity): coincident surfaces computed in different ways agree to far better than that.
//
// Solids whose clipped bounds are empty (behind the eye, outside the window, provably empty)
// are dropped: they cannot cover a pixel.
#include "quadrix/flatten/flattener.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <optional>
#include <span>

#include "quadrix/flatten/bounds.h"
#include "quadrix/flatten/coefficient_scale.h"
#include "quadrix/flatten/hierarchy.h"
#include "quadrix/flatten/literal_cache.h"
#include "quadrix/flatten/view_setup.h"
#include "quadrix/flatten/window_fit.h"
#include "quadrix/lang/big_arrays.h"
#include "quadrix/math/round_scaled.h"
#include "quadrix/scene/light_rig.h"
#include "quadrix/util/hash_slots.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

constexpr double kInf = HUGE_VAL;

// The search limit of the bounds: 1e6 × the scene's scale (bounds.h), the scale being the
// largest of the bodies' half-spaces' characteristic lengths, the window and the eye distance.
// (The perspective near plane, at depth -1e4 d, would inflate it for nothing.)
// In parallel: the largest of the half-spaces' scales is the same in any order (fmax).
double SceneScale(const FlatScene& flat, const ViewSetup& view, const LiteralCache& literals) {
    double s = ParallelReduce(
        tbb::blocked_range<std::size_t>(0, flat.halfSpaces.size(), 1024), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double m) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                const FlatHalfSpace& h = flat.halfSpaces[i];
                if (h.isClip || h.name == kSectionName) continue;
                const LiteralCache::Entry* e = literals.Find(&h);
                m = std::fmax(m,
                              HalfSpaceScale(h, e ? &e->box : nullptr, e ? &e->extent : nullptr));
            }
            return m;
        },
        [](double a, double b) { return std::fmax(a, b); });
    if (view.whh) s = std::fmax(s, *view.whh);
    if (view.whw) s = std::fmax(s, *view.whw);
    s = std::fmax(s, view.d);
    return s > 0 && std::isfinite(s) ? s : 1.0;
}

// Per body: the body whose box it may reuse by translation (itself: none) and the shift from
// that body to it, in provisional space (FlattenerImpl::TranslationReuse).
struct Reuse {
    std::vector<std::size_t> ref;
    std::vector<Vec3> shift;
};

// Per body: a conservative box; where `exact`, the body's own (BodyBounds); elsewhere reused by
// translation, and the body's own box lies between it shrunk and grown by `pad` per axis.
struct BodyBoxes {
    std::vector<Box3> box;
    std::vector<Vec3> pad;
    std::vector<char> exact;
    bool AllExact() const {
        for (char c : exact)
            if (!c) return false;
        return true;
    }
};

// Per body: the box of its extent pieces (hierarchy.h) grown by a rounding allowance, where
// `has` (FlattenerImpl::ExtentBoxes).
struct Extents {
    std::vector<char> has;
    std::vector<Box3> box;
};

// A literal normalised for TranslationReuse: the linear part (3 for a plane, 6 for a quadric)
// and the rest (d; b and k), all divided by the largest |entry| of the linear part; not `ok` for
// a quartic or a degenerate or non-finite one.
struct Norm {
    bool ok = false, plane = true;
    double lin[6] = {0, 0, 0, 0, 0, 0};
    double rest[4] = {0, 0, 0, 0};
};

void NormaliseLiteral(const FlatHalfSpace& hs, Norm& nm) {
    if (hs.IsQuartic()) return;
    nm.plane = hs.isPlane;
    double m = 0;
    if (hs.isPlane) {
        const double v[3] = {hs.plane.a, hs.plane.b, hs.plane.c};
        for (double x : v) m = std::fmax(m, std::fabs(x));
        if (!(m > 0) || !std::isfinite(m)) return;
        for (int k = 0; k < 3; ++k) nm.lin[k] = v[k] / m;
        nm.rest[0] = hs.plane.d / m;
    } else {
        for (int k = 0; k < 6; ++k) m = std::fmax(m, std::fabs(hs.quadric.k[k]));
        if (!(m > 0) || !std::isfinite(m)) return;
        for (int k = 0; k < 6; ++k) nm.lin[k] = hs.quadric.k[k] / m;
        for (int k = 0; k < 4; ++k) nm.rest[k] = hs.quadric.k[6 + k] / m;
    }
    nm.ok = std::isfinite(nm.rest[0]) && std::isfinite(nm.rest[1]) && std::isfinite(nm.rest[2]) &&
            std::isfinite(nm.rest[3]);
}

class FlattenerImpl {
  public:
    // `world`: the kept world stage (FlattenView), or null for a one-shot Flatten.
    FlattenerImpl(const scene::Scene& scene, const FlattenOptions& options, Diagnostics& diags,
                  const WorldScene* world, FlatScene recycle = {})
        : scene_(scene),
          options_(options),
          diags_(diags),
          world_(world),
          recycle_(std::move(recycle)) {}

    std::optional<FlatScene> Run() {
        if (!CheckOptions()) return std::nullopt;
        std::optional<scene::View> view =
            options_.view ? options_.view : scene_.ViewToUse(options_.viewName);
        if (!view) {
            diags_.Error({}, fmt::format("unknown view '{}'", options_.viewName), {},
                         "command line");
            return std::nullopt;
        }
        std::optional<ViewSetup> setup = ResolveView(*view, diags_);
        if (!setup) return std::nullopt;
        view_ = std::move(*setup);

        FlatScene& flat = flat_;
        flat.width = options_.width;
        flat.height = options_.height;
        flat.viewName = view_.id;
        flat.lights = options_.lights ? scene::Scene::WithDefaultLight(*options_.lights)
                                      : scene_.LightsToUse();
        // No light declared: the default rig, which follows the view (scene/light_rig.h).
        if (flat.lights.empty())
            flat.lights = scene::DefaultRig(view_.towardViewer, view_.u, view_.v);
        if (scene_.background) {
            flat.background = *scene_.background;
            flat.backgroundBottom = scene_.backgroundBottom.value_or(*scene_.background);
        }
        // The clip planes come first in halfSpaces: shared by every body.
        for (const Plane& p : view_.finalClips) {
            FlatHalfSpace h;
            h.isPlane = true;
            h.plane = p;
            h.transparent = true;
            h.isClip = true;
            h.name = fmt::format("clip#{}", flat.halfSpaces.size());
            flat.halfSpaces.push_back(std::move(h));
        }
        // The section plane after them, opaque; for the window fit it is one more final clip
        // plane (ignored by the fit, like fbp).
        finalPlanes_ = view_.finalClips;
        if (options_.section) {
            FlatHalfSpace h;
            h.isPlane = true;
            Plane source = *options_.section;
            RescaleCoefficients(source);
            h.plane = source.Transformed(view_.provFromWorld);
            RescaleCoefficients(h.plane);
            h.name = kSectionName;
            flat.section = *options_.section;
            flat.sectionHalfSpace = static_cast<int>(flat.halfSpaces.size());
            finalPlanes_.push_back(h.plane);
            flat.halfSpaces.push_back(std::move(h));
        }
        const int nClip = static_cast<int>(flat.halfSpaces.size());
        LiteralCacheBuilder literalBuilder;  // told by the one-shot walk (literal_cache.h)
        if (world_) {
            if (!PlaceWorld(nClip)) return std::nullopt;
        } else {
            // One-shot: the walk maps every half-space straight into provisional space (one
            // composed transform per half-space, the fewest roundings).
            HierarchyLimits limits;
            limits.clipLiteralsPerBody = nClip;
            limits.halfSpaceNames = options_.halfSpaceNames;
            // The literal cache's entries are made meanwhile on another processor, when the
            // loops may use one (not inline, util/parallel.h).
            const bool alongside = !SerialLoopsOnThisThread() && AvailableProcessors() >= 2;
            if (!FlattenHierarchy(scene_, view_.provFromWorld, limits, flat, hierarchy_, diags_,
                                  alongside ? &literalBuilder : nullptr))
                return std::nullopt;
        }
        if (flat.solids.empty() && flat.freeforms.empty()) {
            diags_.Error({},
                         "nothing to draw: the scene has no body, instance or csg solid "
                         "outside definitions that is not a CSG operand");
            return std::nullopt;
        }
        if (view_.perspective) FindSolidsAroundEye();
        for (FlatBody& b : flat.bodies)
            for (int c = 0; c < nClip; ++c) b.literals.push_back({c, false});
        // The literal lists are final from here to the culling: which bodies share one is
        // found once for every look of the bounds and the fit.
        firstSame_ = FirstWithSameLiterals(flat);

        // Stage (a) of every quadric literal once, for the scale and every body's first bounds
        // in provisional space (literal_cache.h); flat.halfSpaces stays as it is meanwhile.
        LiteralCache literals = literalBuilder.Finish(flat.halfSpaces);
        BoundsOptions bo;
        bo.searchLimit = 1e6 * SceneScale(flat, view_, literals);
        bo.literals = &literals;
        bool anySearched = false;
        const Extents extents = ExtentBoxes(nClip, literals);
        const Reuse reuse = TranslationReuse(nClip, extents);
        boxes_ = AllBodyBounds(flat, firstSame_, bo, &anySearched, &reuse, &extents);
        bodiesOf_ = BodiesOfSolids();
        solidExact_.assign(flat.solids.size(), 1);
        for (std::size_t s = 0; s < flat.solids.size(); ++s)
            for (int b : bodiesOf_[s])
                if (!boxes_.exact[static_cast<std::size_t>(b)]) solidExact_[s] = 0;
        // Boxes reused by translation hold the true ones only to within their pad: the fit
        // boxes are made from the padded boxes, and the solids that can decide the window are
        // bounded directly (SettleExtremes), so the window is the one of the direct boxes.
        std::vector<Box3> fitBoxes = FitSolidBoxes(flat, firstSame_, view_.fitClips, finalPlanes_,
                                                   view_.perspective ? view_.d : 0.0, view_.fitNear,
                                                   PaddedBoxes(true), bo, &passesEye_);
        auto makeExact = [&](const std::vector<std::size_t>& which) {
            MakeSolidsExact(which, bo);
            RefitSolids(which, bo, fitBoxes);
        };
        const bool autoFit = !view_.whw && !view_.whh;
        if (autoFit && !boxes_.AllExact()) SettleExtremes(fitBoxes, solidExact_, makeExact);
        // The few bodies bounded again from here on (a solid settled by the fit's second look or
        // the culling) do without the cache: its memory (about 200 bytes a quadric) goes back to
        // the heap for the second look's arrays, which would otherwise be fresh pages.
        bo.literals = nullptr;
        literals = LiteralCache{};
        // Freeform surfaces take part in the fit through the hull of their control points in
        // provisional space (exact image of the surface, conservative bounds).
        for (const FlatFreeform& f : flat.freeforms) {
            Box3 b = f.surface.Transformed(view_.provFromWorld.Matrix()).Bounds();
            fitBoxes.push_back(b);
            hierarchy_.solidLocs.push_back({});
            hierarchy_.solidIsCsg.push_back(false);
            freeformNames_.push_back(f.name);
        }

        std::optional<WindowFit> fit = Fit(fitBoxes);
        if (!fit) return std::nullopt;
        WarnAboutSolidsAroundEye();
        if (autoFit && anySearched)
            RefineFit(*fit, fitBoxes, solidExact_,
                      [&](const std::vector<std::size_t>& which, std::vector<Box3>& firstBoxes,
                          std::vector<char>& firstKnown) {
                          makeExact(which);
                          for (std::size_t s : which) {
                              firstBoxes[s] = fitBoxes[s];
                              firstKnown[s] = 1;
                          }
                      });
        if (!boxes_.AllExact()) SettleCulling(*fit, bo);
        ToDevice(*fit, boxes_.box);
        Cull();
        SetDepthTolerance(*fit);
        return std::move(flat_);
    }

  private:
    // The world stage into provisional space, after the nClip shared planes already in
    // flat_.halfSpaces: every half-space mapped by provFromWorld and rescaled (as the walk maps
    // and rescales from object to world space), every literal shifted by nClip. false with an
    // error when a half-space's coefficients overflow under the view.
    bool PlaceWorld(int nClip) {
        FlatScene& flat = flat_;
        const WorldScene& world = *world_;
        const std::size_t nWorld = world.flat.halfSpaces.size();
        const auto clip = static_cast<std::size_t>(nClip);
        // Each half-space, body and node on its own (copies and maps of the kept world stage,
        // each a function of its own element): in parallel, in arrays sized first, over the
        // elements of the recycled scene where there is one (FlattenView).
        std::vector<FlatHalfSpace> halfSpaces = std::move(recycle_.halfSpaces);
        halfSpaces.resize(clip + nWorld);
        for (std::size_t k = 0; k < clip; ++k) halfSpaces[k] = std::move(flat.halfSpaces[k]);
        flat.halfSpaces.swap(halfSpaces);
        std::vector<char> finite(nWorld, 1);
        ParallelFor(tbb::blocked_range<std::size_t>(0, nWorld, 512),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                            FlatHalfSpace& h = flat.halfSpaces[clip + i];
                            h = world.flat.halfSpaces[i];
                            if (h.IsQuartic()) {
                                h.TransformBy(view_.provFromWorld);
                                finite[i] = h.quartic->AllFinite();
                            } else if (h.isPlane) {
                                h.plane = h.plane.Transformed(view_.provFromWorld);
                                RescaleCoefficients(h.plane);
                                finite[i] = h.plane.AllFinite();
                            } else {
                                h.quadric = h.quadric.Transformed(view_.provFromWorld);
                                RescaleCoefficients(h.quadric);
                                finite[i] = h.quadric.AllFinite();
                            }
                        }
                    });
        // The first half-space that overflows is the one named.
        for (std::size_t i = 0; i < nWorld; ++i) {
            if (finite[i]) continue;
            diags_.Error(
                i < world.hierarchy.halfSpaceLocs.size() ? world.hierarchy.halfSpaceLocs[i]
                                                         : SourceLoc{},
                fmt::format("half-space '{}' has non-finite coefficients after its transforms and "
                            "the view transformation",
                            flat.halfSpaces[clip + i].name));
            return false;
        }
        // The bodies' boxes from their extents (FlattenHierarchy), in provisional space where
        // the map there is affine (parallel views).
        const Mat4& m = view_.provFromWorld.Matrix();
        const std::size_t nBodies = world.flat.bodies.size();
        const bool affine = IsAffine(m) && world.hierarchy.bodyExtents.size() == nBodies;
        flat.bodies = std::move(recycle_.bodies);
        flat.bodies.resize(nBodies);
        ParallelFor(tbb::blocked_range<std::size_t>(0, nBodies, 512),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                            FlatBody& b = flat.bodies[i];
                            b = world.flat.bodies[i];
                            Box3 box = Box3::Everything();
                            if (affine) {
                                const HierarchyResult::ExtentRange& range =
                                    world.hierarchy.bodyExtents[i];
                                if (range.begin != range.end) box = Box3{};
                                for (std::uint32_t k = range.begin; k < range.end; ++k)
                                    box.Extend(PieceBox(world.hierarchy.extentPieces[k], m));
                            }
                            b.bounds = box;
                            for (FlatLiteral& l : b.literals) l.halfSpace += nClip;
                        }
                    });
        flat.nodes = std::move(recycle_.nodes);
        flat.nodes.resize(world.flat.nodes.size());
        ParallelFor(tbb::blocked_range<std::size_t>(0, flat.nodes.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i)
                            flat.nodes[i] = world.flat.nodes[i];
                    });
        flat.solids = std::move(recycle_.solids);
        flat.solids = world.flat.solids;
        flat.freeforms = world.flat.freeforms;
        recycle_ = FlatScene{};
        hierarchy_.solidLocs = world.hierarchy.solidLocs;  // what the messages use
        hierarchy_.solidIsCsg = world.hierarchy.solidIsCsg;
        return true;
    }

    bool CheckOptions() {
        bool ok = true;
        if (options_.width < 1 || options_.height < 1) {
            diags_.Error({},
                         fmt::format("image size {}x{}: both sides must be at least 1",
                                     options_.width, options_.height),
                         {}, "command line");
            ok = false;
        }
        if (!(options_.autoFitMargin >= 0 && options_.autoFitMargin < 0.5)) {
            diags_.Error(
                {}, fmt::format("auto-fit margin {} must be in [0, 0.5)", options_.autoFitMargin),
                {}, "command line");
            ok = false;
        }
        if (options_.section &&
            (!options_.section->AllFinite() || options_.section->IsZeroNormal())) {
            const Plane& p = *options_.section;
            diags_.Error({},
                         fmt::format("section plane <{} {} {} {}>: the coefficients must be "
                                     "finite and (A, B, C) not zero",
                                     p.a, p.b, p.c, p.d),
                         {}, "command line");
            ok = false;
        }
        return ok;
    }

    // For each body, the first body with the same literal list (itself when there is none
    // before it). A body named by several CSG operands (the drill of ∪(sphereᵢ − drill)) is one
    // FlatBody per reference over the same half-spaces, and a body's box is a pure function of
    // its literals: it is computed once per distinct list and copied, which changes no bit.
    // Lists are matched by a hash and then compared (HashSlots: each earlier list under the same
    // hash is a candidate).
    static std::vector<std::size_t> FirstWithSameLiterals(const FlatScene& flat) {
        const std::size_t n = flat.bodies.size();
        std::vector<std::size_t> first(n);
        HashSlots byHash(n);
        for (std::size_t i = 0; i < n; ++i) {
            const auto& b = flat.bodies[i].literals;
            std::uint64_t h = 1469598103934665603ull;
            for (const FlatLiteral& l : b)
                h = (h ^ (static_cast<std::uint64_t>(l.halfSpace) * 2 + l.complemented)) *
                    1099511628211ull;
            const int found = byHash.Find(h, [&](int j) {
                const auto& a = flat.bodies[static_cast<std::size_t>(j)].literals;
                if (a.size() != b.size()) return false;
                for (std::size_t k = 0; k < a.size(); ++k)
                    if (a[k].halfSpace != b[k].halfSpace || a[k].complemented != b[k].complemented)
                        return false;
                return true;
            });
            if (found >= 0) {
                first[i] = static_cast<std::size_t>(found);
            } else {
                first[i] = i;
                byHash.Insert(h, static_cast<int>(i));
            }
        }
        return first;
    }

    // Every body's box. Bodies in parallel: each box depends only on its body's literals
    // (BodyBounds is a pure function), so the result is the same for any thread count, and
    // bodies with the same literals share one computation (FirstWithSameLiterals). Mitered pipes
    // and other bodies of oblique planes cost milliseconds each (branch and bound, bounds.h).
    // `anySearched` is set when some box was not exact from the analytic stage.
    //
    // Bounds reused by translation (`reuse`, TranslationReuse): a body that is a translate of an
    // earlier one by t gets the earlier one's box moved by t when that box came from the exact
    // stages (analytic, polytope vertices or critical points: within kTight of the true extremes,
    // bounds.h; not a critical-point box tight only within a nappe's neck allowance) and lies
    // well inside the search region. The box moved by t holds the translate
    // of the earlier body exactly (rounded outward); the body's own coefficients are that
    // translate to rounding (two transforms of one statement with one linear part). The body's
    // own box would differ from it by the two certificates' allowances, at most kTightNappe =
    // 1e-5 × (size + |coordinate|) each: `pad` (2e-5 of that) bounds the difference, and the
    // window fit and the culling use it to decide which solids to bound directly after all.
    // A body with an extent box (`extents`, ExtentBoxes) takes it the same way, with the same pad.
    static BodyBoxes AllBodyBounds(const FlatScene& flat, const std::vector<std::size_t>& first,
                                   const BoundsOptions& bo, bool* anySearched,
                                   const Reuse* reuse = nullptr, const Extents* extents = nullptr) {
        const std::size_t n = first.size();
        BodyBoxes out;
        out.box.resize(n);
        out.pad.assign(n, Vec3{0, 0, 0});
        out.exact.assign(n, 1);
        std::vector<char> searched(n, 0), tight(n, 0), done(n, 0);
        auto direct = [&](const std::vector<std::size_t>& which) {
            ParallelFor(tbb::blocked_range<std::size_t>(0, which.size(), 8),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                            for (std::size_t j = r.begin(); j < r.end(); ++j) {
                                const std::size_t i = which[j];
                                BoundsStats st;
                                out.box[i] = BodyBounds(flat, flat.bodies[i], bo, &st);
                                searched[i] = st.analyticOnly == 0;
                                tight[i] = st.convexSolves == 0 && st.boxesPopped == 0 &&
                                           st.neckWideBoxes == 0;
                                done[i] = 1;
                            }
                        });
        };
        auto refOf = [&](std::size_t i) { return reuse ? reuse->ref[i] : i; };
        const double inside = 1e-4 * bo.searchLimit;
        // A body's extent box (ExtentBoxes) holds its true box to rounding (the pieces and the
        // literals are one placement of one shape): like a translated box it stands for the
        // body's own within `pad`, where it lies well inside the search region.
        auto fromExtent = [&](std::size_t i) {
            if (!extents || extents->has.empty() || !extents->has[i]) return false;
            const Box3& eb = extents->box[i];
            if (!eb.Finite()) return false;
            Vec3 pad;
            for (int a = 0; a < 3; ++a) {
                const double reach = std::fmax(std::fabs(eb.lo[a]), std::fabs(eb.hi[a]));
                if (!(reach < inside)) return false;
                pad[a] = 2e-5 * ((eb.hi[a] - eb.lo[a]) + reach);
            }
            out.box[i] = eb;
            out.pad[i] = pad;
            out.exact[i] = 0;
            done[i] = 1;
            return true;
        };
        std::vector<std::size_t> own, later;
        for (std::size_t i = 0; i < n; ++i)
            if (first[i] == i && !fromExtent(i)) (refOf(i) == i ? own : later).push_back(i);
        direct(own);
        std::vector<std::size_t> fallback;
        for (std::size_t i : later) {
            const std::size_t r = first[refOf(i)];
            const Box3& rb = out.box[r];
            bool ok = done[r] && tight[r] && rb.Finite();
            Box3 moved;
            Vec3 pad;
            for (int a = 0; ok && a < 3; ++a) {
                const double t = reuse->shift[i][a];
                double lo = rb.lo[a] + t, hi = rb.hi[a] + t;
                lo -= 4e-16 * (std::fabs(rb.lo[a]) + std::fabs(t)) + 1e-300;
                hi += 4e-16 * (std::fabs(rb.hi[a]) + std::fabs(t)) + 1e-300;
                const double reach = std::fmax(std::fmax(std::fabs(rb.lo[a]), std::fabs(rb.hi[a])),
                                               std::fmax(std::fabs(lo), std::fabs(hi)));
                ok = std::isfinite(t) && reach < inside;
                moved.lo[a] = lo;
                moved.hi[a] = hi;
                pad[a] = 2e-5 * ((rb.hi[a] - rb.lo[a]) + reach);
            }
            if (!ok) {
                fallback.push_back(i);
                continue;
            }
            out.box[i] = moved;
            out.pad[i] = pad;
            out.exact[i] = 0;
            searched[i] = searched[r];
        }
        direct(fallback);
        for (std::size_t i = 0; i < n; ++i)
            if (first[i] != i) {
                out.box[i] = out.box[first[i]];
                out.pad[i] = out.pad[first[i]];
                out.exact[i] = out.exact[first[i]];
                searched[i] = searched[first[i]];
            }
        if (anySearched)
            for (char c : searched) *anySearched |= c != 0;
        return out;
    }

    // Whether a box that is not a body's own (moved from a translate, TranslationReuse, or made
    // from its extent, ExtentBoxes) may stand in for it: only where a translation of the world is
    // one of provisional space and the body's literals are its own, parallel views without clip,
    // fit or section planes (those are not moved with the body and cut it smaller than its
    // extent), and with more than a few solids: such a box only saves work for a solid that does
    // not reach the window's edge, one that may is bounded directly anyway (SettleExtremes), and
    // with at most six solids each may hold one of the six extremes (a union of 100,000 spheres
    // is one solid), so the search is skipped; the flat scene is the same either way.
    bool BoxesMayStandIn(int nClip) const {
        constexpr std::size_t kFewSolids = 6;
        return !view_.perspective && nClip == 0 && view_.fitClips.empty() &&
               flat_.solids.size() > kFewSolids;
    }

    // Per body, the box of its extent pieces (hierarchy.h: an imported primitive's exact image
    // under its placement and the view), where the body has them: grown per axis by 1e-9 of its
    // size and reach, far above the roundings of the pieces' and the literals' coefficients
    // (each a few ulps of one affine map of one shape) and far below the pad that the window
    // fit and the culling allow a box that is not the body's own (AllBodyBounds). Where such a
    // box may stand in (BoxesMayStandIn).
    //
    // The fit and the culling take the body's own box to lie within `pad` of this one (it holds
    // the true box, as the body's own box does, within kTight = 1e-7 of it where that is
    // certified tight). Where the body's own box could be looser, a body with a quartic or a
    // complemented quadric, or a quadric with a clearly negative eigenvalue (a cone's nappes,
    // whose certificate may be as loose as the convex relaxation's, bounds_internal.h), it is
    // bounded directly. (Were another certificate loose too, the window would be the one of a
    // box that still holds the solid, tighter than that certificate's, never cutting it.)
    Extents ExtentBoxes(int nClip, const LiteralCache& literals) const {
        Extents e;
        const std::size_t n = flat_.bodies.size();
        if (!options_.boundsFromExtents || !BoxesMayStandIn(nClip)) return e;
        e.has.assign(n, 0);
        e.box.resize(n);
        // Bodies in parallel: each box is its own body's.
        ParallelFor(tbb::blocked_range<std::size_t>(0, n, 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) ExtentBox(i, literals, e);
                    });
        return e;
    }

    // ExtentBoxes' entry for body i.
    void ExtentBox(std::size_t i, const LiteralCache& literals, Extents& e) const {
        Box3 box = flat_.bodies[i].bounds;  // FlattenHierarchy, PlaceWorld
        if (!box.Finite()) return;
        bool tight = true;
        for (const FlatLiteral& l : flat_.bodies[i].literals) {
            const FlatHalfSpace& h = flat_.halfSpaces[static_cast<std::size_t>(l.halfSpace)];
            if (!h.IsQuartic() && h.isPlane) continue;
            const LiteralCache::Entry* entry =
                h.IsQuartic() || l.complemented ? nullptr : literals.Find(&h);
            const double big =
                entry ? std::fmax(std::fabs(entry->fn.lamMin), std::fabs(entry->fn.lamMax)) : 0.0;
            tight = tight && entry && entry->fn.lamMin >= -1e-9 * big;
        }
        if (!tight) return;
        for (int a = 0; a < 3; ++a) {
            const double grow = 1e-9 * ((box.hi[a] - box.lo[a]) +
                                        std::fmax(std::fabs(box.lo[a]), std::fabs(box.hi[a])));
            box.lo[a] -= grow;
            box.hi[a] += grow;
        }
        e.box[i] = box;
        e.has[i] = 1;
    }

    // Which bodies are translates of an earlier one (AllBodyBounds), read from the coefficients
    // (an imported model places every primitive instance in the top scope with its path matrix
    // applied, so the hierarchy does not say). Bodies are grouped by their literals' kinds,
    // complements and linear parts (a plane's normal, a quadric's A) divided by their largest
    // entry, which agree to rounding for two placements of one primitive with one rotation
    // (A' = L⁻ᵀAL⁻¹ does not involve the translation; the importer's normalisation by the
    // largest coefficient does, in the last bits), so they are matched to 1e-12 and hashed on a
    // grid (a pair split by a grid line is only not shared). Within a group the shift t is the
    // least-squares solution of the translated literals' equations (a plane: n·t = d - d'; a
    // quadric: A t = b - b', with f(x) = xᵀAx + 2bᵀx + k), and the body counts as the translate
    // only when every coefficient of every literal matches its reference's moved by t to 1e-12 of
    // the terms' magnitude (and t is determined: the normals span space). Only where a translation
    // of the world is one of provisional space and moves every literal: parallel views without clip
    // or section planes (those are not moved with the body). Elsewhere every body is its own
    // reference.
    Reuse TranslationReuse(int nClip, const Extents& extents) const {
        const std::size_t n = flat_.bodies.size();
        Reuse r;
        r.ref.resize(n);
        for (std::size_t i = 0; i < n; ++i) r.ref[i] = i;
        r.shift.assign(n, Vec3{0, 0, 0});
        if (!options_.reuseBoundsByTranslation || !BoxesMayStandIn(nClip)) return r;
        // Bodies bounded from their extents (ExtentBoxes) take no part: only the half-spaces
        // of the others are normalised.
        auto byExtent = [&](std::size_t i) { return !extents.has.empty() && extents.has[i]; };
        std::vector<char> used(flat_.halfSpaces.size(), 0);
        bool any = false;
        for (std::size_t i = 0; i < n; ++i)
            if (!byExtent(i))
                for (const FlatLiteral& l : flat_.bodies[i].literals) {
                    used[static_cast<std::size_t>(l.halfSpace)] = 1;
                    any = true;
                }
        if (!any) return r;
        // Per half-space, in parallel (a pure function of its coefficients); big lists in huge
        // pages (lang/big_arrays.h).
        std::vector<Norm> norms;
        lang::ReserveAdvised(norms, flat_.halfSpaces.size());
        norms.resize(flat_.halfSpaces.size());
        ParallelFor(tbb::blocked_range<std::size_t>(0, norms.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t h = range.begin(); h < range.end(); ++h)
                            if (used[h]) NormaliseLiteral(flat_.halfSpaces[h], norms[h]);
                    });
        // A x for the normalised A of a quadric (lin: A B C D E F).
        auto mulA = [](const double* q, const Vec3& x) {
            return Vec3{q[0] * x.x + q[3] * x.y + q[5] * x.z, q[3] * x.x + q[1] * x.y + q[4] * x.z,
                        q[5] * x.x + q[4] * x.y + q[2] * x.z};
        };
        // The shift taking body `ref` to body `i` (same group), or nullopt.
        auto shiftOf = [&](std::size_t ref, std::size_t i) -> std::optional<Vec3> {
            const auto& la = flat_.bodies[ref].literals;
            const auto& lb = flat_.bodies[i].literals;
            double g[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, h[3] = {0, 0, 0};
            auto row = [&](const Vec3& rv, double rhs) {
                const double v[3] = {rv.x, rv.y, rv.z};
                for (int p = 0; p < 3; ++p) {
                    for (int q = 0; q < 3; ++q) g[p][q] += v[p] * v[q];
                    h[p] += v[p] * rhs;
                }
            };
            for (std::size_t l = 0; l < la.size(); ++l) {
                const Norm& x = norms[static_cast<std::size_t>(la[l].halfSpace)];
                const Norm& y = norms[static_cast<std::size_t>(lb[l].halfSpace)];
                if (x.plane) {
                    row({x.lin[0], x.lin[1], x.lin[2]}, x.rest[0] - y.rest[0]);
                } else {
                    row({x.lin[0], x.lin[3], x.lin[5]}, x.rest[0] - y.rest[0]);
                    row({x.lin[3], x.lin[1], x.lin[4]}, x.rest[1] - y.rest[1]);
                    row({x.lin[5], x.lin[4], x.lin[2]}, x.rest[2] - y.rest[2]);
                }
            }
            const Vec3 c0{g[0][0], g[1][0], g[2][0]}, c1{g[0][1], g[1][1], g[2][1]},
                c2{g[0][2], g[1][2], g[2][2]};
            const double det = Dot(c0, Cross(c1, c2));
            const double scale = g[0][0] + g[1][1] + g[2][2];
            if (!(std::fabs(det) > 1e-9 * scale * scale * scale)) return std::nullopt;
            const Vec3 hv{h[0], h[1], h[2]};
            const Vec3 t{Dot(hv, Cross(c1, c2)) / det, Dot(c0, Cross(hv, c2)) / det,
                         Dot(c0, Cross(c1, hv)) / det};
            if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)))
                return std::nullopt;
            constexpr double kMatch = 1e-12;
            auto close = [](double a, double b, double mag) {
                return std::fabs(a - b) <= kMatch * mag;
            };
            for (std::size_t l = 0; l < la.size(); ++l) {
                const Norm& x = norms[static_cast<std::size_t>(la[l].halfSpace)];
                const Norm& y = norms[static_cast<std::size_t>(lb[l].halfSpace)];
                if (x.plane) {
                    // d' = d - n·t
                    const double nt = x.lin[0] * t.x + x.lin[1] * t.y + x.lin[2] * t.z;
                    if (!close(y.rest[0], x.rest[0] - nt,
                               std::fabs(x.rest[0]) + std::fabs(y.rest[0]) + std::fabs(nt)))
                        return std::nullopt;
                } else {
                    // b' = b - A t, k' = k - 2 b·t + tᵀA t
                    const Vec3 at = mulA(x.lin, t);
                    const double bv[3] = {x.rest[0], x.rest[1], x.rest[2]};
                    const double atv[3] = {at.x, at.y, at.z};
                    for (int k = 0; k < 3; ++k)
                        if (!close(y.rest[k], bv[k] - atv[k],
                                   std::fabs(bv[k]) + std::fabs(y.rest[k]) + std::fabs(atv[k])))
                            return std::nullopt;
                    const double bt = bv[0] * t.x + bv[1] * t.y + bv[2] * t.z;
                    const double tat = Dot(t, at);
                    if (!close(y.rest[3], x.rest[3] - 2 * bt + tat,
                               std::fabs(x.rest[3]) + std::fabs(y.rest[3]) + 2 * std::fabs(bt) +
                                   std::fabs(tat)))
                        return std::nullopt;
                }
            }
            return t;
        };
        // Each body's group key (in parallel), then the groups in body order.
        std::vector<std::uint64_t> keys(n);
        std::vector<char> keyed(n);
        ParallelFor(tbb::blocked_range<std::size_t>(0, n, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                            const auto& lits = flat_.bodies[i].literals;
                            bool ok = !lits.empty() && !byExtent(i);
                            std::uint64_t key = 1469598103934665603ull;
                            auto mix = [&](std::uint64_t v) { key = (key ^ v) * 1099511628211ull; };
                            for (const FlatLiteral& l : lits) {
                                const Norm& nm = norms[static_cast<std::size_t>(l.halfSpace)];
                                ok = ok && nm.ok;
                                mix(static_cast<std::uint64_t>(nm.plane) * 2 + l.complemented);
                                // Hashed on a grid of 2^-36 (the entries are in [-1, 1]); matched
                                // to 1e-12 below.
                                for (int k = 0; k < (nm.plane ? 3 : 6); ++k)
                                    mix(static_cast<std::uint64_t>(RoundScaled<36>(nm.lin[k])));
                            }
                            keys[i] = key;
                            keyed[i] = ok;
                        }
                    });
        // Body i is matched against the first kCandidates bodies of its group that were not
        // matched themselves (in body order). Once a group has that many, its candidates are
        // fixed: the later bodies of the group are matched afterwards, in parallel, against the
        // same candidates as in body order (a matched body never becomes a candidate, and one
        // past the first kCandidates never is one), so the result is the same.
        constexpr std::size_t kCandidates = 4;
        // A group's candidates (HashSlots holds the index of each key's group).
        struct Group {
            std::size_t size = 0;
            std::size_t at[kCandidates];
        };
        auto match = [&](std::size_t i, const Group& group) {
            const auto& lits = flat_.bodies[i].literals;
            for (std::size_t c = 0; c < group.size; ++c) {
                const std::size_t j = group.at[c];
                const auto& lj = flat_.bodies[j].literals;
                bool same = lj.size() == lits.size();
                for (std::size_t l = 0; same && l < lits.size(); ++l) {
                    const Norm& x = norms[static_cast<std::size_t>(lj[l].halfSpace)];
                    const Norm& y = norms[static_cast<std::size_t>(lits[l].halfSpace)];
                    same = x.plane == y.plane && lj[l].complemented == lits[l].complemented;
                    for (int k = 0; same && k < 6; ++k)
                        same = std::fabs(x.lin[k] - y.lin[k]) <= 1e-12;
                }
                if (!same) continue;
                if (std::optional<Vec3> t = shiftOf(j, i)) {
                    r.ref[i] = j;
                    r.shift[i] = *t;
                    return;
                }
            }
        };
        HashSlots byKey(n);
        std::vector<Group> groups;
        std::vector<std::pair<std::size_t, int>> later;  // (body, its group)
        for (std::size_t i = 0; i < n; ++i) {
            if (!keyed[i]) continue;
            int g = byKey.Find(keys[i], [](int) { return true; });
            if (g < 0) {
                g = static_cast<int>(groups.size());
                groups.emplace_back();
                byKey.Insert(keys[i], g);
            }
            Group& group = groups[static_cast<std::size_t>(g)];
            if (group.size >= kCandidates) {
                later.push_back({i, g});
                continue;
            }
            match(i, group);
            if (r.ref[i] == i) group.at[group.size++] = i;
        }
        ParallelFor(tbb::blocked_range<std::size_t>(0, later.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t k = range.begin(); k < range.end(); ++k)
                            match(later[k].first,
                                  groups[static_cast<std::size_t>(later[k].second)]);
                    });
        return r;
    }

    // Body boxes grown by their pad (the boxes reused by translation; `grow` false: shrunk, an
    // empty box where the pad exceeds it): between them lies the body's own box.
    std::vector<Box3> PaddedBoxes(bool grow) const {
        std::vector<Box3> out(boxes_.box.size());
        ParallelFor(tbb::blocked_range<std::size_t>(0, out.size(), 2048),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i)
                            out[i] = PaddedBox(i, grow);
                    });
        return out;
    }
    Box3 PaddedBox(std::size_t i, bool grow) const {
        Box3 out = boxes_.box[i];
        if (boxes_.exact[i] || out.Empty()) return out;
        const double sign = grow ? 1 : -1;
        for (int a = 0; a < 3; ++a) {
            out.lo[a] -= sign * boxes_.pad[i][a];
            out.hi[a] += sign * boxes_.pad[i][a];
        }
        return out.Empty() ? Box3{} : out;
    }

    // FitSolidBoxes' box of each solid of `which` (provisional space, the padded body boxes), into
    // fitBoxes[s], from the solid's own bodies and subtree: a body's box is its padded box, a
    // node's box and fit box are functions of its subtree (TreeNodeBounds, FitNodeBounds), so
    // each is bit for bit the one FitSolidBoxes makes over every solid. MakeSolidsExact(which)
    // changes the boxes of the bodies of `which` only, so the other solids' fit boxes stand, and
    // this replaces a FitSolidBoxes of the whole scene per settling round. Boxes are reused only
    // without clip, fbp or section planes (TranslationReuse), so the fit planes are the final
    // ones; were they not, the whole scene's FitSolidBoxes would decide.
    void RefitSolids(const std::vector<std::size_t>& which, const BoundsOptions& bo,
                     std::vector<Box3>& fitBoxes) const {
        const FlatScene& flat = flat_;
        const double farDepth = view_.perspective ? view_.d : 0.0;
        if (view_.fitClips != finalPlanes_) {
            const std::vector<Box3> solidFit =
                FitSolidBoxes(flat, firstSame_, view_.fitClips, finalPlanes_, farDepth,
                              view_.fitNear, PaddedBoxes(true), bo);
            for (std::size_t s : which) fitBoxes[s] = solidFit[s];
            return;
        }
        std::vector<int> nodes, stack;
        for (std::size_t s : which) {
            stack.assign(1, flat.solids[s].root);
            while (!stack.empty()) {
                const int n = stack.back();
                stack.pop_back();
                nodes.push_back(n);
                const FlatCsgNode& node = flat.nodes[static_cast<std::size_t>(n)];
                if (!node.isLeaf)
                    stack.insert(stack.end(), node.children.begin(), node.children.end());
            }
        }
        std::sort(nodes.begin(), nodes.end());  // children before parents
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
        std::vector<Box3> nodeBoxes(flat.nodes.size()), fit(flat.nodes.size());
        for (int n : nodes) {
            const auto i = static_cast<std::size_t>(n);
            const FlatCsgNode& node = flat.nodes[i];
            const Box3 body =
                node.isLeaf ? PaddedBox(static_cast<std::size_t>(node.body), true) : Box3{};
            nodeBoxes[i] = TreeNodeBounds(node, body, nodeBoxes);
            fit[i] = FitNodeBounds(node, nodeBoxes[i], body, fit, farDepth, view_.fitNear);
        }
        for (std::size_t s : which)
            fitBoxes[s] = fit[static_cast<std::size_t>(flat.solids[s].root)];
    }

    // Bounds the bodies of solids `which` directly where their boxes were reused (in parallel).
    void MakeSolidsExact(const std::vector<std::size_t>& which, const BoundsOptions& bo) {
        std::vector<std::size_t> bodies;
        for (std::size_t s : which) {
            for (int b : bodiesOf_[s])
                if (!boxes_.exact[static_cast<std::size_t>(b)])
                    bodies.push_back(static_cast<std::size_t>(b));
            solidExact_[s] = 1;
        }
        // Bodies with the same literals (FirstWithSameLiterals) are bounded once.
        std::vector<std::size_t> firsts;
        firsts.reserve(bodies.size());
        for (std::size_t i : bodies) firsts.push_back(firstSame_[i]);
        std::sort(firsts.begin(), firsts.end());
        firsts.erase(std::unique(firsts.begin(), firsts.end()), firsts.end());
        ParallelFor(tbb::blocked_range<std::size_t>(0, firsts.size(), 4),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t j = r.begin(); j < r.end(); ++j) {
                            const std::size_t i = firsts[j];
                            if (boxes_.exact[i]) continue;
                            boxes_.box[i] = BodyBounds(flat_, flat_.bodies[i], bo);
                            boxes_.exact[i] = 1;
                            boxes_.pad[i] = Vec3{0, 0, 0};
                        }
                    });
        for (std::size_t i : bodies) {
            const std::size_t f = firstSame_[i];
            boxes_.box[i] = boxes_.box[f];
            boxes_.exact[i] = 1;
            boxes_.pad[i] = Vec3{0, 0, 0};
        }
    }

    // Culling with reused boxes: a solid is dropped when its box misses the image (ToDevice,
    // Cull). Where the grown and the shrunk boxes of a solid disagree on that, its own box could
    // go either way, so its bodies are bounded directly: the solids kept (and so every id in
    // the frame) are those of the direct boxes.
    void SettleCulling(const WindowFit& fit, const BoundsOptions& bo) {
        const std::vector<Box3> grown = PaddedBoxes(true), shrunk = PaddedBoxes(false);
        std::vector<Box3> devGrown(grown.size()), devShrunk(shrunk.size());
        ParallelFor(tbb::blocked_range<std::size_t>(0, grown.size(), 2048),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                            devGrown[i] = MapBox(fit, grown[i]);
                            devShrunk[i] = MapBox(fit, shrunk[i]);
                        }
                    });
        const std::vector<Box3> g = TreeBounds(flat_, devGrown), h = TreeBounds(flat_, devShrunk);
        const Box3 image{{0, 0, -kInf}, {double(flat_.width), double(flat_.height), kInf}};
        std::vector<std::size_t> unsure;
        for (std::size_t s = 0; s < flat_.solids.size(); ++s) {
            if (solidExact_[s]) continue;
            const int root = flat_.solids[s].root;
            if (g[root].Intersected(image).Empty() != h[root].Intersected(image).Empty())
                unsure.push_back(s);
        }
        if (!unsure.empty()) MakeSolidsExact(unsure, bo);
    }

    // Solid boxes for the window fit: like the final ones, except that the fit ignores fbp, so
    // where the view's fit clip planes differ from the final ones the bodies are bounded again
    // with their own literals and the fit planes. `flat` and the planes are in one space (the
    // provisional one, or the device space of RefineFit); farDepth and nearDepth as in
    // FitTreeBounds. `passesEye` (when given) gets per solid whether its box reaches the near
    // plane (it holds the eye or passes beside or behind it).
    static std::vector<Box3> FitSolidBoxes(const FlatScene& flat,
                                           const std::vector<std::size_t>& first,
                                           const std::vector<Plane>& fitClips,
                                           const std::vector<Plane>& finalClips, double farDepth,
                                           double nearDepth, std::vector<Box3> bodyBoxes,
                                           const BoundsOptions& bo,
                                           std::vector<char>* passesEye = nullptr) {
        bool same = fitClips.size() == finalClips.size();
        for (std::size_t i = 0; same && i < fitClips.size(); ++i)
            same = fitClips[i] == finalClips[i];
        if (!same) {
            std::vector<FlatHalfSpace> fitPlanes;
            for (const Plane& p : fitClips) {
                FlatHalfSpace h;
                h.plane = p;
                fitPlanes.push_back(h);
            }
            const std::size_t nClip = finalClips.size();
            std::vector<BoundLiteral> lits;
            for (std::size_t i = 0; i < flat.bodies.size(); ++i) {
                if (first[i] != i) {
                    bodyBoxes[i] = bodyBoxes[first[i]];
                    continue;
                }
                const FlatBody& b = flat.bodies[i];
                lits.clear();
                for (std::size_t l = 0; l + nClip < b.literals.size(); ++l)
                    lits.push_back(
                        {&flat.halfSpaces[b.literals[l].halfSpace], b.literals[l].complemented});
                for (const FlatHalfSpace& h : fitPlanes) lits.push_back({&h, false});
                bodyBoxes[i] = IntersectionBounds(lits, bo);
            }
        }
        std::vector<Box3> nodeBoxes = TreeBounds(flat, bodyBoxes);
        std::vector<Box3> fitBoxes = FitTreeBounds(flat, bodyBoxes, nodeBoxes, farDepth, nearDepth);
        std::vector<Box3> solidBoxes(flat.solids.size());
        for (std::size_t i = 0; i < flat.solids.size(); ++i)
            solidBoxes[i] = fitBoxes[flat.solids[i].root];
        if (passesEye) {
            passesEye->assign(flat.solids.size(), 0);
            for (std::size_t i = 0; i < flat.solids.size(); ++i) {
                // Bounded in the world (not reaching the image of infinity, z = farDepth): an
                // unbounded solid keeps its own message.
                const Box3& b = nodeBoxes[flat.solids[i].root];
                (*passesEye)[i] = ReachesNearPlane(b, nearDepth) &&
                                  (farDepth <= 0 || b.hi.z < farDepth * (1 - 1e-9));
            }
        }
        return solidBoxes;
    }

    // The bodies under each solid's root, in the order of a depth-first walk from the root, all
    // in one array (one allocation, not one per solid).
    struct SolidBodies {
        std::vector<std::size_t> start;  // per solid, and one past the last
        std::vector<int> bodies;
        std::span<const int> operator[](std::size_t s) const {
            return {bodies.data() + start[s], bodies.data() + start[s + 1]};
        }
    };
    SolidBodies BodiesOfSolids() const {
        SolidBodies out;
        out.start.reserve(flat_.solids.size() + 1);
        out.bodies.reserve(flat_.bodies.size());
        std::vector<int> stack;
        for (std::size_t s = 0; s < flat_.solids.size(); ++s) {
            out.start.push_back(out.bodies.size());
            stack.assign(1, flat_.solids[s].root);
            while (!stack.empty()) {
                const FlatCsgNode& node = flat_.nodes[static_cast<std::size_t>(stack.back())];
                stack.pop_back();
                if (node.isLeaf)
                    out.bodies.push_back(node.body);
                else
                    stack.insert(stack.end(), node.children.begin(), node.children.end());
            }
        }
        out.start.push_back(out.bodies.size());
        return out;
    }

    // FitSolidBoxes for the solids `which` only (the boxes of the others are left as they are in
    // `solidBoxes`): their bodies are bounded (in parallel) and their trees combined exactly as
    // FitSolidBoxes does for all, so each of their boxes is bit for bit FitSolidBoxes' (a body's
    // box is a pure function of its literals, a node's of its subtree).
    static void SomeFitSolidBoxes(
        const FlatScene& flat, const std::vector<const FlatHalfSpace*>& halfSpaces,
        const std::vector<Plane>& fitClips, const std::vector<Plane>& finalClips, double farDepth,
        double nearDepth, const BoundsOptions& bo, const SolidBodies& bodiesOf,
        const std::vector<std::size_t>& firstSame, const std::vector<std::size_t>& which,
        std::vector<Box3>& solidBoxes) {
        bool same = fitClips.size() == finalClips.size();
        for (std::size_t i = 0; same && i < fitClips.size(); ++i)
            same = fitClips[i] == finalClips[i];
        std::vector<FlatHalfSpace> fitPlanes;
        for (const Plane& p : fitClips) {
            FlatHalfSpace h;
            h.plane = p;
            fitPlanes.push_back(h);
        }
        const std::size_t nClip = finalClips.size();
        // Bodies with the same literals (firstSame, FirstWithSameLiterals) are bounded once: a
        // subtracted tool repeated in every term of a union is one body per term.
        std::vector<int> bodies;
        std::vector<char> queued(flat.bodies.size(), 0);
        for (std::size_t s : which)
            for (int b : bodiesOf[s]) {
                const std::size_t rep = firstSame[static_cast<std::size_t>(b)];
                if (!queued[rep]) {
                    queued[rep] = 1;
                    bodies.push_back(static_cast<int>(rep));
                }
            }
        std::vector<Box3> bodyBoxes(flat.bodies.size());
        ParallelFor(
            tbb::blocked_range<std::size_t>(0, bodies.size(), 4),
            [&](const tbb::blocked_range<std::size_t>& r) {
                std::vector<BoundLiteral> lits;
                for (std::size_t j = r.begin(); j < r.end(); ++j) {
                    const FlatBody& b = flat.bodies[static_cast<std::size_t>(bodies[j])];
                    // All literals (as BodyBounds), or the fit planes instead of the final ones.
                    const std::size_t own = same ? b.literals.size() : b.literals.size() - nClip;
                    lits.clear();
                    for (std::size_t l = 0; l < own; ++l)
                        lits.push_back(
                            {halfSpaces[static_cast<std::size_t>(b.literals[l].halfSpace)],
                             b.literals[l].complemented});
                    if (!same)
                        for (const FlatHalfSpace& h : fitPlanes) lits.push_back({&h, false});
                    bodyBoxes[static_cast<std::size_t>(bodies[j])] = IntersectionBounds(lits, bo);
                }
            });
        for (std::size_t s : which)
            for (int b : bodiesOf[s]) {
                const auto i = static_cast<std::size_t>(b);
                if (firstSame[i] != i) bodyBoxes[i] = bodyBoxes[firstSame[i]];
            }
        std::vector<Box3> nodeBoxes = TreeBounds(flat, bodyBoxes);
        std::vector<Box3> fitBoxes = FitTreeBounds(flat, bodyBoxes, nodeBoxes, farDepth, nearDepth);
        for (std::size_t s : which) solidBoxes[s] = fitBoxes[flat.solids[s].root];
    }

    // The auto-fit window depends on the solids' fit boxes only through their hull on x and y
    // (FitWindow). Given boxes of which those not `known` are only known to CONTAIN the true ones
    // (on the axes where they are finite), SettleExtremes makes known (through `make`, which
    // replaces the box and sets the flag) every solid that could decide a side of the hull: one
    // whose box reaches beyond the most extreme known box on that side, or is not finite on
    // that axis. The hull of the boxes is then the hull of the true ones, bit for bit; the others
    // lie inside it whatever their true boxes are. Rounds of the eight most extreme candidates
    // per side, until none is left.
    template <class Make>
    static void SettleExtremes(const std::vector<Box3>& boxes, const std::vector<char>& known,
                               Make&& make) {
        const std::size_t n = known.size();
        std::vector<std::pair<double, std::size_t>> cand;
        for (;;) {
            std::vector<std::size_t> todo;
            for (int axis = 0; axis < 2; ++axis)
                for (int hi = 0; hi < 2; ++hi) {
                    auto out = [&](const Box3& b) { return hi ? b.hi[axis] : -b.lo[axis]; };
                    auto finiteOn = [&](const Box3& b) {
                        return !b.Empty() && std::isfinite(b.lo[axis]) && std::isfinite(b.hi[axis]);
                    };
                    double best = -kInf;
                    for (std::size_t s = 0; s < n; ++s)
                        if (known[s] && finiteOn(boxes[s])) best = std::fmax(best, out(boxes[s]));
                    cand.clear();
                    for (std::size_t s = 0; s < n; ++s) {
                        if (known[s] || boxes[s].Empty()) continue;
                        if (!finiteOn(boxes[s]))
                            cand.push_back({kInf, s});
                        else if (out(boxes[s]) > best)
                            cand.push_back({out(boxes[s]), s});
                    }
                    const std::size_t take = std::min<std::size_t>(cand.size(), 8);
                    std::partial_sort(
                        cand.begin(), cand.begin() + static_cast<std::ptrdiff_t>(take), cand.end(),
                        [](const auto& a, const auto& b) {
                            return a.first > b.first || (a.first == b.first && a.second < b.second);
                        });
                    for (std::size_t c = 0; c < take; ++c) todo.push_back(cand[c].second);
                }
            if (todo.empty()) return;
            std::sort(todo.begin(), todo.end());
            todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
            make(todo);
        }
    }

    // Auto-fit, second look. The bounds are tightest where the scene is centred and about as
    // large as the search expects, which provisional space is not for a model far from vrp or
    // much smaller than its distance (a cone frustum 1 km from the origin is bounded 1.5 to 50
    // times too loosely there). So when some box came from the search, the bodies are bounded
    // again in the device space of the fit just made, where the scene fills the image; both
    // boxes are conservative, so the fit uses their intersection. Twice at most, and only while
    // the fit still changes (scale up by 0.1 % or a shift of a quarter pixel).
    //
    // Only the solids that can decide the window are bounded again (SettleExtremes): a solid's
    // box after a look is its box before it intersected with the new one, so it never reaches
    // beyond the box before; a solid whose box before lies inside the hull of the boxes already
    // settled cannot move the window. The window is therefore bit for bit the one made from
    // every solid's second look, at the cost of a few solids (the helicopter: 2 × 2,211 bodies
    // bounded again before, a few dozen now). `firstKnown` marks the solids whose first boxes
    // are exact; `makeFirstKnown` makes others so (boxes reused by translation, flattener.cpp).
    template <class MakeFirst>
    void RefineFit(WindowFit& fit, std::vector<Box3>& fitBoxes, std::vector<char> firstKnown,
                   MakeFirst&& makeFirstKnown) {
        const std::size_t nSolids = flat_.solids.size();
        const SolidBodies& bodiesOf = bodiesOf_;
        const std::vector<std::size_t>& firstSame = firstSame_;
        struct Look {
            WindowFit fit;
            Transform dev;
            // Device space of `fit`: per half-space of flat_, its image (null until a solid that
            // uses it is bounded in this look); only those are mapped, kept in `mapped`.
            std::vector<const FlatHalfSpace*> halfSpaces;
            std::deque<FlatHalfSpace> mapped;
            std::vector<Plane> fitClips, finalClips;
            std::vector<Box3> boxes;  // per solid: the box after this look (where known)
            std::vector<char> known;
        };
        // A deque: a look never moves once made, so its table's pointers into `mapped` stay valid.
        std::deque<Look> looks;
        // Level 0 is the first boxes; level p > 0 the boxes after look p.
        std::vector<Box3> firstBoxes(fitBoxes.begin(),
                                     fitBoxes.begin() + static_cast<std::ptrdiff_t>(nSolids));
        auto boxesAt = [&](std::size_t level) -> std::vector<Box3>& {
            return level == 0 ? firstBoxes : looks[level - 1].boxes;
        };
        auto knownAt = [&](std::size_t level) -> std::vector<char>& {
            return level == 0 ? firstKnown : looks[level - 1].known;
        };
        BoundsOptions bo;
        bo.searchLimit = 1e6 * std::fmax(options_.width, options_.height);
        // Makes the boxes of `which` known at `level` (and at the levels before).
        std::function<void(std::size_t, const std::vector<std::size_t>&)> makeKnown =
            [&](std::size_t level, const std::vector<std::size_t>& which) {
                std::vector<std::size_t> before;
                for (std::size_t s : which)
                    if (!knownAt(level - 1)[s]) before.push_back(s);
                if (!before.empty()) {
                    if (level == 1)
                        makeFirstKnown(before, firstBoxes, firstKnown);
                    else
                        makeKnown(level - 1, before);
                }
                Look& look = looks[level - 1];
                // The half-spaces of these solids in the look's device space (once each): which
                // ones first, then their images in parallel (each its own).
                std::vector<std::size_t> fresh;
                std::vector<char> seen(flat_.halfSpaces.size(), 0);
                for (std::size_t s : which)
                    for (int b : bodiesOf[s])
                        for (const FlatLiteral& l :
                             flat_.bodies[static_cast<std::size_t>(b)].literals) {
                            const std::size_t k = static_cast<std::size_t>(l.halfSpace);
                            if (look.halfSpaces[k] || seen[k]) continue;
                            seen[k] = 1;
                            fresh.push_back(k);
                        }
                const std::size_t base = look.mapped.size();
                look.mapped.resize(base + fresh.size());
                ParallelFor(tbb::blocked_range<std::size_t>(0, fresh.size(), 512),
                            [&](const tbb::blocked_range<std::size_t>& r) {
                                for (std::size_t j = r.begin(); j < r.end(); ++j) {
                                    FlatHalfSpace& h = look.mapped[base + j];
                                    h = flat_.halfSpaces[fresh[j]];
                                    if (h.IsQuartic())
                                        h.TransformBy(look.dev);
                                    else if (h.isPlane)
                                        h.plane = h.plane.Transformed(look.dev);
                                    else
                                        h.quadric = h.quadric.Transformed(look.dev);
                                    look.halfSpaces[fresh[j]] = &h;
                                }
                            });
                std::vector<Box3> dev = look.boxes;
                SomeFitSolidBoxes(flat_, look.halfSpaces, look.fitClips, look.finalClips,
                                  view_.perspective ? look.fit.k * view_.d : 0.0,
                                  look.fit.k * view_.fitNear, bo, bodiesOf, firstSame, which, dev);
                // Back to provisional space, x = (x_dev - ox) / k, and intersected with the
                // boxes before where both are finite.
                const double off[3] = {look.fit.ox, look.fit.oy, 0};
                const std::vector<Box3>& prev = boxesAt(level - 1);
                for (std::size_t i : which) {
                    Box3 b = dev[i];
                    const Box3& first = prev[i];
                    if (b.Empty() || first.Empty()) {
                        b = Box3{};
                    } else {
                        for (int axis = 0; axis < 3; ++axis) {
                            double lo = (b.lo[axis] - off[axis]) / look.fit.k,
                                   hi = (b.hi[axis] - off[axis]) / look.fit.k;
                            if (!(std::isfinite(lo) && std::isfinite(hi))) lo = -kInf, hi = kInf;
                            if (std::isfinite(first.lo[axis]) && std::isfinite(first.hi[axis])) {
                                lo = std::fmax(lo, first.lo[axis]);
                                hi = std::fmin(hi, first.hi[axis]);
                                if (!(lo <= hi)) lo = first.lo[axis], hi = first.hi[axis];
                            }
                            b.lo[axis] = lo;
                            b.hi[axis] = hi;
                        }
                    }
                    look.boxes[i] = b;
                    look.known[i] = 1;
                }
            };
        for (int pass = 0; pass < 2; ++pass) {
            Look look;
            look.fit = fit;
            const Transform dev =
                Transform::Translate({fit.ox, fit.oy, 0}) * Transform::Scale({fit.k, fit.k, fit.k});
            look.dev = dev;
            look.halfSpaces.assign(flat_.halfSpaces.size(), nullptr);
            for (const Plane& p : view_.fitClips) look.fitClips.push_back(p.Transformed(dev));
            for (const Plane& p : finalPlanes_) look.finalClips.push_back(p.Transformed(dev));
            // Until known, a solid's box after the look is bounded by its box before it.
            look.boxes = boxesAt(looks.size());
            look.known.assign(nSolids, 0);
            looks.push_back(std::move(look));
            const std::size_t level = looks.size();
            SettleExtremes(looks.back().boxes, looks.back().known,
                           [&](const std::vector<std::size_t>& which) { makeKnown(level, which); });
            std::vector<Box3> boxes = looks.back().boxes;
            for (std::size_t i = nSolids; i < fitBoxes.size(); ++i) boxes.push_back(fitBoxes[i]);
            WindowRequest request;
            request.width = options_.width;
            request.height = options_.height;
            request.margin = options_.autoFitMargin;
            WindowFit next;
            if (FitWindow(request, boxes, next) != WindowFitStatus::kOk) return;
            bool changed = next.k > 1.001 * fit.k || std::fabs(next.ox - fit.ox) > 0.25 ||
                           std::fabs(next.oy - fit.oy) > 0.25;
            if (!changed) return;
            fit = next;
        }
    }

    // The window fit (window_fit.h); freeform surfaces reaching infinity, and a scene with
    // nothing bounded and no window, are errors.
    std::optional<WindowFit> Fit(const std::vector<Box3>& fitBoxes) {
        const bool autoFit = !view_.whw && !view_.whh;
        if (autoFit)
            for (std::size_t i = flat_.solids.size(); i < fitBoxes.size(); ++i)
                if (!fitBoxes[i].Empty() && !fitBoxes[i].Finite()) {
                    diags_.Error({}, fmt::format("freeform surface '{}' reaches infinity in the "
                                                 "view (a weight vanishes); give the view a "
                                                 "window with whh or whw",
                                                 freeformNames_[i - flat_.solids.size()]));
                    return std::nullopt;
                }
        WindowRequest request;
        request.width = options_.width;
        request.height = options_.height;
        request.margin = options_.autoFitMargin;
        request.whh = view_.whh;
        request.whw = view_.whw;
        WindowFit fit;
        switch (FitWindow(request, fitBoxes, fit)) {
            case WindowFitStatus::kOk:
                return fit;
            case WindowFitStatus::kNothingBounded: {
                bool any = false;
                for (const Box3& b : fitBoxes) any |= !b.Empty();
                if (!any) {
                    diags_.Error(view_.loc,
                                 fmt::format("nothing to draw in view '{}': every solid is empty "
                                             "or behind the eye",
                                             view_.id));
                    return std::nullopt;
                }
                // Name the first solid: every one of them is unbounded.
                std::size_t i = 0;
                while (fitBoxes[i].Empty()) ++i;
                if (i >= flat_.solids.size()) return std::nullopt;  // (freeforms are finite)
                const SourceLoc& loc = hierarchy_.solidLocs[i];
                bool isBody = !hierarchy_.solidIsCsg[i];
                // A solid holding the eye, or passing beside or behind it, has no bounded
                // picture either (window_fit.h): say so rather than "unbounded".
                if (i < eyeInside_.size() && eyeInside_[i]) {
                    diags_.Error(loc, fmt::format("the eye of view '{}' (cop {}) is inside {} "
                                                  "'{}' at {}, so nothing in front of the eye "
                                                  "bounds the window; give the view a window "
                                                  "with whh or whw (the solid is then drawn cut "
                                                  "open by the near plane and seen from inside), "
                                                  "or move cop out of it",
                                                  view_.id, FormatPoint(view_.eye),
                                                  isBody ? "body" : "csg solid",
                                                  flat_.solids[i].name, loc.ToString()));
                    return std::nullopt;
                }
                if (i < passesEye_.size() && passesEye_[i]) {
                    diags_.Error(loc,
                                 fmt::format("{} '{}' at {} reaches beside or behind the "
                                             "eye of view '{}' (cop {}), so its picture "
                                             "has no bounded extent and nothing else "
                                             "bounds the window; give the view a window "
                                             "with whh or whw",
                                             isBody ? "body" : "csg solid", flat_.solids[i].name,
                                             loc.ToString(), view_.id, FormatPoint(view_.eye)));
                    return std::nullopt;
                }
                // A quadric scaled by more than about 1e7 along one axis is, to double precision,
                // a cylinder along it (its coefficient there underflows against the others): say
                // so, since the scene may mean a bounded solid (issue 23).
                bool quadric = false;
                std::vector<int> stack{flat_.solids[i].root};
                while (!stack.empty() && !quadric) {
                    const FlatCsgNode& node = flat_.nodes[static_cast<std::size_t>(stack.back())];
                    stack.pop_back();
                    if (!node.isLeaf) {
                        stack.insert(stack.end(), node.children.begin(), node.children.end());
                        continue;
                    }
                    for (const FlatLiteral& l :
                         flat_.bodies[static_cast<std::size_t>(node.body)].literals)
                        quadric |= !flat_.halfSpaces[static_cast<std::size_t>(l.halfSpace)].isPlane;
                }
                diags_.Error(
                    loc,
                    fmt::format("{} '{}' at {} is unbounded in the view{} and nothing "
                                "bounded is there to fit the window to; give the view a "
                                "window with whh or whw",
                                isBody ? "body" : "csg solid", flat_.solids[i].name, loc.ToString(),
                                quadric ? " (to double precision: a quadric stretched by "
                                          "about 1e7 or more along an axis is a cylinder "
                                          "there)"
                                        : ""));
                return std::nullopt;
            }
            case WindowFitStatus::kNoExtent:
                diags_.Error(view_.loc, fmt::format("the scene has no extent in view '{}' (it is "
                                                    "flat or a point seen edge-on); give the "
                                                    "view a window with whh or whw",
                                                    view_.id));
                return std::nullopt;
        }
        return std::nullopt;
    }

    // A box maps exactly under a positive scale and a translation, up to rounding: pad by a
    // few ulps of the coordinates.
    static Box3 MapBox(const WindowFit& fit, const Box3& b) {
        if (b.Empty()) return Box3{};
        Box3 r;
        const double o[3] = {fit.ox, fit.oy, 0};
        for (int i = 0; i < 3; ++i) {
            double lo = fit.k * b.lo[i] + o[i], hi = fit.k * b.hi[i] + o[i];
            r.lo[i] = lo - 4e-16 * (std::fabs(lo) + std::fabs(o[i])) - 1e-300;
            r.hi[i] = hi + 4e-16 * (std::fabs(hi) + std::fabs(o[i])) + 1e-300;
        }
        return r;
    }

    // Maps everything from provisional to device space: D = T(ox, oy, 0) · S(k, k, k).
    void ToDevice(const WindowFit& fit, const std::vector<Box3>& bodyBoxes) {
        FlatScene& flat = flat_;
        Transform dev =
            Transform::Translate({fit.ox, fit.oy, 0}) * Transform::Scale({fit.k, fit.k, fit.k});
        // Each half-space and each body box on its own: in parallel.
        ParallelFor(tbb::blocked_range<std::size_t>(0, flat.halfSpaces.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                            FlatHalfSpace& h = flat.halfSpaces[i];
                            if (h.IsQuartic()) {
                                h.TransformBy(dev);
                            } else if (h.isPlane) {
                                h.plane = h.plane.Transformed(dev);
                                RescaleCoefficients(h.plane);
                            } else {
                                h.quadric = h.quadric.Transformed(dev);
                                RescaleCoefficients(h.quadric);
                            }
                        }
                    });
        std::vector<Box3> devBodies(bodyBoxes.size());
        ParallelFor(tbb::blocked_range<std::size_t>(0, bodyBoxes.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                            devBodies[i] = MapBox(fit, bodyBoxes[i]);
                            flat.bodies[i].bounds = devBodies[i];
                        }
                    });
        std::vector<Box3> nodes = TreeBounds(flat, devBodies);
        for (std::size_t i = 0; i < nodes.size(); ++i) flat.nodes[i].bounds = nodes[i];
        Box3 image{{0, 0, -kInf}, {double(flat.width), double(flat.height), kInf}};
        for (FlatSolid& s : flat.solids) {
            Box3 b = nodes[s.root].Intersected(image);
            s.bounds = b.Empty() ? Box3{} : b;
        }
        flat.projection.perspective = view_.perspective;
        flat.projection.deviceFromWorld = dev * view_.provFromWorld;
        flat.projection.eye = view_.eye;
        flat.projection.towardViewer = view_.towardViewer;
    }

    // Drops solids with empty bounds and renumbers what remains (half-spaces no longer used are
    // dropped too, except the shared clip planes).
    void Cull() {
        FlatScene& flat = flat_;
        bool any = false;
        for (const FlatSolid& s : flat.solids) any |= s.bounds.Empty();
        if (!any) return;
        FlatScene out;
        out.width = flat.width;
        out.height = flat.height;
        out.lights = std::move(flat.lights);
        out.background = flat.background;
        out.backgroundBottom = flat.backgroundBottom;
        out.projection = flat.projection;
        out.viewName = flat.viewName;
        out.freeforms = std::move(flat.freeforms);
        std::vector<int> hsMap(flat.halfSpaces.size(), -1);
        for (std::size_t i = 0; i < flat.halfSpaces.size(); ++i)
            if (flat.halfSpaces[i].isClip) {
                hsMap[i] = static_cast<int>(out.halfSpaces.size());
                out.halfSpaces.push_back(flat.halfSpaces[i]);
            }
        std::vector<int> nodeMap(flat.nodes.size(), -1);
        for (const FlatSolid& s : flat.solids) {
            if (s.bounds.Empty()) continue;
            int solidIndex = static_cast<int>(out.solids.size());
            FlatSolid ns = s;
            ns.root = CopyNode(flat, s.root, solidIndex, out, hsMap, nodeMap);
            out.solids.push_back(std::move(ns));
        }
        // The section's half-space is a literal of every body, renumbered with the first one
        // (none when no solid is left).
        out.section = flat.section;
        if (flat.sectionHalfSpace >= 0)
            out.sectionHalfSpace = hsMap[static_cast<std::size_t>(flat.sectionHalfSpace)];
        flat_ = std::move(out);
    }

    // Copies a subtree (children before parents, as the walk emitted them). Iterative: a union
    // of 10,000 bodies is one node, but nodes can still nest deeply.
    int CopyNode(const FlatScene& from, int root, int solid, FlatScene& to, std::vector<int>& hsMap,
                 std::vector<int>& nodeMap) {
        std::vector<std::pair<int, bool>> stack{{root, false}};
        while (!stack.empty()) {
            auto [n, expanded] = stack.back();
            stack.pop_back();
            if (nodeMap[n] >= 0) continue;
            const FlatCsgNode& node = from.nodes[n];
            if (!expanded && !node.isLeaf) {
                stack.push_back({n, true});
                for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
                    stack.push_back({*it, false});
                continue;
            }
            FlatCsgNode copy = node;
            if (node.isLeaf) {
                FlatBody body = from.bodies[node.body];
                body.solid = solid;
                for (FlatLiteral& l : body.literals) {
                    if (hsMap[l.halfSpace] < 0) {
                        hsMap[l.halfSpace] = static_cast<int>(to.halfSpaces.size());
                        to.halfSpaces.push_back(from.halfSpaces[l.halfSpace]);
                    }
                    l.halfSpace = hsMap[l.halfSpace];
                }
                to.bodies.push_back(std::move(body));
                copy.body = static_cast<int>(to.bodies.size()) - 1;
            } else {
                for (int& c : copy.children) c = nodeMap[c];
            }
            to.nodes.push_back(std::move(copy));
            nodeMap[n] = static_cast<int>(to.nodes.size()) - 1;
        }
        return nodeMap[root];
    }

    void SetDepthTolerance(const WindowFit& fit) {
        double extent = std::fmax(options_.width, options_.height);
        Box3 all;
        for (const FlatSolid& s : flat_.solids) all.Extend(s.bounds);
        if (!all.Empty() && std::isfinite(all.lo.z) && std::isfinite(all.hi.z))
            extent = std::fmax(extent, all.hi.z - all.lo.z);
        if (view_.perspective) extent = std::fmax(extent, fit.k * view_.d);
        flat_.depthTolerance = 1e-9 * extent;
    }

    static std::string FormatPoint(const Vec3& p) {
        return fmt::format("({:g} {:g} {:g})", p.x, p.y, p.z);
    }

    // Issue 23, the eye inside a solid: eyeInside_[solid] when the eye of a perspective view lies
    // strictly inside the solid (its clipping planes aside). In provisional space the eye is the
    // point at infinity (0, 0, -1, 0) (view_setup.h: X = Y = W = 0 and Z = -d² there), where a
    // plane <a b c d> takes the value -c and a quadric its coefficient C: positive multiples of
    // their values at the eye in world space, so the signs are the world's. Values within 1e-12
    // of the largest coefficient count as on the surface (not inside). O(literals + nodes).
    void FindSolidsAroundEye() {
        const FlatScene& flat = flat_;
        // Per half-space: +1 the eye is strictly outside, -1 strictly inside, 0 on it.
        std::vector<signed char> side(flat.halfSpaces.size(), 0);
        for (std::size_t i = 0; i < flat.halfSpaces.size(); ++i) {
            const FlatHalfSpace& h = flat.halfSpaces[i];
            if (h.isClip) continue;
            double v, scale;
            if (h.isPlane) {
                v = -h.plane.c;
                scale = std::fmax(std::fmax(std::fabs(h.plane.a), std::fabs(h.plane.b)),
                                  std::fmax(std::fabs(h.plane.c), std::fabs(h.plane.d)));
            } else {
                v = h.quadric.C();
                scale = h.quadric.MaxAbs();
            }
            const double tol = 1e-12 * scale;
            side[i] = v < -tol ? -1 : (v > tol ? 1 : 0);
        }
        std::vector<char> in(flat.nodes.size(), 0);  // children come before their parents
        for (std::size_t n = 0; n < flat.nodes.size(); ++n) {
            const FlatCsgNode& node = flat.nodes[n];
            if (node.isLeaf) {
                bool all = true;
                for (const FlatLiteral& l : flat.bodies[node.body].literals) {
                    if (flat.halfSpaces[l.halfSpace].isClip) continue;
                    all = all && side[l.halfSpace] == (l.complemented ? 1 : -1);
                }
                in[n] = all;
                continue;
            }
            bool v = node.op != scene::CsgOp::kUnion;
            for (std::size_t c = 0; c < node.children.size(); ++c) {
                const bool child = in[node.children[c]] != 0;
                switch (node.op) {
                    case scene::CsgOp::kUnion:
                        v = v || child;
                        break;
                    case scene::CsgOp::kIntersection:
                        v = v && child;
                        break;
                    case scene::CsgOp::kDifference:
                        v = c == 0 ? child : v && !child;
                        break;
                }
            }
            in[n] = v;
        }
        eyeInside_.assign(flat.solids.size(), 0);
        for (std::size_t i = 0; i < flat.solids.size(); ++i)
            eyeInside_[i] = in[flat.solids[i].root];
    }

    // A warning per solid holding the eye (the picture is defined: the near plane cuts the solid
    // open and its inside faces are drawn), three named at most.
    void WarnAboutSolidsAroundEye() {
        std::size_t count = 0;
        for (char c : eyeInside_) count += c != 0;
        std::size_t named = 0;
        for (std::size_t i = 0; i < eyeInside_.size() && named < 3; ++i) {
            if (!eyeInside_[i]) continue;
            ++named;
            const SourceLoc& loc = hierarchy_.solidLocs[i];
            diags_.Warning(loc, fmt::format("the eye of view '{}' (cop {}) is inside {} '{}': the "
                                            "near plane cuts it open and it is seen from inside",
                                            view_.id, FormatPoint(view_.eye),
                                            hierarchy_.solidIsCsg[i] ? "csg solid" : "body",
                                            flat_.solids[i].name));
        }
        if (count > named)
            diags_.Warning({}, fmt::format("the eye of view '{}' is inside {} more solids",
                                           view_.id, count - named));
    }

    const scene::Scene& scene_;
    const FlattenOptions& options_;
    Diagnostics& diags_;
    const WorldScene* world_;
    ViewSetup view_;
    // The planes cutting every body (view_.finalClips, then the section plane), provisional space.
    std::vector<Plane> finalPlanes_;
    FlatScene flat_;
    FlatScene recycle_;  // FlattenView's: its arrays' elements assigned over (PlaceWorld)
    HierarchyResult hierarchy_;
    std::vector<std::string> freeformNames_;  // fit boxes past the solids
    std::vector<char> eyeInside_;             // per solid (FindSolidsAroundEye)
    std::vector<char> passesEye_;             // per solid: its box reaches the fit's near plane
    BodyBoxes boxes_;                         // per body, provisional space (AllBodyBounds)
    SolidBodies bodiesOf_;                    // per solid: its bodies
    std::vector<std::size_t> firstSame_;      // per body (FirstWithSameLiterals)
    std::vector<char> solidExact_;            // per solid: every body's box is its own
};

}  // namespace

std::optional<WorldScene> FlattenWorld(const scene::Scene& scene, Diagnostics& diags) {
    WorldScene world;
    HierarchyLimits limits;
    limits.clipLiteralsPerBody = kMostClipLiteralsPerBody;
    limits.keepExtentPieces = true;
    limits.keepHalfSpaceLocs = true;
    if (!FlattenHierarchy(scene, Transform{}, limits, world.flat, world.hierarchy, diags))
        return std::nullopt;
    return world;
}

std::optional<FlatScene> FlattenView(const scene::Scene& scene, const WorldScene& world,
                                     const FlattenOptions& options, Diagnostics& diags,
                                     FlatScene recycle) {
    return FlattenerImpl(scene, options, diags, &world, std::move(recycle)).Run();
}

std::optional<FlatScene> Flatten(const scene::Scene& scene, const FlattenOptions& options,
                                 Diagnostics& diags) {
    return FlattenerImpl(scene, options, diags, nullptr).Run();
}

}  // namespace quadrix
