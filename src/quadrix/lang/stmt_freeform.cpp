// Freeform surface statements (extension; seed 002, docs/language.md "Freeform surfaces"):
//
//   bezier  [id] du dv < x y z ... > [=r < w ... >] [transforms] [=c r g b];
//   bspline [id] du dv nu nv < u knots > < v knots > < x y z ... > [=r < w ... >]
//                                                               [transforms] [=c r g b];
//   patches [id] "file" [newell | bpt | geomview | obj] [transforms] [=c r g b];
//
// Control points are listed u fastest: (du+1)(dv+1) of them for `bezier`, nu·nv for `bspline`
// with knot vectors of nu+du+1 and nv+dv+1 non-decreasing values. `=r` makes the surface rational
// with one positive weight per control point (Euclidean points and weights, as in OBJ; stored
// homogeneous). Transforms are those of instances (=tx ... =rz ...), applied to the control
// points (exact for any affine map). `patches` reads every surface of a freeform file (format from
// the extension or the text unless named), relative to the file holding the statement.
//
// A freeform surface has no inside: it is drawn by adaptive isocurves and composes with solids in
// the Frame, but it cannot be named by a body or csg solid.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/lang/input_files.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"
#include "quadrix/lang/transforms.h"

namespace quadrix::lang {

namespace {

using import::kMaxFreeformDegree;
// Bounds that keep one statement's work and memory reasonable (a 1000×1000 net is 24 MB).
inline constexpr double kMaxControlPoints = 1'000'000;

// A whole number in [lo, hi] (degrees, counts).
std::optional<int> ExpectCount(Parser& p, std::string_view what, int lo, int hi) {
    const SourceLoc at = p.Peek().loc;
    auto v = p.ExpectNumber(what);
    if (!v) return std::nullopt;
    if (!(*v >= lo && *v <= hi) || std::floor(*v) != *v) {
        p.Error(at,
                fmt::format("{} must be a whole number from {} to {}; got {}", what, lo, hi, *v));
        return std::nullopt;
    }
    return static_cast<int>(*v);
}

// "<" exactly n numbers ">".
bool ExpectList(Parser& p, std::string_view what, std::size_t n, std::vector<double>& out) {
    if (!p.PeekIs(TokenKind::kLAngle)) return p.Expected(fmt::format("'<' before the {}", what));
    const Token open = p.Take();
    out.clear();
    out.reserve(n);
    while (!p.PeekIs(TokenKind::kRAngle)) {
        if (out.size() == n) {
            p.Error(p.Peek().loc, fmt::format("too many numbers in the {} (expected {}, list "
                                              "opened at {})",
                                              what, n, open.loc.ToString()));
            return false;
        }
        auto v = p.ExpectNumber(fmt::format("a number of the {} or '>'", what));
        if (!v) return false;
        out.push_back(*v);
    }
    if (out.size() != n) {
        p.Error(p.Peek().loc,
                fmt::format("the {} has {} numbers; expected {}", what, out.size(), n));
        return false;
    }
    p.Take();
    return true;
}

bool CheckKnots(Parser& p, const SourceLoc& at, const std::vector<double>& knots, int degree,
                char dir) {
    for (std::size_t i = 1; i < knots.size(); ++i)
        if (!(knots[i] >= knots[i - 1])) {
            p.Error(at, fmt::format("{} knot {} ({}) is smaller than knot {} ({}): knots must not "
                                    "decrease",
                                    dir, i + 1, knots[i], i, knots[i - 1]));
            return false;
        }
    const std::size_t count = knots.size() - static_cast<std::size_t>(degree) - 1;
    if (!(knots[count] > knots[static_cast<std::size_t>(degree)])) {
        p.Error(at, fmt::format("the {} knots leave an empty parameter range (knot {} = knot {})",
                                dir, degree + 1, count + 1));
        return false;
    }
    return true;
}

// The tail shared by all three statements: [=r <weights>] [transforms] [=c r g b] ';'.
struct Tail {
    std::vector<double> weights;
    bool rational = false;
    Transform transform;
    std::optional<scene::Color> color;
    scene::Finish finish;
};

bool ParseTail(Parser& p, std::string_view statement, std::size_t points, bool allowWeights,
               Tail& tail) {
    while (p.PeekIs(TokenKind::kOption)) {
        const Token& option = p.Peek();
        if (option.text == "r" && allowWeights) {
            p.Take();
            const SourceLoc at = p.Peek().loc;
            if (!ExpectList(p, "weights (one per control point)", points, tail.weights))
                return false;
            for (std::size_t i = 0; i < tail.weights.size(); ++i)
                if (!(tail.weights[i] > 0) || !std::isfinite(tail.weights[i])) {
                    p.Error(at, fmt::format("weight {} is {}; weights must be positive", i + 1,
                                            tail.weights[i]));
                    return false;
                }
            tail.rational = true;
        } else if (IsTransformOption(option.text)) {
            if (!ParseTransforms(p, tail.transform)) return false;
        } else if (Parser::IsAppearanceOption(option.text)) {
            Token c = p.Take();
            if (!p.ParseAppearance(c, tail.color, tail.finish)) return false;
        } else {
            p.Error(option.loc,
                    fmt::format("unknown option {} for a {} (expected {}transforms, =c r g b, "
                                "=finish or =alpha)",
                                Describe(option), statement, allowWeights ? "=r <weights>, " : ""),
                    kSyntax);
            return false;
        }
    }
    return p.ExpectSemicolon(fmt::format("the {}", statement));
}

void AddSurface(Parser& p, const Token& keyword, std::string id, const SourceLoc& idLoc,
                freeform::Surface surface, const Tail& tail) {
    ReaderState& s = p.State();
    if (id.empty()) id = s.GenerateId(std::string(keyword.text), ReaderState::Namespace::kSolid);
    if (std::string dup = s.DuplicateSolidMessage(id); !dup.empty()) {
        p.Error(idLoc, dup);
        return;
    }
    for (const scene::FreeformSurface& f : s.CurrentScope().freeforms)
        if (f.id == id) {
            p.Error(idLoc, fmt::format("freeform surface '{}' is already defined at {}", id,
                                       f.loc.ToString()));
            return;
        }
    scene::FreeformSurface f;
    f.id = id;
    surface.SetName(id);
    f.surface = surface.Transformed(tail.transform.Matrix());
    f.color = tail.color;
    f.finish = tail.finish;
    f.loc = keyword.loc;
    s.CurrentScope().freeforms.push_back(std::move(f));
}

// Control points (and weights) into the coefficients of a BSplineSurface: dimension 3, or 4
// (homogeneous w·x, w·y, w·z, w) when rational.
std::vector<double> Coefficients(const std::vector<double>& xyz, const Tail& tail) {
    if (!tail.rational) return xyz;
    std::vector<double> c;
    c.reserve(xyz.size() / 3 * 4);
    for (std::size_t i = 0; i < tail.weights.size(); ++i) {
        const double w = tail.weights[i];
        c.insert(c.end(), {w * xyz[3 * i], w * xyz[3 * i + 1], w * xyz[3 * i + 2], w});
    }
    return c;
}

std::vector<double> ClampedBezierKnots(int degree) {
    std::vector<double> k(static_cast<std::size_t>(degree) + 1, 0.0);
    k.resize(2 * (static_cast<std::size_t>(degree) + 1), 1.0);
    return k;
}

}  // namespace

bool ParseBezier(Parser& p, const Token& keyword) {
    std::string id;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(id, idLoc)) return false;
    auto du = ExpectCount(p, "the degree in u", 1, kMaxFreeformDegree);
    if (!du) return false;
    auto dv = ExpectCount(p, "the degree in v", 1, kMaxFreeformDegree);
    if (!dv) return false;
    const std::size_t points = static_cast<std::size_t>((*du + 1) * (*dv + 1));
    std::vector<double> xyz;
    if (!ExpectList(
            p, fmt::format("control points ({} × {} points of x y z, u fastest)", *du + 1, *dv + 1),
            3 * points, xyz))
        return false;
    Tail tail;
    if (!ParseTail(p, "bezier", points, true, tail)) return false;
    freeform::BSplineSurface net(tail.rational ? 4 : 3, *du, *dv, ClampedBezierKnots(*du),
                                 ClampedBezierKnots(*dv), Coefficients(xyz, tail));
    AddSurface(p, keyword, std::move(id), idLoc, freeform::Surface(std::move(net)), tail);
    return true;
}

bool ParseBspline(Parser& p, const Token& keyword) {
    std::string id;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(id, idLoc)) return false;
    auto du = ExpectCount(p, "the degree in u", 1, kMaxFreeformDegree);
    if (!du) return false;
    auto dv = ExpectCount(p, "the degree in v", 1, kMaxFreeformDegree);
    if (!dv) return false;
    auto nu = ExpectCount(p, "the number of control points in u", *du + 1, 100000);
    if (!nu) return false;
    const SourceLoc nvLoc = p.Peek().loc;
    auto nv = ExpectCount(p, "the number of control points in v", *dv + 1, 100000);
    if (!nv) return false;
    if (double(*nu) * double(*nv) > kMaxControlPoints) {
        p.Error(nvLoc, fmt::format("{} × {} control points is more than the {} a statement may "
                                   "hold",
                                   *nu, *nv, kMaxControlPoints));
        return false;
    }
    std::vector<double> ku, kv, xyz;
    const SourceLoc kuLoc = p.Peek().loc;
    if (!ExpectList(p, "u knots", static_cast<std::size_t>(*nu + *du + 1), ku)) return false;
    const SourceLoc kvLoc = p.Peek().loc;
    if (!ExpectList(p, "v knots", static_cast<std::size_t>(*nv + *dv + 1), kv)) return false;
    const std::size_t points = static_cast<std::size_t>(*nu) * static_cast<std::size_t>(*nv);
    if (!ExpectList(p, fmt::format("control points ({} × {} points of x y z, u fastest)", *nu, *nv),
                    3 * points, xyz))
        return false;
    Tail tail;
    if (!ParseTail(p, "bspline", points, true, tail)) return false;
    if (!CheckKnots(p, kuLoc, ku, *du, 'u') || !CheckKnots(p, kvLoc, kv, *dv, 'v')) return true;
    freeform::BSplineSurface net(tail.rational ? 4 : 3, *du, *dv, std::move(ku), std::move(kv),
                                 Coefficients(xyz, tail));
    AddSurface(p, keyword, std::move(id), idLoc, freeform::Surface(std::move(net)), tail);
    return true;
}

bool ParsePatches(Parser& p, const Token& keyword) {
    std::string id;
    SourceLoc idLoc = keyword.loc;
    if (!p.PeekIs(TokenKind::kString) && !p.OptionalId(id, idLoc)) return false;
    const Token& t = p.Peek();
    if (t.kind != TokenKind::kString && t.kind != TokenKind::kId)
        return p.Expected("a file name in quotes");
    const Token file = p.Take();
    import::FreeformFormat format = import::FreeformFormat::kAuto;
    if (p.PeekIs(TokenKind::kId)) {
        const Token f = p.Take();
        if (f.text == "newell")
            format = import::FreeformFormat::kNewell;
        else if (f.text == "bpt")
            format = import::FreeformFormat::kBpt;
        else if (f.text == "geomview")
            format = import::FreeformFormat::kGeomview;
        else if (f.text == "obj")
            format = import::FreeformFormat::kObj;
        else {
            p.Error(f.loc,
                    fmt::format("unknown freeform format '{}' (expected newell, bpt, "
                                "geomview or obj)",
                                f.text),
                    kSyntax);
            return false;
        }
    }
    Tail tail;
    if (!ParseTail(p, "patches statement", 0, false, tail)) return false;
    if (file.text.empty()) {
        p.Error(file.loc, "empty file name");
        return true;
    }
    const std::string path = ResolveAgainstIncluder(p, file.text);
    // Problems with the file itself are reported at the statement, so the error has a position
    // (the reader's fuzzing property, issue 7), and a device or pipe that never ends ("/dev/zero")
    // is refused instead of being read until memory runs out.
    {
        std::error_code ec;
        const auto status = std::filesystem::status(path, ec);
        if (ec || !std::filesystem::is_regular_file(status)) {
            p.Error(file.loc,
                    fmt::format("cannot read freeform model file {}: {}", path,
                                ec ? ec.message() : std::string("not a regular file")),
                    kParser);
            return true;
        }
    }
    const int errorsBefore = p.State().diags.ErrorCount();
    auto model = import::ReadFreeformFile(path, p.State().diags, format);
    if (!model) {
        if (p.State().diags.ErrorCount() == errorsBefore)
            p.Error(file.loc, fmt::format("cannot read freeform surfaces from {}", path));
        return true;
    }
    if (model->surfaces.empty()) {
        p.Warning(file.loc, fmt::format("{} holds no freeform surface", path));
        return true;
    }
    if (id.empty()) id = std::filesystem::path(path).stem().string();
    for (std::size_t k = 0; k < model->surfaces.size(); ++k)
        AddSurface(p, keyword, fmt::format("{}[{}]", id, k), idLoc, model->surfaces[k], tail);
    return true;
}

}  // namespace quadrix::lang
