#include "quadrix/viewer/picking.h"

#include <fmt/format.h>

namespace quadrix::viewer {

namespace {

// "a/b[2]/c" → "c"; "c[3]" → "c".
std::string LastComponent(const std::string& path) {
    std::string last = path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1);
    if (auto bracket = last.find('['); bracket != std::string::npos) last.resize(bracket);
    return last;
}

std::string BodyLocation(const scene::Scene& scene, const std::string& bodyPath) {
    const std::string id = LastComponent(bodyPath);
    auto find = [&](const scene::Scope& scope) -> std::string {
        for (const scene::Body& b : scope.bodies)
            if (b.id == id && b.loc.line > 0) return b.loc.ToString();
        return {};
    };
    if (std::string w = find(scene.top); !w.empty()) return w;
    for (const scene::Scope& d : scene.definitions)
        if (std::string w = find(d); !w.empty()) return w;
    return {};
}

}  // namespace

PickResult Pick(const Frame& frame, const FlatScene& flat, const scene::Scene* scene, int x,
                int y) {
    PickResult r;
    r.x = x;
    r.y = y;
    if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) return r;
    const std::size_t i = static_cast<std::size_t>(y) * frame.width + x;
    if (frame.surface[i] == Frame::kNone || !std::isfinite(frame.depth[i])) return r;
    r.hit = true;
    r.solid = frame.Solid(i);
    r.body = frame.body[i];
    r.surface = frame.surface[i];
    r.depth = frame.depth[i];
    r.normal = frame.normal[i];
    r.point = flat.projection.deviceFromWorld.Inverse().MapPoint({x + 0.5, y + 0.5, r.depth});
    const int halfSpaces = static_cast<int>(flat.halfSpaces.size());
    if (r.surface >= 0 && r.surface < halfSpaces) {
        r.surfaceName = flat.halfSpaces[r.surface].name;
    } else if (r.surface >= halfSpaces &&
               r.surface - halfSpaces < static_cast<int>(flat.freeforms.size())) {
        r.freeform = true;
        const FlatFreeform& f = flat.freeforms[r.surface - halfSpaces];
        r.surfaceName = f.name;
        // A freeform surface has no body: its own statement (a `bezier`, `patches` ...) is where.
        if (f.loc.line > 0) r.where = f.loc.ToString();
    }
    if (r.solid >= 0 && r.solid < static_cast<int>(flat.solids.size()))
        r.solidName = flat.solids[r.solid].name;
    if (r.body >= 0 && r.body < static_cast<int>(flat.bodies.size())) {
        r.bodyName = flat.bodies[r.body].name;
        if (scene && r.where.empty()) r.where = BodyLocation(*scene, r.bodyName);
    }
    return r;
}

std::string FormatPick(const PickResult& p) {
    if (!p.hit) return fmt::format("pick {} {}: background", p.x, p.y);
    std::string s = fmt::format("pick {} {}:", p.x, p.y);
    if (p.freeform) {
        s += fmt::format(" freeform surface {}", p.surfaceName);
    } else {
        s += fmt::format(" solid {} body {} half-space {}", p.solidName, p.bodyName, p.surfaceName);
    }
    if (!p.where.empty()) s += fmt::format(" ({})", p.where);
    s += fmt::format(" point {:.6g} {:.6g} {:.6g} normal {:.4f} {:.4f} {:.4f}", p.point.x,
                     p.point.y, p.point.z, p.normal.x, p.normal.y, p.normal.z);
    return s;
}

std::vector<std::string> PickOverlayLines(const PickResult& p) {
    if (!p.hit) return {fmt::format("pick {} {}: background", p.x, p.y)};
    std::vector<std::string> lines;
    if (p.freeform)
        lines.push_back(fmt::format("pick {} {}: freeform surface {}", p.x, p.y, p.surfaceName));
    else
        lines.push_back(fmt::format("pick {} {}: solid {}  body {}  half-space {}", p.x, p.y,
                                    p.solidName, p.bodyName, p.surfaceName));
    if (!p.where.empty()) lines.push_back("  at " + p.where);
    lines.push_back(fmt::format("  point {:.6g} {:.6g} {:.6g}", p.point.x, p.point.y, p.point.z));
    lines.push_back(
        fmt::format("  normal {:.4f} {:.4f} {:.4f}", p.normal.x, p.normal.y, p.normal.z));
    return lines;
}

}  // namespace quadrix::viewer
