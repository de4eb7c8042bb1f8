#include "quadrix/draw/scene_probe.h"

#include <cmath>

namespace quadrix::draw {

namespace {

bool XYInside(const Box3& b, double x, double y) {
    // Empty or NaN bounds never cull (conservative).
    return !(x < b.lo.x || x > b.hi.x || y < b.lo.y || y > b.hi.y);
}

// A surface parallel to the rays (a plane seen edge-on, a cylinder seen along its axis) whose
// value on the ray vanishes to within the rounding of its evaluation (1e-11 of the sum of the
// magnitudes of its terms).
bool ContainsRay(const eval::RayHalfSpace& h, double x, double y) {
    if (h.c != 0) return false;
    if (h.isPlane) {
        const double e = h.px * x + h.py * y + h.pd;
        return std::fabs(e) <=
               1e-11 * (std::fabs(h.px * x) + std::fabs(h.py * y) + std::fabs(h.pd));
    }
    if (h.hx != 0 || h.hy != 0 || h.h0 != 0) return false;
    const double dx = x - h.x0, dy = y - h.y0;
    const double k = dx * (h.axx * dx + h.axy * dy + h.ax) + dy * (h.byy * dy + h.by) + h.k0;
    const double scale = std::fabs(h.axx * dx * dx) + std::fabs(h.axy * dx * dy) +
                         std::fabs(h.ax * dx) + std::fabs(h.byy * dy * dy) + std::fabs(h.by * dy) +
                         std::fabs(h.k0);
    return std::fabs(k) <= 1e-11 * scale;
}

}  // namespace

SceneProbe::SceneProbe(const FlatScene& scene) : scene_(scene) {
    rays_.reserve(scene.halfSpaces.size());
    for (const FlatHalfSpace& h : scene.halfSpaces) {
        Vec3 ref{};
        if (!h.isPlane) {
            if (auto c = eval::RayHalfSpace::Centre(h.quadric)) ref = *c;
        }
        rays_.push_back(eval::RayHalfSpace::From(h, ref));
    }
}

bool SceneProbe::InsideBody(int body, const Vec3& p) const {
    const FlatBody& b = scene_.bodies[static_cast<std::size_t>(body)];
    for (const FlatLiteral& lit : b.literals) {
        if (lit.halfSpace < 0 || lit.halfSpace >= static_cast<int>(scene_.halfSpaces.size()))
            return false;
        const double v = scene_.halfSpaces[static_cast<std::size_t>(lit.halfSpace)].Evaluate(p);
        if (!std::isfinite(v)) return false;
        if (lit.complemented ? !(v >= 0) : !(v <= 0)) return false;
    }
    return true;
}

bool SceneProbe::InsideNode(int node, const Vec3& p) const {
    if (node < 0 || node >= static_cast<int>(scene_.nodes.size())) return false;
    const FlatCsgNode& n = scene_.nodes[static_cast<std::size_t>(node)];
    if (n.isLeaf) {
        if (n.body < 0 || n.body >= static_cast<int>(scene_.bodies.size())) return false;
        return InsideBody(n.body, p);
    }
    if (n.children.empty()) return false;
    switch (n.op) {
        case scene::CsgOp::kUnion:
            for (int c : n.children)
                if (InsideNode(c, p)) return true;
            return false;
        case scene::CsgOp::kIntersection:
            for (int c : n.children)
                if (!InsideNode(c, p)) return false;
            return true;
        case scene::CsgOp::kDifference:
            if (!InsideNode(n.children[0], p)) return false;
            for (std::size_t i = 1; i < n.children.size(); ++i)
                if (InsideNode(n.children[i], p)) return false;
            return true;
    }
    return false;
}

bool SceneProbe::Inside(const Vec3& p) const {
    for (const FlatSolid& s : scene_.solids)
        if (InsideNode(s.root, p)) return true;
    return false;
}

IntervalList& SceneProbe::Scratch(std::size_t depth, int which) {
    const std::size_t i = depth * 3 + static_cast<std::size_t>(which);
    if (scratch_.size() <= i) scratch_.resize(i + 1);
    return scratch_[i];
}

void SceneProbe::BodyOnRay(int body, double x, double y, IntervalList& out) {
    out.clear();
    if (body < 0 || body >= static_cast<int>(scene_.bodies.size())) return;
    const FlatBody& b = scene_.bodies[static_cast<std::size_t>(body)];
    if (!XYInside(b.bounds, x, y)) return;
    out = IntervalList::All();
    eval::LiteralCounters counters;
    for (const FlatLiteral& lit : b.literals) {
        if (lit.halfSpace < 0 || lit.halfSpace >= static_cast<int>(rays_.size())) {
            out.clear();
            return;
        }
        const eval::RayHalfSpace& rh = rays_[static_cast<std::size_t>(lit.halfSpace)];
        eval::RaySet s;
        if (ContainsRay(rh, x, y)) {
            // The ray lies in the surface (to rounding): H holds along all of it, !H nowhere
            // (raycast's convention for a plane containing the ray), decided the same way at
            // every point of the curve instead of by the sign of a rounding error.
            if (!lit.complemented) s.piece[s.count++] = {-HUGE_VAL, HUGE_VAL, -1, -1};
        } else {
            s = eval::LiteralOnRay(rh, lit.complemented, x, y, lit.halfSpace, counters);
        }
        if (s.count == 0) {
            out.clear();
            return;
        }
        if (s.count == 1) {
            ClipTo(out, s.piece[0]);
        } else {
            literalList_.clear();
            literalList_.Append(s.piece[0].lo, s.piece[0].loId, s.piece[0].hi, s.piece[0].hiId);
            literalList_.Append(s.piece[1].lo, s.piece[1].loId, s.piece[1].hi, s.piece[1].hiId);
            Intersection(out, literalList_, tmp_);
            out = tmp_;
        }
        if (out.empty()) return;
    }
}

void SceneProbe::NodeOnRay(int node, double x, double y, std::size_t depth, IntervalList& out) {
    out.clear();
    if (node < 0 || node >= static_cast<int>(scene_.nodes.size())) return;
    const FlatCsgNode& n = scene_.nodes[static_cast<std::size_t>(node)];
    if (!XYInside(n.bounds, x, y)) return;
    if (n.isLeaf) {
        BodyOnRay(n.body, x, y, out);
        return;
    }
    if (n.children.empty()) return;
    NodeOnRay(n.children[0], x, y, depth + 1, out);
    IntervalList& child = Scratch(depth, 0);
    IntervalList& acc = Scratch(depth, 1);
    for (std::size_t i = 1; i < n.children.size(); ++i) {
        if (out.empty() && n.op != scene::CsgOp::kUnion) return;  // ∅ ∩ B = ∅ − B = ∅
        NodeOnRay(n.children[i], x, y, depth + 1, child);
        switch (n.op) {
            case scene::CsgOp::kUnion:
                Union(out, child, acc);
                break;
            case scene::CsgOp::kIntersection:
                Intersection(out, child, acc);
                break;
            case scene::CsgOp::kDifference:
                Difference(out, child, acc);
                break;
        }
        out = acc;
    }
}

void SceneProbe::SolidOnRay(int s, double x, double y, IntervalList& out) {
    out.clear();
    if (s < 0 || s >= static_cast<int>(scene_.solids.size())) return;
    const FlatSolid& solid = scene_.solids[static_cast<std::size_t>(s)];
    NodeOnRay(solid.root, x, y, 0, out);
}

double SceneProbe::FirstOpaqueHit(double x, double y) {
    double best = HUGE_VAL;
    for (std::size_t s = 0; s < scene_.solids.size(); ++s) {
        const FlatSolid& solid = scene_.solids[s];
        if (!XYInside(solid.bounds, x, y) || solid.bounds.lo.z >= best) continue;
        SolidOnRay(static_cast<int>(s), x, y, solidList_);
        for (const Interval& v : solidList_) {
            if (v.lo >= best) break;
            if (v.loId >= 0 && std::isfinite(v.lo) && Opaque(v.loId)) {
                best = v.lo;
                break;
            }
            if (v.hiId >= 0 && std::isfinite(v.hi) && Opaque(v.hiId)) {
                best = std::fmin(best, v.hi);
                break;
            }
        }
    }
    return best;
}

}  // namespace quadrix::draw
