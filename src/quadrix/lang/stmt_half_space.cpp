// plane and quadric statements (seed 001 §2.1.1):
//   plane   [id] <A B C D> [=t] [=0];               Ax + By + Cz + D <= 0 inside
//   quadric [id] <A B C D E F G H J K> [=t] [=0];   xᵀQx <= 0 inside (DESIGN.md "Coefficients")
// =t makes the half-space bound transparent, =0 (or =o) opaque; opaque is the default and the
// last option given wins.
#include <fmt/format.h>

#include <array>
#include <string>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

// Reads "<" n numbers ">" into `out`; `names` holds one letter per coefficient.
bool ParseCoefficients(Parser& p, std::string_view statement, std::string_view names, double* out,
                       SourceLoc& listLoc) {
    listLoc = p.Peek().loc;
    if (!p.PeekIs(TokenKind::kLAngle))
        return p.Expected(fmt::format("'<' before the {} coefficients", statement));
    p.Take();
    const bool fast = p.TakePlainNumbers(out, names.size());
    for (std::size_t i = 0; i < names.size() && !fast; ++i) {
        if (p.TakeNumber(out[i])) continue;
        auto v =
            p.ExpectNumber(fmt::format("coefficient {} of the {} ({} numbers between '<' and '>')",
                                       names[i], statement, names.size()));
        if (!v) return false;
        out[i] = *v;
    }
    if (p.TakeIf(TokenKind::kRAngle)) return true;
    return p.Expected(
        fmt::format("'>' after the {} coefficients of the {}", names.size(), statement));
}

bool ParseTransparency(Parser& p, std::string_view statement, bool& transparent) {
    while (p.PeekIs(TokenKind::kOption)) {
        const Token& t = p.Peek();
        if (t.text == "t") {
            transparent = true;
        } else if (t.text == "0" || t.text == "o") {
            transparent = false;
        } else {
            p.Error(t.loc,
                    fmt::format("unknown option {} for a {} (expected =t or =0)", Describe(t),
                                statement),
                    kSyntax);
            return false;
        }
        p.Take();
    }
    return true;
}

// Shared head and tail of both statements; `check` validates the coefficients.
template <class Check>
bool ParseHalfSpace(Parser& p, const Token& keyword, scene::HalfSpace hs, std::string_view names,
                    double* coefficients, Check check) {
    std::string_view statement = hs.kind == scene::HalfSpace::Kind::kPlane ? "plane" : "quadric";
    TokenLoc idLoc = keyword.loc;
    if (!p.OptionalId(hs.id, idLoc)) return false;
    SourceLoc listLoc;
    if (!ParseCoefficients(p, statement, names, coefficients, listLoc)) return false;
    if (!ParseTransparency(p, statement, hs.transparent)) return false;
    if (!p.TakeIf(TokenKind::kSemicolon) &&
        !p.ExpectSemicolon(fmt::format("{} coefficients", statement)))
        return false;

    ReaderState& s = p.State();
    // Generated ids: p#1, q#1, ... (quietly; only lights announce theirs).
    if (hs.id.empty())
        hs.id =
            s.GenerateId(std::string(statement.substr(0, 1)), ReaderState::Namespace::kHalfSpace);
    if (!check(hs, listLoc)) return true;  // reported; the statement itself was well formed
    if (int first = s.FindHalfSpace(hs.id); first >= 0) {
        p.Error(idLoc, fmt::format("half-space '{}' is already defined at {}", hs.id,
                                   s.CurrentScope().halfSpaces[first].loc.ToString()));
        return true;
    }
    hs.loc = keyword.loc;
    s.AddHalfSpace(std::move(hs));
    return true;
}

}  // namespace

bool ParsePlane(Parser& p, const Token& keyword) {
    scene::HalfSpace hs;
    hs.kind = scene::HalfSpace::Kind::kPlane;
    double c[4];
    return ParseHalfSpace(p, keyword, std::move(hs), "ABCD", c,
                          [&](scene::HalfSpace& h, const SourceLoc& at) {
                              h.plane = Plane{c[0], c[1], c[2], c[3]};
                              if (!h.plane.IsZeroNormal()) return true;
                              p.Error(at, fmt::format("plane '{}' has A = B = C = 0: it has no "
                                                      "normal and bounds nothing",
                                                      h.id));
                              return false;
                          });
}

bool ParseQuadric(Parser& p, const Token& keyword) {
    scene::HalfSpace hs;
    hs.kind = scene::HalfSpace::Kind::kQuadric;
    std::array<double, 10> k{};
    return ParseHalfSpace(
        p, keyword, std::move(hs), "ABCDEFGHJK", k.data(),
        [&](scene::HalfSpace& h, const SourceLoc& at) {
            h.quadric = Quadric::FromCoefficients(k);
            if (h.quadric.IsZero()) {
                p.Error(at, fmt::format("quadric '{}' has all coefficients zero", h.id));
                return false;
            }
            if (h.quadric.IsDegenerateToLinear()) {
                if (k[6] == 0 && k[7] == 0 && k[8] == 0)
                    p.Warning(at, fmt::format("quadric '{}' is a constant ({}): it holds {}", h.id,
                                              k[9], k[9] < 0 ? "all of space" : "nothing"));
                else
                    p.Warning(at, fmt::format("quadric '{}' has no second-order terms: it is a "
                                              "plane",
                                              h.id));
            }
            return true;
        });
}

}  // namespace quadrix::lang
