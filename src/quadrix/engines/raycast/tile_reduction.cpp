#include "quadrix/engines/raycast/tile_reduction.h"

#include <cmath>

namespace quadrix::raycast {
namespace {

// ReduceBody's first step: the literals' plane bounds at the corners into `bounds`, dropping
// those that hold on every ray; true when a quadric literal holds on no ray of r.
bool CornerBounds(const SceneTables& tables, bool tileCull, const std::int32_t* tags, std::size_t n,
                  const Rect& r, std::vector<PlaneBound>& bounds) {
    const double cx[4] = {r.x0, r.x1, r.x0, r.x1}, cy[4] = {r.y0, r.y0, r.y1, r.y1};
    bounds.clear();
    bool bodyEmptyByQuadric = false;
    for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t tag = tags[i];
        const Tag& t = tables.TagOf(tag);
        const RayHalfSpace& hs = tables.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
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
                    const double m = 1e-9 * (std::fabs(hs.px * cx[k]) + std::fabs(hs.py * cy[k]) +
                                             std::fabs(hs.pd)) +
                                     1e-300;
                    holds &= t.complemented ? b.r[k] > m : b.r[k] < -m;
                }
                if (holds) continue;  // the literal holds on every ray: drop it
            } else if (finite) {
                b.side = (hs.c > 0) != t.complemented ? 1 : -1;  // 1: t <= r, -1: t >= r
            }
        } else if (hs.IsQuadric() && tileCull) {  // (quartics: no proof, kept)
            const QuadricOnRect q = ClassifyQuadric(hs, r.x0, r.x1, r.y0, r.y1);
            if (q != QuadricOnRect::kUnknown) {
                // No ray of the rectangle meets the surface: the literal holds on all of every
                // ray (dropped) or on none (the body is empty).
                const bool holds = (q == QuadricOnRect::kInsideEverywhere) != t.complemented;
                if (holds) continue;
                bodyEmptyByQuadric = true;
            }
        }
        bounds.push_back(b);
    }
    return bodyEmptyByQuadric;
}

// The pair tests below compare bounds two by two. For a body of more than kExactPairs bounds
// (a body of 10⁵ planes: 10¹⁰ pairs per sub-tile) each bound is compared only with the
// candidates most likely to decide it, the tightest near and far bound at each corner, making
// the tests O(n) (issue 23 item 3; docs/performance.md "Complexity guards"). Both tests only
// ever prove: a proof missed keeps a literal that cannot decide an endpoint in the rectangle,
// or evaluates a body that is empty, so the pictures are the same bit for bit.
constexpr std::size_t kExactPairs = 32;

bool Beyond(const PlaneBound& nearB, const PlaneBound& farB) {
    for (int k = 0; k < 4; ++k) {
        const double m = 1e-9 * (std::fabs(nearB.r[k]) + std::fabs(farB.r[k])) + 1e-300;
        if (!(nearB.r[k] - farB.r[k] > m)) return false;
    }
    return true;
}

// Whether a is tighter than b (same side) at all four corners, by the margin. Near bounds: a is
// tighter where r_a > r_b; far bounds where r_a < r_b.
bool Tighter(const PlaneBound& a, const PlaneBound& b) {
    for (int k = 0; k < 4; ++k) {
        const double m = 1e-9 * (std::fabs(a.r[k]) + std::fabs(b.r[k])) + 1e-300;
        if (!(b.side < 0 ? a.r[k] - b.r[k] > m : b.r[k] - a.r[k] > m)) return false;
    }
    return true;
}

// Indices of the tightest near (side < 0, largest r) and far (side > 0, smallest r) bound at
// each corner; −1 where there is none.
struct Candidates {
    std::ptrdiff_t nearAt[4] = {-1, -1, -1, -1}, farAt[4] = {-1, -1, -1, -1};
};
Candidates TightestAtCorners(const std::vector<PlaneBound>& bounds) {
    Candidates c;
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        const PlaneBound& b = bounds[i];
        if (b.side == 0) continue;
        std::ptrdiff_t* at = b.side < 0 ? c.nearAt : c.farAt;
        for (int k = 0; k < 4; ++k) {
            const std::ptrdiff_t j = at[k];
            if (j < 0 || (b.side < 0 ? b.r[k] > bounds[static_cast<std::size_t>(j)].r[k]
                                     : b.r[k] < bounds[static_cast<std::size_t>(j)].r[k]))
                at[k] = static_cast<std::ptrdiff_t>(i);
        }
    }
    return c;
}

// Whether some near bound lies beyond some far bound at all four corners (by the margin).
bool NearBeyondFar(const std::vector<PlaneBound>& bounds) {
    if (bounds.size() > kExactPairs) {
        const Candidates c = TightestAtCorners(bounds);
        for (std::ptrdiff_t i : c.nearAt)
            for (std::ptrdiff_t j : c.farAt)
                if (i >= 0 && j >= 0 &&
                    Beyond(bounds[static_cast<std::size_t>(i)],
                           bounds[static_cast<std::size_t>(j)]))
                    return true;
        return false;
    }
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        if (bounds[i].side >= 0) continue;
        for (std::size_t j = 0; j < bounds.size(); ++j)
            if (bounds[j].side > 0 && Beyond(bounds[i], bounds[j])) return true;
    }
    return false;
}

// Whether bounds[i] is dominated by another bound of the same side at all four corners (by
// the candidates of `c` only when the body is large).
bool Dominated(const std::vector<PlaneBound>& bounds, std::size_t i, const Candidates& c) {
    const PlaneBound& b = bounds[i];
    if (b.side == 0) return false;
    if (bounds.size() > kExactPairs) {
        for (std::ptrdiff_t j : b.side < 0 ? c.nearAt : c.farAt)
            if (j >= 0 && static_cast<std::size_t>(j) != i &&
                Tighter(bounds[static_cast<std::size_t>(j)], b))
                return true;
        return false;
    }
    for (std::size_t j = 0; j < bounds.size(); ++j)
        if (j != i && bounds[j].side == b.side && Tighter(bounds[j], b)) return true;
    return false;
}

}  // namespace

void TileReduction::PrepareStrip(const CsgProgram& program, const Rect& r) {
    ++stripStamp_;
    if (stripBody_.size() < tables_->bodyValid.size()) stripBody_.resize(tables_->bodyValid.size());
    stripTags_.clear();
    for (const ProgNode& node : program.nodes) {
        if (node.kind != NodeKind::kBody) continue;
        const auto body = static_cast<std::size_t>(node.first);
        StripBody& sb = stripBody_[body];
        if (sb.stamp == stripStamp_) continue;  // (a body is one node; cheap guard anyway)
        // A body of one literal gains nothing from the strip: its literal is a plane bound or
        // a quadric to classify again on every sub-tile, so PrepareTile reduces it from its
        // own literal there (the same proofs on a smaller rectangle; the frame is the same
        // either way, tile_reduction.h). A body the strip would prove empty is then proved so
        // on each of its sub-tiles instead.
        if (tables_->BodyTagCount(body) == 1) continue;
        const auto begin = static_cast<std::int32_t>(stripTags_.size());
        const bool empty =
            ReduceBody(tables_->BodyTags(body), tables_->BodyTagCount(body), r, stripTags_);
        sb = {begin, static_cast<std::int32_t>(stripTags_.size()), empty, stripStamp_};
    }
}

void TileReduction::PrepareTile(const CsgProgram& program, const Rect& r) {
    tileProgram_ = &program;
    tileRect_ = r;
    tileTags_.clear();
    nodeTags_.assign(program.nodes.size(), {0, 0});
    nodeState_.assign(program.nodes.size(), kUnknown);
    // A small program (at most kEagerNodes nodes) has nearly every body asked for: reduced at
    // once, without a test per question.
    if (program.nodes.size() <= kEagerNodes)
        for (std::size_t n = 0; n < program.nodes.size(); ++n) ReduceNode(n);
}

std::uint8_t TileReduction::ReduceNode(std::size_t n) const {
    const ProgNode& node = tileProgram_->nodes[n];
    if (node.kind != NodeKind::kBody) return nodeState_[n] = kKept;
    const auto body = static_cast<std::size_t>(node.first);
    const auto begin = static_cast<std::int32_t>(tileTags_.size());
    const auto all = static_cast<std::int32_t>(tables_->BodyTagCount(body));
    bool empty;
    if (body < stripBody_.size() && stripBody_[body].stamp == stripStamp_) {
        const StripBody& sb = stripBody_[body];
        empty = sb.empty ||
                ReduceBody(stripTags_.data() + sb.begin,
                           static_cast<std::size_t>(sb.end - sb.begin), tileRect_, tileTags_);
    } else {
        empty =
            ReduceBody(tables_->BodyTags(body), tables_->BodyTagCount(body), tileRect_, tileTags_);
    }
    if (empty) {
        tileTags_.resize(static_cast<std::size_t>(begin));
        ++counters_.emptyBodies;
        nodeTags_[n] = {begin, begin};
        return nodeState_[n] = kEmpty;
    }
    nodeTags_[n] = {begin, static_cast<std::int32_t>(tileTags_.size())};
    counters_.prunedLiterals += static_cast<std::uint64_t>(all - (nodeTags_[n].second - begin));
    return nodeState_[n] = kKept;
}

inline bool TileReduction::ReduceBody(const std::int32_t* tags, std::size_t n, const Rect& r,
                                      std::vector<std::int32_t>& out) const {
    const bool bodyEmptyByQuadric = CornerBounds(*tables_, settings_.tileCull, tags, n, r, bounds_);
    // Empty everywhere: a near bound beyond a far bound at the four corners (margin as below)
    // stays beyond it on the whole rectangle, so no ray of the sub-tile meets the body, and
    // Evaluate takes it as ∅ without evaluating it (exactly what the body's literals would give:
    // an empty set, and ∅ is an exact identity of every operator).
    const bool empty = bodyEmptyByQuadric || (settings_.tileCull && NearBeyondFar(bounds_));
    if (empty) return true;
    const Candidates c = bounds_.size() > kExactPairs ? TightestAtCorners(bounds_) : Candidates{};
    for (std::size_t i = 0; i < bounds_.size(); ++i)
        if (!Dominated(bounds_, i, c)) out.push_back(bounds_[i].tag);
    return false;
}

bool TileReduction::ReduceLiterals(const std::int32_t* tags, std::size_t n, const Rect& r,
                                   std::vector<std::int32_t>& out) {
    return ReduceBody(tags, n, r, out);
}

// TryFlatFill's plane test for the body of program node bodyNode on r: the tag of the one opaque
// near plane that every kept far plane lies beyond by a margin at the four corner centres, or −1
// when the body's kept literals are not such planes.
inline std::int32_t TileReduction::FlatNearPlane(std::int32_t bodyNode, const Rect& r) const {
    const auto [begin, end] = NodeTags(static_cast<std::size_t>(bodyNode));
    const double cx[4] = {r.x0, r.x1, r.x0, r.x1}, cy[4] = {r.y0, r.y0, r.y1, r.y1};
    std::int32_t nearTag = -1;
    double nearR[4] = {0, 0, 0, 0};
    for (std::int32_t i = begin; i < end; ++i) {
        const std::int32_t tag = tileTags_[static_cast<std::size_t>(i)];
        const Tag& t = tables_->TagOf(tag);
        const RayHalfSpace& hs = tables_->halfSpaces[static_cast<std::size_t>(t.halfSpace)];
        if (!hs.isPlane || !std::isfinite(hs.c) || hs.c == 0) return -1;
        if ((hs.c > 0) != t.complemented) continue;  // a far bound: checked below
        if (nearTag >= 0 || !t.opaque) return -1;
        nearTag = tag;
        for (int k = 0; k < 4; ++k) {
            nearR[k] = -(hs.px * cx[k] + hs.py * cy[k] + hs.pd) / hs.c;
            if (!(std::fabs(nearR[k]) < 1e300)) return -1;
        }
    }
    if (nearTag < 0) return -1;
    for (std::int32_t i = begin; i < end; ++i) {
        const std::int32_t tag = tileTags_[static_cast<std::size_t>(i)];
        const Tag& t = tables_->TagOf(tag);
        const RayHalfSpace& hs = tables_->halfSpaces[static_cast<std::size_t>(t.halfSpace)];
        if ((hs.c > 0) == t.complemented) continue;  // the near bound
        for (int k = 0; k < 4; ++k) {
            const double far = -(hs.px * cx[k] + hs.py * cy[k] + hs.pd) / hs.c;
            const double m = 1e-9 * (std::fabs(far) + std::fabs(nearR[k])) + 1e-300;
            if (!(far - nearR[k] > m)) return -1;
        }
    }
    return nearTag;
}

// Flat sub-tiles. When the sub-tile program is one solid whose tree is one body, PrepareTile has
// kept only planes, every pixel centre of `r` lies inside the node's and the solid's bounds, and
// exactly one kept plane bounds the body from the near side, that plane is the body's near end at
// every pixel (PrepareTile dropped the others because it dominates them everywhere in the
// rectangle). If moreover every kept far-side plane lies beyond it by a margin at the four corner
// centres, the difference of the two depths is linear in (x, y) and stays positive on the whole
// rectangle, so the set on every ray is the one interval [r_near, r_far] and the visible point is
// r_near. The pixel's result is then written directly, with the very expression EvaluateBody uses
// for r (the same bits), the plane's constant normal and ids. Returns false (nothing written)
// when any condition fails.
bool TileReduction::TryFlatFill(const CsgProgram& program, const Rect& r, int x0, int y0, int x1,
                                int y1, const PixelRows& out) {
    if (!settings_.tileCull || program.solids.size() != 1) return false;
    const ProgSolid& solid = program.solids[0];
    auto contains = [&](const Rect& b) {
        return b.x0 <= r.x0 && b.x1 >= r.x1 && b.y0 <= r.y0 && b.y1 >= r.y1;
    };
    if (!contains(solid.xy)) return false;
    const std::int32_t bodyNode = SingleBody(program, solid.root, r);
    if (bodyNode < 0) return false;
    const ProgNode& node = program.nodes[static_cast<std::size_t>(bodyNode)];
    if (tables_->BodyVoid(static_cast<std::size_t>(node.first))) return false;
    const std::int32_t nearTag = FlatNearPlane(bodyNode, r);
    if (nearTag < 0) return false;
    const Tag& near = tables_->TagOf(nearTag);
    const auto hsIndex = static_cast<std::size_t>(near.halfSpace);
    const RayHalfSpace& hs = tables_->halfSpaces[hsIndex];
    const PackedNormal normal = tables_->packedPlaneNormal[hsIndex];
    for (int j = y0; j < y1; ++j) {
        const double y = j + 0.5;
        std::size_t k = out.Index(x0, j);
        for (int i = x0; i < x1; ++i, ++k) {
            const double x = i + 0.5;
            const double e = hs.px * x + hs.py * y + hs.pd;  // as EvaluateBody
            out.depth[k] = static_cast<float>(-e / hs.c);
            out.normal[k] = normal;
            out.surface[k] = near.halfSpace;
            out.body[k] = near.body;
        }
    }
    const auto n = static_cast<std::uint64_t>((x1 - x0) * (y1 - y0));
    counters_.covered += n;
    counters_.flatPixels += n;
    ++counters_.flatTiles;
    return true;
}

std::int32_t TileReduction::SingleBody(const CsgProgram& p, std::int32_t n, const Rect& r) const {
    const ProgNode& node = p.nodes[static_cast<std::size_t>(n)];
    if (NodeEmpty(static_cast<std::size_t>(n))) return kEmptyNode;
    if (!(node.xy.x0 <= r.x0 && node.xy.x1 >= r.x1 && node.xy.y0 <= r.y0 && node.xy.y1 >= r.y1))
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
        if (found != kEmptyNode) return -1;                          // two non-empty operands
        if (node.kind == NodeKind::kDifference && i > 0) return -1;  // a real subtrahend
        found = c;
    }
    return found;  // (an intersection gets here only with one operand: ∅ returned above)
}

}  // namespace quadrix::raycast
