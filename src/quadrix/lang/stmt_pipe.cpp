// `solid pipe` (Quadrix extension, docs/language.md §3.13, issue 20): BRL-CAD's pipe in the
// language, drawn exactly by the builder the BRL-CAD importer uses (import/brlcad/pipe_solid.h).
//
//   solid pipe [id] =p x y z od id bend  =p ... { transform | =t | =0 | =open | =open0 | =open1
//                                                | =hsb | =c r g b } ;
//
// Each `=p` is one point of the centre line with BRL-CAD's per-point values: the outer and inner
// diameters (id 0: a solid rod) and the bend radius used at that point. The pipe is laid out as
// librt lays it out (straight runs, cones where the diameters change, torus bends at interior
// points), each run or bend one body: its outer surface, its bore complemented, and the joint
// planes at its two ends, shared (with opposite signs) with its neighbours.
//
// Names. Piece k = 1, 2, ... (in order along the pipe) makes the half-spaces `id#k` (its outer
// surface: a cone/cylinder or a torus), `id#k.bore` (the bore, when the inner diameter is not 0),
// `id#k.0` and `id#k.1` (the planes at its start and end; `id#1.0` and the last piece's `.1` are
// the pipe's end caps) and the body `id#k`; the csg solid `id` is the union of the pieces, and the
// piece bodies are its operands (drawn as part of it). With =hsb only the half-spaces are made.
// Transforms (=tx ... =vzy) apply to the whole pipe in place, left to right.
#include <fmt/format.h>

#include <optional>
#include <string>
#include <vector>

#include "quadrix/import/brlcad/pipe_solid.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"
#include "quadrix/lang/transforms.h"

namespace quadrix::lang {

namespace {

struct PipeOptions {
    std::vector<import::brlcad::Primitive::PipePoint> points;
    std::vector<SourceLoc> pointLocs;
    bool transparent = false, open0 = false, open1 = false, hsbOnly = false;
    std::optional<scene::Color> color;
    scene::Finish finish;
    Transform placement;
};

constexpr const char* kPipeOptions =
    "=p x y z od id bend, =open, =open0, =open1, =hsb, =c, =finish, =alpha, =t, =0 or a "
    "transform (=tx, =ry, ...)";

// Reads the options up to the ';'. False after a syntax error (reported).
bool ParsePipeOptions(Parser& p, PipeOptions& o) {
    while (p.PeekIs(TokenKind::kOption)) {
        if (IsTransformOption(p.Peek().text)) {
            if (!ParseTransforms(p, o.placement)) return false;
            continue;
        }
        Token option = p.Take();
        const std::string& name = option.text;
        if (name == "t" || name == "0" || name == "o") {
            o.transparent = name == "t";
        } else if (name == "open" || name == "open0" || name == "open1") {
            o.open0 |= name != "open1";
            o.open1 |= name != "open0";
        } else if (name == "hsb") {
            o.hsbOnly = true;
        } else if (Parser::IsAppearanceOption(name)) {
            if (!p.ParseAppearance(option, o.color, o.finish)) return false;
        } else if (name == "p") {
            std::vector<double> v;
            while (p.PeekIsNumber()) {
                auto x = p.ExpectNumber(fmt::format("a value of {}", Describe(option)));
                if (!x) return false;
                v.push_back(*x);
            }
            if (v.size() != 6) {
                p.Error(option.loc,
                        fmt::format("'=p' of a solid pipe takes 6 numbers (x y z od id bend: the "
                                    "point, its outer and inner diameters and its bend radius), "
                                    "found {}",
                                    v.size()),
                        kSyntax);
                return false;
            }
            import::brlcad::Primitive::PipePoint pt;
            pt.at = {v[0], v[1], v[2]};
            pt.od = v[3];
            pt.id = v[4];
            pt.bend = v[5];
            o.points.push_back(pt);
            o.pointLocs.push_back(option.loc);
        } else {
            p.Error(option.loc,
                    fmt::format("unknown option {} for a solid pipe (expected {})",
                                Describe(option), kPipeOptions),
                    kSyntax);
            return false;
        }
    }
    return true;
}

// Checks each point's own values at its `=p`: od > 0, 0 <= id < od, bend >= 0.
bool CheckPoints(Parser& p, const PipeOptions& o) {
    for (std::size_t k = 0; k < o.points.size(); ++k) {
        const auto& pt = o.points[k];
        std::string why;
        if (!(pt.od > 0))
            why = fmt::format("the outer diameter of a pipe point must be > 0, found {}", pt.od);
        else if (!(pt.id >= 0) || !(pt.id < pt.od))
            why = fmt::format(
                "the inner diameter of a pipe point must be >= 0 and smaller than "
                "its outer diameter {}, found {}",
                pt.od, pt.id);
        else if (!(pt.bend >= 0))
            why = fmt::format("the bend radius of a pipe point must be >= 0, found {}", pt.bend);
        if (!why.empty()) {
            p.Error(o.pointLocs[k], why);
            return false;
        }
    }
    return true;
}

}  // namespace

bool ParsePipeSolid(Parser& p, const Token& keyword) {
    std::string id;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(id, idLoc)) return false;
    const int errorsBefore = p.State().diags.ErrorCount();
    PipeOptions o;
    if (!ParsePipeOptions(p, o)) return false;
    if (!p.ExpectSemicolon("the options of the solid pipe")) return false;
    if (p.State().diags.ErrorCount() > errorsBefore) return true;
    if (o.points.size() < 2) {
        p.Error(keyword.loc, fmt::format("solid pipe needs at least 2 points (=p x y z od id "
                                         "bend), found {}",
                                         o.points.size()));
        return true;
    }
    if (!CheckPoints(p, o)) return true;
    import::brlcad::PipeLayout layout = import::brlcad::LayOutPipe(o.points);
    if (!layout.ok) {
        const SourceLoc& at =
            layout.point >= 0 && layout.point < static_cast<int>(o.pointLocs.size())
                ? o.pointLocs[layout.point]
                : keyword.loc;
        // At the `=p` of the point concerned (the layout's message counts points from 0).
        p.Error(at, fmt::format("the solid pipe cannot be built: {}", layout.problem));
        return true;
    }
    import::brlcad::PipeShape shape = import::brlcad::PipeToShape(layout);
    if (!shape.ok) {
        p.Error(keyword.loc, fmt::format("the solid pipe cannot be built: {}", shape.problem));
        return true;
    }

    ReaderState& s = p.State();
    if (id.empty()) {
        for (;;) {
            id = s.GenerateId("pipe", ReaderState::Namespace::kSolid);
            if (s.FindHalfSpace(id + "#1") < 0) break;
        }
    }
    // The half-spaces of each piece, named as in the header, transformed; checked before any is
    // added so that a clash leaves nothing half-made.
    struct Named {
        std::string id;
        PlaneOrQuadric surface;
        bool complemented = false;
        bool cap = false;  // an end cap of the whole pipe (=open)
        bool cap0 = false;
    };
    std::vector<std::vector<Named>> pieces;
    const std::size_t n = shape.shape.bodies.size();
    for (std::size_t k = 0; k < n; ++k) {
        const import::ShapeBody& body = shape.shape.bodies[k];
        std::vector<Named> named;
        int planes = 0;
        for (const import::ShapeHalfSpace& h : body) {
            Named m;
            m.surface = h;
            m.surface.TransformBy(o.placement);
            m.complemented = h.complement;
            const std::string base = fmt::format("{}#{}", id, k + 1);
            if (h.isPlane) {
                // pipe_solid.cpp lists the start joint before the end joint.
                m.id = fmt::format("{}.{}", base, planes);
                m.cap = (planes == 0 && k == 0) || (planes == 1 && k + 1 == n);
                m.cap0 = planes == 0;
                ++planes;
            } else {
                m.id = h.complement ? base + ".bore" : base;
            }
            const bool finite = m.surface.IsQuartic() ? m.surface.quartic->AllFinite()
                                : m.surface.isPlane   ? m.surface.plane.AllFinite()
                                                      : m.surface.quadric.AllFinite();
            if (!finite) {
                p.Error(keyword.loc, fmt::format("the solid pipe '{}' has coefficients too large "
                                                 "to represent",
                                                 id));
                return true;
            }
            if (int first = s.FindHalfSpace(m.id); first >= 0) {
                p.Error(idLoc,
                        fmt::format("half-space '{}' of the solid pipe '{}' is already "
                                    "defined at {}",
                                    m.id, id, s.CurrentScope().halfSpaces[first].loc.ToString()));
                return true;
            }
            named.push_back(std::move(m));
        }
        pieces.push_back(std::move(named));
    }
    if (!o.hsbOnly) {
        for (std::size_t k = 0; k < n; ++k)
            if (std::string dup = s.DuplicateSolidMessage(fmt::format("{}#{}", id, k + 1));
                !dup.empty()) {
                p.Error(idLoc, dup);
                return true;
            }
        if (std::string dup = s.DuplicateSolidMessage(id); !dup.empty()) {
            p.Error(idLoc, dup);
            return true;
        }
    }

    scene::Csg csg;
    csg.id = id;
    csg.loc = keyword.loc;
    csg.color = o.color;
    csg.finish = o.finish;
    for (std::size_t k = 0; k < n; ++k) {
        scene::Body body;
        body.id = fmt::format("{}#{}", id, k + 1);
        body.loc = keyword.loc;
        for (const Named& m : pieces[k]) {
            scene::HalfSpace hs;
            hs.id = m.id;
            hs.loc = keyword.loc;
            hs.kind = m.surface.IsQuartic() ? scene::HalfSpace::Kind::kQuartic
                      : m.surface.isPlane   ? scene::HalfSpace::Kind::kPlane
                                            : scene::HalfSpace::Kind::kQuadric;
            hs.plane = m.surface.plane;
            hs.quadric = m.surface.quadric;
            hs.quartic = m.surface.quartic;
            const bool open = m.cap && (m.cap0 ? o.open0 : o.open1);
            hs.transparent = o.transparent || open;
            body.literals.push_back({s.AddHalfSpace(std::move(hs)), m.complemented});
        }
        if (o.hsbOnly) continue;
        const int index = s.AddBody(std::move(body));
        scene::CsgNode leaf;
        leaf.ref = {scene::SolidRef::Kind::kBody, index};
        leaf.loc = keyword.loc;
        csg.nodes.push_back(leaf);
        const int leafIndex = static_cast<int>(csg.nodes.size()) - 1;
        if (csg.root < 0) {
            csg.root = leafIndex;
        } else {
            scene::CsgNode join;
            join.isLeaf = false;
            join.op = scene::CsgOp::kUnion;
            join.left = csg.root;
            join.right = leafIndex;
            join.loc = keyword.loc;
            csg.nodes.push_back(join);
            csg.root = static_cast<int>(csg.nodes.size()) - 1;
        }
    }
    if (o.hsbOnly) return true;
    for (const scene::CsgNode& node : csg.nodes)
        if (node.isLeaf) s.MarkOperand(node.ref);
    s.AddCsg(std::move(csg));
    return true;
}

}  // namespace quadrix::lang
