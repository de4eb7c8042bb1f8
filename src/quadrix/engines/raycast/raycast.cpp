// Engine `raycast` (see raycast.h). Structure of a render:
//
//  1. Tables: per half-space its coefficients regrouped for rays along z (RayHalfSpace); per
//     literal of every body a global "tag" naming (half-space, body, complemented, opaque). Tags
//     are the ids carried by interval endpoints, so the visible endpoint names its surface and
//     body.
//  2. The scene's solids become one CsgProgram (csg_program.h), sorted by nearest depth.
//  3. The image is cut into 256×256 blocks, 256×8 tiles and 8×8 sub-tiles, run in parallel
//     (oneTBB, nested parallel_for, in the arena of the caller: Engine::Render makes one of
//     RenderOptions::threads when it is > 0). Each level prunes its parent's program against its pixel centres, so a
//     sub-tile sees only the solids and leaves whose bounds reach it, and pruning a 10,000-leaf
//     union costs one walk per block rather than one per sub-tile.
//  4. Per sub-tile, before any pixel: its bodies' literals are reduced (planes that cannot bound
//     a body there dropped, bodies proved empty; once per tile, then per sub-tile: PrepareStrip,
//     PrepareTile), and the sub-tile is filled as background or as one plane when that is proved
//     (AllEmpty, TryFlatFill). Bodies covering the sub-tile are evaluated for all its pixels at
//     once when first needed (body batches, vectorised).
//  5. The pixels of the rest, by the first of these that applies: one body left (its batch);
//     a small tree of bodies (a kernel: postfix code run over lanes of pixels, CompileKernel,
//     RunKernelTile); otherwise Trace. Trace visits the solids by nearest depth until the best
//     depth found is nearer than the next solid can be; a solid's interval list is computed by
//     recursion over its pruned tree (bodies clip their literals' sets into each other,
//     operators fold their operands left to right, with short cuts on ∅) using lists
//     preallocated per thread, so no pixel allocates once warm. The solid's visible point is its
//     first finite endpoint whose surface is opaque (transparent half-spaces and clipping planes
//     bound but are not drawn); across solids the nearest wins and exact ties keep the lower
//     solid index. Every fast path gives Trace's result bit for bit (the engine options switch
//     them off to show it: Settings).
//  6. A tile's pixels are written into a per-thread staging copy, then into the Frame row by row.
//
// Every pixel's result depends only on the scene and the pixel's tile rectangles, never on the
// thread that ran it, so renders are bit-for-bit reproducible for any thread count.
#include "quadrix/engines/raycast/raycast.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/engines/raycast/csg_program.h"
#include "quadrix/engines/raycast/ray_literal.h"
#include "quadrix/math/interval_list.h"

namespace quadrix {
namespace raycast {
namespace {

constexpr int kBlock = 256;   // first pruning level (pixels per side)
// Second level: strips, not squares. A tile's sub-tiles then write eight rows of the frame's
// five arrays, one after the other along each row; a 64×64 tile writes 64 rows at once, whose
// pages and streams thrash the TLB and the prefetchers (the machined part at 1280×720: 21 → 17
// ms a frame, docs/performance.md).
constexpr int kTileW = 256, kTileH = 8;
constexpr int kSubTile = 8;  // last level: the pixels of a sub-tile share one program

// Per-literal facts looked up from an endpoint's tag.
struct Tag {
    std::int32_t halfSpace = -1;
    std::int32_t body = -1;
    bool complemented = false;
    bool opaque = true;
};

struct SceneTables {
    std::vector<RayHalfSpace> halfSpaces;
    std::vector<Tag> tags;
    std::vector<std::int32_t> bodyFirstTag;  // body b's literals are tags [first[b], first[b+1])
    std::vector<bool> bodyValid;             // false when a literal names a missing half-space
    // Per half-space: true for a plane, whose world normal (FlatScene::WorldNormal) is the same
    // at every point and is computed once here, in `planeNormal`.
    std::vector<bool> constantNormal;
    std::vector<Vec3> planeNormal;
    // 0, 1, 2, … (one per tag): body b's literal tags as an array, tagSequence.data() +
    // bodyFirstTag[b] (Worker::ReduceBody takes its literals as an array).
    std::vector<std::int32_t> tagSequence;

    explicit SceneTables(const FlatScene& scene) {
        std::vector<Vec3> reference = ReferencePoints(scene);
        halfSpaces.reserve(scene.halfSpaces.size());
        constantNormal.assign(scene.halfSpaces.size(), false);
        planeNormal.assign(scene.halfSpaces.size(), Vec3{});
        for (std::size_t h = 0; h < scene.halfSpaces.size(); ++h) {
            halfSpaces.push_back(RayHalfSpace::From(scene.halfSpaces[h], reference[h]));
            if (scene.halfSpaces[h].isPlane) {
                constantNormal[h] = true;
                planeNormal[h] = scene.WorldNormal(static_cast<int>(h), Vec3{});
            }
        }
        bodyFirstTag.reserve(scene.bodies.size() + 1);
        bodyValid.assign(scene.bodies.size(), true);
        for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
            bodyFirstTag.push_back(static_cast<std::int32_t>(tags.size()));
            for (const FlatLiteral& lit : scene.bodies[b].literals) {
                if (lit.halfSpace < 0 ||
                    static_cast<std::size_t>(lit.halfSpace) >= scene.halfSpaces.size()) {
                    bodyValid[b] = false;
                    continue;
                }
                const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
                tags.push_back({lit.halfSpace, static_cast<std::int32_t>(b), lit.complemented,
                                !hs.transparent && !hs.isClip});
            }
        }
        bodyFirstTag.push_back(static_cast<std::int32_t>(tags.size()));
        tagSequence.resize(tags.size());
        for (std::size_t i = 0; i < tagSequence.size(); ++i)
            tagSequence[i] = static_cast<std::int32_t>(i);
    }

    // Re-centring points for the quadrics (ray_literal.h): the quadric's own centre when it has
    // one (RayHalfSpace::Centre), else the image centre at depth 0. They depend on nothing but the
    // half-space, so bounds (culling) cannot change a single bit of the result.
    static std::vector<Vec3> ReferencePoints(const FlatScene& scene) {
        Vec3 anchor{std::round(0.5 * scene.width), std::round(0.5 * scene.height), 0};
        std::vector<Vec3> ref;
        ref.reserve(scene.halfSpaces.size());
        for (const FlatHalfSpace& hs : scene.halfSpaces)
            ref.push_back(hs.isPlane ? anchor : RayHalfSpace::Centre(hs.quadric).value_or(anchor));
        return ref;
    }
};

// Engine options (--engine-opt KEY=VALUE), both "on" by default; switching them off changes
// speed only, never a bit of the frame (RaycastOptions.* tests), which is how their effect is
// measured:
//   batch=on|off      body batches over the pixels of a sub-tile (Worker::BodyBatch);
//   tile-cull=on|off  per-sub-tile proofs: bodies empty there (crossing plane bounds, quadrics no
//                     ray meets), quadric literals that hold on every ray, and flat sub-tiles
//                     filled directly (Worker::TryFlatFill);
//   kernel=on|off     small sub-tile programs compiled to postfix code over body batches and run
//                     per pixel without Evaluate's recursion (Worker::CompileKernel; needs batch).
struct Settings {
    bool batch = true;
    bool tileCull = true;
    bool kernel = true;
};

const OptionSchema& RaycastSchema() {
    using O = OptionSpec;
    static const OptionSchema kSchema{
        O::Bool("batch", "on", "body batches over the pixels of a sub-tile"),
        O::Bool("tile-cull", "on",
                "per-sub-tile proofs (empty bodies, literals that always hold, flat fills)"),
        O::Bool("kernel", "on",
                "sub-tile programs compiled to postfix code over body batches (needs batch)"),
    };
    return kSchema;
}

Settings ReadSettings(const EngineOptions& options) {
    Settings st;
    st.batch = options.Bool("batch");
    st.tileCull = options.Bool("tile-cull");
    st.kernel = options.Bool("kernel");
    return st;
}

struct Counters {
    std::uint64_t blocks = 0, coarseTiles = 0, tiles = 0, pixels = 0, tileSolids = 0,
                  pixelSolids = 0, zStops = 0, bodies = 0, csgOps = 0, covered = 0,
                  cutRetries = 0, prunedLiterals = 0, flatTiles = 0, flatPixels = 0,
                  emptyBodies = 0, batchBodies = 0, batchPixels = 0, bodyFillTiles = 0,
                  emptyTiles = 0, kernelTiles = 0, kernelPixels = 0, kernelScalarBodies = 0,
                  kernelScalarPixels = 0;
    LiteralCounters literals;

    void Add(const Counters& o) {
        blocks += o.blocks;
        coarseTiles += o.coarseTiles;
        tiles += o.tiles;
        pixels += o.pixels;
        tileSolids += o.tileSolids;
        pixelSolids += o.pixelSolids;
        zStops += o.zStops;
        bodies += o.bodies;
        csgOps += o.csgOps;
        covered += o.covered;
        cutRetries += o.cutRetries;
        prunedLiterals += o.prunedLiterals;
        flatTiles += o.flatTiles;
        flatPixels += o.flatPixels;
        emptyBodies += o.emptyBodies;
        batchBodies += o.batchBodies;
        batchPixels += o.batchPixels;
        bodyFillTiles += o.bodyFillTiles;
        emptyTiles += o.emptyTiles;
        kernelTiles += o.kernelTiles;
        kernelPixels += o.kernelPixels;
        kernelScalarBodies += o.kernelScalarBodies;
        kernelScalarPixels += o.kernelScalarPixels;
        literals.planes += o.literals.planes;
        literals.quadrics += o.literals.quadrics;
    }
};

struct Hit {
    double t = HUGE_VAL;
    std::int32_t tag = -1;
    std::int32_t solid = -1;
};

// Where pixels are written: the Frame's five arrays, or a tile's staging copy of them (Worker's
// tile buffer), addressed by pixel (x, y) relative to the origin (x0, y0) with `stride` pixels
// a row. A tile writes its sub-tiles into the staging copy, which RenderTile then copies into
// the Frame row by row: eight 256-pixel runs per array, where writing each 8×8 sub-tile into the
// Frame directly touched its rows eight pixels at a time (write misses the prefetchers cannot
// follow: about 20 cycles a pixel, against 6 for the runs).
struct PixelRows {
    double* depth;
    Vec3* normal;
    std::int32_t* surface;
    std::int32_t* body;
    std::int32_t* solid;
    std::size_t stride;
    int x0, y0;

    static PixelRows Of(Frame& f) {
        return {f.depth.data(), f.normal.data(), f.surface.data(), f.body.data(), f.solid.data(),
                static_cast<std::size_t>(f.width), 0, 0};
    }
    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y - y0) * stride + static_cast<std::size_t>(x - x0);
    }
    void SetBackground(std::size_t k) const {
        depth[k] = HUGE_VAL;
        normal[k] = Vec3{};
        surface[k] = Frame::kNone;
        body[k] = Frame::kNone;
        solid[k] = Frame::kNone;
    }
    // Background on the pixel rectangle [x0, x1) × [y0, y1): array by array along each row
    // (contiguous stores the compiler turns into wide ones), not pixel by pixel.
    void FillBackground(int xa, int ya, int xb, int yb) const {
        const auto n = static_cast<std::size_t>(xb - xa);
        for (int j = ya; j < yb; ++j) {
            const std::size_t k = Index(xa, j);
            std::fill_n(depth + k, n, HUGE_VAL);
            std::fill_n(normal + k, n, Vec3{});
            std::fill_n(surface + k, n, Frame::kNone);
            std::fill_n(body + k, n, Frame::kNone);
            std::fill_n(solid + k, n, Frame::kNone);
        }
    }
};

// One plane literal over the n pixels of a body batch (Worker::BodyBatch): r = -(px x + py y +
// pd)/c as EvaluateBody computes it, a near bound replacing lo unless lo > r, a far bound
// replacing hi unless hi <= r; `bad` becomes non-zero where r is not finite. Branch-free, so the
// compiler vectorises it; built for AVX2 and for the baseline, chosen at load time (the results
// are the same bits: IEEE division and comparisons, no FMA contraction).
// kNear: a near bound (t >= r) into lo/loId; else a far bound (t <= r) into hi/hiId.
template <bool kNear>
__attribute__((target_clones("avx2", "default"))) void PlaneBatch(
    int n, const double* xs, const double* ys, double px, double py, double pd, double c,
    std::int64_t tag, double* __restrict bound, std::int64_t* __restrict boundId,
    double* __restrict bad) {
    for (int p = 0; p < n; ++p) {
        const double r = -(px * xs[p] + py * ys[p] + pd) / c;
        bad[p] = std::fabs(r) < HUGE_VAL ? bad[p] : 1.0;
        const bool take = kNear ? !(bound[p] > r) : !(bound[p] <= r);
        bound[p] = take ? r : bound[p];
        boundId[p] = take ? tag : boundId[p];
    }
}

// Lanes: the kernel's sets (Worker::RunKernelTile) over the pixels of a sub-tile, one array per
// field. Per pixel a lane holds ∅ or one interval (n = 0 or 1) and a cut T: the lane equals the
// kernel's exact set on t < T, ids included (T = +inf: exactly). Where an operation would give a
// second interval, the lane keeps the first and sets T to the second one's start; everything
// below T is then as in the full list (set operations are pointwise in t, and a sweep emits the
// same endpoints below T from the same events below T: the argument of Trace's depth cuts). The
// first visible endpoint of a solid is therefore exact when it lies below T; a pixel where it
// does not, or where a body's set is not in its batch, is marked in `over` and evaluated by
// RunKernel. The operations are the one-interval cases of math/interval_list.h written as
// selects, with the same comparisons and tie rules (checked bit for bit against RunKernel and
// Trace by RaycastOptions.SpeedOptionsChangeNoBit): no arithmetic, so nothing to round.
constexpr int kLanePixels = kSubTile * kSubTile;
struct Lane {
    double lo[kLanePixels], hi[kLanePixels], cut[kLanePixels];
    std::int64_t loId[kLanePixels], hiId[kLanePixels], n[kLanePixels];
};

// A body's set from its batch: ∅ where the pixel centre is outside the body's bounds `r` or the
// batch is kEmpty, its interval where kOne, its first interval and cut where kCut, `over` where
// kScalar.
__attribute__((target_clones("avx2", "default"))) void LanePush(
    int np, const double* xs, const double* ys, const Rect& r, const std::uint8_t* state,
    const double* lo, const double* hi, const double* cut, const std::int64_t* loId,
    const std::int64_t* hiId, Lane& out, std::int64_t* __restrict over) {
    for (int p = 0; p < np; ++p) {
        // Bitwise, not short-circuit, so that every comparison is made and the loop has no
        // branches (a skipped comparison could not be if-converted under -ftrapping-math).
        const bool in = !((xs[p] < r.x0) | (xs[p] > r.x1) | (ys[p] < r.y0) | (ys[p] > r.y1));
        out.lo[p] = lo[p];
        out.hi[p] = hi[p];
        out.loId[p] = loId[p];
        out.hiId[p] = hiId[p];
        // BodyBatch::kOne: the interval; kCut: its first interval below its cut; kScalar: over.
        const bool isCut = in & (state[p] == 3);
        out.cut[p] = isCut ? cut[p] : HUGE_VAL;
        out.n[p] = (in & (state[p] == 1)) | (isCut & (lo[p] < hi[p]));
        over[p] |= in & (state[p] == 2);
    }
}

// a = a ∪ b (UnionOfOne; ∅ ∪ B = B, A ∪ ∅ = A); two disjoint pieces keep the first.
__attribute__((target_clones("avx2", "default"))) void LaneUnion(int np, Lane& a, const Lane& b) {
    for (int p = 0; p < np; ++p) {
        const double alo = a.lo[p], ahi = a.hi[p], blo = b.lo[p], bhi = b.hi[p];
        const std::int64_t aloId = a.loId[p], ahiId = a.hiId[p], bloId = b.loId[p],
                           bhiId = b.hiId[p];
        const bool na = a.n[p] != 0, nb = b.n[p] != 0;
        const bool aFirst = alo <= blo;
        const double flo = aFirst ? alo : blo, fhi = aFirst ? ahi : bhi;
        const std::int64_t floId = aFirst ? aloId : bloId, fhiId = aFirst ? ahiId : bhiId;
        const double glo = aFirst ? blo : alo;
        const bool joined = glo <= fhi;
        const bool bLast = bhi >= ahi;
        const double lastHi = bLast ? bhi : ahi;
        const std::int64_t lastHiId = bLast ? bhiId : ahiId;
        const double uhi = joined ? lastHi : fhi;
        const std::int64_t uhiId = joined ? lastHiId : fhiId;
        const bool both = na & nb, onlyB = !na & nb;
        const double ac = a.cut[p], bc = b.cut[p];
        const double cut0 = ac < bc ? ac : bc;
        const bool cutHere = both & !joined & (glo < cut0);
        // Both: the joined (or first) piece; only b: b; else a as it is.
        const double keepLo = onlyB ? blo : alo, keepHi = onlyB ? bhi : ahi;
        const std::int64_t keepLoId = onlyB ? bloId : aloId, keepHiId = onlyB ? bhiId : ahiId;
        a.lo[p] = both ? flo : keepLo;
        a.loId[p] = both ? floId : keepLoId;
        a.hi[p] = both ? uhi : keepHi;
        a.hiId[p] = both ? uhiId : keepHiId;
        a.n[p] = na | nb;
        a.cut[p] = cutHere ? glo : cut0;
    }
}

// a = a ∩ b (IntersectionOfOne; ∅ when either is ∅ or they meet in a point or not at all).
__attribute__((target_clones("avx2", "default"))) void LaneIntersection(int np, Lane& a,
                                                                        const Lane& b) {
    for (int p = 0; p < np; ++p) {
        const bool openB = b.lo[p] >= a.lo[p], closeA = a.hi[p] <= b.hi[p];
        const double lo = openB ? b.lo[p] : a.lo[p], hi = closeA ? a.hi[p] : b.hi[p];
        const std::int64_t loId = openB ? b.loId[p] : a.loId[p];
        const std::int64_t hiId = closeA ? a.hiId[p] : b.hiId[p];
        const bool keep = (a.n[p] != 0) & (b.n[p] != 0) & (lo < hi);
        a.lo[p] = lo;
        a.hi[p] = hi;
        a.loId[p] = loId;
        a.hiId[p] = hiId;
        a.n[p] = keep;
        a.cut[p] = a.cut[p] < b.cut[p] ? a.cut[p] : b.cut[p];
    }
}

// a = a − b (AppendDifferenceOfOne; ∅ − B = ∅, A − ∅ = A): b covering a's start leaves
// [b.hi, a.hi] when b ends first; b before or after a leaves a; b starting inside a leaves
// [a.lo, b.lo] and [b.hi, a.hi], each when not a point (both: the first, cut at b.hi).
__attribute__((target_clones("avx2", "default"))) void LaneDifference(int np, Lane& a,
                                                                      const Lane& b) {
    for (int p = 0; p < np; ++p) {
        const bool na = a.n[p] != 0, nb = b.n[p] != 0;
        const double alo = a.lo[p], ahi = a.hi[p], blo = b.lo[p], bhi = b.hi[p];
        const std::int64_t aloId = a.loId[p], ahiId = a.hiId[p], bloId = b.loId[p],
                           bhiId = b.hiId[p];
        const bool covers = (blo < alo) & (bhi >= alo);
        const bool apart = (bhi < alo) | (blo > ahi);
        const bool tail = bhi < ahi;  // [b.hi, a.hi] is a piece
        const bool head = alo < blo;  // [a.lo, b.lo] is a piece (when b starts inside a)
        const bool inside = !covers & !apart;
        // The result when both are non-empty: covers → tail or ∅; apart → a; inside → head
        // (cut at the tail when there is one), or else tail, or else ∅.
        const bool useTail = covers | (inside & !head);
        const bool useHead = inside & head;
        const bool nonEmpty = apart | (useTail & tail) | useHead;
        const bool change = na & nb;
        const double ac = a.cut[p], bc = b.cut[p];
        const double cut0 = ac < bc ? ac : bc;
        const bool cutHere = change & useHead & tail & (bhi < cut0);
        const bool newLo = change & useTail, newHi = change & useHead;
        a.lo[p] = newLo ? bhi : alo;
        a.loId[p] = newLo ? bhiId : aloId;
        a.hi[p] = newHi ? blo : ahi;
        a.hiId[p] = newHi ? bloId : ahiId;
        a.n[p] = na & (!nb | nonEmpty);
        a.cut[p] = cutHere ? bhi : cut0;
    }
}

// Everything one thread needs; reused across tiles and pixels.
class Worker {
  public:
    Worker(const SceneTables* tables, int maxDepth, Settings settings)
        : tables_(*tables), settings_(settings) {
        // Slot d holds the result of a node at depth d; a node at depth d also uses d+1 and d+2
        // (operand and scratch). Results move between slots by swapping pointers.
        lists_.resize(static_cast<std::size_t>(maxDepth) + 3);
        for (IntervalList& l : lists_) slots_.push_back(&l);
    }

    CsgProgram tileProgram, subTileProgram;
    std::vector<std::int32_t> stack;
    Counters counters;

    // The staging copy of the current tile's pixels (PixelRows), and its copy into the Frame.
    PixelRows TileRows(int x0, int y0) {
        return {tileDepth_.data(), tileNormal_.data(), tileSurface_.data(), tileBody_.data(),
                tileSolid_.data(),  kTileW,            x0,                  y0};
    }
    void CopyTile(int x0, int y0, int x1, int y1, Frame& frame) const {
        const auto n = static_cast<std::ptrdiff_t>(x1 - x0);
        for (int j = y0; j < y1; ++j) {
            const auto from = static_cast<std::ptrdiff_t>(j - y0) * kTileW;
            const auto to = static_cast<std::ptrdiff_t>(frame.Index(x0, j));
            std::copy_n(tileDepth_.begin() + from, n, frame.depth.begin() + to);
            std::copy_n(tileNormal_.begin() + from, n, frame.normal.begin() + to);
            std::copy_n(tileSurface_.begin() + from, n, frame.surface.begin() + to);
            std::copy_n(tileBody_.begin() + from, n, frame.body.begin() + to);
            std::copy_n(tileSolid_.begin() + from, n, frame.solid.begin() + to);
        }
    }

    // The literals each body of a sub-tile program evaluates (EvaluateBody): all of the body's, in
    // its order, except planes that provably never bound it anywhere in the sub-tile `r`:
    //  - a plane parallel to the rays (c = 0) that holds at every pixel centre of the rectangle;
    //  - a plane giving a near bound t >= r_b (far bound t <= r_b) when another plane of the same
    //    body gives a near bound r_a > r_b (far bound r_a < r_b) at every pixel centre.
    // r is linear in (x, y), so comparing at the rectangle's four corner centres decides the
    // whole rectangle; a relative margin of 1e-9 (far above the few ulps of rounding in
    // r = -(A x + B y + D)/C) keeps ties out. A dropped plane is then never the maximum (minimum)
    // bound and never empties the set alone, and ClipTo with it changes no endpoint, so the
    // result is bit-for-bit that of all the literals.
    //
    // Two levels. PrepareStrip runs the same reduction (ReduceBody) once per tile (a 256×8 strip)
    // for the bodies of the tile program; PrepareTile then starts each body from the literals the
    // strip kept, or takes it as empty when the strip proved it so. Every proof on the strip's
    // rectangle holds on each sub-tile's rectangle inside it, and a dropped plane's dominator is
    // kept or dropped for a plane that dominates both (dominance with margins is transitive), so
    // the sub-tile's literals are again the body's minus droppable ones, in the body's order.
    void PrepareStrip(const CsgProgram& program, const Rect& r) {
        ++stripStamp_;
        if (stripBody_.size() < tables_.bodyValid.size()) stripBody_.resize(tables_.bodyValid.size());
        stripTags_.clear();
        for (const ProgNode& node : program.nodes) {
            if (node.kind != NodeKind::kBody) continue;
            const auto body = static_cast<std::size_t>(node.first);
            StripBody& sb = stripBody_[body];
            if (sb.stamp == stripStamp_) continue;  // (a body is one node; cheap guard anyway)
            const auto begin = static_cast<std::int32_t>(stripTags_.size());
            const bool empty = ReduceBody(BodyTags(body), BodyTagCount(body), r, stripTags_);
            sb = {begin, static_cast<std::int32_t>(stripTags_.size()), empty, stripStamp_};
        }
    }
    void PrepareTile(const CsgProgram& program, const Rect& r) {
        tileTags_.clear();
        nodeTags_.assign(program.nodes.size(), {0, 0});
        nodeEmpty_.assign(program.nodes.size(), false);
        for (std::size_t n = 0; n < program.nodes.size(); ++n) {
            const ProgNode& node = program.nodes[n];
            if (node.kind != NodeKind::kBody) continue;
            const auto body = static_cast<std::size_t>(node.first);
            const auto begin = static_cast<std::int32_t>(tileTags_.size());
            const auto all = static_cast<std::int32_t>(BodyTagCount(body));
            bool empty;
            if (body < stripBody_.size() && stripBody_[body].stamp == stripStamp_) {
                const StripBody& sb = stripBody_[body];
                empty = sb.empty ||
                        ReduceBody(stripTags_.data() + sb.begin,
                                   static_cast<std::size_t>(sb.end - sb.begin), r, tileTags_);
            } else {
                empty = ReduceBody(BodyTags(body), BodyTagCount(body), r, tileTags_);
            }
            if (empty) {
                tileTags_.resize(static_cast<std::size_t>(begin));
                nodeEmpty_[n] = true;
                ++counters.emptyBodies;
                nodeTags_[n] = {begin, begin};
                continue;
            }
            nodeTags_[n] = {begin, static_cast<std::int32_t>(tileTags_.size())};
            counters.prunedLiterals +=
                static_cast<std::uint64_t>(all - (nodeTags_[n].second - begin));
        }
    }

    // All of body b's literal tags, in its order.
    const std::int32_t* BodyTags(std::size_t b) const {
        return tables_.tagSequence.data() + tables_.bodyFirstTag[b];
    }
    std::size_t BodyTagCount(std::size_t b) const {
        return static_cast<std::size_t>(tables_.bodyFirstTag[b + 1] - tables_.bodyFirstTag[b]);
    }

    // The reduction of PrepareTile for one body on the rectangle r: appends to `out` the literals
    // of tags[0, n) (a body's literals in its order, or a subsequence of them already reduced on a
    // rectangle containing r) that may bound the body somewhere in r, and returns true (with
    // nothing appended) when the body is provably empty on every ray of r.
    bool ReduceBody(const std::int32_t* tags, std::size_t n, const Rect& r,
                    std::vector<std::int32_t>& out) {
        const double cx[4] = {r.x0, r.x1, r.x0, r.x1}, cy[4] = {r.y0, r.y0, r.y1, r.y1};
        bounds_.clear();
        bool bodyEmptyByQuadric = false;
        for (std::size_t i = 0; i < n; ++i) {
            const std::int32_t tag = tags[i];
            const Tag& t = TagOf(tag);
            const RayHalfSpace& hs = tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
            PlaneBound b{tag, 0, {}};
            if (hs.isPlane && std::isfinite(hs.c)) {
                bool finite = true;
                for (int k = 0; k < 4; ++k) {
                    const double e = hs.px * cx[k] + hs.py * cy[k] + hs.pd;
                    finite &= std::isfinite(e);
                    b.r[k] = hs.c == 0 ? e : -e / hs.c;
                    finite &= std::isfinite(b.r[k]);
                }
                if (finite && hs.c == 0) {
                    bool holds = true;  // strictly, everywhere in the rectangle
                    for (int k = 0; k < 4; ++k) {
                        const double m = 1e-9 * (std::fabs(hs.px * cx[k]) +
                                                 std::fabs(hs.py * cy[k]) + std::fabs(hs.pd)) +
                                         1e-300;
                        holds &= t.complemented ? b.r[k] > m : b.r[k] < -m;
                    }
                    if (holds) continue;  // the literal holds on every ray: drop it
                } else if (finite) {
                    b.side = (hs.c > 0) != t.complemented ? 1 : -1;  // 1: t <= r, -1: t >= r
                }
            } else if (!hs.isPlane && settings_.tileCull) {
                const QuadricOnRect q = ClassifyQuadric(hs, r.x0, r.x1, r.y0, r.y1);
                if (q != QuadricOnRect::kUnknown) {
                    // No ray of the rectangle meets the surface: the literal holds on all
                    // of every ray (dropped) or on none (the body is empty).
                    const bool holds = (q == QuadricOnRect::kInsideEverywhere) != t.complemented;
                    if (holds) continue;
                    bodyEmptyByQuadric = true;
                }
            }
            bounds_.push_back(b);
        }
        // Empty everywhere: a near bound beyond a far bound at the four corners (margin as
        // below) stays beyond it on the whole rectangle, so no ray of the sub-tile meets the
        // body, and Evaluate takes it as ∅ without evaluating it (exactly what the body's
        // literals would give: an empty set, and ∅ is an exact identity of every operator).
        bool empty = bodyEmptyByQuadric;
        for (std::size_t i = 0; i < bounds_.size() && !empty && settings_.tileCull; ++i) {
            if (bounds_[i].side >= 0) continue;
            for (std::size_t j = 0; j < bounds_.size() && !empty; ++j) {
                if (bounds_[j].side <= 0) continue;
                bool all = true;
                for (int k = 0; k < 4 && all; ++k) {
                    const double m =
                        1e-9 * (std::fabs(bounds_[i].r[k]) + std::fabs(bounds_[j].r[k])) + 1e-300;
                    all = bounds_[i].r[k] - bounds_[j].r[k] > m;
                }
                empty = all;
            }
        }
        if (empty) return true;
        for (std::size_t i = 0; i < bounds_.size(); ++i) {
            const PlaneBound& b = bounds_[i];
            bool dominated = false;
            for (std::size_t j = 0; j < bounds_.size() && !dominated && b.side != 0; ++j) {
                const PlaneBound& a = bounds_[j];
                if (j == i || a.side != b.side) continue;
                bool all = true;
                for (int k = 0; k < 4 && all; ++k) {
                    const double m = 1e-9 * (std::fabs(a.r[k]) + std::fabs(b.r[k])) + 1e-300;
                    // Near bounds: a is tighter where r_a > r_b; far bounds where r_a < r_b.
                    all = b.side < 0 ? a.r[k] - b.r[k] > m : b.r[k] - a.r[k] > m;
                }
                dominated = all;
            }
            if (!dominated) out.push_back(b.tag);
        }
        return false;
    }

    // Flat sub-tiles. When the sub-tile program is one solid whose tree is one body, PrepareTile
    // has kept only planes, every pixel centre of `r` lies inside the node's and the solid's
    // bounds, and exactly one kept plane bounds the body from the near side, that plane is the
    // body's near end at every pixel (PrepareTile dropped the others because it dominates them
    // everywhere in the rectangle). If moreover every kept far-side plane lies beyond it by a
    // margin at the four corner centres, the difference of the two depths is linear in (x, y)
    // and stays positive on the whole rectangle, so the set on every ray is the one interval
    // [r_near, r_far] and the visible point is r_near. The pixel's result is then written
    // directly, with the very expression EvaluateBody uses for r (the same bits), the plane's
    // constant normal and ids. Returns false (nothing written) when any condition fails.
    bool TryFlatFill(const CsgProgram& program, const Rect& r, int x0, int y0, int x1, int y1,
                     const PixelRows& out) {
        if (!settings_.tileCull || program.solids.size() != 1) return false;
        const ProgSolid& solid = program.solids[0];
        auto contains = [&](const Rect& b) {
            return b.x0 <= r.x0 && b.x1 >= r.x1 && b.y0 <= r.y0 && b.y1 >= r.y1;
        };
        if (!contains(solid.xy)) return false;
        const std::int32_t bodyNode = SingleBody(program, solid.root, r);
        if (bodyNode < 0) return false;
        const ProgNode& node = program.nodes[static_cast<std::size_t>(bodyNode)];
        const auto body = static_cast<std::size_t>(node.first);
        if (!tables_.bodyValid[body] || tables_.bodyFirstTag[body] == tables_.bodyFirstTag[body + 1])
            return false;
        const auto [begin, end] = nodeTags_[static_cast<std::size_t>(bodyNode)];
        const double cx[4] = {r.x0, r.x1, r.x0, r.x1}, cy[4] = {r.y0, r.y0, r.y1, r.y1};
        std::int32_t nearTag = -1;
        double nearR[4] = {0, 0, 0, 0};
        for (std::int32_t i = begin; i < end; ++i) {
            const std::int32_t tag = tileTags_[static_cast<std::size_t>(i)];
            const Tag& t = TagOf(tag);
            const RayHalfSpace& hs = tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
            if (!hs.isPlane || !std::isfinite(hs.c) || hs.c == 0) return false;
            if ((hs.c > 0) != t.complemented) continue;  // a far bound: checked below
            if (nearTag >= 0 || !t.opaque) return false;
            nearTag = tag;
            for (int k = 0; k < 4; ++k) {
                nearR[k] = -(hs.px * cx[k] + hs.py * cy[k] + hs.pd) / hs.c;
                if (!(std::fabs(nearR[k]) < 1e300)) return false;
            }
        }
        if (nearTag < 0) return false;
        for (std::int32_t i = begin; i < end; ++i) {
            const std::int32_t tag = tileTags_[static_cast<std::size_t>(i)];
            const Tag& t = TagOf(tag);
            const RayHalfSpace& hs = tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
            if ((hs.c > 0) == t.complemented) continue;  // the near bound
            for (int k = 0; k < 4; ++k) {
                const double far = -(hs.px * cx[k] + hs.py * cy[k] + hs.pd) / hs.c;
                const double m = 1e-9 * (std::fabs(far) + std::fabs(nearR[k])) + 1e-300;
                if (!(far - nearR[k] > m)) return false;
            }
        }
        const Tag& near = TagOf(nearTag);
        const auto hsIndex = static_cast<std::size_t>(near.halfSpace);
        const RayHalfSpace& hs = tables_.halfSpaces[hsIndex];
        const Vec3 normal = tables_.planeNormal[hsIndex];
        for (int j = y0; j < y1; ++j) {
            const double y = j + 0.5;
            std::size_t k = out.Index(x0, j);
            for (int i = x0; i < x1; ++i, ++k) {
                const double x = i + 0.5;
                const double e = hs.px * x + hs.py * y + hs.pd;  // as EvaluateBody
                out.depth[k] = -e / hs.c;
                out.normal[k] = normal;
                out.surface[k] = near.halfSpace;
                out.body[k] = near.body;
                out.solid[k] = solid.solid;
            }
        }
        const auto n = static_cast<std::uint64_t>((x1 - x0) * (y1 - y0));
        counters.covered += n;
        counters.flatPixels += n;
        ++counters.flatTiles;
        return true;
    }

    // True when every solid of the sub-tile program is ∅ on every ray of the rectangle (the
    // bodies PrepareTile proved empty leave nothing, by the identities of SingleBody): the
    // sub-tile is background.
    bool AllEmpty(const CsgProgram& program, const Rect& r) const {
        if (!settings_.tileCull) return false;
        for (const ProgSolid& s : program.solids)
            if (SingleBody(program, s.root, r) != kEmptyNode) return false;
        return true;
    }

    // The body node that the subtree of node n is equal to on every ray of the sub-tile `r`
    // (ids included), given the bodies PrepareTile found empty there: the identities
    // A ∪ ∅ = A, A − ∅ = A, op(A) = A (math/interval_list.h) leave one body when all its
    // siblings are empty. kEmptyNode when the subtree is empty; -1 when it is not one body or a
    // node on the way does not contain the whole rectangle (MissesPoint could then cut pixels).
    static constexpr std::int32_t kEmptyNode = -2;
    std::int32_t SingleBody(const CsgProgram& p, std::int32_t n, const Rect& r) const {
        const ProgNode& node = p.nodes[static_cast<std::size_t>(n)];
        if (nodeEmpty_[static_cast<std::size_t>(n)]) return kEmptyNode;
        if (!(node.xy.x0 <= r.x0 && node.xy.x1 >= r.x1 && node.xy.y0 <= r.y0 &&
              node.xy.y1 >= r.y1))
            return -1;
        if (node.kind == NodeKind::kBody) return n;
        const std::int32_t* child = p.children.data() + node.first;
        std::int32_t found = kEmptyNode;
        for (std::int32_t i = 0; i < node.count; ++i) {
            const std::int32_t c = SingleBody(p, child[i], r);
            if (c == -1) return -1;
            if (c == kEmptyNode) {
                // ∅ ∩ B = ∅, ∅ − B = ∅; a union or a later subtrahend just drops it.
                if (node.kind == NodeKind::kIntersection) return kEmptyNode;
                if (node.kind == NodeKind::kDifference && i == 0) return kEmptyNode;
                continue;
            }
            if (found != kEmptyNode) return -1;  // two non-empty operands
            if (node.kind == NodeKind::kDifference && i > 0) return -1;  // a real subtrahend
            found = c;
        }
        return found;  // (an intersection gets here only with one operand: ∅ returned above)
    }

    // Depth cuts of the current sub-tile (see SetCuts), ascending, the last one +inf.
    std::vector<double> cuts{HUGE_VAL};

    // Cut levels for a sub-tile program: the 8th, 32nd, 128th and 512th nearest leaf depths
    // (zlo) when the program has more leaves than that, then +inf.
    void SetCuts(const CsgProgram& program) {
        cuts.clear();
        zlos_.clear();
        for (const ProgNode& n : program.nodes)
            if (n.kind == NodeKind::kBody) zlos_.push_back(n.zlo);
        for (std::size_t k : {8u, 32u, 128u, 512u}) {
            if (zlos_.size() <= k) break;
            std::nth_element(zlos_.begin(), zlos_.begin() + static_cast<std::ptrdiff_t>(k),
                             zlos_.end());
            const double cut = zlos_[k];
            if (std::isfinite(cut) && (cuts.empty() || cut > cuts.back())) cuts.push_back(cut);
        }
        cuts.push_back(HUGE_VAL);
    }

    // The visible point of the pixel (x, y): per solid in order of nearest depth, its first
    // opaque endpoint.
    //
    // Depth cuts: evaluating a tree with every node whose zlo >= T replaced by ∅ gives its set
    // exactly on t < T (set operations are pointwise in t, and a node with zlo >= T is empty
    // there), ids included (the dropped nodes have no endpoints before T, so no sweep sees a
    // different event before T). A first visible endpoint found below T is therefore the
    // exact one. Big unions (thousands of spheres) are evaluated with growing cuts and most
    // pixels stop at the first: cost grows with the depth complexity near the visible surface,
    // not with every primitive behind it.
    Hit Trace(const CsgProgram& program, double x, double y) {
        Hit best;
        for (const ProgSolid& s : program.solids) {
            if (best.t < s.zlo) {  // strictly: a tie at s.zlo may still go to a lower index
                ++counters.zStops;
                break;
            }
            if (x < s.xy.x0 || x > s.xy.x1 || y < s.xy.y0 || y > s.xy.y1) continue;
            ++counters.pixelSolids;
            for (double cut : cuts) {
                if (cut <= s.zlo) continue;  // the whole solid is cut away
                Evaluate(program, s.root, x, y, 0, cut);
                double t;
                std::int32_t tag;
                if (FirstVisible(*slots_[0], t, tag) && t < cut) {
                    if (t < best.t || (t == best.t && s.solid < best.solid))
                        best = {t, tag, s.solid};
                    break;
                }
                // Nothing visible before the cut: this solid cannot beat a best nearer than it.
                if (best.t < cut) break;
                if (cut != HUGE_VAL) ++counters.cutRetries;
            }
        }
        return best;
    }

    const Tag& TagOf(std::int32_t tag) const { return tables_.tags[static_cast<std::size_t>(tag)]; }

    // The visible end of one interval: its near end when it is finite and on an opaque surface,
    // else its far end on the same terms; false when neither is.
    bool VisibleEnd(double lo, std::int32_t loId, double hi, std::int32_t hiId, double& t,
                    std::int32_t& tag) const {
        if (loId >= 0 && std::isfinite(lo) && TagOf(loId).opaque) {
            t = lo;
            tag = loId;
            return true;
        }
        if (hiId >= 0 && std::isfinite(hi) && TagOf(hiId).opaque) {
            t = hi;
            tag = hiId;
            return true;
        }
        return false;
    }

  private:
    // The first finite endpoint on an opaque surface.
    bool FirstVisible(const IntervalList& list, double& t, std::int32_t& tag) const {
        for (const Interval& v : list)
            if (VisibleEnd(v.lo, v.loId, v.hi, v.hiId, t, tag)) return true;
        return false;
    }

    // *slots_[slot] = the set of node n on the ray through (x, y), exact on t < cut (nodes with
    // zlo >= cut are taken as ∅; see Trace).
    void Evaluate(const CsgProgram& p, std::int32_t n, double x, double y, std::size_t slot,
                  double cut) {
        const ProgNode& node = p.nodes[static_cast<std::size_t>(n)];
        if (node.MissesPoint(x, y) || node.zlo >= cut || nodeEmpty_[static_cast<std::size_t>(n)]) {
            slots_[slot]->clear();
            return;
        }
        if (node.kind == NodeKind::kBody) {
            EvaluateBody(node.first, n, x, y, slot);
            return;
        }
        const std::int32_t* child = p.children.data() + node.first;
        Evaluate(p, child[0], x, y, slot, cut);
        for (std::int32_t i = 1; i < node.count; ++i) {
            IntervalList& out = *slots_[slot];
            if (out.empty() && node.kind != NodeKind::kUnion) return;  // ∅ ∩ B = ∅ − B = ∅
            // The operand's bounds are tested here as well as in the call, to skip the call for
            // the many operands of a big union that miss this pixel.
            const ProgNode& c = p.nodes[static_cast<std::size_t>(child[i])];
            if (c.MissesPoint(x, y) || c.zlo >= cut ||
                nodeEmpty_[static_cast<std::size_t>(child[i])]) {
                slots_[slot + 1]->clear();
            } else {
                Evaluate(p, child[i], x, y, slot + 1, cut);
            }
            IntervalList& operand = *slots_[slot + 1];
            if (operand.empty()) {
                if (node.kind == NodeKind::kIntersection) {
                    out.clear();
                    return;
                }
                continue;  // A ∪ ∅ = A − ∅ = A
            }
            if (out.empty()) {  // union: ∅ ∪ B = B
                std::swap(slots_[slot], slots_[slot + 1]);
                continue;
            }
            ++counters.csgOps;
            IntervalList& scratch = *slots_[slot + 2];
            switch (node.kind) {
                case NodeKind::kUnion:
                    Union(out, operand, scratch);
                    break;
                case NodeKind::kIntersection:
                    Intersection(out, operand, scratch);
                    break;
                default:
                    Difference(out, operand, scratch);
                    break;
            }
            std::swap(slots_[slot], slots_[slot + 2]);
        }
    }

    // A body is the intersection of its literals, taken in the body's order: each literal's set
    // clips the running set. While that set is one interval (always, for bodies of planes and of
    // quadrics cut by planes, the common case) it is kept in registers and planes are evaluated
    // inline; the first literal whose set has two pieces switches to interval lists. The tie rules
    // are ClipTo's in both paths (a later literal wins a tie at the near end, an earlier one at
    // the far end), so the result does not depend on the path taken.
    //
    // `node` is the body's node in the sub-tile program: its literals are the ones PrepareTile
    // kept (planes that cannot bound the body anywhere in the sub-tile are dropped).
    void EvaluateBody(std::int32_t body, std::int32_t node, double x, double y, std::size_t slot) {
        ++counters.bodies;
        IntervalList& result = *slots_[slot];
        result.clear();  // a body without literals is empty
        if (!tables_.bodyValid[static_cast<std::size_t>(body)]) return;
        if (tables_.bodyFirstTag[static_cast<std::size_t>(body)] ==
            tables_.bodyFirstTag[static_cast<std::size_t>(body) + 1])
            return;
        if (batchOn_) {
            std::int32_t b = nodeBatch_[static_cast<std::size_t>(node)];
            if (b == kNoBatch) b = ComputeBatch(node);
            if (b >= 0) {
                const BodyBatch& batch = batches_[static_cast<std::size_t>(b)];
                const std::size_t p = pixel_;
                if (batch.state[p] == BodyBatch::kEmpty) return;
                if (batch.state[p] == BodyBatch::kOne) {
                    result.Append(batch.lo[p], static_cast<std::int32_t>(batch.loId[p]),
                                  batch.hi[p], static_cast<std::int32_t>(batch.hiId[p]));
                    return;
                }
                // kScalar, kCut: evaluated below, literal by literal, exactly as without batches.
            }
        }
        const auto [begin, end] = nodeTags_[static_cast<std::size_t>(node)];
        const std::int32_t* const tagsEnd = tileTags_.data() + end;
        Interval run{-HUGE_VAL, HUGE_VAL, Interval::kNoId, Interval::kNoId};
        for (const std::int32_t* it = tileTags_.data() + begin; it != tagsEnd; ++it) {
            const std::int32_t tag = *it;
            const Tag& t = TagOf(tag);
            const RayHalfSpace& hs = tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
            Interval w;
            if (hs.isPlane) {
                // LiteralOnRay's plane case, inline: c t + e <= 0 (or its closed complement).
                ++counters.literals.planes;
                const double e = hs.px * x + hs.py * y + hs.pd;
                if (!std::isfinite(e) || !std::isfinite(hs.c)) return;  // empty both ways
                if (hs.c == 0) {
                    if ((e <= 0) == t.complemented) return;  // holds nowhere on this ray
                    continue;                                 // holds everywhere
                }
                const double r = -e / hs.c;
                const bool below = (hs.c > 0) != t.complemented;  // the set is t <= r
                w = below ? Interval{-HUGE_VAL, r, Interval::kNoId, tag}
                          : Interval{r, HUGE_VAL, tag, Interval::kNoId};
                if (std::isinf(r)) {
                    if (!(w.lo < w.hi)) return;  // r overflowed to the empty side
                    continue;                    // r overflowed to the full side
                }
            } else {
                RaySet set = LiteralOnRay(hs, t.complemented, x, y, tag, counters.literals);
                if (set.count == 0) return;
                if (set.count == 2) {
                    EvaluateBodyLists(run, set, it + 1, tagsEnd, x, y, slot);
                    return;
                }
                w = set.piece[0];
            }
            // ClipTo's rules for one piece.
            if (!(run.lo > w.lo)) {
                run.lo = w.lo;
                run.loId = w.loId;
            }
            if (!(run.hi <= w.hi)) {
                run.hi = w.hi;
                run.hiId = w.hiId;
            }
            if (!(run.lo < run.hi)) return;
        }
        AppendPiece(result, run);
    }

  public:
    // Body batches ("SIMD over pixels"). The first time a body is needed in a sub-tile, its set
    // is computed for every pixel of the sub-tile at once, literal by literal over arrays of
    // pixels (the plane loop has no branches and is vectorised by the compiler), with
    // EvaluateBody's exact arithmetic and tie rules: r = -(px x + py y + pd)/c, a near bound
    // replaces lo unless lo > r, a far bound replaces hi unless hi <= r, in the body's literal
    // order. lo only grows and hi only shrinks, so "empty once lo >= hi" needs no early exit.
    // A pixel where anything is out of the ordinary — a non-finite bound, a plane parallel to
    // the rays that does not simply hold, a quadric set of two pieces — is marked kScalar and
    // evaluated by EvaluateBody's scalar loop when asked; every other pixel gets the very
    // interval, ids included, that loop would give.
    // kCut: the pixel's set has more than one interval; [lo, hi] is its first (∅ when lo >= hi)
    // and is exact on t < cut (QuadricBatch's cut mode). EvaluateBody takes kCut as kScalar.
    struct BodyBatch {
        static constexpr std::uint8_t kEmpty = 0, kOne = 1, kScalar = 2, kCut = 3;
        double lo[kSubTile * kSubTile], hi[kSubTile * kSubTile], cut[kSubTile * kSubTile];
        std::int64_t loId[kSubTile * kSubTile], hiId[kSubTile * kSubTile];  // 64-bit: vectorises
                                                                             // with the doubles
        std::uint8_t state[kSubTile * kSubTile];
    };
    static constexpr std::int32_t kNoBatch = -1, kNoBatchWanted = -2;

    // Called by RenderTile before the pixels of a sub-tile [x0, x1) × [y0, y1).
    void StartBatches(const CsgProgram& program, int x0, int y0, int x1, int y1) {
        tileX0_ = x0;
        tileY0_ = y0;
        tileW_ = x1 - x0;
        tileH_ = y1 - y0;
        batchesUsed_ = 0;
        nodeBatch_.assign(program.nodes.size(), kNoBatchWanted);
        // Only bodies whose bounds cover the whole sub-tile are batched: they are likely wanted
        // at most of its pixels (a small body in a big union — spheres — is evaluated where
        // needed only).
        const Rect r = {x0 + 0.5, x1 - 0.5, y0 + 0.5, y1 - 0.5};
        std::size_t wanted = 0;
        for (std::size_t n = 0; n < program.nodes.size(); ++n) {
            const ProgNode& node = program.nodes[n];
            if (node.kind != NodeKind::kBody || nodeEmpty_[n]) continue;
            if (node.xy.x0 <= r.x0 && node.xy.x1 >= r.x1 && node.xy.y0 <= r.y0 &&
                node.xy.y1 >= r.y1) {
                nodeBatch_[n] = kNoBatch;
                ++wanted;
            }
        }
        batchOn_ = wanted > 0 && settings_.batch;
        bodyBatchesWanted_ = wanted;
        if (batches_.size() < wanted) batches_.resize(wanted);
        for (int j = 0; j < tileH_; ++j)
            for (int i = 0; i < tileW_; ++i) {
                xs_[j * tileW_ + i] = x0 + i + 0.5;
                ys_[j * tileW_ + i] = y0 + j + 0.5;
            }
    }
    std::size_t Pixel() const { return pixel_; }

    // The batch of the body the sub-tile program reduces to (SingleBody) when there is one and
    // batches are on; every pixel of the sub-tile then sees exactly that body's set, so its
    // visible point is FirstVisibleOfOne of the batch (or, at kScalar pixels, Trace's).
    const BodyBatch* SingleBodyBatch(const CsgProgram& program, const Rect& r) {
        if (!settings_.tileCull || !batchOn_ || program.solids.size() != 1) return nullptr;
        const ProgSolid& solid = program.solids[0];
        if (!(solid.xy.x0 <= r.x0 && solid.xy.x1 >= r.x1 && solid.xy.y0 <= r.y0 &&
              solid.xy.y1 >= r.y1))
            return nullptr;
        const std::int32_t node = SingleBody(program, solid.root, r);
        if (node < 0 || nodeBatch_[static_cast<std::size_t>(node)] == kNoBatchWanted) return nullptr;
        const auto body = static_cast<std::size_t>(program.nodes[static_cast<std::size_t>(node)].first);
        if (!tables_.bodyValid[body] || tables_.bodyFirstTag[body] == tables_.bodyFirstTag[body + 1])
            return nullptr;
        std::int32_t b = nodeBatch_[static_cast<std::size_t>(node)];
        if (b == kNoBatch) b = ComputeBatch(node);
        singleSolid_ = solid.solid;
        return &batches_[static_cast<std::size_t>(b)];
    }

    // FirstVisible of the one-interval set of pixel p of a batch: its near end when it is finite
    // and on an opaque surface, else its far end on the same terms, else nothing.
    Hit FirstVisibleOfOne(const BodyBatch& batch, std::size_t p, const CsgProgram&) const {
        Hit h;
        double t;
        std::int32_t tag;
        if (VisibleEnd(batch.lo[p], static_cast<std::int32_t>(batch.loId[p]), batch.hi[p],
                       static_cast<std::int32_t>(batch.hiId[p]), t, tag))
            h = {t, tag, singleSolid_};
        return h;
    }

    void SetPixel(int i, int j) {
        pixel_ = static_cast<std::size_t>((j - tileY0_) * tileW_ + (i - tileX0_));
    }

    // Sub-tile kernels. Most pixels that are not background, flat or one body lie in sub-tiles
    // whose program is a small tree of bodies — the machined part's "block ∪ bosses minus the
    // holes that reach here" — and Trace spends most of its time there on the machinery around
    // the set operations: the depth-cut loop, Evaluate's recursion with its bounds tests and list
    // slots, EvaluateBody's look-ups. CompileKernel turns such a program, once per sub-tile, into
    // postfix code, already simplified by the identities of SingleBody for the bodies PrepareTile
    // proved empty; RunKernel evaluates it per pixel on a small stack of lists with the same set
    // operations (the one-interval ones inline), reading each body's set from its batch where it
    // has one and the pixel is ordinary there, else from EvaluateBody.
    //
    // Exactness. Without depth cuts (at most 8 leaves: SetCuts leaves only +inf) Trace evaluates
    // each solid's whole tree; the identities ∅ ∪ B = B, A ∪ ∅ = A, A − ∅ = A, ∅ − B = ∅,
    // A ∩ ∅ = ∅ hold for the lists ids included (math/interval_list.h), so dropping empty
    // operands at compile time (proved empty on the sub-tile) or at run time (a body whose
    // bounds miss the pixel, or empty there) gives Evaluate's list bit for bit; the solids are
    // combined by Trace's rule (nearest, ties to the lower solid index).
    bool CompileKernel(const CsgProgram& program, const Rect& r) {
        if (!settings_.kernel || cuts.size() != 1) return false;
        program_ = &program;
        extraBatches_ = 0;
        kernelCode_.clear();
        kernelSolids_.clear();
        int bodies = 0;
        for (const ProgSolid& s : program.solids) {
            const auto begin = static_cast<std::int32_t>(kernelCode_.size());
            const int e = EmitKernel(program, s.root, r, bodies);
            if (e < 0 || bodies > kKernelMaxBodies) return false;
            if (e == 0) continue;  // ∅ on the whole sub-tile
            kernelSolids_.push_back(
                {begin, static_cast<std::int32_t>(kernelCode_.size()), s.solid, s.xy, s.zlo});
        }
        const std::size_t depth = static_cast<std::size_t>(bodies) + 2;
        if (kernelLists_.size() < depth) kernelLists_.resize(depth);
        kernelStack_.clear();
        for (IntervalList& l : kernelLists_) kernelStack_.push_back(&l);
        ++counters.kernelTiles;
        return true;
    }

    // The kernel's visible point of the current pixel (SetPixel) at (x, y).
    Hit RunKernel(double x, double y) {
        Hit best;
        for (const KernelSolid& s : kernelSolids_) {
            if (best.t < s.zlo) break;  // as Trace: no later solid can be nearer
            if (x < s.xy.x0 || x > s.xy.x1 || y < s.xy.y0 || y > s.xy.y1) continue;
            IntervalList** stack = kernelStack_.data();
            std::size_t sp = 0;
            for (std::int32_t k = s.begin; k < s.end; ++k) {
                const KernelOp& op = kernelCode_[static_cast<std::size_t>(k)];
                if (op.kind == NodeKind::kBody) {
                    IntervalList* const l = stack[sp++];
                    l->clear();
                    if (x < op.xy.x0 || x > op.xy.x1 || y < op.xy.y0 || y > op.xy.y1) continue;
                    // The body's batch when it has one (StartBatches batches the bodies that
                    // cover the sub-tile) and the pixel is ordinary there; else EvaluateBody.
                    const std::int32_t b = nodeBatch_[static_cast<std::size_t>(op.node)];
                    if (batchOn_ && b != kNoBatchWanted) {
                        const BodyBatch& batch =
                            batches_[static_cast<std::size_t>(b >= 0 ? b : ComputeBatch(op.node))];
                        const std::uint8_t state = batch.state[pixel_];
                        if (state == BodyBatch::kEmpty) continue;
                        if (state == BodyBatch::kOne) {
                            l->AssignOne(batch.lo[pixel_],
                                         static_cast<std::int32_t>(batch.loId[pixel_]),
                                         batch.hi[pixel_],
                                         static_cast<std::int32_t>(batch.hiId[pixel_]));
                            continue;
                        }
                    }
                    ++counters.kernelScalarBodies;
                    EvaluateBody(program_->nodes[static_cast<std::size_t>(op.node)].first, op.node,
                                 x, y, 0);
                    *l = *slots_[0];
                    continue;
                }
                IntervalList& b = *stack[--sp];
                IntervalList& a = *stack[sp - 1];
                IntervalList& out = *stack[sp + 1];  // free: above the operand
                if (op.kind == NodeKind::kUnion) {
                    if (b.empty()) continue;                                 // A ∪ ∅ = A
                    if (a.empty()) {                                         // ∅ ∪ B = B
                        std::swap(stack[sp - 1], stack[sp]);
                        continue;
                    }
                    if (a.size() == 1 && b.size() == 1)
                        UnionOfOne(a[0], b[0], out);
                    else
                        Union(a, b, out);
                } else if (op.kind == NodeKind::kIntersection) {
                    if (a.empty()) continue;  // ∅ ∩ B = ∅
                    if (b.empty()) {
                        a.clear();
                        continue;
                    }
                    if (a.size() == 1 && b.size() == 1)
                        IntersectionOfOne(a[0], b[0], out);
                    else
                        Intersection(a, b, out);
                } else {
                    if (a.empty() || b.empty()) continue;  // ∅ − B = ∅, A − ∅ = A
                    if (b.size() == 1) {
                        out.clear();
                        for (const Interval& v : a) AppendDifferenceOfOne(v, b[0], out);
                    } else {
                        Difference(a, b, out);
                    }
                }
                ++counters.csgOps;
                std::swap(stack[sp - 1], stack[sp + 1]);
            }
            double t;
            std::int32_t tag;
            if (FirstVisible(*stack[0], t, tag) && (t < best.t || (t == best.t && s.solid < best.solid)))
                best = {t, tag, s.solid};
        }
        return best;
    }

    // The kernel's visible points of all the pixels of the sub-tile, row-major, into `hits`:
    // the kernel's code run over lanes of pixels (Lane), then RunKernel for the pixels marked
    // `over` (a set of several intervals, or a body without a batch there).
    void RunKernelTile(Hit* hits) {
        const int np = tileW_ * tileH_;
        for (int p = 0; p < np; ++p) hits[p] = Hit{};
        std::int64_t over[kLanePixels] = {};
        if (lanes_.size() < kernelStack_.size()) lanes_.resize(kernelStack_.size());
        for (const KernelSolid& s : kernelSolids_) {
            std::size_t sp = 0;
            for (std::int32_t k = s.begin; k < s.end; ++k) {
                const KernelOp& op = kernelCode_[static_cast<std::size_t>(k)];
                if (op.kind == NodeKind::kBody) {
                    Lane& l = lanes_[sp++];
                    const std::int32_t b = nodeBatch_[static_cast<std::size_t>(op.node)];
                    if (batchOn_ && b != kNoBatchWanted) {
                        const BodyBatch& batch =
                            batches_[static_cast<std::size_t>(b >= 0 ? b : ComputeBatch(op.node))];
                        LanePush(np, xs_, ys_, op.xy, batch.state, batch.lo, batch.hi, batch.cut,
                                 batch.loId, batch.hiId, l, over);
                    } else {  // no batch: every pixel in its bounds goes to RunKernel
                        LanePush(np, xs_, ys_, op.xy, kAllScalar, kNoValues, kNoValues, kNoValues,
                                 kNoIds, kNoIds, l, over);
                    }
                    continue;
                }
                --sp;
                if (op.kind == NodeKind::kUnion)
                    LaneUnion(np, lanes_[sp - 1], lanes_[sp]);
                else if (op.kind == NodeKind::kIntersection)
                    LaneIntersection(np, lanes_[sp - 1], lanes_[sp]);
                else
                    LaneDifference(np, lanes_[sp - 1], lanes_[sp]);
            }
            // FirstVisible of the solid's set when it lies below the lane's cut (else RunKernel),
            // combined by Trace's rule.
            const Lane& l = lanes_[0];
            for (int p = 0; p < np; ++p) {
                if (over[p]) continue;
                if (xs_[p] < s.xy.x0 || xs_[p] > s.xy.x1 || ys_[p] < s.xy.y0 || ys_[p] > s.xy.y1)
                    continue;
                double t = HUGE_VAL;
                std::int32_t tag = -1;
                if (l.n[p])  // (t stays +inf when neither end is visible)
                    VisibleEnd(l.lo[p], static_cast<std::int32_t>(l.loId[p]), l.hi[p],
                               static_cast<std::int32_t>(l.hiId[p]), t, tag);
                if (!(t < l.cut[p])) {
                    // Nothing visible below the cut: exact only without one.
                    if (l.cut[p] != HUGE_VAL) over[p] = 1;
                    continue;
                }
                Hit& best = hits[p];
                if (t < best.t || (t == best.t && s.solid < best.solid)) best = {t, tag, s.solid};
            }
        }
        for (int p = 0; p < np; ++p) {
            if (!over[p]) continue;
            pixel_ = static_cast<std::size_t>(p);
            hits[p] = RunKernel(xs_[p], ys_[p]);
            ++counters.kernelScalarPixels;
        }
        counters.kernelPixels += static_cast<std::uint64_t>(np);
    }

  private:
    // Kernel code (CompileKernel): bodies push their set at the pixel (∅ outside their bounds),
    // operators combine the two sets on top of the stack.
    struct KernelOp {
        NodeKind kind;
        std::int32_t node;  // kBody: the body's program node
        Rect xy;            // kBody: the node's bounds
    };
    struct KernelSolid {
        std::int32_t begin, end;  // its code
        std::int32_t solid;
        Rect xy;
        double zlo;
    };
    static constexpr int kKernelMaxBodies = 8;  // bodies a kernel may hold
    static constexpr std::uint8_t kAllScalar[kLanePixels] = {
        2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2,
        2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2};
    static constexpr double kNoValues[kLanePixels] = {};
    static constexpr std::int64_t kNoIds[kLanePixels] = {};
    std::vector<Lane> lanes_;

    // Appends the code of node n: 1 when code was emitted, 0 when the node is ∅ on every pixel
    // of r (nothing emitted), -1 when the node cannot be compiled (an operator whose bounds do
    // not contain r: MissesPoint could then empty it at some pixels).
    int EmitKernel(const CsgProgram& p, std::int32_t n, const Rect& r, int& bodies) {
        const ProgNode& node = p.nodes[static_cast<std::size_t>(n)];
        if (nodeEmpty_[static_cast<std::size_t>(n)]) return 0;
        if (node.kind == NodeKind::kBody) {
            const auto body = static_cast<std::size_t>(node.first);
            // EvaluateBody gives ∅ for these at every pixel.
            if (!tables_.bodyValid[body] ||
                tables_.bodyFirstTag[body] == tables_.bodyFirstTag[body + 1])
                return 0;
            kernelCode_.push_back({NodeKind::kBody, n, node.xy});
            ++bodies;
            // A body whose bounds cover at least half of the sub-tile's pixel centres is batched
            // too (StartBatches batches only those covering all of them): its pixels then stay
            // in the lanes instead of going to RunKernel. Smaller ones (a sphere of a big union)
            // are evaluated only where needed.
            if (nodeBatch_[static_cast<std::size_t>(n)] == kNoBatchWanted && settings_.batch) {
                int nx = 0, ny = 0;
                for (int i = 0; i < tileW_; ++i) {
                    const double x = tileX0_ + i + 0.5;
                    nx += x >= node.xy.x0 && x <= node.xy.x1;
                }
                for (int j = 0; j < tileH_; ++j) {
                    const double y = tileY0_ + j + 0.5;
                    ny += y >= node.xy.y0 && y <= node.xy.y1;
                }
                if (2 * nx * ny >= tileW_ * tileH_) {
                    // (Room for its batch now: Trace may compute it even if compiling fails.)
                    nodeBatch_[static_cast<std::size_t>(n)] = kNoBatch;
                    batchOn_ = true;
                    ++extraBatches_;
                    if (batches_.size() < bodyBatchesWanted_ + extraBatches_)
                        batches_.resize(bodyBatchesWanted_ + extraBatches_);
                }
            }
            return 1;
        }
        if (!(node.xy.x0 <= r.x0 && node.xy.x1 >= r.x1 && node.xy.y0 <= r.y0 &&
              node.xy.y1 >= r.y1))
            return -1;
        const std::size_t mark = kernelCode_.size();
        const std::int32_t* child = p.children.data() + node.first;
        bool have = false;  // an accumulated operand is on the stack
        for (std::int32_t i = 0; i < node.count; ++i) {
            const int e = EmitKernel(p, child[i], r, bodies);
            if (e < 0) return -1;
            if (e == 0) {
                // ∅ ∩ B = A ∩ ∅ = ∅ and ∅ − B = ∅; a union or a subtrahend just drops it.
                if (node.kind == NodeKind::kIntersection ||
                    (node.kind == NodeKind::kDifference && i == 0)) {
                    kernelCode_.resize(mark);
                    return 0;
                }
                continue;
            }
            if (have) kernelCode_.push_back({node.kind, -1, {}});
            have = true;
        }
        return have ? 1 : 0;
    }

    std::int32_t ComputeBatch(std::int32_t node) {
        const auto b = static_cast<std::int32_t>(batchesUsed_++);
        nodeBatch_[static_cast<std::size_t>(node)] = b;
        BodyBatch& out = batches_[static_cast<std::size_t>(b)];
        const int n = tileW_ * tileH_;
        ++counters.batchBodies;
        counters.batchPixels += static_cast<std::uint64_t>(n);
        double* const lo = out.lo;
        double* const hi = out.hi;
        std::int64_t* const loId = out.loId;
        std::int64_t* const hiId = out.hiId;
        double* const cut = out.cut;
        std::uint8_t flag[kSubTile * kSubTile];  // kBatchLive, kBatchDead or kBatchScalar
        double bad[kSubTile * kSubTile];  // non-zero: a plane bound was not finite
        for (int p = 0; p < n; ++p) {
            lo[p] = -HUGE_VAL;
            hi[p] = HUGE_VAL;
            cut[p] = HUGE_VAL;
            loId[p] = hiId[p] = Interval::kNoId;
            flag[p] = kBatchLive;
            bad[p] = 0;
        }
        const auto [begin, end] = nodeTags_[static_cast<std::size_t>(node)];
        for (std::int32_t k = begin; k < end; ++k) {
            const std::int32_t tag = tileTags_[static_cast<std::size_t>(k)];
            const Tag& t = TagOf(tag);
            const RayHalfSpace& hs = tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
            if (hs.isPlane && std::isfinite(hs.c) && hs.c != 0) {
                counters.literals.planes += static_cast<std::uint64_t>(n);
                const double px = hs.px, py = hs.py, pd = hs.pd, c = hs.c;
                if ((c > 0) != t.complemented)  // t <= r: a far bound
                    PlaneBatch<false>(n, xs_, ys_, px, py, pd, c, tag, hi, hiId, bad);
                else  // t >= r: a near bound
                    PlaneBatch<true>(n, xs_, ys_, px, py, pd, c, tag, lo, loId, bad);
                continue;
            }
            // A pixel with a bad plane bound is kScalar in the end whatever follows: skip it.
            for (int p = 0; p < n; ++p)
                if (bad[p] != 0 && flag[p] == kBatchLive) flag[p] = kBatchScalar;
            if (hs.isPlane && hs.c == 0) {
                // Parallel to the rays (a mitre or slot plane seen edge-on): on each ray the
                // literal holds everywhere or nowhere, as EvaluateBody decides it: nowhere where
                // e = px x + py y + pd is not finite or on the wrong side.
                counters.literals.planes += static_cast<std::uint64_t>(n);
                const double px = hs.px, py = hs.py, pd = hs.pd;
                for (int p = 0; p < n; ++p) {
                    const double e = px * xs_[p] + py * ys_[p] + pd;
                    const bool none = !std::isfinite(e) || (e <= 0) == t.complemented;
                    if (none && flag[p] == kBatchLive) flag[p] = kBatchDead;
                }
                continue;
            }
            if (hs.isPlane) {  // a non-finite coefficient: rare
                for (int p = 0; p < n; ++p)
                    if (flag[p] == kBatchLive) flag[p] = kBatchScalar;
                continue;
            }
            // The quadric's set at every live pixel (one piece clipped in, none: dead, two pieces:
            // kScalar), exactly as LiteralOnRay gives it (ray_literal.h).
            // Cut mode: a two-piece set keeps the first piece below a cut (BodyBatch::kCut).
            QuadricBatch(hs, t.complemented, tag, n, xs_, ys_, lo, loId, hi, hiId, flag,
                         counters.literals, cut);
        }
        for (int p = 0; p < n; ++p)
            out.state[p] = flag[p] == kBatchScalar || bad[p] != 0 ? BodyBatch::kScalar
                           : flag[p] == kBatchDead           ? BodyBatch::kEmpty
                           : cut[p] != HUGE_VAL              ? BodyBatch::kCut
                           : !(lo[p] < hi[p])                ? BodyBatch::kEmpty
                                                             : BodyBatch::kOne;
        return b;
    }

  private:
    // The rest of a body from the first literal with a two-piece set: the running interval `run`
    // intersected with `set`, then literals [next, last) as interval lists.
    void EvaluateBodyLists(const Interval& run, const RaySet& set, const std::int32_t* next,
                           const std::int32_t* last, double x, double y, std::size_t slot) {
        {
            IntervalList& out = *slots_[slot];
            out.clear();
            for (int i = 0; i < set.count; ++i) AppendPiece(out, set.piece[i]);
            // run ∩ set, the running set first (the earlier operand), as in the loop below.
            IntervalList& runList = *slots_[slot + 1];
            runList.clear();
            AppendPiece(runList, run);
            Intersection(runList, out, *slots_[slot + 2]);
            std::swap(slots_[slot], slots_[slot + 2]);
            if (slots_[slot]->empty()) return;
        }
        for (const std::int32_t* it = next; it != last; ++it) {
            const std::int32_t tag = *it;
            const Tag& t = TagOf(tag);
            const RayHalfSpace& hs = tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
            RaySet s = LiteralOnRay(hs, t.complemented, x, y, tag, counters.literals);
            IntervalList& out = *slots_[slot];
            if (s.count == 0) {
                out.clear();
                return;
            }
            if (s.count == 1) {
                ClipTo(out, s.piece[0]);
            } else {
                IntervalList& literal = *slots_[slot + 1];
                literal.clear();
                for (int i = 0; i < s.count; ++i) AppendPiece(literal, s.piece[i]);
                Intersection(out, literal, *slots_[slot + 2]);
                std::swap(slots_[slot], slots_[slot + 2]);
            }
            if (slots_[slot]->empty()) return;
        }
    }

    static void AppendPiece(IntervalList& l, const Interval& v) {
        l.Append(v.lo, v.loId, v.hi, v.hiId);
    }

    // A literal's bound at the four corners of a sub-tile (PrepareTile): side 1 = t <= r,
    // -1 = t >= r, 0 = not a plane bound (kept as it is).
    struct PlaneBound {
        std::int32_t tag;
        int side;
        double r[4];
    };

    const SceneTables& tables_;
    const Settings settings_;
    std::vector<double> zlos_;  // SetCuts scratch
    std::vector<PlaneBound> bounds_;  // ReduceBody scratch
    // PrepareStrip's result per FlatScene body, valid when its stamp is stripStamp_.
    struct StripBody {
        std::int32_t begin = 0, end = 0;  // its literals: stripTags_[begin, end)
        bool empty = false;
        std::uint32_t stamp = 0;
    };
    std::vector<StripBody> stripBody_;
    std::vector<std::int32_t> stripTags_;
    std::uint32_t stripStamp_ = 0;
    std::vector<std::int32_t> tileTags_;
    std::vector<std::pair<std::int32_t, std::int32_t>> nodeTags_;  // per program node
    std::vector<bool> nodeEmpty_;  // per program node: a body empty on every ray of the sub-tile
    // Body batches of the current sub-tile (see BodyBatch).
    std::vector<BodyBatch> batches_;
    std::vector<std::int32_t> nodeBatch_;  // per node: batch index, kNoBatch(Wanted)
    std::size_t batchesUsed_ = 0;
    bool batchOn_ = false;
    int tileX0_ = 0, tileY0_ = 0, tileW_ = 0, tileH_ = 0;
    std::size_t pixel_ = 0;  // the current pixel, row-major in the sub-tile
    std::int32_t singleSolid_ = -1;  // the solid of SingleBodyBatch's body
    double xs_[kSubTile * kSubTile] = {}, ys_[kSubTile * kSubTile] = {};
    std::vector<IntervalList> lists_;
    std::vector<IntervalList*> slots_;
    static constexpr std::size_t kTilePixels = static_cast<std::size_t>(kTileW) * kTileH;
    std::vector<double> tileDepth_ = std::vector<double>(kTilePixels);
    std::vector<Vec3> tileNormal_ = std::vector<Vec3>(kTilePixels);
    std::vector<std::int32_t> tileSurface_ = std::vector<std::int32_t>(kTilePixels);
    std::vector<std::int32_t> tileBody_ = std::vector<std::int32_t>(kTilePixels);
    std::vector<std::int32_t> tileSolid_ = std::vector<std::int32_t>(kTilePixels);
    const CsgProgram* program_ = nullptr;  // the sub-tile program of the kernel
    std::size_t extraBatches_ = 0;         // bodies the kernel batches beyond StartBatches'
    std::size_t bodyBatchesWanted_ = 0;    // StartBatches' count
    std::vector<KernelOp> kernelCode_;
    std::vector<KernelSolid> kernelSolids_;
    std::vector<IntervalList> kernelLists_;
    std::vector<IntervalList*> kernelStack_;
};

// The pixel centres of the pixel rectangle [x0, x1) × [y0, y1).
Rect Centres(int x0, int y0, int x1, int y1) { return {x0 + 0.5, x1 - 0.5, y0 + 0.5, y1 - 0.5}; }

// The frame is sized without clearing (Frame::ResizeForOverwrite): every pixel is written, by
// the tile that owns it, as a hit or as background.
void FillBackground(Frame& frame, int x0, int y0, int x1, int y1) {
    PixelRows::Of(frame).FillBackground(x0, y0, x1, y1);
}

// Renders one 256×8 tile (pixel rectangle [x0, x1) × [y0, y1)) from its block's program.
void RenderTile(const FlatScene& scene, const SceneTables& tables, const CsgProgram& block, int x0,
                int y0, int x1, int y1, Worker& w, Frame& frame) {
    ++w.counters.coarseTiles;
    PruneProgram(block, Centres(x0, y0, x1, y1), w.tileProgram, w.stack);
    if (w.tileProgram.solids.empty()) {
        w.counters.pixels += static_cast<std::uint64_t>((x1 - x0) * (y1 - y0));
        FillBackground(frame, x0, y0, x1, y1);
        return;
    }
    w.PrepareStrip(w.tileProgram, Centres(x0, y0, x1, y1));
    const PixelRows out = w.TileRows(x0, y0);
    for (int sy = y0; sy < y1; sy += kSubTile) {
        for (int sx = x0; sx < x1; sx += kSubTile) {
            int ex = std::min(sx + kSubTile, x1), ey = std::min(sy + kSubTile, y1);
            ++w.counters.tiles;
            PruneProgram(w.tileProgram, Centres(sx, sy, ex, ey), w.subTileProgram, w.stack);
            w.counters.tileSolids += w.subTileProgram.solids.size();
            w.counters.pixels += static_cast<std::uint64_t>((ex - sx) * (ey - sy));
            if (w.subTileProgram.solids.empty()) {
                out.FillBackground(sx, sy, ex, ey);
                continue;
            }
            w.SetCuts(w.subTileProgram);
            w.PrepareTile(w.subTileProgram, Centres(sx, sy, ex, ey));
            if (w.AllEmpty(w.subTileProgram, Centres(sx, sy, ex, ey))) {
                ++w.counters.emptyTiles;
                out.FillBackground(sx, sy, ex, ey);
                continue;
            }
            if (w.TryFlatFill(w.subTileProgram, Centres(sx, sy, ex, ey), sx, sy, ex, ey, out))
                continue;
            w.StartBatches(w.subTileProgram, sx, sy, ex, ey);
            // A sub-tile that is one body (SingleBody) is read straight from the body's batch;
            // only its kScalar pixels, and kCut pixels with nothing visible below the cut, are traced.
            const Worker::BodyBatch* single = w.SingleBodyBatch(w.subTileProgram, Centres(sx, sy, ex, ey));
            if (single) ++w.counters.bodyFillTiles;
            const bool kernel =
                !single && w.CompileKernel(w.subTileProgram, Centres(sx, sy, ex, ey));
            Hit kernelHits[kLanePixels];
            if (kernel) w.RunKernelTile(kernelHits);
            for (int j = sy; j < ey; ++j) {
                for (int i = sx; i < ex; ++i) {
                    double x = i + 0.5, y = j + 0.5;
                    w.SetPixel(i, j);
                    Hit hit;
                    using Batch = Worker::BodyBatch;
                    const std::uint8_t state = single ? single->state[w.Pixel()] : Batch::kScalar;
                    if (state == Batch::kEmpty) {
                        // background
                    } else if (state == Batch::kOne) {
                        hit = w.FirstVisibleOfOne(*single, w.Pixel(), w.subTileProgram);
                    } else if (state == Batch::kCut) {
                        // The first interval is exact below the cut; beyond it, trace.
                        const std::size_t p = w.Pixel();
                        if (single->lo[p] < single->hi[p])
                            hit = w.FirstVisibleOfOne(*single, p, w.subTileProgram);
                        if (!(hit.t < single->cut[p])) hit = w.Trace(w.subTileProgram, x, y);
                    } else if (kernel) {
                        hit = kernelHits[w.Pixel()];
                    } else {
                        hit = w.Trace(w.subTileProgram, x, y);
                    }
                    const std::size_t k = out.Index(i, j);
                    if (hit.tag < 0) {
                        out.SetBackground(k);
                        continue;
                    }
                    ++w.counters.covered;
                    const Tag& tag = w.TagOf(hit.tag);
                    out.depth[k] = hit.t;
                    const auto hsIndex = static_cast<std::size_t>(tag.halfSpace);
                    out.normal[k] = tables.constantNormal[hsIndex]
                                        ? tables.planeNormal[hsIndex]
                                        : scene.WorldNormal(tag.halfSpace, {x, y, hit.t});
                    out.surface[k] = tag.halfSpace;
                    out.body[k] = tag.body;
                    out.solid[k] = hit.solid;
                }
            }
        }
    }
    w.CopyTile(x0, y0, x1, y1, frame);
}

class RaycastEngine final : public Engine {
  public:
    std::string_view Name() const override { return "raycast"; }
    const OptionSchema& Schema() const override { return RaycastSchema(); }

  protected:
    RenderStats Draw(const FlatScene& scene, const EngineOptions& options,
                     Frame& frame) override {
        auto start = std::chrono::steady_clock::now();
        int width = std::max(scene.width, 0), height = std::max(scene.height, 0);
        frame.ResizeForOverwrite(width, height);
        SceneTables tables(scene);
        CsgProgram full;
        BuildProgram(scene, full);

        int blocksX = (width + kBlock - 1) / kBlock, blocksY = (height + kBlock - 1) / kBlock;
        constexpr int kTilesX = kBlock / kTileW, kTilesY = kBlock / kTileH;
        const Settings settings = ReadSettings(options);
        tbb::enumerable_thread_specific<Worker> workers(&tables, full.maxDepth, settings);
        // Blocks own their pruned program (not the thread: a thread waiting in the nested loop may
        // run another block); tiles use per-thread scratch, held by no task across a wait.
        auto renderBlock = [&](int b) {
            int bx0 = (b % blocksX) * kBlock, by0 = (b / blocksX) * kBlock;
            int bx1 = std::min(bx0 + kBlock, width), by1 = std::min(by0 + kBlock, height);
            CsgProgram block;
            std::vector<std::int32_t> stack;
            PruneProgram(full, Centres(bx0, by0, bx1, by1), block, stack);
            ++workers.local().counters.blocks;
            if (block.solids.empty()) {
                workers.local().counters.pixels +=
                    static_cast<std::uint64_t>((bx1 - bx0) * (by1 - by0));
                FillBackground(frame, bx0, by0, bx1, by1);
                return;
            }
            tbb::parallel_for(tbb::blocked_range<int>(0, kTilesX * kTilesY, 1),
                              [&](const tbb::blocked_range<int>& range) {
                                  Worker& w = workers.local();
                                  for (int k = range.begin(); k < range.end(); ++k) {
                                      int x0 = bx0 + (k % kTilesX) * kTileW;
                                      int y0 = by0 + (k / kTilesX) * kTileH;
                                      if (x0 >= bx1 || y0 >= by1) continue;
                                      RenderTile(scene, tables, block, x0, y0, std::min(x0 + kTileW, bx1),
                                                 std::min(y0 + kTileH, by1), w, frame);
                                  }
                              });
        };
        tbb::parallel_for(tbb::blocked_range<int>(0, blocksX * blocksY, 1),
                          [&](const tbb::blocked_range<int>& range) {
                              for (int b = range.begin(); b < range.end(); ++b) renderBlock(b);
                          });

        Counters total;
        for (const Worker& w : workers) total.Add(w.counters);
        RenderStats stats;
        stats.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto add = [&](const char* name, std::uint64_t v) {
            stats.counters.emplace_back(name, static_cast<double>(v));
        };
        add("solids", full.solids.size());
        add("program_nodes", full.nodes.size());
        add("blocks_256", total.blocks);
        add("tiles_256x8", total.coarseTiles);
        add("sub_tiles", total.tiles);
        add("pixels", total.pixels);
        add("covered_pixels", total.covered);
        add("tile_solids", total.tileSolids);
        add("pixel_solids", total.pixelSolids);
        add("depth_early_outs", total.zStops);
        add("body_evaluations", total.bodies);
        add("literal_evaluations", total.literals.planes + total.literals.quadrics);
        add("plane_evaluations", total.literals.planes);
        add("quadric_solves", total.literals.quadrics);
        add("csg_operations", total.csgOps);
        add("depth_cut_retries", total.cutRetries);
        add("tile_literals_pruned", total.prunedLiterals);
        add("flat_sub_tiles", total.flatTiles);
        add("flat_pixels", total.flatPixels);
        add("tile_bodies_empty", total.emptyBodies);
        add("batched_bodies", total.batchBodies);
        add("batched_body_pixels", total.batchPixels);
        add("single_body_sub_tiles", total.bodyFillTiles);
        add("empty_sub_tiles", total.emptyTiles);
        add("kernel_sub_tiles", total.kernelTiles);
        add("kernel_pixels", total.kernelPixels);
        add("kernel_scalar_bodies", total.kernelScalarBodies);
        add("kernel_scalar_pixels", total.kernelScalarPixels);
        return stats;
    }
};

}  // namespace
}  // namespace raycast

std::unique_ptr<Engine> MakeRaycastEngine() { return std::make_unique<raycast::RaycastEngine>(); }

}  // namespace quadrix
