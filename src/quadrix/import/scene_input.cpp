// The input dispatcher and rt-style views; see scene_input.h.
#include "quadrix/import/scene_input.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "quadrix/import/brlcad/readers.h"
#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/import/openscad/openscad_import.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/lang/reader.h"

namespace quadrix::import {

Mat4 QuadrixFromZUp() {
    Mat4 m = Mat4::Zero();
    m.m[0][0] = 1;
    m.m[1][2] = 1;
    m.m[2][1] = 1;
    m.m[3][3] = 1;
    return m;
}

namespace {

Vec3 SwapYZ(const Vec3& v) { return {v.x, v.z, v.y}; }

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

SourceLoc FileLoc(const std::string& path) {
    SourceLoc loc;
    loc.file = std::make_shared<const std::string>(path);
    return loc;
}

}  // namespace

InputFormat DetectInputFormat(const std::string& path, std::string_view text) {
    std::string p = Lower(path);
    if (EndsWith(p, ".uq")) return InputFormat::kUniQuadrix;
    for (const char* ext : {".asc", ".g-ascii", ".comgeom", ".cg", ".g"})
        if (EndsWith(p, ext)) return InputFormat::kBrlcad;
    for (const char* ext : {".csg", ".scad"})
        if (EndsWith(p, ext)) return InputFormat::kOpenScad;
    for (const char* ext : {".obj", ".bpt", ".bez", ".bbp", ".teaset"})
        if (EndsWith(p, ext)) return InputFormat::kFreeform;
    if (brlcad::DetectFormat(text) == brlcad::TextFormat::kV4 || brlcad::IsV5Binary(text))
        return InputFormat::kBrlcad;
    return InputFormat::kUniQuadrix;
}

bool ReadSceneInputs(const std::vector<std::string>& paths, const InputOptions& options,
                     scene::Scene& scene, Diagnostics& diags, InputReport& report) {
    std::unique_ptr<lang::Reader> uq;  // one reader for every .uq file, as before importers
    auto uqReader = [&]() -> lang::Reader& {
        if (!uq) {
            lang::ReadOptions ro;
            ro.clock = options.clock;
            uq = std::make_unique<lang::Reader>(scene, diags, ro);
        }
        return *uq;
    };
    for (const std::string& path : paths) {
        if (path == "-") {
            uqReader().ReadFile(path);
            continue;
        }
        // Every format through the bounded reader (io/bounded_read.h), read once: a FIFO or
        // process substitution cannot be read twice.
        std::string text;
        if (std::string why = ReadBoundedFile(path, text); !why.empty()) {
            diags.Error(FileLoc(path), fmt::format("cannot read '{}': {}", path, why), {}, "input");
            continue;
        }
        switch (DetectInputFormat(path, text)) {
            case InputFormat::kUniQuadrix:
                uqReader().ReadText(text, path);
                break;
            case InputFormat::kBrlcad: {
                ImportReport r;
                ImportBrlcad(text, path, options.import, scene, diags, r);
                report.importedBounds.Extend(r.bounds);
                report.imports.emplace_back(path, std::move(r));
                break;
            }
            case InputFormat::kOpenScad: {
                ImportReport r;
                ImportOpenScad(text, path, options.import, scene, diags, r);
                report.importedBounds.Extend(r.bounds);
                report.imports.emplace_back(path, std::move(r));
                break;
            }
            case InputFormat::kFreeform: {
                // Freeform models (docs/isocurve.md): every surface of the file, drawn by
                // adaptive isocurves. OBJ is Y-up like Quadrix; the tea-set formats (BPT,
                // Geomview BEZ/BBP, Newell) are Z-up like BRL-CAD and get the same axis swap.
                auto model = ReadFreeformText(text, path, FreeformFormat::kAuto, diags);
                if (!model) break;
                const bool zUp = model->format != FreeformFormat::kObj;
                const std::string stem = std::filesystem::path(path).stem().string();
                for (std::size_t k = 0; k < model->surfaces.size(); ++k) {
                    scene::FreeformSurface f;
                    f.id = fmt::format("{}[{}]", stem, k);
                    f.surface = zUp ? model->surfaces[k].Transformed(QuadrixFromZUp())
                                    : model->surfaces[k];
                    f.surface.SetName(f.id);
                    f.loc = FileLoc(path);
                    scene.top.freeforms.push_back(std::move(f));
                }
                if (model->surfaces.empty())
                    diags.Warning(FileLoc(path),
                                  fmt::format("'{}' holds no freeform surface", path), {}, "input");
                break;
            }
        }
    }
    // A --top name must be defined by at least one imported file.
    const auto& tops = options.import.topObjects;
    if (!tops.empty() && report.imports.empty()) {
        diags.Warning({}, "--top has no effect: no BRL-CAD or OpenSCAD file was given", {},
                      "command line");
    }
    for (const std::string& name : tops) {
        if (report.imports.empty() || name == "all") continue;
        bool found = std::any_of(report.imports.begin(), report.imports.end(), [&](auto& r) {
            const auto& m = r.second.missingTops;
            return std::find(m.begin(), m.end(), name) == m.end();
        });
        if (!found)
            diags.Error({},
                        fmt::format("--top {}: no object of that name in {}", name,
                                    report.imports.size() == 1 ? "'" + report.imports[0].first + "'"
                                                               : std::string("the imported files")),
                        {}, "command line");
    }
    report.usesClock = uq && uq->UsesClock();
    return !diags.HasErrors();
}

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
        Vec3 x, y, z;
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
    brlcad::TextMap map(text, file);
    RtView rt;
    bool haveSize = false, haveEye = false, haveRot = false;
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
        } else if (cmd == "viewrot") {
            if ((ok = numbers(16, v) && ok)) {
                for (int k = 0; k < 16; ++k) rt.viewrot.m[k / 4][k % 4] = v[k];
                haveRot = true;
            }
        } else if (cmd == "orientation") {
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
    if (!haveSize || !haveEye || !haveRot || !(rt.viewsize > 0)) {
        diags.Error(map.At(0),
                    "an rt view needs a positive viewsize, an eye_pt and a viewrot (or "
                    "orientation)");
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
