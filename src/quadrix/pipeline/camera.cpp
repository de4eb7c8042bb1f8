#include "quadrix/pipeline/camera.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>

namespace quadrix {

namespace {

// Model coordinates → Quadrix space: (x, y, z) → (x, z, y) for Z-up models (QuadrixFromZUp).
Vec3 ToQuadrix(const Vec3& p, bool zUp) { return zUp ? Vec3{p.x, p.z, p.y} : p; }

}  // namespace

std::string ParseCamera(const std::string& text, CameraRequest& request) {
    std::vector<double> v;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || end == item.c_str() || *end != 0 || !std::isfinite(x))
            return fmt::format("--camera: '{}' is not a number", item);
        v.push_back(x);
    }
    if (v.size() != 6)
        return fmt::format(
            "--camera: expected eye_x,eye_y,eye_z,center_x,center_y,center_z (6 numbers), found "
            "{} in '{}'",
            v.size(), text);
    request.eye = Vec3{v[0], v[1], v[2]};
    request.center = Vec3{v[3], v[4], v[5]};
    if (*request.eye == *request.center) return "--camera: the eye is at the center";
    return {};
}

std::string ParseProjection(const std::string& text, CameraRequest& request) {
    if (text == "ortho" || text == "orthogonal" || text == "o") {
        request.orthographic = true;
        return {};
    }
    if (text == "persp" || text == "perspective" || text == "p") {
        request.orthographic = false;
        return {};
    }
    return fmt::format("--projection: expected ortho or persp, found '{}'", text);
}

std::optional<scene::View> CameraView(const CameraRequest& r, const scene::View& sceneView,
                                      std::string& error) {
    error.clear();
    if (r.fovDegrees && !(*r.fovDegrees > 0 && *r.fovDegrees < 180)) {
        error = fmt::format("--fov: expected degrees in (0, 180), found {}", *r.fovDegrees);
        return std::nullopt;
    }
    if (!r.eye) {
        if (r.fovDegrees) {
            error = "--fov needs --camera (the scene's view has no eye to project from)";
            return std::nullopt;
        }
        scene::View v = sceneView;
        if (r.viewAll) v.whh = v.whw = std::nullopt;
        return v;
    }
    const Vec3 eye = ToQuadrix(*r.eye, r.zUp), center = ToQuadrix(*r.center, r.zUp);
    const Vec3 into = center - eye;
    const double distance = Length(into);
    if (!(distance > 0)) {
        error = "--camera: the eye is at the center";
        return std::nullopt;
    }
    scene::View v;
    v.id = "camera";
    v.vrp = center;
    v.vpn = into;
    // Screen up: Quadrix's y (the model's up either way), or z when looking along it.
    const Vec3 dir = into / distance;
    v.vup = std::fabs(dir.y) > 0.999 ? Vec3{0, 0, dir.y > 0 ? -1.0 : 1.0} : Vec3{0, 1, 0};
    if (r.orthographic)
        v.dop = -1.0 * into;
    else
        v.cop = eye;
    if (!r.viewAll) {
        const double fov = r.fovDegrees.value_or(22.5) * std::numbers::pi / 180;
        v.whh = distance * std::tan(fov / 2);
    }
    return v;
}

scene::View CentreOnScene(const scene::View& view, const FlatScene& fitted) {
    Box3 box;
    for (const FlatSolid& s : fitted.solids)
        if (s.bounds.Finite()) box.Extend(s.bounds);
    if (!box.Finite() || !view.vpn) return view;
    const Transform worldFromDevice = fitted.projection.deviceFromWorld.Inverted();
    const Vec3 middle = worldFromDevice.MapPoint(0.5 * (box.lo + box.hi));
    const Vec3 vrp = view.vrp.value_or(Vec3{0, 0, 0});
    const Vec3 dir = Normalize(*view.vpn);
    Vec3 shift = middle - vrp;
    shift = shift - Dot(shift, dir) * dir;  // across the view only: the distance stays
    if (!IsFinite(shift)) return view;
    scene::View v = view;
    v.vrp = vrp + shift;
    if (v.cop) v.cop = *v.cop + shift;
    return v;
}

}  // namespace quadrix
