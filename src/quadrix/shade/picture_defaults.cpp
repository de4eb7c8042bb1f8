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
    const FlatBody* widest = nullptr;
    for (const FlatBody& b : flat.bodies)
        if (!widest || b.literals.size() > widest->literals.size()) widest = &b;
    const bool wide = widest && widest->literals.size() > kPictureDefaultLiterals;
    const bool small = flat.bodies.size() <= kPictureDefaultBodies && !wide;
    const bool shadows = defaults.shadows && !options.shadows && DeclaresLights(flat);
    const bool aa = defaults.antialiasing;
    if (small) {
        if (shadows) options.shadows = true;
        if (aa) options.aaSamples = kDefaultAaSamples;
        return {};
    }
    if (!shadows && !aa) return {};
    const std::string why =
        flat.bodies.size() > kPictureDefaultBodies
            ? fmt::format("{} bodies", flat.bodies.size())
            : fmt::format("body '{}' has {} literals", widest->name, widest->literals.size());
    return fmt::format("{}: no default{}{} (--shadows, --aa N ask for them)", why,
                       shadows ? " shadows" : "",
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
