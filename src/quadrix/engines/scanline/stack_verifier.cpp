#include "quadrix/engines/scanline/stack_verifier.h"

#include <algorithm>
#include <cmath>

#include "quadrix/engines/scanline/coefficients.h"
#include "quadrix/engines/scanline/face_stack.h"
#include "quadrix/engines/scanline/span_shader.h"
#include "quadrix/math/quadratic.h"

namespace quadrix::scanline {

StackVerifier::StackVerifier(ScanContext& ctx, FaceOrder& order) : ctx_(ctx), order_(order) {
    const FlatScene& scene = ctx.scene;
    const std::size_t nb = scene.bodies.size();
    markP_.assign(ctx.faces.size(), 0);
    markT_.assign(ctx.faces.size(), 0);
    bodyLiterals_.resize(nb);
    for (std::size_t b = 0; b < nb; ++b) {
        if (!ctx.useStack[b]) continue;
        for (const FlatLiteral& lit : scene.bodies[b].literals) {
            const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
            OrientedLiteral o;
            o.halfSpace = lit.halfSpace;
            o.isPlane = hs.isPlane;
            o.plane = hs.plane;
            o.quadric = hs.quadric;
            o.zFree = hs.isPlane
                          ? PlaneIsEdgeOn(hs.plane)
                          : QuadricIsViewCylinder(hs.quadric, std::max(scene.width, scene.height));
            if (lit.complemented) {  // !h: −h <= 0
                o.plane = {-hs.plane.a, -hs.plane.b, -hs.plane.c, -hs.plane.d};
                for (double& v : o.quadric.k) v = -v;
            }
            bodyLiterals_[b].push_back(o);
        }
    }
}

// Is show-face f on its body's boundary at (x, y): does its sheet have a point there that
// lies DEFINITELY inside every other HSI of the body (value < −E of zero test (4))? Q is at
// least kCluster / 2 from every crossing, so a face that is there has a margin far above E;
// a face that only touches the body (a row exactly on a horizontal edge where the body has
// zero thickness, e.g. the base edge of a pyramid) is not there, as in raycast, whose
// interval [t, t] of zero length draws nothing. HSBs that contain the view direction
// (edge-on planes, view-axis cylinders) are tested closed instead (value <= E): a row on
// such a boundary is inside the body along the whole ray, as in raycast.
bool StackVerifier::PresentAt(int f, double x, double y) const {
    const ShowFace& sf = ctx_.Face(f);
    double z;
    return FaceZ(sf, x, y, z) && InsideOtherLiterals(sf, x, y, z);
}

inline bool StackVerifier::FaceZ(const ShowFace& sf, double x, double y, double& z) const {
    const FlatHalfSpace& hs = ctx_.scene.halfSpaces[static_cast<std::size_t>(sf.halfSpace)];
    if (hs.isPlane) {
        if (hs.plane.c == 0) return false;
        z = -(hs.plane.a * x + hs.plane.b * y + hs.plane.d) / hs.plane.c;
    } else {
        const Quadric& q = hs.quadric;
        QuadraticRoots r = SolveQuadratic(q.C(), q.F() * x + q.E() * y + q.J(),
                                          q.A() * x * x + q.B() * y * y + 2 * q.D() * x * y +
                                              2 * q.G() * x + 2 * q.H() * y + q.K());
        const bool back = sf.sheet == Sheet::kBack;
        switch (r.kind) {
            case RootKind::kTwo:
                z = back ? r.t1 : r.t0;
                break;
            case RootKind::kDouble:
                z = r.t0;
                break;
            case RootKind::kSingle:  // C = 0: one root, the front face's (as FaceDepth)
                if (back) return false;
                z = r.t0;
                break;
            default:
                return false;
        }
    }
    return std::isfinite(z);
}

inline bool StackVerifier::InsideOtherLiterals(const ShowFace& sf, double x, double y,
                                               double z) const {
    const Vec3 p{x, y, z};
    // The face point comes from one plane or quadratic solve (relative error ~1e-15 away from a
    // double root); 1e-9 (1 + |z|) px leaves a wide margin and still resolves Q, which lies at
    // least kCluster / 2 from every crossing.
    const double pointError = 1e-9 * (1 + std::fabs(z));
    const std::vector<OrientedLiteral>& lits = bodyLiterals_[static_cast<std::size_t>(sf.body)];
    // ∂/∂z of the face's own HSI: the body lies along the ray on the side where it is < 0.
    double gz = 0;
    for (const OrientedLiteral& l : lits) {
        if (l.halfSpace != sf.halfSpace) continue;
        const Quadric& q = l.quadric;
        gz = l.isPlane ? l.plane.c : q.F() * x + q.E() * y + q.C() * z + q.J();
        break;
    }
    for (const OrientedLiteral& l : lits) {
        if (l.halfSpace == sf.halfSpace) continue;
        const double v = l.isPlane ? l.plane.Evaluate(p) : l.quadric.Evaluate(p);
        const double e = l.isPlane ? PlaneErrorEstimate(l.plane, p, pointError)
                                   : QuadricErrorEstimate(l.quadric, p, pointError);
        if (l.zFree) {
            if (!(v <= e)) return false;
            continue;
        }
        if (v < -e) continue;
        if (v > e || gz == 0) return false;
        // The point lies ON this HSI's surface: Q is on an edge of the face that runs along the
        // CSL (a row exactly on a horizontal edge). The face is there when the body goes on
        // along the ray from it (raycast's interval has a length: the front face at a box's
        // slanted top edge), not when the body only touches the ray there (zero thickness: the
        // base edge of a pyramid).
        const double step = (gz > 0 ? -1e-6 : 1e-6) * (1 + std::fabs(z));
        const Vec3 p2{x, y, z + step};
        const double v2 = l.isPlane ? l.plane.Evaluate(p2) : l.quadric.Evaluate(p2);
        const double e2 = l.isPlane ? PlaneErrorEstimate(l.plane, p2, pointError)
                                    : QuadricErrorEstimate(l.quadric, p2, pointError);
        if (!(v2 < -e2)) return false;
    }
    return true;
}

// The verifier. After an event whose stack edges are [b, e) (the last one `last`), the stack
// must be the stack before the event with the event's faces toggled (structure), and each
// toggled face must be on it exactly when the face test at Q finds the face on its body's
// boundary there (geometry). A structural mismatch (a vertex whose change was not carried on) is
// counted in stackRepairs, a face the test overrules in stackCorrections; both are corrected: the
// stack is rebuilt from `before` with the faces the test finds, and the next stack edge is
// derived again. Then the faces that entered are checked against the nearest faces of their own
// body on the stack (order, §5.5.1; stackOrderCorrections). The faces entering/leaving at the
// event are counted as face_stack_inserts/deletes.
bool StackVerifier::VerifyEvent(const std::vector<int>& before, std::vector<ActiveEdge>& ael,
                                std::size_t b, std::size_t e, std::size_t last, double xq,
                                double y) {
    std::vector<int>& t = ael[last].stack;
    const double xe = ael[last].x;
    if (++gen_ == 0) {  // stamp overflow: clear the marks
        std::fill(markP_.begin(), markP_.end(), 0);
        std::fill(markT_.begin(), markT_.end(), 0);
        gen_ = 1;
    }
    for (int f : before) markP_[static_cast<std::size_t>(f)] = gen_;
    for (int f : t) markT_[static_cast<std::size_t>(f)] = gen_;
    CollectToggles(ael, b, e);
    const bool structural = Structural(before, t);
    const bool geometric = FaceTestsAgree(xq, y);
    if (!structural) ++ctx_.c.stackRepairs;
    const bool rebuilt = !structural || !geometric;
    if (rebuilt) Rebuild(before, t, xe, xq, y);
    for (int f : t)
        if (!InP(f)) ++ctx_.c.stackInserts;
    for (int f : before)
        if (!Contains(t, f)) ++ctx_.c.stackDeletes;
    FixOrder(t, xe, xq, y);
    return rebuilt;
}

inline void StackVerifier::CollectToggles(const std::vector<ActiveEdge>& ael, std::size_t b,
                                          std::size_t e) {
    toggles_.clear();
    for (std::size_t k = b; k < e; ++k) {
        if (!ael[k].Participates()) continue;
        for (int f : ctx_.Edge(ael[k].edge).faces) {
            if (f < 0) continue;
            auto it = std::find_if(toggles_.begin(), toggles_.end(),
                                   [&](const std::pair<int, bool>& p) { return p.first == f; });
            if (it == toggles_.end())
                toggles_.push_back({f, true});
            else
                it->second = !it->second;
        }
    }
}

inline bool StackVerifier::Toggled(int f) const {
    return std::any_of(toggles_.begin(), toggles_.end(),
                       [&](const std::pair<int, bool>& p) { return p.first == f; });
}

inline bool StackVerifier::Structural(const std::vector<int>& before,
                                      const std::vector<int>& t) const {
    bool structural = true;
    for (int f : t) structural = structural && (Toggled(f) || InP(f));
    for (int f : before) structural = structural && (Toggled(f) || InT(f));
    for (auto [f, odd] : toggles_) structural = structural && (InT(f) == (InP(f) != odd));
    return structural;
}

inline bool StackVerifier::FaceTestsAgree(double xq, double y) {
    bool geometric = true;
    present_.clear();
    for (auto [f, odd] : toggles_) {
        const bool p = PresentAt(f, xq, y);
        present_.push_back(p);
        if (p != InT(f)) {
            geometric = false;
            ++ctx_.c.stackCorrections;
        }
    }
    return geometric;
}

inline void StackVerifier::Rebuild(const std::vector<int>& before, std::vector<int>& t, double xe,
                                   double xq, double y) {
    // From the stack before the event: it was verified at its own event.
    derived_.assign(before.begin(), before.end());
    for (std::size_t k = 0; k < toggles_.size(); ++k) {
        const int f = toggles_[k].first;
        auto it = std::find(derived_.begin(), derived_.end(), f);
        if (it != derived_.end() && !present_[k]) derived_.erase(it);
        if (it == derived_.end() && present_[k]) order_.InsertInto(derived_, f, xe, xq, y);
    }
    t.swap(derived_);
}

// Order: each entering face against the nearest faces of its own body above and below. A
// misplaced face is inserted again (InsertInto leaves it in order with its own body's faces) and
// the scan restarts, a bounded number of times.
inline void StackVerifier::FixOrder(std::vector<int>& t, double xe, double xq, double y) {
    int retries = static_cast<int>(t.size());
    for (std::size_t s = 0; s < t.size(); ++s) {
        const int f = t[s];
        if (InP(f)) continue;
        const int body = ctx_.Face(f).body;
        bool ok = true;
        for (std::size_t r = s; r-- > 0;) {
            if (ctx_.Face(t[r]).body != body) continue;
            ok = order_.CompareAt(t[r], f, xe, xq, y) <= 0;
            break;
        }
        for (std::size_t r = s + 1; ok && r < t.size(); ++r) {
            if (ctx_.Face(t[r]).body != body) continue;
            ok = order_.CompareAt(f, t[r], xe, xq, y) <= 0;
            break;
        }
        if (ok || retries-- <= 0) continue;
        ++ctx_.c.stackOrderCorrections;
        t.erase(t.begin() + static_cast<std::ptrdiff_t>(s));
        order_.InsertInto(t, f, xe, xq, y);
        s = static_cast<std::size_t>(-1);  // rescan from the head
    }
}

void StackVerifier::VerifySpan(const std::vector<int>& activeUnits, const std::vector<int>& shown,
                               const std::vector<StackFace>& spanFaces, int sample, double y) {
    eval::RayEvaluator::Hit best;
    for (int u : activeUnits) {
        const Unit& unit = ctx_.UnitOf(u);
        if (unit.kind != Unit::Kind::kBody || !ctx_.useStack[static_cast<std::size_t>(unit.body)])
            continue;
        if (sample < unit.x0 || sample > unit.x1) continue;
        eval::RayEvaluator::Hit hit;
        if (ctx_.eval.Body(unit.body, sample + 0.5, y, hit) && hit.t < best.t) best = hit;
    }
    const bool head = !shown.empty();
    if (!head && best.halfSpace < 0) return;
    ++ctx_.c.verifySpans;
    bool same = head && best.halfSpace >= 0;
    if (same) {
        const FaceRef h = ctx_.RefOf(shown.front());
        same = h.halfSpace == best.halfSpace &&
               h.sheet == ctx_.eval.SheetOf(best.halfSpace, best.t, sample + 0.5, y);
    }
    if (!same) ++ctx_.c.verifyMismatchSpans;
    // Per body: its first face on the stack against its exact visible face.
    for (int u : activeUnits) {
        const Unit& unit = ctx_.UnitOf(u);
        if (unit.kind != Unit::Kind::kBody || !ctx_.useStack[static_cast<std::size_t>(unit.body)])
            continue;
        if (sample < unit.x0 || sample > unit.x1) continue;
        eval::RayEvaluator::Hit hit;
        const bool exact = ctx_.eval.Body(unit.body, sample + 0.5, y, hit);
        const StackFace* mine = nullptr;
        for (const StackFace& sf : spanFaces)
            if (sf.body == unit.body) mine = &sf;
        if (!exact && !mine) continue;
        ++ctx_.c.verifyBodies;
        if (!exact || !mine || mine->halfSpace != hit.halfSpace ||
            mine->sheet != ctx_.eval.SheetOf(hit.halfSpace, hit.t, sample + 0.5, y))
            ++ctx_.c.verifyBodyMismatches;
    }
}

}  // namespace quadrix::scanline
