// solid statement (Quadrix extension, docs/language.md §3.13): solids by their dimensions, the
// front end asked for by seed 001 §7.2.3 ("half-axes, center coordinates, and orientation angles"
// instead of the coefficients of the quadric equation).
//
//   solid kind [id] { =param numbers | transform | =t | =0 | =open | =open0 | =open1 | =hsb
//                   | =c r g b } ;
//
// Each statement expands into ordinary half-spaces (named id, id#0, id#1, id#x0, ...; see
// model/solids.h) and, unless =hsb is given, a body `id` intersecting them, exactly as if the
// plane, quadric and body statements had been written: every engine sees plain HSBs, and the
// half-spaces and the body may be named by bodies (with '!'), csg solids and definitions like any
// other.
//
// Placement: the solid is built from its parameters; the transforms (=tx ... =vzy, as in
// instance statements) are then applied left to right; a centred solid (=at) is built about the
// origin and moved to its centre last, so rotations turn it about its own centre.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"
#include "quadrix/lang/transforms.h"
#include "quadrix/model/solids.h"

namespace quadrix::lang {

namespace {

using model::AxisFrame;
using model::Section;
using model::SolidShape;

// One =param with the numbers that followed it.
struct Param {
    SourceLoc loc;
    std::vector<double> values;
    Vec3 AsVec3() const { return {values[0], values[1], values[2]}; }
};

// What a kind accepts: parameter name → allowed numbers of values (bit n set: n values).
struct ParamSpec {
    std::string_view name;
    unsigned counts;  // bit mask
    std::string_view meaning;
};

constexpr unsigned kOne = 1u << 1, kTwo = 1u << 2, kThree = 1u << 3;

struct SolidContext;
using BuildFn = std::optional<SolidShape> (*)(SolidContext& ctx);

struct Kind {
    std::string_view name;
    std::vector<ParamSpec> params;
    bool centred;  // built about the origin; =at moves it there last
    bool axial;    // has caps (=open applies)
    bool makesBody;
    BuildFn build;
};

// The parameters of one statement, with error reporting at their positions.
struct SolidContext {
    Parser& p;
    const Kind& kind;
    const Token& keyword;
    std::map<std::string, Param, std::less<>> params;

    const Param* Get(std::string_view name) const {
        auto it = params.find(name);
        return it == params.end() ? nullptr : &it->second;
    }
    bool Has(std::string_view name) const { return Get(name) != nullptr; }
    // Reports a missing required parameter at the statement's keyword.
    const Param* Require(std::string_view name, std::string_view what) {
        if (const Param* q = Get(name)) return q;
        p.Error(keyword.loc, fmt::format("solid {} needs ={} ({})", kind.name, name, what));
        return nullptr;
    }
    bool Fail(const Param& at, std::string message) {
        p.Error(at.loc, std::move(message));
        return false;
    }
    // A positive radius/half-axis list; reports the first value <= 0.
    bool Positive(const Param& q, std::string_view what) {
        for (double v : q.values)
            if (!(v > 0))
                return Fail(
                    q, fmt::format("{} of the solid {} must be > 0, found {}", what, kind.name, v));
        return true;
    }
    // The axis from =from to =to (and =u across it).
    std::optional<AxisFrame> Axis() {
        const Param* from = Require("from", "the centre of its first end");
        const Param* to = Require("to", "the centre of its second end");
        if (!from || !to) return std::nullopt;
        std::optional<Vec3> hint;
        if (const Param* u = Get("u")) {
            hint = u->AsVec3();
            if (Length(*hint) == 0) {
                Fail(*u, "=u must not be the zero vector");
                return std::nullopt;
            }
        }
        auto frame = model::MakeAxisFrame(from->AsVec3(), to->AsVec3(), hint);
        if (!frame) {
            const double length = Length(to->AsVec3() - from->AsVec3());
            if (!std::isfinite(length))
                Fail(*to, fmt::format("the distance from =from to =to of the solid {} is too "
                                      "large to represent",
                                      kind.name));
            else if (!(length > 0))
                Fail(*to, fmt::format("=to is the same point as =from: the solid {} has no axis",
                                      kind.name));
            else
                Fail(*Get("u"),
                     "=u is parallel to the axis from =from to =to: it gives no "
                     "direction across it");
            return std::nullopt;
        }
        return frame;
    }
    // A section from =name: one radius, or half-axes a (along u) and b.
    std::optional<Section> SectionOf(std::string_view name, std::string_view what,
                                     bool allowZero = false) {
        const Param* q = Require(name, what);
        if (!q) return std::nullopt;
        for (double v : q->values)
            if (!(v > 0) && !(allowZero && v == 0)) {
                Fail(*q, fmt::format("={} of the solid {} must be {}, found {}", name, kind.name,
                                     allowZero ? ">= 0" : "> 0", v));
                return std::nullopt;
            }
        Section s;
        s.a = q->values[0];
        s.b = q->values.size() > 1 ? q->values[1] : q->values[0];
        if ((s.a == 0) != (s.b == 0)) {
            Fail(*q, fmt::format("={} gives one half-axis 0 and the other not: use a single 0 "
                                 "for an apex",
                                 name));
            return std::nullopt;
        }
        return s;
    }
};

std::optional<SolidShape> BuildSphere(SolidContext& ctx) {
    const Param* r = ctx.Require("r", "its radius");
    if (!r || !ctx.Positive(*r, "the radius")) return std::nullopt;
    return model::MakeSphere({0, 0, 0}, r->values[0]);
}

std::optional<SolidShape> BuildEllipsoid(SolidContext& ctx) {
    const Param* r = ctx.Require("r", "its three half-axes a b c along x, y and z");
    if (!r || !ctx.Positive(*r, "each half-axis")) return std::nullopt;
    return model::MakeEllipsoid(r->values[0], r->values[1], r->values[2]);
}

std::optional<SolidShape> BuildCylinder(SolidContext& ctx) {
    auto frame = ctx.Axis();
    auto sec = ctx.SectionOf("r", "its radius, or half-axes a b");
    if (!frame || !sec) return std::nullopt;
    return model::MakeCylinder(*frame, *sec);
}

std::optional<SolidShape> BuildCone(SolidContext& ctx) {
    auto frame = ctx.Axis();
    auto s0 = ctx.SectionOf("r0", "the radius at =from, 0 for an apex", true);
    auto s1 = ctx.SectionOf("r1", "the radius at =to, 0 for an apex", true);
    if (!frame || !s0 || !s1) return std::nullopt;
    if (s0->a == 0 && s1->a == 0) {
        ctx.Fail(*ctx.Get("r1"),
                 "a cone needs a radius > 0 at one end at least (=r0 and =r1 "
                 "are both 0)");
        return std::nullopt;
    }
    // Both ends must have the same shape a/b, else the surface is not a quadric cone. Relative
    // tolerance 1e-9: the values are typed by hand, so anything closer is meant to be equal.
    if (s0->a > 0 && s1->a > 0 &&
        std::fabs(s0->a * s1->b - s1->a * s0->b) > 1e-9 * (s0->a * s1->b)) {
        ctx.Fail(*ctx.Get("r1"),
                 "the two ends of an elliptic cone must have the same shape "
                 "(a0/b0 = a1/b1)");
        return std::nullopt;
    }
    return model::MakeCone(*frame, *s0, *s1);
}

std::optional<SolidShape> BuildBox(SolidContext& ctx) {
    const bool corners = ctx.Has("from") || ctx.Has("to");
    if (corners && (ctx.Has("at") || ctx.Has("size"))) {
        const Param* at = ctx.Has("at") ? ctx.Get("at") : ctx.Get("size");
        ctx.Fail(*at,
                 "a box is given either by corners (=from, =to) or by =at and =size, not "
                 "both");
        return std::nullopt;
    }
    if (corners) {
        const Param* from = ctx.Require("from", "one corner");
        const Param* to = ctx.Require("to", "the opposite corner");
        if (!from || !to) return std::nullopt;
        for (int i = 0; i < 3; ++i)
            if (from->values[i] == to->values[i]) {
                ctx.Fail(*to, fmt::format("the corners of the box have the same {} coordinate: "
                                          "the box is flat",
                                          "xyz"[i]));
                return std::nullopt;
            }
        return model::MakeBox(from->AsVec3(), to->AsVec3());
    }
    const Param* size = ctx.Require("size", "its edge lengths along x, y, z; or give =from, =to");
    if (!size || !ctx.Positive(*size, "each edge length")) return std::nullopt;
    Vec3 half = size->AsVec3() * 0.5;
    return model::MakeBox(-half, half);
}

std::optional<SolidShape> BuildParaboloid(SolidContext& ctx) {
    auto frame = ctx.Axis();
    auto sec = ctx.SectionOf("r", "its radius at =to, or half-axes a b");
    if (!frame || !sec) return std::nullopt;
    return model::MakeParaboloid(*frame, *sec);
}

std::optional<SolidShape> BuildHyperboloid1(SolidContext& ctx) {
    auto frame = ctx.Axis();
    auto sec = ctx.SectionOf("r", "its radius at both ends, or half-axes a b");
    const Param* waist = ctx.Require("waist", "its radius at the middle");
    if (!frame || !sec || !waist || !ctx.Positive(*waist, "the waist")) return std::nullopt;
    if (waist->values[0] >= sec->a) {
        ctx.Fail(*waist, fmt::format("the waist ({}) must be smaller than the radius at the ends "
                                     "({}); use a cylinder for equal radii",
                                     waist->values[0], sec->a));
        return std::nullopt;
    }
    return model::MakeHyperboloid1(*frame, *sec, waist->values[0] / sec->a);
}

std::optional<SolidShape> BuildHyperboloid2(SolidContext& ctx) {
    auto frame = ctx.Axis();
    auto sec = ctx.SectionOf("r", "its radius at both ends, or half-axes a b");
    const Param* gap = ctx.Require("gap", "the distance between the vertices of its two sheets");
    if (!frame || !sec || !gap || !ctx.Positive(*gap, "the gap")) return std::nullopt;
    if (gap->values[0] >= frame->length) {
        ctx.Fail(*gap, fmt::format("the gap ({}) must be smaller than the distance from =from "
                                   "to =to ({})",
                                   gap->values[0], frame->length));
        return std::nullopt;
    }
    return model::MakeHyperboloid2(*frame, *sec, gap->values[0]);
}

std::optional<SolidShape> BuildHalfSpace(SolidContext& ctx) {
    const Param* n = ctx.Require("n", "its outward normal");
    if (!n) return std::nullopt;
    if (Length(n->AsVec3()) == 0) {
        ctx.Fail(*n, "the normal =n of a half-space must not be the zero vector");
        return std::nullopt;
    }
    return model::MakeHalfSpace({0, 0, 0}, n->AsVec3());
}

// The axis of a torus (=axis, default z), checked non-zero.
std::optional<Vec3> TorusAxis(SolidContext& ctx) {
    const Param* a = ctx.Get("axis");
    if (!a) return Vec3{0, 0, 1};
    const Vec3 v = a->AsVec3();
    if (!(Length(v) > 0) || !IsFinite(v)) {
        ctx.Fail(*a, fmt::format("=axis of the solid {} must be a non-zero vector", ctx.kind.name));
        return std::nullopt;
    }
    return v;
}

std::optional<SolidShape> BuildTorus(SolidContext& ctx) {
    const Param* r = ctx.Require("r", "its major radius R and tube radius r");
    auto axis = TorusAxis(ctx);
    if (!r || !axis || !ctx.Positive(*r, "each radius")) return std::nullopt;
    if (!(r->values[1] < r->values[0])) {
        ctx.Fail(*r, fmt::format("the tube radius r ({}) of a torus must be smaller than its "
                                 "major radius R ({})",
                                 r->values[1], r->values[0]));
        return std::nullopt;
    }
    std::string why;
    auto q = QuarticSurface::Torus({0, 0, 0}, *axis, r->values[0], r->values[1], &why);
    if (!q) {
        ctx.Fail(*r, fmt::format("the torus cannot be built: {}", why));
        return std::nullopt;
    }
    return model::MakeTorus(*q);
}

std::optional<SolidShape> BuildEllipticalTorus(SolidContext& ctx) {
    const Param* r = ctx.Require("r", "its radius of revolution");
    const Param* c = ctx.Require("e", "the ellipse's semi-axis vector x y z");
    const Param* d = ctx.Require("d", "the ellipse's other semi-axis length");
    auto axis = TorusAxis(ctx);
    if (!r || !c || !d || !axis || !ctx.Positive(*r, "the radius") ||
        !ctx.Positive(*d, "the semi-axis"))
        return std::nullopt;
    if (!(Length(c->AsVec3()) > 0)) {
        ctx.Fail(*c, "=e of the solid etorus must be a non-zero vector");
        return std::nullopt;
    }
    std::string why;
    auto q = QuarticSurface::EllipticalTorus({0, 0, 0}, *axis, r->values[0], c->AsVec3(),
                                             d->values[0], &why);
    if (!q) {
        ctx.Fail(*r, fmt::format("the elliptical torus cannot be built: {}", why));
        return std::nullopt;
    }
    return model::MakeEllipticalTorus(*q);
}

std::optional<SolidShape> BuildGeneralCone(SolidContext& ctx) {
    const Param* v = ctx.Require("v", "the centre of its base");
    const Param* h = ctx.Require("h", "its height vector");
    const Param* a = ctx.Require("a", "the base's first semi-axis vector");
    const Param* b = ctx.Require("b", "the base's second semi-axis vector");
    const Param* top = ctx.Require("top", "the top's semi-axis lengths along a and b");
    if (!v || !h || !a || !b || !top) return std::nullopt;
    for (double t : top->values)
        if (!(t >= 0)) {
            ctx.Fail(*top,
                     fmt::format("the top semi-axes of the solid tgc must be >= 0, found {}", t));
            return std::nullopt;
        }
    std::string why;
    auto q = QuarticSurface::GeneralCone(v->AsVec3(), h->AsVec3(), a->AsVec3(), b->AsVec3(),
                                         top->values[0], top->values[1], &why);
    if (!q) {
        ctx.Fail(*h, fmt::format("the general cone cannot be built: {}", why));
        return std::nullopt;
    }
    return model::MakeGeneralCone(*q);
}

const ParamSpec kAt{"at", kThree, "centre x y z"};
const ParamSpec kFrom{"from", kThree, "x y z"};
const ParamSpec kTo{"to", kThree, "x y z"};
const ParamSpec kU{"u", kThree, "direction x y z across the axis"};
const ParamSpec kRadius{"r", kOne | kTwo, "a radius, or half-axes a b"};

const std::vector<Kind>& Kinds() {
    static const std::vector<Kind> kinds = {
        {"sphere", {kAt, {"r", kOne, "the radius"}}, true, false, true, BuildSphere},
        {"ellipsoid", {kAt, {"r", kThree, "half-axes a b c"}}, true, false, true, BuildEllipsoid},
        {"cylinder", {kFrom, kTo, kRadius, kU}, false, true, true, BuildCylinder},
        {"cone",
         {kFrom,
          kTo,
          {"r0", kOne | kTwo, "a radius, or half-axes a b"},
          {"r1", kOne | kTwo, "a radius, or half-axes a b"},
          kU},
         false,
         true,
         true,
         BuildCone},
        {"box",
         {kAt, {"size", kThree, "edge lengths x y z"}, kFrom, kTo},
         true,
         false,
         true,
         BuildBox},
        {"paraboloid", {kFrom, kTo, kRadius, kU}, false, true, true, BuildParaboloid},
        {"hyperboloid",
         {kFrom, kTo, kRadius, {"waist", kOne, "the waist radius"}, kU},
         false,
         true,
         true,
         BuildHyperboloid1},
        {"hyperboloid2",
         {kFrom, kTo, kRadius, {"gap", kOne, "the distance of the vertices"}, kU},
         false,
         true,
         true,
         BuildHyperboloid2},
        {"torus",
         {kAt, {"r", kTwo, "major radius R and tube radius r"}, {"axis", kThree, "axis x y z"}},
         true,
         false,
         true,
         BuildTorus},
        {"etorus",
         {kAt,
          {"r", kOne, "the radius of revolution"},
          {"e", kThree, "the ellipse's semi-axis vector x y z"},
          {"d", kOne, "the ellipse's other semi-axis"},
          {"axis", kThree, "axis x y z"}},
         true,
         false,
         true,
         BuildEllipticalTorus},
        {"tgc",
         {{"v", kThree, "base centre x y z"},
          {"h", kThree, "height vector x y z"},
          {"a", kThree, "base semi-axis vector x y z"},
          {"b", kThree, "base semi-axis vector x y z"},
          {"top", kTwo, "the top's semi-axes along a and b"}},
         false,
         true,
         true,
         BuildGeneralCone},
        {"halfspace",
         {kAt, {"n", kThree, "outward normal x y z"}},
         true,
         false,
         false,
         BuildHalfSpace},
    };
    return kinds;
}

const Kind* FindKind(std::string_view name) {
    for (const Kind& k : Kinds())
        if (k.name == name) return &k;
    return nullptr;
}

std::string KindNames() {
    std::string s;
    for (const Kind& k : Kinds()) s += (s.empty() ? "" : ", ") + std::string(k.name);
    return s + ", pipe";
}

std::string CountText(unsigned counts) {
    std::string s;
    for (int n = 0; n < 4; ++n)
        if (counts & (1u << n)) s += (s.empty() ? "" : " or ") + std::to_string(n);
    return s;
}

// The options a kind accepts besides transforms, for "unknown option" messages.
std::string OptionList(const Kind& kind) {
    std::string s;
    for (const ParamSpec& ps : kind.params) s += "=" + std::string(ps.name) + ", ";
    if (kind.axial) s += "=open, =open0, =open1, ";
    if (kind.makesBody) s += "=hsb, =c, =finish, =alpha, ";
    return s + "=t, =0 or a transform (=tx, =ry, ...)";
}

struct Flags {
    bool transparent = false;
    bool open0 = false, open1 = false;
    bool hsbOnly = false;
    std::optional<scene::Color> color;
    scene::Finish finish;
};

// Reads the options up to the ';'. Returns false after a syntax error (reported).
bool ParseOptions(Parser& p, const Kind& kind, SolidContext& ctx, Flags& flags,
                  Transform& placement) {
    while (p.PeekIs(TokenKind::kOption)) {
        if (IsTransformOption(p.Peek().text)) {
            if (!ParseTransforms(p, placement)) return false;
            continue;
        }
        Token option = p.Take();
        const std::string& name = option.text;
        if (name == "t" || name == "0" || name == "o") {
            flags.transparent = name == "t";
            continue;
        }
        if (kind.axial && (name == "open" || name == "open0" || name == "open1")) {
            flags.open0 |= name != "open1";
            flags.open1 |= name != "open0";
            continue;
        }
        if (kind.makesBody && name == "hsb") {
            flags.hsbOnly = true;
            continue;
        }
        if (kind.makesBody && Parser::IsAppearanceOption(name)) {
            if (!p.ParseAppearance(option, flags.color, flags.finish)) return false;
            continue;
        }
        const ParamSpec* spec = nullptr;
        for (const ParamSpec& ps : kind.params)
            if (ps.name == name) spec = &ps;
        if (!spec) {
            p.Error(option.loc,
                    fmt::format("unknown option {} for a solid {} (expected {})", Describe(option),
                                kind.name, OptionList(kind)),
                    kSyntax);
            return false;
        }
        Param param;
        param.loc = option.loc;
        while (p.PeekIsNumber()) {
            auto v = p.ExpectNumber(fmt::format("a value of {}", Describe(option)));
            if (!v) return false;
            param.values.push_back(*v);
        }
        const std::size_t n = param.values.size();
        if (n > 3 || !(spec->counts & (1u << n))) {
            p.Error(option.loc,
                    fmt::format("{} of a solid {} takes {} number{} ({}), found {}",
                                Describe(option), kind.name, CountText(spec->counts),
                                spec->counts == kOne ? "" : "s", spec->meaning, n),
                    kSyntax);
            return false;
        }
        if (ctx.params.count(name))
            p.Warning(option.loc,
                      fmt::format("{} given twice; the last one is used", Describe(option)));
        ctx.params[name] = std::move(param);
    }
    return true;
}

// A free base id: unused as a solid and as a half-space ("cylinder#1", ...).
std::string GenerateBaseId(ReaderState& s, std::string_view kind) {
    for (;;) {
        std::string id = s.GenerateId(std::string(kind), ReaderState::Namespace::kSolid);
        if (s.FindHalfSpace(id) < 0) return id;
    }
}

}  // namespace

bool ParseSolid(Parser& p, const Token& keyword) {
    const Token& kindToken = p.Peek();
    if (kindToken.kind == TokenKind::kId && kindToken.text == "pipe") {
        p.Take();
        return ParsePipeSolid(p, keyword);  // stmt_pipe.cpp: a union of pieces, not one body
    }
    const Kind* kind = kindToken.kind == TokenKind::kId ? FindKind(kindToken.text) : nullptr;
    if (!kind) return p.Expected(fmt::format("a solid kind ({}) after 'solid'", KindNames()));
    p.Take();

    std::string id;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(id, idLoc)) return false;

    // Errors about values inside the options (a zero scale) are reported without stopping the
    // statement; the solid is then left out, so that nothing half-right is drawn.
    const int errorsBefore = p.State().diags.ErrorCount();
    SolidContext ctx{p, *kind, keyword, {}};
    Flags flags;
    Transform placement;
    if (!ParseOptions(p, *kind, ctx, flags, placement)) return false;
    if (!p.ExpectSemicolon(fmt::format("the options of the solid {}", kind->name))) return false;

    if (p.State().diags.ErrorCount() > errorsBefore) return true;
    std::optional<SolidShape> shape = kind->build(ctx);
    if (!shape) return true;  // reported; the statement itself was well formed
    if (const Param* at = kind->centred ? ctx.Get("at") : nullptr)
        placement = Transform::Translate(at->AsVec3()) * placement;
    SolidShape placed = shape->Transformed(placement);

    ReaderState& s = p.State();
    if (id.empty()) id = GenerateBaseId(s, kind->name);
    // Check every id before adding anything, so a clash leaves no half-made solid behind.
    for (const model::SolidSurface& surface : placed.surfaces) {
        const bool finite = surface.IsQuartic() ? surface.quartic->AllFinite()
                            : surface.isPlane   ? surface.plane.AllFinite()
                                                : surface.quadric.AllFinite();
        if (!finite) {
            p.Error(keyword.loc, fmt::format("the solid {} '{}' has coefficients too large to "
                                             "represent",
                                             kind->name, id));
            return true;
        }
        std::string hsId = id + surface.suffix;
        if (int first = s.FindHalfSpace(hsId); first >= 0) {
            p.Error(idLoc, fmt::format("half-space '{}' of the solid {} '{}' is already defined "
                                       "at {}",
                                       hsId, kind->name, id,
                                       s.CurrentScope().halfSpaces[first].loc.ToString()));
            return true;
        }
    }
    const bool makeBody = kind->makesBody && !flags.hsbOnly;
    if (makeBody) {
        if (std::string dup = s.DuplicateSolidMessage(id); !dup.empty()) {
            p.Error(idLoc, dup);
            return true;
        }
    }

    scene::Body body;
    body.id = id;
    body.loc = keyword.loc;
    body.color = flags.color;
    body.finish = flags.finish;
    for (const model::SolidSurface& surface : placed.surfaces) {
        scene::HalfSpace hs;
        hs.id = id + surface.suffix;
        hs.loc = keyword.loc;
        hs.kind = surface.IsQuartic() ? scene::HalfSpace::Kind::kQuartic
                  : surface.isPlane   ? scene::HalfSpace::Kind::kPlane
                                      : scene::HalfSpace::Kind::kQuadric;
        hs.plane = surface.plane;
        hs.quadric = surface.quadric;
        hs.quartic = surface.quartic;
        bool openCap = surface.isCap && (surface.suffix == "#0" ? flags.open0 : flags.open1);
        hs.transparent = flags.transparent || openCap;
        body.literals.push_back({s.AddHalfSpace(std::move(hs)), false});
    }
    if (makeBody) s.AddBody(std::move(body));
    return true;
}

}  // namespace quadrix::lang
