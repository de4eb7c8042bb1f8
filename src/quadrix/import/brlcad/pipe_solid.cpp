// BRL-CAD pipe → runs and bends → Shape; the layout and its rules are in pipe_solid.h.
#include "quadrix/import/brlcad/pipe_solid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "quadrix/import/shapes/local_frame.h"
#include "quadrix/math/quartic_surface.h"

namespace quadrix::import::brlcad {

namespace {

// Points closer than this are the same point (librt's SQRT_SMALL_FASTF test is far smaller; a
// micrometre in millimetre units is well below any modelled size and above rounding).
constexpr double kSamePoint = 1e-9;
// |n1 × n2| below this: collinear (no bend).
constexpr double kCollinear = 1e-12;

// The right circular cone (a cylinder when r0 = r1) about the segment a → b, radius r0 at a and r1
// at b: |d|² − (d·t)² − (r0 + g d·t)² <= 0 with d = P − a, t = unit(b − a), g = (r1 − r0)/|b − a|.
// (Only the slab between the joint planes is used, where r0 + g d·t >= 0: one nappe.)
ShapeHalfSpace Cone(const Vec3& a, const Vec3& b, double r0, double r1, bool complement) {
    const double len = Length(b - a);
    const Vec3 t = (b - a) / len;
    const double g = (r1 - r0) / len;
    // Symmetric matrix over (d, 1).
    Mat4 q = Mat4::Zero();
    const double tt[3] = {t.x, t.y, t.z};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) q.m[i][j] = (i == j ? 1.0 : 0.0) - (1 + g * g) * tt[i] * tt[j];
        q.m[i][3] = q.m[3][i] = -r0 * g * tt[i];
    }
    q.m[3][3] = -r0 * r0;
    // d = P − a: Q_world = Tᵀ Q T with T = [[I, −a], [0, 1]].
    Mat4 tr = Mat4::Identity();
    tr.m[0][3] = -a.x, tr.m[1][3] = -a.y, tr.m[2][3] = -a.z;
    ShapeHalfSpace h;
    h.isPlane = false;
    h.quadric = Quadric::FromMatrix(tr.Transposed() * q * tr);
    h.complement = complement;
    return h;
}

// The plane through x perpendicular to the direction t, inside "before" x: t·(P − x) <= 0.
ShapeHalfSpace Joint(const Vec3& x, const Vec3& t) {
    ShapeHalfSpace h;
    h.plane = Plane{t.x, t.y, t.z, -Dot(t, x)};
    return h;
}

ShapeHalfSpace Flipped(const ShapeHalfSpace& h) {
    ShapeHalfSpace f = h;
    f.plane = Plane{-h.plane.a, -h.plane.b, -h.plane.c, -h.plane.d};
    return f;
}

PipeLayout Fail(std::string why, int point = -1) {
    PipeLayout l;
    l.problem = std::move(why);
    l.point = point;
    return l;
}

}  // namespace

PipeLayout LayOutPipe(const std::vector<Primitive::PipePoint>& pts) {
    if (pts.size() < 2) return Fail("a pipe needs at least 2 points");
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto& p = pts[i];
        if (!(p.od > 0) || !(p.id >= 0) || !(p.id < p.od) || !std::isfinite(p.od) ||
            !std::isfinite(p.bend) || !std::isfinite(p.at.x + p.at.y + p.at.z))
            return Fail(
                fmt::format("point {} has outer diameter {} and inner diameter {} (need 0 <= id < "
                            "od)",
                            i, p.od, p.id),
                static_cast<int>(i));
    }
    PipeLayout out;
    Vec3 x = pts[0].at;
    double od = pts[0].od, id = pts[0].id;
    double prevBendDist = 0;  // tangent distance of the bend that ended at x
    Vec3 prevPoint = x;       // the pipe point before Pi (x is on the run from it to Pi)
    auto run = [&](const Vec3& to, double od1, double id1) {
        PipePiece r;
        r.kind = PipePiece::Kind::kRun;
        r.a = x, r.b = to;
        r.ro0 = od / 2, r.ri0 = id / 2, r.ro1 = od1 / 2, r.ri1 = id1 / 2;
        if (Length(to - x) > kSamePoint) out.pieces.push_back(r);
    };
    for (std::size_t i = 1; i < pts.size(); ++i) {
        const auto& p = pts[i];
        const Vec3 toX = x - p.at;
        if (Length(toX) <= kSamePoint) {  // duplicate point
            od = p.od, id = p.id;
            continue;
        }
        const double runLength = Length(p.at - prevPoint);
        if (i + 1 == pts.size()) {
            if (prevBendDist > runLength * (1 + 1e-9))
                return Fail(fmt::format("the last run (to point {}) is too short for the bend "
                                        "before it",
                                        i),
                            static_cast<int>(i));
            run(p.at, p.od, p.id);
            break;
        }
        const Vec3 n1 = Normalize(toX);
        const Vec3 toNext = pts[i + 1].at - p.at;
        const bool nextSame = Length(toNext) <= kSamePoint;
        const Vec3 n2 = nextSame ? -n1 : Normalize(toNext);
        const Vec3 axis = Cross(n1, n2);
        const double deflection = std::numbers::pi - std::acos(std::clamp(Dot(n1, n2), -1.0, 1.0));
        const double t = p.bend * std::tan(deflection / 2);
        if (nextSame || Length(axis) < kCollinear || !(t > kSamePoint)) {
            if (Dot(n1, n2) > 0.5 && !nextSame)
                return Fail(fmt::format("the pipe turns back on itself at point {}", i),
                            static_cast<int>(i));
            // Collinear (or no bend radius): a straight run to the point.
            run(p.at, p.od, p.id);
            x = p.at, od = p.od, id = p.id;
            prevBendDist = 0;
            prevPoint = p.at;
            continue;
        }
        if (p.bend < p.od / 2)
            return Fail(fmt::format("the bend radius {} at point {} is smaller than the outer "
                                    "radius {}",
                                    p.bend, i, p.od / 2),
                        static_cast<int>(i));
        if (deflection >= std::numbers::pi * (1 - 1e-9))
            return Fail(fmt::format("the bend at point {} turns through 180°", i),
                        static_cast<int>(i));
        if (prevBendDist + t > runLength * (1 + 1e-9))
            return Fail(fmt::format("the bends at and before point {} overlap on the run "
                                    "between them",
                                    i),
                        static_cast<int>(i));
        const Vec3 s = p.at + n1 * t, e = p.at + n2 * t;
        run(s, p.od, p.id);
        PipePiece b;
        b.kind = PipePiece::Kind::kBend;
        b.a = s, b.b = e;
        b.ro0 = b.ro1 = p.od / 2;
        b.ri0 = b.ri1 = p.id / 2;
        b.normal = Normalize(axis);
        b.bend = p.bend;
        b.angle = deflection;
        // The centre: R from S towards the inside of the bend, i.e. along the bisector of n1, n2.
        const Vec3 inward = Normalize(Cross(b.normal, n1));  // ⊥ to the tangent −n1, in the plane
        b.centre = s + inward * p.bend;
        out.pieces.push_back(b);
        x = e, od = p.od, id = p.id;
        prevBendDist = t;
        prevPoint = p.at;
    }
    if (out.pieces.empty()) return Fail("all its points coincide");
    out.ok = true;
    return out;
}

PipeShape PipeToShape(const PipeLayout& layout) {
    PipeShape out;
    if (!layout.ok) {
        out.problem = layout.problem;
        return out;
    }
    auto dirIn = [](const PipePiece& p) {  // travel direction where the piece starts
        if (p.kind == PipePiece::Kind::kRun) return Normalize(p.b - p.a);
        return Normalize(Cross(p.a - p.centre, p.normal));
    };
    auto dirOut = [](const PipePiece& p) {  // and where it ends
        if (p.kind == PipePiece::Kind::kRun) return Normalize(p.b - p.a);
        return Normalize(Cross(p.b - p.centre, p.normal));
    };
    // The open joint: the plane where the previous piece ended ("before" side), flipped for the
    // next piece. At the start, the end cap.
    ShapeHalfSpace open = Joint(layout.pieces.front().a, dirIn(layout.pieces.front()));
    Shape& shape = out.shape;
    for (std::size_t k = 0; k < layout.pieces.size(); ++k) {
        const PipePiece& p = layout.pieces[k];
        const Vec3 tOut = dirOut(p);
        const ShapeHalfSpace close = Joint(p.b, tOut);
        ShapeBody body;
        if (p.kind == PipePiece::Kind::kRun) {
            body.push_back(Cone(p.a, p.b, p.ro0, p.ro1, false));
            if (p.ri0 > 0 || p.ri1 > 0) body.push_back(Cone(p.a, p.b, p.ri0, p.ri1, true));
            const Vec3 t = Normalize(p.b - p.a);
            const Vec3 e1 = AnyPerpendicular(t), e2 = Cross(t, e1);
            shape.extent.push_back({p.a, e1 * p.ro0, e2 * p.ro0, {}});
            shape.extent.push_back({p.b, e1 * p.ro1, e2 * p.ro1, {}});
        } else {
            std::string why;
            auto outer = QuarticSurface::Torus(p.centre, p.normal, p.bend, p.ro0, &why);
            if (!outer) {
                out.problem = fmt::format("bend {}: {}", k, why);
                return out;
            }
            ShapeHalfSpace o;
            o.SetQuartic(*outer);
            body.push_back(o);
            if (p.ri0 > 0) {
                auto inner = QuarticSurface::Torus(p.centre, p.normal, p.bend, p.ri0, &why);
                if (!inner) {
                    out.problem = fmt::format("bend {}: {}", k, why);
                    return out;
                }
                ShapeHalfSpace in;
                in.SetQuartic(*inner);
                in.complement = true;
                body.push_back(in);
            }
            // Balls of the outer radius at the corners of a tangent polygon around the arc.
            const Vec3 ra = Normalize(p.a - p.centre), rb = Cross(ra, p.normal);
            const int n =
                std::max(1, static_cast<int>(std::ceil(p.angle / (std::numbers::pi / 8))));
            const double delta = p.angle / n;
            const Vec3 bx{p.ro0, 0, 0}, by{0, p.ro0, 0}, bz{0, 0, p.ro0};
            for (int j = 0; j <= 2 * n; ++j) {
                const double phi = delta * j / 2;
                const double rad = (j % 2 == 0) ? p.bend : p.bend / std::cos(delta / 2);
                const Vec3 c = p.centre + (ra * std::cos(phi) + rb * std::sin(phi)) * rad;
                shape.extent.push_back({c, bx, by, bz});
            }
        }
        body.push_back(Flipped(open));
        body.push_back(close);
        shape.bodies.push_back(std::move(body));
        open = close;
    }
    out.ok = true;
    return out;
}

}  // namespace quadrix::import::brlcad
