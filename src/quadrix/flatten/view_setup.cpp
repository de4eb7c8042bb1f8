// The view transformation; the formulas are written out in view_setup.h.
#include "quadrix/flatten/view_setup.h"

#include <fmt/format.h>

#include <cmath>

namespace quadrix {

namespace {

// Smallest |r_n| (cosine between the projection direction and vpn) accepted for an oblique
// parallel projection: beyond ~89.9° the shear factors exceed 1000 and quadrics degenerate.
constexpr double kMinObliqueCosine = 1e-3;
// Perspective near plane as a fraction of the eye's distance to the view plane.
constexpr double kNearFraction = 1e-4;

std::string Fmt(const Vec3& v) { return fmt::format("({} {} {})", v.x, v.y, v.z); }

// Rows u, v, n and translation -R·origin: world → view coordinates relative to `origin`.
Transform FrameFromWorld(const Vec3& u, const Vec3& v, const Vec3& n, const Vec3& origin) {
    Mat4 m = Mat4::Identity(), inv = Mat4::Identity();
    const Vec3 rows[3] = {u, v, n};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            m.m[i][j] = rows[i][j];
            inv.m[j][i] = rows[i][j];
        }
        m.m[i][3] = -Dot(rows[i], origin);
        inv.m[i][3] = origin[i];
    }
    return {m, inv};
}

class ViewResolver {
  public:
    ViewResolver(const scene::View& view, Diagnostics& diags) : view_(view), diags_(diags) {}

    std::optional<ViewSetup> Run() {
        ViewSetup s;
        s.id = view_.id;
        s.loc = view_.loc;
        if (!CheckVectors()) return std::nullopt;
        s.vrp = view_.vrp.value_or(Vec3{0, 0, 0});
        s.perspective = view_.cop.has_value();
        if (view_.cop && view_.dop)
            diags_.Warning(view_.loc, fmt::format("view '{}' gives both dop and cop; cop wins "
                                                  "(perspective projection)",
                                                  view_.id));
        Vec3 dop = view_.dop.value_or(Vec3{0.3, 0.3, -1});
        // vpn: given, else opposite dop (parallel) or from cop to vrp (perspective).
        Vec3 vpn;
        if (view_.vpn) {
            vpn = *view_.vpn;
        } else if (s.perspective) {
            vpn = s.vrp - *view_.cop;
            if (Length(vpn) == 0)
                return Fail(
                    fmt::format("view '{}': cop {} coincides with vrp and no vpn is "
                                "given, so the viewing direction is undefined",
                                view_.id, Fmt(*view_.cop)));
        } else {
            vpn = -dop;
        }
        s.n = Normalize(vpn);
        Vec3 vup = view_.vup.value_or(Vec3{0, 1, 0});
        // Both unit vectors first: a vup or vpn of any magnitude (1e-200, 1e200) gives the same
        // screen (issue 23), where the raw cross product under- or overflowed.
        // The raw vup where its products are safe, so ordinary views keep their exact bits.
        const double vupLength = Length(vup);
        const Vec3 up = vupLength > 1e-100 && vupLength < 1e100 ? vup : vup / vupLength;
        Vec3 right = Cross(up, s.n);
        if (!(Length(right) > 1e-9 * Length(up)))
            return Fail(
                fmt::format("view '{}': vup {} is parallel to the view plane normal {}; "
                            "the screen's up direction is undefined",
                            view_.id, Fmt(vup), Fmt(vpn)));
        s.u = Normalize(right);
        s.v = Cross(s.n, s.u);
        if (!CheckWindow(s)) return std::nullopt;
        bool ok = s.perspective ? Perspective(s) : Parallel(s, dop);
        if (!ok) return std::nullopt;
        return s;
    }

  private:
    std::optional<ViewSetup> Fail(std::string message) {
        diags_.Error(view_.loc, std::move(message));
        return std::nullopt;
    }
    bool Error(std::string message) {
        diags_.Error(view_.loc, std::move(message));
        return false;
    }

    bool CheckVectors() {
        struct Named {
            const char* name;
            const std::optional<Vec3>& value;
            bool direction;
        };
        const Named all[] = {{"vrp", view_.vrp, false},
                             {"vpn", view_.vpn, true},
                             {"vup", view_.vup, true},
                             {"dop", view_.dop, true},
                             {"cop", view_.cop, false}};
        bool ok = true;
        for (const Named& v : all) {
            if (!v.value) continue;
            if (!IsFinite(*v.value))
                ok = Error(
                    fmt::format("view '{}': {} {} is not finite", view_.id, v.name, Fmt(*v.value)));
            else if (v.direction && Length(*v.value) == 0)
                ok = Error(fmt::format("view '{}': {} is the zero vector", view_.id, v.name));
        }
        return ok;
    }

    bool CheckWindow(ViewSetup& s) {
        bool ok = true;
        auto check = [&](const char* name, const std::optional<double>& w) {
            if (w && !(std::isfinite(*w) && *w > 0))
                ok = Error(fmt::format("view '{}': {} must be a positive size, found {}", view_.id,
                                       name, *w));
        };
        check("whh", view_.whh);
        check("whw", view_.whw);
        s.whh = view_.whh;
        s.whw = view_.whw;
        for (const auto& f : {view_.front, view_.back})
            if (f && !std::isfinite(*f))
                ok = Error(fmt::format("view '{}': fbp distances must be finite", view_.id));
        return ok;
    }

    // fbp: front = the smaller distance, back = the larger (seed 001 §2.1.6: "distances from
    // vrp along vpn"). Either may be missing when the view was built by other means.
    void FrontBack(std::optional<double>& front, std::optional<double>& back) const {
        front = view_.front;
        back = view_.back;
        if (front && back && *front > *back) std::swap(front, back);
    }

    bool Parallel(ViewSetup& s, const Vec3& dop) {
        // r = -dop in the view frame; the projection runs along r, into the scene.
        Vec3 r = -Normalize(dop);
        double ru = Dot(r, s.u), rv = Dot(r, s.v), rn = Dot(r, s.n);
        if (std::fabs(rn) < kMinObliqueCosine)
            return Error(
                fmt::format("view '{}': dop {} is parallel (or nearly) to the view "
                            "plane, whose normal is {}",
                            view_.id, Fmt(dop), Fmt(s.n)));
        if (rn < 0)
            return Error(
                fmt::format("view '{}': dop {} points away from the viewer; dop is the "
                            "direction toward the viewer and vpn {} the direction into "
                            "the scene, so dop·vpn must be negative",
                            view_.id, Fmt(dop), Fmt(s.n)));
        double a = ru / rn, b = rv / rn;
        Mat4 p = Mat4::Identity(), pinv = Mat4::Identity();
        p.m[0][2] = -a;
        p.m[1][1] = -1;
        p.m[1][2] = b;
        pinv.m[0][2] = a;
        pinv.m[1][1] = -1;
        pinv.m[1][2] = b;
        s.provFromWorld = Transform(p, pinv) * FrameFromWorld(s.u, s.v, s.n, s.vrp);
        s.towardViewer = Normalize(dop);
        std::optional<double> front, back;
        FrontBack(front, back);
        if (front) s.finalClips.push_back(Plane{0, 0, -1, *front});  // z >= front
        if (back) s.finalClips.push_back(Plane{0, 0, 1, -*back});    // z <= back
        return true;
    }

    bool Perspective(ViewSetup& s) {
        s.eye = *view_.cop;
        Vec3 toVrp = s.vrp - s.eye;
        double d = Dot(toVrp, s.n);
        if (!(d > 1e-12 * Length(toVrp)))
            return Error(
                fmt::format("view '{}': the eye (cop {}) must be in front of the view "
                            "plane through vrp {}: (vrp - cop)·vpn must be positive",
                            view_.id, Fmt(s.eye), Fmt(s.vrp)));
        s.d = d;
        double cu = Dot(toVrp, s.u), cv = Dot(toVrp, s.v);
        Mat4 p = Mat4::Zero(), pinv = Mat4::Zero();
        p.m[0][0] = d;
        p.m[0][2] = -cu;
        p.m[1][1] = -d;
        p.m[1][2] = cv;
        p.m[2][2] = d;
        p.m[2][3] = -d * d;
        p.m[3][2] = 1;
        pinv.m[0][0] = 1 / d;
        pinv.m[0][3] = cu / d;
        pinv.m[1][1] = -1 / d;
        pinv.m[1][3] = cv / d;
        pinv.m[2][3] = 1;
        pinv.m[3][2] = -1 / (d * d);
        pinv.m[3][3] = 1 / d;
        s.provFromWorld = Transform(p, pinv) * FrameFromWorld(s.u, s.v, s.n, s.eye);
        s.towardViewer = -s.n;
        auto depthOf = [d](double ne) { return d * (1 - d / ne); };
        const double near0 = kNearFraction * d;
        // The window fit ignores fbp: near plane at 1e-4 d and the image of n_e = +∞.
        s.fitNear = depthOf(near0);
        s.fitClips.push_back(Plane{0, 0, -1, s.fitNear});  // z >= z(near0)
        s.fitClips.push_back(Plane{0, 0, 1, -d});          // z <= d
        std::optional<double> front, back;
        FrontBack(front, back);
        double nearDist = near0;
        if (front && d + *front > near0) nearDist = d + *front;
        s.finalClips.push_back(Plane{0, 0, -1, depthOf(nearDist)});
        if (back) {
            double farDist = d + *back;
            if (!(farDist > nearDist))
                return Error(
                    fmt::format("view '{}': the fbp clipping planes leave nothing in "
                                "front of the eye (back plane at distance {} from the "
                                "eye, near limit {})",
                                view_.id, farDist, nearDist));
            s.finalClips.push_back(Plane{0, 0, 1, -depthOf(farDist)});
        } else {
            s.finalClips.push_back(Plane{0, 0, 1, -d});
        }
        return true;
    }

    const scene::View& view_;
    Diagnostics& diags_;
};

}  // namespace

std::optional<ViewSetup> ResolveView(const scene::View& view, Diagnostics& diags) {
    return ViewResolver(view, diags).Run();
}

}  // namespace quadrix
