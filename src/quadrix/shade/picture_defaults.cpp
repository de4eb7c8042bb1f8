#include "quadrix/shade/picture_defaults.h"

#include <fmt/format.h>

namespace quadrix {

bool DeclaresLights(const FlatScene& flat) {
    for (const scene::Light& l : flat.lights)
        if (!l.isRig && l.kind != scene::Light::Kind::kAmbient) return true;
    return false;
}

std::string ApplyPictureDefaults(const FlatScene& flat, const PictureDefaults& defaults,
                                 ShadeOptions& options) {
    const bool small = flat.bodies.size() <= kPictureDefaultBodies;
    const bool shadows = defaults.shadows && !options.shadows && DeclaresLights(flat);
    const bool aa = defaults.antialiasing;
    if (small) {
        if (shadows) options.shadows = true;
        if (aa) options.aaSamples = kDefaultAaSamples;
        return {};
    }
    if (!shadows && !aa) return {};
    return fmt::format("{} bodies: no default{}{} (--shadows, --aa N ask for them)",
                       flat.bodies.size(), shadows ? " shadows" : "",
                       aa ? (shadows ? " or anti-aliasing" : " anti-aliasing") : "");
}

std::string ParseAaSamples(const std::string& text, int& samples) {
    if (text == "default") {
        samples = kDefaultAaSamples;
        return {};
    }
    if (text == "off" || text == "0" || text == "1") {
        samples = 0;
        return {};
    }
    for (int n : {4, 16, 64})
        if (text == std::to_string(n)) {
            samples = n;
            return {};
        }
    return fmt::format("--aa: expected off, 4, 16 or 64, found '{}'", text);
}

}  // namespace quadrix
