// patch statement (extension; the quadric patch of seed 000 §1.1):
//   patch [id] ( [!]quadricId [!]planeId ... ) [=c r g b];
// A quadric patch is the piece of ONE quadric surface that lies inside up to FOUR bounding planes.
// The planes only bound: they are never drawn, whether their own statements made them opaque or
// transparent. A complement on the quadric chooses its outside as the solid side, which changes
// nothing that is seen (the surface is the same); a complement on a plane keeps the other side.
//
// Expansion (so that every engine sees ordinary HSBs): for each bounding plane a transparent copy
// `<patch>~<plane>` is added to the scope, and the patch becomes a body of the quadric and those
// copies. The quadric's own transparency is kept: a patch of a transparent quadric draws nothing
// (a warning says so). Engine `patch` draws such a body as one patch of the processor.
#include <fmt/format.h>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

inline constexpr int kMaxPatchPlanes = 4;  // seed 000 §1.1: "bounded by up to four planes"

struct PatchItem {
    int halfSpace = -1;
    bool complemented = false;
    SourceLoc loc;
};

}  // namespace

bool ParsePatch(Parser& p, const Token& keyword) {
    std::string id;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(id, idLoc)) return false;
    if (!p.PeekIs(TokenKind::kLParen))
        return p.Expected("'(' to start the patch's quadric and bounding planes");
    const Token open = p.Take();

    ReaderState& s = p.State();
    std::vector<PatchItem> items;
    bool unknown = false;
    while (!p.PeekIs(TokenKind::kRParen)) {
        PatchItem item;
        if (p.PeekIs(TokenKind::kBang)) {
            p.Take();
            item.complemented = true;
        }
        std::string hs;
        if (!p.ExpectId(items.empty() && !item.complemented
                            ? "a quadric id"
                            : fmt::format("a half-space id or ')' to end the list opened at {}",
                                          open.loc.ToString()),
                        hs, item.loc))
            return false;
        item.halfSpace = s.FindHalfSpace(hs);
        if (item.halfSpace < 0) {
            p.Error(item.loc, fmt::format("unknown half-space '{}'", hs));
            unknown = true;
            continue;
        }
        items.push_back(item);
    }
    p.Take();
    std::optional<scene::Color> color;
    while (p.PeekIs(TokenKind::kOption)) {
        Token option = p.Take();
        if (option.text != "c") {
            p.Error(
                option.loc,
                fmt::format("unknown option {} for a patch (expected =c r g b)", Describe(option)),
                kSyntax);
            return false;
        }
        if (color) p.Warning(option.loc, "color given twice; the last one is used");
        color = p.ParseColor(option);
        if (!color) return false;
    }
    if (!p.ExpectSemicolon("patch list")) return false;
    if (unknown) return true;  // reported

    // Exactly one quadric, at most four planes.
    const scene::Scope& scope = s.CurrentScope();
    int quadric = -1;
    std::vector<PatchItem> planes;
    for (const PatchItem& item : items) {
        const scene::HalfSpace& h = scope.halfSpaces[static_cast<std::size_t>(item.halfSpace)];
        if (h.kind == scene::HalfSpace::Kind::kQuartic) {
            p.Error(item.loc, fmt::format("'{}' is a {} (a quartic surface): a patch takes one "
                                          "quadric and planes",
                                          h.id, h.quartic->KindName()));
            return true;
        }
        if (h.kind == scene::HalfSpace::Kind::kQuadric) {
            if (quadric >= 0) {
                p.Error(item.loc,
                        fmt::format("a patch has one quadric; '{}' is a second one", h.id));
                return true;
            }
            quadric = static_cast<int>(&item - items.data());
        } else {
            planes.push_back(item);
        }
    }
    if (quadric < 0) {
        p.Error(open.loc, "a patch needs one quadric (and up to four bounding planes)");
        return true;
    }
    if (static_cast<int>(planes.size()) > kMaxPatchPlanes) {
        p.Error(planes[kMaxPatchPlanes].loc,
                fmt::format("a patch is bounded by at most {} planes; this is plane {}",
                            kMaxPatchPlanes, kMaxPatchPlanes + 1));
        return true;
    }
    const PatchItem q = items[static_cast<std::size_t>(quadric)];
    if (scope.halfSpaces[static_cast<std::size_t>(q.halfSpace)].transparent)
        p.Warning(q.loc, fmt::format("quadric '{}' is transparent: the patch draws nothing",
                                     scope.halfSpaces[static_cast<std::size_t>(q.halfSpace)].id));

    if (id.empty()) id = s.GenerateId("patch", ReaderState::Namespace::kSolid);
    if (std::string dup = s.DuplicateSolidMessage(id); !dup.empty()) {
        p.Error(idLoc, dup);
        return true;
    }
    scene::Body body;
    body.id = id;
    body.loc = keyword.loc;
    body.color = color;
    body.literals.push_back({q.halfSpace, q.complemented});
    for (const PatchItem& item : planes) {
        // Copy before AddHalfSpace: it may reallocate the scope's vector.
        scene::HalfSpace copy =
            s.CurrentScope().halfSpaces[static_cast<std::size_t>(item.halfSpace)];
        copy.id = fmt::format("{}~{}", id, copy.id);
        copy.transparent = true;
        copy.loc = item.loc;
        int index = s.FindHalfSpace(copy.id);
        if (index < 0) index = s.AddHalfSpace(std::move(copy));
        body.literals.push_back({index, item.complemented});
    }
    s.AddBody(std::move(body));
    return true;
}

}  // namespace quadrix::lang
