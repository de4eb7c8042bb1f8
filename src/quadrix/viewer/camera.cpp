#include "quadrix/viewer/camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "quadrix/flatten/view_setup.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::viewer {

namespace {

// Rodrigues' rotation of v about the unit axis k by `angle` radians (right-hand rule):
// v cos a + (k × v) sin a + k (k·v)(1 - cos a).
Vec3 Rotate(const Vec3& v, const Vec3& k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + Cross(k, v) * s + k * (Dot(k, v) * (1 - c));
}

// Keeps toward and up unit and perpendicular after a rotation (rounding drifts).
void Orthonormalize(Vec3& toward, Vec3& up) {
    toward = Normalize(toward);
    up = Normalize(up - toward * Dot(up, toward));
}

}  // namespace

void Camera::Orbit(double dx, double dy, int height) {
    if (height <= 0) return;
    const double yaw = std::numbers::pi * dx / height;
    const double pitch = std::numbers::pi * dy / height;
    const Vec3 axis = Dot(up, worldUp) < 0 ? -worldUp : worldUp;
    Vec3 offset = pivot ? target - *pivot : Vec3{};
    toward = Rotate(toward, axis, yaw);
    up = Rotate(up, axis, yaw);
    offset = Rotate(offset, axis, yaw);
    const Vec3 right = Right();
    toward = Rotate(toward, right, pitch);
    up = Rotate(up, right, pitch);
    offset = Rotate(offset, right, pitch);
    if (pivot) target = *pivot + offset;
    Orthonormalize(toward, up);
}

void Camera::Pan(double dx, double dy, int height) {
    if (height <= 0) return;
    const double s = 2 * halfHeight / height;
    target += Right() * (-dx * s) + up * (dy * s);
}

void Camera::Zoom(double clicks, double x, double y, int width, int height) {
    if (height <= 0 || width <= 0) return;
    const double f = std::pow(0.8, clicks);
    const double s = 2 * halfHeight / height;
    const Vec3 o = Right() * ((x - 0.5 * width) * s) + up * ((0.5 * height - y) * s);
    target += o * (1 - f);
    halfHeight *= f;
    distance *= f;
}

void Camera::SetStandardView(StandardView view, const SceneSphere& sphere) {
    target = sphere.centre;
    pivot.reset();
    worldUp = {0, 1, 0};
    // The default view looks along +z (docs/language.md §2): the front is seen from -z.
    switch (view) {
        case StandardView::kFront:
            toward = {0, 0, -1}, up = {0, 1, 0};
            break;
        case StandardView::kBack:
            toward = {0, 0, 1}, up = {0, 1, 0};
            break;
        case StandardView::kLeft:
            toward = {-1, 0, 0}, up = {0, 1, 0};
            break;
        case StandardView::kRight:
            toward = {1, 0, 0}, up = {0, 1, 0};
            break;
        // From above, the front (-z) at the bottom of the screen; from below, at the top.
        case StandardView::kTop:
            toward = {0, 1, 0}, up = {0, 0, 1};
            break;
        case StandardView::kBottom:
            toward = {0, -1, 0}, up = {0, 0, -1};
            break;
        case StandardView::kIso:
            toward = Normalize({1, 1, -1}), up = {0, 1, 0};
            break;
    }
    Orthonormalize(toward, up);
}

void Camera::FitAll(const SceneSphere& sphere, int width, int height) {
    target = sphere.centre;
    pivot.reset();
    const double aspect = (width > 0 && height > 0) ? double(height) / width : 1.0;
    // In perspective the silhouette of a sphere of radius r seen from D is r D / sqrt(D² - r²)
    // wide at the target's plane; with D >= 2.75 · 1.05 r that is at most 7% more.
    halfHeight = 1.05 * sphere.radius * std::max(1.0, aspect) * (perspective ? 1.07 : 1.0);
    if (perspective) distance = kEyeRatio * halfHeight;
}

void Camera::SetPerspective(bool on, double minDistance) {
    if (on && !perspective) distance = std::max(kEyeRatio * halfHeight, minDistance);
    perspective = on;
}

void Camera::MoveTargetToDepthOf(const Vec3& p) {
    if (!perspective) target += toward * Dot(p - target, toward);
}

scene::View Camera::ToView() const {
    scene::View v;
    v.id = "camera";
    v.vrp = target;
    v.vpn = -toward;
    v.vup = up;
    v.whh = halfHeight;
    if (perspective)
        v.cop = Eye();
    else
        v.dop = toward;
    return v;
}

std::string FormatViewStatement(const Camera& camera, int width, int height, const std::string& id,
                                const std::string& renderOptions) {
    const scene::View v = camera.ToView();
    auto vec = [](const char* name, const Vec3& p) {
        return fmt::format(" {} {:.17g} {:.17g} {:.17g}", name, p.x, p.y, p.z);
    };
    std::string s = fmt::format("{{ quadrix view at {}x{}: quadrix render ... --size {}x{}{} }}\n",
                                width, height, width, height, renderOptions);
    s += "view " + id + vec("vrp", *v.vrp) + vec("vpn", *v.vpn) + vec("vup", *v.vup);
    s += v.cop ? vec("cop", *v.cop) : vec("dop", *v.dop);
    s += fmt::format(" whh {:.17g};\n", *v.whh);
    return s;
}

std::optional<Camera> CameraFromView(const scene::View& view, const FlatScene& flat) {
    Diagnostics diags;
    const std::optional<ViewSetup> vs = ResolveView(view, diags);
    if (!vs || flat.width <= 0 || flat.height <= 0) return std::nullopt;
    const Mat4& m = flat.projection.deviceFromWorld.Matrix();
    const Vec3 p0 = m.MapPoint(vs->vrp);
    const Vec3 p1 = m.MapPoint(vs->vrp + vs->v);  // on the view plane: k pixels away
    const double k = std::fabs(p1.y - p0.y);
    if (!(k > 0) || !std::isfinite(k)) return std::nullopt;
    Camera c;
    c.halfHeight = 0.5 * flat.height / k;
    if (view.vup) c.worldUp = Normalize(*view.vup);
    if (vs->perspective) {
        c.perspective = true;
        c.target = vs->vrp;
        c.distance = Length(vs->eye - vs->vrp);
        c.toward = (vs->eye - vs->vrp) / c.distance;
        c.up = vs->v;
    } else {
        // The window's centre on the view plane (device y grows downward).
        const double du = (0.5 * flat.width - p0.x) / k, dv = -(0.5 * flat.height - p0.y) / k;
        c.target = vs->vrp + vs->u * du + vs->v * dv;
        c.toward = -vs->n;
        c.up = vs->v;
        c.distance = Camera::kEyeRatio * c.halfHeight;
    }
    Orthonormalize(c.toward, c.up);
    return c;
}

std::optional<SceneSphere> BoundingSphere(const FlatScene& flat) {
    const Mat4& worldFromDevice = flat.projection.deviceFromWorld.Inverse();
    Box3 world;
    for (const FlatSolid& solid : flat.solids) {
        if (!solid.bounds.Finite()) continue;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p{(corner & 1) ? solid.bounds.hi.x : solid.bounds.lo.x,
                         (corner & 2) ? solid.bounds.hi.y : solid.bounds.lo.y,
                         (corner & 4) ? solid.bounds.hi.z : solid.bounds.lo.z};
            world.Extend(worldFromDevice.MapPoint(p));
        }
    }
    if (!world.Finite()) return std::nullopt;
    SceneSphere s;
    s.centre = (world.lo + world.hi) * 0.5;
    s.radius = 0.5 * Length(world.hi - world.lo);
    if (!(s.radius > 0)) s.radius = 1;
    return s;
}

}  // namespace quadrix::viewer
