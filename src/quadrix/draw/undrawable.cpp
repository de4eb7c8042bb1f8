#include "quadrix/draw/undrawable.h"

#include <fmt/format.h>

#include <string_view>

#include "quadrix/flatten/blank_quartics.h"

namespace quadrix::draw {

namespace {

// "a torus", "an elliptical torus".
std::string WithArticle(std::string_view noun) {
    const bool vowel =
        !noun.empty() && std::string_view("aeiouAEIOU").find(noun[0]) != std::string_view::npos;
    return fmt::format("{} {}", vowel ? "an" : "a", noun);
}

bool UsesQuartic(const FlatScene& scene, const FlatBody& b) {
    for (const FlatLiteral& l : b.literals)
        if (scene.halfSpaces[static_cast<std::size_t>(l.halfSpace)].IsQuartic()) return true;
    return false;
}

// Bodies reachable from solid `s`'s CSG tree.
template <typename F>
void ForEachBody(const FlatScene& scene, const FlatSolid& s, F&& f) {
    std::vector<int> stack{s.root};
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0) continue;
        const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
        if (!node.isLeaf)
            stack.insert(stack.end(), node.children.begin(), node.children.end());
        else if (node.body >= 0)
            f(node.body);
    }
}

// Where the quartic half-space of flat name `name` ("inst[2]/ring") was defined: the quartic
// half-space of its id in the top scope or, failing that, the first definition that has one.
SourceLoc QuarticLoc(const scene::Scene* source, const std::string& name) {
    if (!source) return {};
    const std::size_t slash = name.rfind('/');
    const std::string id = slash == std::string::npos ? name : name.substr(slash + 1);
    auto find = [&](const scene::Scope& scope, SourceLoc& out) {
        for (const scene::HalfSpace& h : scope.halfSpaces)
            if (h.id == id && h.quartic) {
                out = h.loc;
                return true;
            }
        return false;
    };
    SourceLoc loc;
    if (slash == std::string::npos && find(source->top, loc)) return loc;
    for (const scene::Scope& d : source->definitions)
        if (find(d, loc)) return loc;
    find(source->top, loc);
    return loc;
}

}  // namespace

bool CheckDrawable(const FlatScene& scene, bool allowMissing, Diagnostics& diags,
                   const scene::Scene* source) {
    const FlatHalfSpace* firstQuartic = nullptr;
    std::size_t quartics = 0;
    for (const FlatHalfSpace& h : scene.halfSpaces)
        if (h.IsQuartic()) {
            if (!firstQuartic) firstQuartic = &h;
            ++quartics;
        }
    if (firstQuartic) {
        const std::string what =
            fmt::format("half-space '{}' is {} (a quartic surface){}", firstQuartic->name,
                        WithArticle(firstQuartic->quartic->KindName()),
                        quartics > 1 ? fmt::format(" (and {} more quartic half-space{})",
                                                   quartics - 1, quartics > 2 ? "s" : "")
                                     : "");
        const SourceLoc loc = QuarticLoc(source, firstQuartic->name);
        if (!allowMissing) {
            diags.Error(loc,
                        what +
                            ": drawings handle planes and quadrics only (render it with quadrix "
                            "render; --allow-missing draws the other solids)",
                        {}, "draw");
            return false;
        }
        int left = 0;
        for (const FlatSolid& s : scene.solids) {
            bool quartic = false;
            ForEachBody(scene, s, [&](int b) {
                quartic = quartic || UsesQuartic(scene, scene.bodies[static_cast<std::size_t>(b)]);
            });
            left += quartic;
        }
        diags.Warning(loc,
                      fmt::format("{}: {} solid{} using quartics left out of the drawing "
                                  "(--allow-missing)",
                                  what, left, left == 1 ? "" : "s"),
                      {}, "draw");
    }
    const std::size_t n = scene.freeforms.size();
    if (n == 0) return true;
    const FlatFreeform& first = scene.freeforms.front();
    const std::string others =
        n > 1 ? fmt::format(" (and {} more freeform surface{})", n - 1, n > 2 ? "s" : "") : "";
    if (!allowMissing) {
        diags.Error(first.loc,
                    fmt::format("freeform surface '{}'{} cannot be drawn: hidden-line drawings "
                                "handle planes and quadrics only (--allow-missing draws the "
                                "drawing without them)",
                                first.name, others),
                    {}, "draw");
        return false;
    }
    diags.Warning(first.loc,
                  fmt::format("freeform surface '{}'{} left out of the drawing (--allow-missing)",
                              first.name, others),
                  {}, "draw");
    return true;
}

FlatScene DrawableSubset(const FlatScene& scene) {
    FlatScene sub = scene;
    sub.freeforms.clear();
    bool anyQuartic = false;
    for (const FlatHalfSpace& h : scene.halfSpaces) anyQuartic = anyQuartic || h.IsQuartic();
    if (!anyQuartic) return sub;
    sub.solids.clear();
    std::vector<char> kept(scene.bodies.size(), 0);
    for (const FlatSolid& s : scene.solids) {
        bool quartic = false;
        ForEachBody(scene, s, [&](int b) {
            quartic = quartic || UsesQuartic(scene, scene.bodies[static_cast<std::size_t>(b)]);
        });
        if (quartic) continue;
        sub.solids.push_back(s);
        ForEachBody(scene, s, [&](int b) { kept[static_cast<std::size_t>(b)] = 1; });
    }
    for (std::size_t b = 0; b < sub.bodies.size(); ++b)
        if (!kept[b]) {
            sub.bodies[b].literals.clear();
            sub.bodies[b].bounds = Box3{};
        }
    BlankQuarticHalfSpaces(sub);
    return sub;
}

}  // namespace quadrix::draw
