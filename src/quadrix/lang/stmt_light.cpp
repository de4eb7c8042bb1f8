// Light statements (seed 001 §2.1.5, §2.3, and the point/spot extension, docs/language.md §3.7):
//   light [id] intensity;          ambient (isotropic)
//   light [id] intensity x y z;    parallel; (x y z) is the direction TO the light
//   light [id] intensity =at x y z;                                  point light at (x y z)
//   light [id] intensity =at x y z =aim x y z [=cone deg [deg]];     spot light
//   any of them [=c r g b | =c name]                                 the light's color
//   redef light id [intensity [x y z] [options]];
// Intensities outside [0, 1] are truncated with a warning ("UniQuadrix truncates values outside
// this range"). A light written without an id gets one, announced by a warning as in the paper's
// session ("warning: id l#1 created").
#include <fmt/format.h>

#include <algorithm>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

struct LightValues {
    std::optional<double> intensity;
    std::optional<Vec3> direction;
    std::optional<Vec3> position, aim;
    std::optional<double> cone, falloff;
    std::optional<scene::Color> color;
    SourceLoc intensityLoc, directionLoc, positionLoc, aimLoc, coneLoc;
};

bool ParsePoint(Parser& p, const Token& option, Vec3& v) {
    static constexpr const char* kAxes[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
        auto c =
            p.ExpectNumber(fmt::format("the {} coordinate after {}", kAxes[i], Describe(option)));
        if (!c) return false;
        v[i] = *c;
    }
    return true;
}

// =at, =aim, =cone and =c after the numbers. False on a syntax error.
bool ParseLightOptions(Parser& p, LightValues& v) {
    while (p.PeekIs(TokenKind::kOption)) {
        Token option = p.Take();
        if (option.text == "at" || option.text == "aim") {
            Vec3 point;
            (option.text == "at" ? v.positionLoc : v.aimLoc) = option.loc;
            if (!ParsePoint(p, option, point)) return false;
            (option.text == "at" ? v.position : v.aim) = point;
        } else if (option.text == "cone") {
            v.coneLoc = option.loc;
            v.cone = p.ExpectNumber("the cone half-angle in degrees after =cone");
            if (!v.cone) return false;
            v.falloff.reset();
            if (p.PeekIsNumber()) {
                v.falloff = p.ExpectNumber("the spot light's falloff exponent");
                if (!v.falloff) return false;
            }
        } else if (option.text == "c") {
            if (v.color) p.Warning(option.loc, "color given twice; the last one is used");
            v.color = p.ParseColor(option);
            if (!v.color) return false;
        } else {
            p.Error(option.loc,
                    fmt::format("unknown option {} for a light (expected =at, =aim, =cone or =c)",
                                Describe(option)),
                    kSyntax);
            return false;
        }
    }
    return true;
}

// intensity [x y z], or nothing at all when `optional` (redef). False on a syntax error.
bool ParseLightValues(Parser& p, LightValues& v, bool optional) {
    if (optional && !p.PeekIsNumber()) return ParseLightOptions(p, v);
    v.intensityLoc = p.Peek().loc;
    v.intensity = p.ExpectNumber("the light's intensity");
    if (!v.intensity) return false;
    if (!p.PeekIsNumber()) return ParseLightOptions(p, v);
    v.directionLoc = p.Peek().loc;
    Vec3 d;
    static constexpr const char* kAxes[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
        auto c =
            p.ExpectNumber(fmt::format("the {} component of the direction to the light "
                                       "(a light has 1 or 4 numbers)",
                                       kAxes[i]));
        if (!c) return false;
        d[i] = *c;
    }
    v.direction = d;
    return ParseLightOptions(p, v);
}

// Truncation and direction checks shared by light and redef light.
void ApplyLightValues(Parser& p, const LightValues& v, scene::Light& light) {
    if (v.intensity) {
        double clamped = std::clamp(*v.intensity, 0.0, 1.0);
        if (clamped != *v.intensity)
            p.Warning(v.intensityLoc, fmt::format("light intensity {} is outside [0, 1]; "
                                                  "truncated to {}",
                                                  *v.intensity, clamped));
        light.intensity = clamped;
    }
    if (v.direction) {
        if (*v.direction == Vec3{0, 0, 0}) {
            p.Error(v.directionLoc,
                    fmt::format("the direction to light '{}' is the zero vector", light.id));
        } else {
            light.kind = scene::Light::Kind::kParallel;
            light.direction = *v.direction;
        }
    }
    if (v.color) light.color = *v.color;
    if (v.position) {
        if (v.direction) {
            p.Error(v.positionLoc, fmt::format("light '{}' has both a direction (parallel) and =at "
                                               "(point or spot); give one of them",
                                               light.id));
            return;
        }
        light.kind = scene::Light::Kind::kPoint;
        light.position = *v.position;
    }
    if (v.aim) {
        if (light.kind != scene::Light::Kind::kPoint && light.kind != scene::Light::Kind::kSpot) {
            p.Error(v.aimLoc, fmt::format("=aim makes light '{}' a spot light, which needs =at "
                                          "(its position)",
                                          light.id));
            return;
        }
        if (*v.aim == light.position) {
            p.Error(v.aimLoc,
                    fmt::format("spot light '{}' is aimed at its own position", light.id));
            return;
        }
        light.kind = scene::Light::Kind::kSpot;
        light.aim = *v.aim;
    }
    if (v.cone) {
        if (light.kind != scene::Light::Kind::kSpot) {
            p.Error(v.coneLoc, fmt::format("=cone is for spot lights (=at ... =aim ...); light "
                                           "'{}' is not one",
                                           light.id));
            return;
        }
        const double falloff = v.falloff.value_or(std::min(*v.cone + 10, 89.0));
        if (!(*v.cone > 0) || !(falloff >= *v.cone) || !(falloff < 90)) {
            p.Error(v.coneLoc, fmt::format("=cone {} {}: the half-angles must satisfy 0 < cone "
                                           "<= falloff < 90 degrees",
                                           *v.cone, falloff));
            return;
        }
        light.coneDegrees = *v.cone;
        light.falloffDegrees = falloff;
    }
}

}  // namespace

bool ParseLight(Parser& p, const Token& keyword) {
    scene::Light light;
    light.loc = keyword.loc;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(light.id, idLoc)) return false;
    LightValues values;
    if (!ParseLightValues(p, values, false)) return false;
    if (!p.ExpectSemicolon("the light")) return false;

    ReaderState& s = p.State();
    if (light.id.empty()) {
        light.id = s.GenerateId("l", ReaderState::Namespace::kLight);
        p.Warning(keyword.loc, fmt::format("id {} created", light.id));
    } else if (int first = s.FindLight(light.id); first >= 0) {
        p.Error(idLoc, fmt::format("light '{}' is already defined at {} (use redef light to "
                                   "change it)",
                                   light.id, s.scene.lights[first].loc.ToString()));
        return true;
    }
    light.kind = scene::Light::Kind::kAmbient;
    const int errors = s.diags.ErrorCount();
    ApplyLightValues(p, values, light);
    if (s.diags.ErrorCount() != errors) return true;  // reported
    s.AddLight(std::move(light));
    return true;
}

bool ParseRedefLight(Parser& p, const Token& keyword) {
    Command command;
    command.kind = Command::Kind::kRedefLight;
    command.loc = keyword.loc;
    SourceLoc idLoc;
    if (!p.ExpectId("the id of the light to redefine", command.id, idLoc)) return false;
    LightValues values;
    if (!ParseLightValues(p, values, true)) return false;
    if (!p.ExpectSemicolon("the redef light statement")) return false;

    ReaderState& s = p.State();
    int index = s.FindLight(command.id);
    bool changed = values.intensity || values.position || values.aim || values.cone || values.color;
    if (index < 0 && command.id != "default") {
        p.Error(idLoc, fmt::format("unknown light '{}'", command.id));
        return true;
    }
    if (changed) {
        // Redefining the automatic default light makes it an ordinary light of the scene.
        scene::Light light = index >= 0 ? s.scene.lights[index] : scene::DefaultLight();
        light.isDefault = false;
        int errors = s.diags.ErrorCount();
        ApplyLightValues(p, values, light);
        if (s.diags.ErrorCount() != errors) return true;
        if (index >= 0)
            s.scene.lights[index] = std::move(light);
        else
            s.AddLight(std::move(light));
    }
    RunCommand(p, command, changed);
    return true;
}

}  // namespace quadrix::lang
