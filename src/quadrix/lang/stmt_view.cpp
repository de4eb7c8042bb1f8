// View statements (seed 001 §2.1.6, §2.3):
//   view [id] params;
//   redef view id [params];
// params, parsed and set left to right (the last of a repeated parameter wins):
//   vrp x y z              view reference point
//   vpn x y z [=v|=p]      view plane normal: =v a direction (default), =p a point; the direction
//   vup x y z [=v|=p]        is then the vector from the vrp given so far to that point
//   dop x y z [=v|=p]      direction of parallel projection
//   cop x y z [=a|=r]      centre of projection: =a absolute (default), =r relative to the vrp
//   whh s / whw s          window half-height / half-width (> 0)
//   fbp d1 d2              front and back clipping distances from vrp along vpn (d1 < d2)
// The scene::View stores directions and an absolute cop; the Flattener applies the defaults and
// the orientation convention documented in scene.h and docs/language.md.
#include <fmt/format.h>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

bool IsViewParameterKeyword(Keyword k) { return IsViewParameter(k); }

struct ParamState {
    bool usedVrp = false;  // a =p or =r has been resolved against the vrp so far
    bool dopHere = false, copHere = false;
    SourceLoc vupLoc;
};

std::optional<Vec3> ParseVec(Parser& p, const Token& param) {
    Vec3 v;
    static constexpr const char* kAxes[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
        auto c = p.ExpectNumber(fmt::format("the {} component of {}", kAxes[i], param.text));
        if (!c) return std::nullopt;
        v[i] = *c;
    }
    return v;
}

// The =v/=p (or =a/=r for cop) options after a vector; `second` is the non-default one.
// Returns nullopt on a syntax error, else whether the last option given was `second`.
std::optional<bool> ParseVectorOption(Parser& p, const Token& param, const char* first,
                                      const char* second) {
    bool isSecond = false;
    while (p.PeekIs(TokenKind::kOption)) {
        const Token& t = p.Peek();
        if (t.text != first && t.text != second) {
            p.Error(t.loc,
                    fmt::format("unknown option {} for {} (expected ={} or ={})", Describe(t),
                                param.text, first, second),
                    kSyntax);
            return std::nullopt;
        }
        isSecond = t.text == second;
        p.Take();
    }
    return isSecond;
}

// vpn, vup, dop: a direction, or with =p a point whose offset from the vrp is the direction.
bool ParseDirection(Parser& p, const Token& param, scene::View& view, ParamState& st,
                    std::optional<Vec3>& out) {
    auto v = ParseVec(p, param);
    if (!v) return false;
    auto isPoint = ParseVectorOption(p, param, "v", "p");
    if (!isPoint) return false;
    if (*isPoint) {
        *v = *v - view.vrp.value_or(Vec3{});
        st.usedVrp = true;
    }
    if (*v == Vec3{0, 0, 0}) {
        p.Error(param.loc, fmt::format("{} is the zero vector{}", param.text,
                                       *isPoint ? " (the point =p is the vrp itself)" : ""));
        return true;
    }
    out = *v;
    return true;
}

bool ParsePositive(Parser& p, const Token& param, std::optional<double>& out) {
    SourceLoc at = p.Peek().loc;
    auto v = p.ExpectNumber(fmt::format("the size after {}", param.text));
    if (!v) return false;
    if (*v <= 0)
        p.Error(at, fmt::format("{} must be greater than 0, not {}", param.text, *v));
    else
        out = *v;
    return true;
}

// dop and cop exclude each other: both in one statement is an error; in a redef the new one
// replaces the projection the view had.
void CheckProjection(Parser& p, const Token& param, scene::View& view, ParamState& st, bool redef) {
    bool isDop = param.keyword == Keyword::kDop;
    if (isDop ? st.copHere : st.dopHere) {
        p.Error(param.loc, "a view cannot have both dop (parallel) and cop (perspective)");
    } else if (redef) {
        if (isDop)
            view.cop.reset();
        else
            view.dop.reset();
    } else if (isDop ? view.cop.has_value() : view.dop.has_value()) {
        p.Error(param.loc, "a view cannot have both dop (parallel) and cop (perspective)");
    }
    (isDop ? st.dopHere : st.copHere) = true;
}

bool ParseOneParam(Parser& p, scene::View& view, ParamState& st, bool redef) {
    Token param = p.Take();
    switch (param.keyword) {
        case Keyword::kVrp: {
            auto v = ParseVec(p, param);
            if (!v) return false;
            if (p.PeekIs(TokenKind::kOption)) {
                p.Error(p.Peek().loc,
                        fmt::format("vrp takes no option (found {})", Describe(p.Peek())), kSyntax);
                return false;
            }
            if (st.usedVrp)
                p.Warning(param.loc,
                          "vrp given after a parameter with =p or =r; that parameter "
                          "used the vrp given before it");
            view.vrp = *v;
            return true;
        }
        case Keyword::kVpn:
            return ParseDirection(p, param, view, st, view.vpn);
        case Keyword::kVup:
            st.vupLoc = param.loc;
            return ParseDirection(p, param, view, st, view.vup);
        case Keyword::kDop:
            CheckProjection(p, param, view, st, redef);
            return ParseDirection(p, param, view, st, view.dop);
        case Keyword::kCop: {
            CheckProjection(p, param, view, st, redef);
            auto v = ParseVec(p, param);
            if (!v) return false;
            auto relative = ParseVectorOption(p, param, "a", "r");
            if (!relative) return false;
            if (*relative) {
                *v = view.vrp.value_or(Vec3{}) + *v;
                st.usedVrp = true;
            }
            view.cop = *v;
            return true;
        }
        case Keyword::kWhh:
            return ParsePositive(p, param, view.whh);
        case Keyword::kWhw:
            return ParsePositive(p, param, view.whw);
        case Keyword::kFbp: {
            auto front = p.ExpectNumber("the front clipping distance after fbp");
            if (!front) return false;
            auto back = p.ExpectNumber("the back clipping distance after fbp");
            if (!back) return false;
            if (!(*front < *back)) {
                p.Error(param.loc, fmt::format("fbp: the front distance {} must be less than the "
                                               "back distance {}",
                                               *front, *back));
                return true;
            }
            view.front = *front;
            view.back = *back;
            return true;
        }
        default:
            return true;  // not reached: the caller checks IsViewParameter
    }
}

// Parameters up to and including the final ';'. False on a syntax error; `valuesOk` tells
// whether the values were all valid (errors about them are reported).
bool ParseViewParams(Parser& p, scene::View& view, bool redef, const char* statement,
                     bool& valuesOk) {
    ParamState st;
    int errors = p.State().diags.ErrorCount();
    ++p.State().viewDepth;  // `clock` here animates the camera, not the geometry
    bool ok = true;
    while (ok && p.PeekIs(TokenKind::kKeyword) && IsViewParameter(p.Peek().keyword))
        ok = ParseOneParam(p, view, st, redef);
    --p.State().viewDepth;
    if (!ok) return false;
    if (view.vpn && view.vup && Cross(*view.vpn, *view.vup) == Vec3{0, 0, 0})
        p.Error(st.vupLoc.line ? st.vupLoc : view.loc,
                "vup is parallel to vpn: the view has no "
                "up direction on the screen");
    valuesOk = p.State().diags.ErrorCount() == errors;
    if (!p.ExpectStatementEnd(fmt::format("a view parameter (vrp vpn vup dop cop whh whw fbp) "
                                          "or ';' after {}",
                                          statement)))
        return false;
    return true;
}

}  // namespace

bool ParseView(Parser& p, const Token& keyword) {
    scene::View view;
    view.loc = keyword.loc;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(view.id, idLoc, IsViewParameterKeyword)) return false;
    bool valuesOk = true;
    if (!ParseViewParams(p, view, false, "the view", valuesOk)) return false;
    p.RecordViewStatement(keyword);

    ReaderState& s = p.State();
    if (view.id.empty()) view.id = s.GenerateId("v", ReaderState::Namespace::kView);
    if (int first = s.FindView(view.id); first >= 0) {
        p.Error(idLoc, fmt::format("view '{}' is already defined at {} (use redef view to "
                                   "change it)",
                                   view.id, s.scene.views[first].loc.ToString()));
        return true;
    }
    if (valuesOk) s.AddView(std::move(view));
    return true;
}

bool ParseRedefView(Parser& p, const Token& keyword) {
    Command command;
    command.kind = Command::Kind::kRedefView;
    command.loc = keyword.loc;
    SourceLoc idLoc;
    if (!p.ExpectId("the id of the view to redefine", command.id, idLoc)) return false;
    ReaderState& s = p.State();
    int index = s.FindView(command.id);
    // Parameters start from the view as it is, so =p and =r use its vrp.
    scene::View view = index >= 0 ? s.scene.views[index] : scene::DefaultView();
    bool changed = p.PeekIs(TokenKind::kKeyword) && IsViewParameter(p.Peek().keyword);
    bool valuesOk = true;
    if (!ParseViewParams(p, view, true, "the redef view statement", valuesOk)) return false;
    p.RecordViewStatement(keyword);
    if (index < 0 && command.id != "default") {
        p.Error(idLoc, fmt::format("unknown view '{}'", command.id));
        return true;
    }
    if (!valuesOk) return true;
    if (changed) {
        // Redefining the automatic default view makes it an ordinary view of the scene.
        view.isDefault = false;
        if (index >= 0)
            s.scene.views[index] = std::move(view);
        else
            s.AddView(std::move(view));
    }
    RunCommand(p, command, changed);
    return true;
}

}  // namespace quadrix::lang
