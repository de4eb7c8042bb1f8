// rt-style views; see rt_view.h.
#include "quadrix/import/rt_view.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "quadrix/import/text_map.h"

namespace quadrix::import {

namespace {

Vec3 SwapYZ(const Vec3& v) { return {v.x, v.z, v.y}; }

}  // namespace

scene::View MakeRtView(const RtView& rt, int width, int height) {
    Vec3 x, y, z;
    for (int k = 0; k < 3; ++k) {
        x[k] = rt.viewrot.m[0][k];
        y[k] = rt.viewrot.m[1][k];
        z[k] = rt.viewrot.m[2][k];
    }
    double cell = rt.viewsize / width;
    // Quadrix pixel centres sit half a cell right of and below rt's sample points (rt samples at
    // eye + (-vs/2 + i·cell) X, i = 0..w-1): move the window by half a cell along -X and -Y.
    Vec3 vrp = rt.eye - (x + y) * (0.5 * cell);
    scene::View v;
    v.id = "rt";
    v.vrp = SwapYZ(vrp);
    v.vpn = SwapYZ(-z);
    v.dop = SwapYZ(z);
    v.vup = SwapYZ(y);
    v.whw = 0.5 * rt.viewsize;
    v.whh = 0.5 * cell * height;
    v.front = 0;  // rt's rays start at the eye plane
    return v;
}

RtView AzElRtView(double azimuth, double elevation, const Box3& modelBox,
                  std::optional<double> viewsize) {
    double sa = 0, ca = 1, se = 0, ce = 1;
    SinCosDegrees(azimuth, sa, ca);
    SinCosDegrees(elevation, se, ce);
    Vec3 z{ce * ca, ce * sa, se};    // toward the viewer
    Vec3 y{-se * ca, -se * sa, ce};  // model Z projected: screen up
    Vec3 x = Cross(y, z);            // screen right (right-handed, as rt)
    RtView rt;
    for (int k = 0; k < 3; ++k) {
        rt.viewrot.m[0][k] = x[k];
        rt.viewrot.m[1][k] = y[k];
        rt.viewrot.m[2][k] = z[k];
    }
    if (modelBox.Finite()) {
        Vec3 centre = SwapYZ(modelBox.Center());
        double radius = 0.5 * Length(modelBox.Size());
        rt.viewsize = viewsize.value_or(2 * radius);
        rt.eye = centre + z * (radius * 1.01 + 1e-9);
    } else {
        rt.viewsize = viewsize.value_or(0);
    }
    return rt;
}

scene::View MakeAzElView(double azimuth, double elevation, const Box3& modelBox,
                         std::optional<double> viewsize, int width, int height) {
    RtView rt = AzElRtView(azimuth, elevation, modelBox, viewsize);
    scene::View v;
    if (rt.viewsize > 0) {
        v = MakeRtView(rt, width, height);
        v.front.reset();  // the eye is outside the model's bounding sphere
    } else {
        // No imported model box: direction only; the Flattener fits the window to the scene.
        Vec3 y, z;
        for (int k = 0; k < 3; ++k) {
            y[k] = rt.viewrot.m[1][k];
            z[k] = rt.viewrot.m[2][k];
        }
        v.vpn = SwapYZ(-z);
        v.dop = SwapYZ(z);
        v.vup = SwapYZ(y);
    }
    v.id = "azel";
    return v;
}

std::optional<RtView> ParseRtViewScript(std::string_view text, const std::string& file,
                                        Diagnostics& diags) {
    TextMap map(text, file);
    RtView rt;
    bool haveSize = false, haveEye = false, haveRot = false;
    // The last `ae` not yet followed by an eye_pt, viewrot or orientation (rt's do_ae puts the
    // eye at the model's centre and keeps the viewsize set before it).
    std::optional<std::pair<double, double>> fittedAe;
    std::size_t i = 0;
    bool ok = true;
    while (i < text.size()) {
        // One command: words up to ';'.
        std::vector<std::pair<std::string, std::size_t>> words;
        while (i < text.size() && text[i] != ';') {
            if (std::isspace(static_cast<unsigned char>(text[i]))) {
                ++i;
                continue;
            }
            std::size_t s = i;
            while (i < text.size() && text[i] != ';' &&
                   !std::isspace(static_cast<unsigned char>(text[i])))
                ++i;
            words.emplace_back(std::string(text.substr(s, i - s)), s);
        }
        ++i;
        if (words.empty()) continue;
        auto numbers = [&](std::size_t n, double* out) {
            if (words.size() != n + 1) {
                diags.Error(map.At(words[0].second),
                            fmt::format("rt view command '{}' takes {} number{}, found {}",
                                        words[0].first, n, n == 1 ? "" : "s", words.size() - 1),
                            map.LineText(words[0].second));
                return false;
            }
            for (std::size_t k = 0; k < n; ++k) {
                char* end = nullptr;
                out[k] = std::strtod(words[k + 1].first.c_str(), &end);
                if (*end != 0 || !std::isfinite(out[k])) {
                    diags.Error(map.At(words[k + 1].second),
                                fmt::format("'{}' is not a finite number", words[k + 1].first),
                                map.LineText(words[k + 1].second));
                    return false;
                }
            }
            return true;
        };
        const std::string& cmd = words[0].first;
        double v[16];
        if (cmd == "viewsize") {
            if ((ok = numbers(1, v) && ok)) rt.viewsize = v[0], haveSize = true;
        } else if (cmd == "eye_pt") {
            if ((ok = numbers(3, v) && ok)) rt.eye = {v[0], v[1], v[2]}, haveEye = true;
            fittedAe.reset();
        } else if (cmd == "ae") {
            if (words.size() == 4) {
                diags.Error(map.At(words[3].second),
                            "rt's 'ae' takes the azimuth and the elevation only (a third "
                            "number, MGED's twist, is not an rt view command)",
                            map.LineText(words[3].second));
                ok = false;
            } else if ((ok = numbers(2, v) && ok)) {
                const RtView azel = AzElRtView(v[0], v[1], Box3{}, std::nullopt);
                rt.viewrot = azel.viewrot;
                haveRot = true;
                fittedAe = std::pair{v[0], v[1]};
            }
        } else if (cmd == "viewrot") {
            fittedAe.reset();
            if ((ok = numbers(16, v) && ok)) {
                for (int k = 0; k < 16; ++k) rt.viewrot.m[k / 4][k % 4] = v[k];
                haveRot = true;
            }
        } else if (cmd == "orientation") {
            fittedAe.reset();
            if ((ok = numbers(4, v) && ok)) {
                // Unit quaternion (x y z w) → rotation matrix (the usual right-handed form).
                // A zero quaternion is no rotation at all (it gave the identity, issue 23); any
                // other is normalised first (scaled by its largest component so that no square
                // overflows), with a warning when it was not a unit quaternion to begin with.
                double big = 0;
                for (int k = 0; k < 4; ++k) big = std::max(big, std::fabs(v[k]));
                if (!(big > 0)) {
                    diags.Error(map.At(words[0].second),
                                "orientation 0 0 0 0 is not a rotation (the zero quaternion)",
                                map.LineText(words[0].second));
                    ok = false;
                    continue;
                }
                double sum = 0;
                for (int k = 0; k < 4; ++k) sum += (v[k] / big) * (v[k] / big);
                const double norm = big * std::sqrt(sum);
                if (std::fabs(norm - 1) > 1e-4)
                    diags.Warning(map.At(words[0].second),
                                  fmt::format("orientation: the quaternion has length {} (not "
                                              "1); it is normalised",
                                              norm),
                                  map.LineText(words[0].second));
                for (int k = 0; k < 4; ++k) v[k] = (v[k] / big) / std::sqrt(sum);
                double qx = v[0], qy = v[1], qz = v[2], qw = v[3];
                Mat4& m = rt.viewrot;
                m = Mat4::Identity();
                m.m[0][0] = 1 - 2 * (qy * qy + qz * qz);
                m.m[0][1] = 2 * (qx * qy - qw * qz);
                m.m[0][2] = 2 * (qx * qz + qw * qy);
                m.m[1][0] = 2 * (qx * qy + qw * qz);
                m.m[1][1] = 1 - 2 * (qx * qx + qz * qz);
                m.m[1][2] = 2 * (qy * qz - qw * qx);
                m.m[2][0] = 2 * (qx * qz - qw * qy);
                m.m[2][1] = 2 * (qy * qz + qw * qx);
                m.m[2][2] = 1 - 2 * (qx * qx + qy * qy);
                haveRot = true;
            }
        }
        // Other rt commands (start, end, clean, ...) do not change the view.
    }
    if (!ok) return std::nullopt;
    if (fittedAe) {
        if (haveSize && !(rt.viewsize > 0)) {
            diags.Error(map.At(0), "an rt view needs a positive viewsize");
            return std::nullopt;
        }
        rt.aeAzimuth = fittedAe->first;
        rt.aeElevation = fittedAe->second;
        if (!haveSize) rt.viewsize = 0;
        return rt;
    }
    if (!haveSize || !haveEye || !haveRot || !(rt.viewsize > 0)) {
        diags.Error(map.At(0),
                    "an rt view needs a positive viewsize, an eye_pt and a viewrot (or "
                    "orientation), or an 'ae azimuth elevation'");
        return std::nullopt;
    }
    return rt;
}

void AddRtLights(scene::Scene& scene, const scene::View& view) {
    if (!scene.lights.empty()) return;
    scene::Light ambient;
    ambient.id = "rt_ambient";
    ambient.kind = scene::Light::Kind::kAmbient;
    ambient.intensity = 0.4;
    scene.lights.push_back(ambient);
    scene::Light eye;
    eye.id = "rt_eye";
    eye.kind = scene::Light::Kind::kParallel;
    eye.intensity = 0.6;
    eye.direction = view.dop ? Normalize(*view.dop) : Vec3{0, 0, -1};
    scene.lights.push_back(eye);
}

}  // namespace quadrix::import
