// The v4 ASCII record format (FORMAT.md §2): one record per line, the first character the record
// type. S solids carry 24 floats; C combinations are followed by their M member lines, which form
// a flat list with GIFT precedence (+ and - bind tighter than u; the first operator is a union).
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iterator>

#include "quadrix/import/brlcad/readers.h"

namespace quadrix::import::brlcad {

namespace {

struct Token {
    std::string_view text;
    std::size_t offset = 0;
};

std::vector<Token> Split(std::string_view line, std::size_t base) {
    std::vector<Token> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        std::size_t s = i;
        while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        if (i > s) out.push_back({line.substr(s, i - s), base + s});
    }
    return out;
}

bool ToDouble(std::string_view s, double& v) {
    std::string str(s);
    char* end = nullptr;
    errno = 0;
    v = std::strtod(str.c_str(), &end);
    return end == str.c_str() + str.size() && !str.empty() && std::isfinite(v);
}

bool ToInt(std::string_view s, int& v) {
    double d = 0;
    if (!ToDouble(s, d) || d != std::floor(d) || std::fabs(d) > 2e9) return false;
    v = static_cast<int>(d);
    return true;
}

using Member = GiftMember;

class V4Reader {
  public:
    V4Reader(std::string_view text, const std::string& file, Database& db, Diagnostics& diags)
        : map_(text, file), db_(db), diags_(diags) {}

    bool Run() {
        db_.format = "v4";
        std::string_view text = map_.text();
        std::size_t pos = 0;
        while (pos < text.size()) {
            std::size_t end = text.find('\n', pos);
            if (end == std::string_view::npos) end = text.size();
            lines_.push_back({text.substr(pos, end - pos), pos});
            pos = end + 1;
        }
        for (li_ = 0; li_ < lines_.size(); ++li_) {
            auto toks = Split(lines_[li_].text, lines_[li_].offset);
            if (toks.empty()) continue;
            std::string_view id = toks[0].text;
            if (id == "I")
                Ident(toks);
            else if (id == "S")
                Solid(toks);
            else if (id == "C")
                Comb(toks);
            else if (id == "M")
                Member4(toks);
            else if (id == "m")
                ColorEntry(toks);
            else if (id == "s")
                StringSolid(toks);
            else if (id == "A")
                Ars(toks);
            else if (id == "B" && inArs_)
                ArsGranule(toks);
            else
                Error(toks[0], fmt::format("unknown or unsupported v4 record type '{}' (this "
                                           "reader knows I S C M m s A/B)",
                                           id));
            if (id != "B") {
                if (inArs_ && id != "A") FinishArs();
                inArs_ = id == "A";
            }
            if (diags_.ErrorCount() > 50) break;
        }
        if (inArs_) FinishArs();
        FinishComb();
        return !diags_.HasErrors();
    }

  private:
    struct Line {
        std::string_view text;
        std::size_t offset;
    };

    void Error(const Token& t, std::string message) {
        diags_.Error(map_.At(t.offset), std::move(message), map_.LineText(t.offset));
    }

    bool Numbers(const std::vector<Token>& toks, std::size_t first, std::size_t count, double* out,
                 const std::string& what) {
        if (toks.size() < first + count) {
            const Token& last = toks.back();
            Token at{last.text, last.offset + last.text.size()};
            Error(at, fmt::format("truncated {}: expected {} numbers, found {}", what, count,
                                  toks.size() > first ? toks.size() - first : 0));
            return false;
        }
        for (std::size_t i = 0; i < count; ++i) {
            if (!ToDouble(toks[first + i].text, out[i])) {
                Error(toks[first + i],
                      fmt::format("{}: '{}' is not a finite number", what, toks[first + i].text));
                return false;
            }
        }
        return true;
    }

    void Ident(const std::vector<Token>&) {
        if (li_ + 1 < lines_.size()) {
            ++li_;
            db_.title = std::string(lines_[li_].text);
        }
    }

    void Solid(const std::vector<Token>& toks) {
        if (toks.size() < 4) {
            Error(toks.back(),
                  "truncated solid record: expected 'S type name cgtype' and 24 "
                  "numbers");
            return;
        }
        int stype = 0;
        if (!ToInt(toks[1].text, stype)) {
            Error(toks[1], fmt::format("solid type '{}' is not an integer", toks[1].text));
            return;
        }
        Primitive p;
        p.name = std::string(toks[2].text);
        p.loc = map_.At(toks[0].offset);
        p.sourceLine = map_.LineText(toks[0].offset);
        static constexpr int kKnown[] = {16, 18, 19, 20, 24, 26, 27, 28, 29, 30, 31, 32, 33};
        if (std::find(std::begin(kKnown), std::end(kKnown), stype) == std::end(kKnown)) {
            Error(toks[1], fmt::format("unknown solid type {} in record '{}'", stype, p.name));
            return;
        }
        double v[24];
        if (!Numbers(toks, 4, 24, v, fmt::format("solid record '{}'", p.name))) return;
        auto vec = [&](int i) { return Vec3{v[3 * i], v[3 * i + 1], v[3 * i + 2]}; };
        switch (stype) {
            case 20:
                p.type = "arb8";
                p.pts[0] = vec(0);
                for (int i = 1; i < 8; ++i) p.pts[i] = p.pts[0] + vec(i);
                break;
            case 18:
                p.type = "tgc";
                p.V = vec(0), p.H = vec(1), p.A = vec(2), p.B = vec(3), p.C = vec(4), p.D = vec(5);
                break;
            case 19:
                p.type = "ell";
                p.V = vec(0), p.A = vec(1), p.B = vec(2), p.C = vec(3);
                break;
            case 24:
                p.type = "half";
                p.N = vec(0), p.d = v[3];
                break;
            case 26:
            case 27:
                p.type = stype == 26 ? "rpc" : "rhc";
                p.V = vec(0), p.H = vec(1), p.B = vec(2), p.r = v[9], p.c = v[10];
                break;
            case 28:
            case 29:
                p.type = stype == 28 ? "epa" : "ehy";
                p.V = vec(0), p.H = vec(1), p.A = vec(2), p.r1 = v[9], p.r2 = v[10], p.c = v[11];
                break;
            case 33:
                p.type = "hyp";
                p.V = vec(0), p.H = vec(1), p.A = vec(2), p.b = v[9], p.bnr = v[10];
                break;
            case 16:  // V H A B C D E F: H is the normal scaled to r2, |A| = r1 (FORMAT.md §2.3)
                p.type = "tor";
                p.V = vec(0);
                p.r2 = Length(vec(1));
                p.H = p.r2 > 0 ? vec(1) / p.r2 : vec(1);
                p.r1 = Length(vec(2));
                break;
            case 30:  // V N C r rd
                p.type = "eto";
                p.V = vec(0), p.N = vec(1), p.C = vec(2), p.r = v[9], p.rd = v[10];
                break;
            case 31:
                p.type = "grip";
                break;
            case 32:
                p.type = "superell";
                break;
            default:
                Error(toks[1], fmt::format("unknown solid type {} in record '{}'", stype, p.name));
                return;
        }
        db_.AddPrimitive(std::move(p));
    }

    void FinishComb() {
        if (!inComb_) return;
        BuildGiftTree(comb_, members_);
        db_.AddCombination(std::move(comb_));
        comb_ = {};
        members_.clear();
        inComb_ = false;
    }

    void Comb(const std::vector<Token>& toks) {
        FinishComb();
        if (toks.size() < 3) {
            Error(toks.back(), "truncated combination record: expected 'C flag name ...'");
            return;
        }
        comb_ = {};
        comb_.name = std::string(toks[2].text);
        comb_.loc = map_.At(toks[0].offset);
        comb_.sourceLine = map_.LineText(toks[0].offset);
        char flag = toks[1].text.empty() ? 'N' : toks[1].text[0];
        comb_.region = flag == 'Y' || flag == 'P' || flag == 'V' || flag == 'R';
        // Trailing fields may be missing in old records (FORMAT.md §2.4): they default to 0.
        int f[13] = {};
        for (std::size_t i = 3; i < toks.size() && i - 3 < 13; ++i) {
            if (!ToInt(toks[i].text, f[i - 3])) {
                Error(toks[i], fmt::format("combination record '{}': field '{}' is not an "
                                           "integer",
                                           comb_.name, toks[i].text));
                return;
            }
        }
        comb_.regionId = f[0];
        comb_.aircode = f[1];
        // f: region_id aircode nmemb num material los override r g b m1 m2 inherit
        if (f[6] != 0) comb_.rgb = std::array<int, 3>{f[7], f[8], f[9]};
        comb_.inherit = f[12] != 0;
        inComb_ = true;
        // m1 = 1: a shader-name line follows; m2 = 1: a shader-parameter line follows.
        if (f[10] != 0 && li_ + 1 < lines_.size()) {
            ++li_;
            auto t = Split(lines_[li_].text, 0);
            if (!t.empty()) comb_.shader = std::string(t[0].text);
        }
        if (f[11] != 0 && li_ + 1 < lines_.size()) ++li_;
    }

    void Member4(const std::vector<Token>& toks) {
        if (!inComb_) {
            Error(toks[0], "member record 'M' outside a combination (no 'C' record before it)");
            return;
        }
        if (toks.size() < 3) {
            Error(toks.back(),
                  fmt::format("truncated member record in combination '{}'", comb_.name));
            return;
        }
        Member m;
        std::string_view op = toks[1].text;
        if (op != "u" && op != "+" && op != "-") {
            Error(toks[1], fmt::format("unknown boolean operator '{}' in combination '{}' "
                                       "(expected u, + or -)",
                                       op, comb_.name));
            return;
        }
        m.op = op[0];
        m.name = std::string(toks[2].text);
        m.loc = map_.At(toks[2].offset);
        double v[16];
        if (!Numbers(toks, 3, 16, v,
                     fmt::format("member '{}' of combination '{}'", m.name, comb_.name)))
            return;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) m.matrix.m[r][c] = v[4 * r + c];
        members_.push_back(std::move(m));
    }

    void ColorEntry(const std::vector<Token>& toks) {
        double v[6];
        if (!Numbers(toks, 1, 6, v, "colour table record 'm'")) return;
        // Range checks before any conversion to int (a double beyond int is undefined behaviour,
        // UBSan float-cast-overflow; issue 23): region ids are whole numbers from 0 to 2^31 - 1,
        // colour components whole numbers from 0 to 255.
        static const char* kField[] = {"",    "low region id", "high region id",
                                       "red", "green",         "blue"};
        for (int k = 1; k < 6; ++k) {
            const double hi = k <= 2 ? 2147483647.0 : 255.0;
            if (v[k] != std::floor(v[k]) || v[k] < 0 || v[k] > hi) {
                Error(toks[1 + k], fmt::format("colour table record 'm': {} '{}' is not a whole "
                                               "number from 0 to {}",
                                               kField[k], toks[1 + k].text, hi));
                return;
            }
        }
        ColorTableEntry e;
        e.low = static_cast<int>(v[1]);
        e.high = static_cast<int>(v[2]);
        e.rgb = {static_cast<int>(v[3]), static_cast<int>(v[4]), static_cast<int>(v[5])};
        db_.colorTable.push_back(e);
    }

    void StringSolid(const std::vector<Token>& toks) {
        if (toks.size() < 3) {
            Error(toks.back(), "truncated string solid record: expected 's keyword name ...'");
            return;
        }
        Primitive p;
        p.type = std::string(toks[1].text);
        p.name = std::string(toks[2].text);
        p.loc = map_.At(toks[0].offset);
        p.sourceLine = map_.LineText(toks[0].offset);
        db_.AddPrimitive(std::move(p));
    }

    // ARS (g2asc's arsadump/arsbdump): `A type name m n curlen totlen` — m curves of n points,
    // each curve stored in curlen granules, totlen granules in all — then totlen records
    // `B type curve granule v0 … v23`, 8 points a granule. As in librt's rt_ars_import4, the first
    // point of the first curve is absolute and every other point is relative to it.
    void Ars(const std::vector<Token>& toks) {
        if (inArs_) FinishArs();
        ars_ = {};
        if (toks.size() < 7) {
            Error(toks.back(),
                  "truncated ARS record: expected 'A type name curves "
                  "points_per_curve granules_per_curve granules'");
            return;
        }
        Primitive& p = ars_.prim;
        p.type = "ars";
        p.name = std::string(toks[2].text);
        p.loc = map_.At(toks[0].offset);
        p.sourceLine = map_.LineText(toks[0].offset);
        double v[4];
        if (!Numbers(toks, 3, 4, v, fmt::format("ARS record '{}'", p.name))) return;
        static const char* kField[] = {"number of curves", "points per curve", "granules per curve",
                                       "number of granules"};
        for (int k = 0; k < 4; ++k)
            if (v[k] != std::floor(v[k]) || v[k] < 0 || v[k] > 1e7) {
                Error(toks[3 + k], fmt::format("ARS record '{}': {} '{}' is not a whole number "
                                               "from 0 to 10000000",
                                               p.name, kField[k], toks[3 + k].text));
                return;
            }
        ars_.curves = static_cast<std::size_t>(v[0]);
        ars_.points = static_cast<std::size_t>(v[1]);
        ars_.perCurve = static_cast<std::size_t>(v[2]);
        ars_.granules = static_cast<std::size_t>(v[3]);
        if (ars_.perCurve * 8 < ars_.points || ars_.curves * ars_.perCurve != ars_.granules) {
            Error(toks[5],
                  fmt::format("ARS record '{}': {} curves of {} points do not fit {} "
                              "granules of 8 points ({} a curve)",
                              p.name, ars_.curves, ars_.points, ars_.granules, ars_.perCurve));
            return;
        }
        ars_.ok = true;
        ars_.at = toks[0];
    }

    void ArsGranule(const std::vector<Token>& toks) {
        if (!ars_.ok) return;  // the A record was refused (reported)
        double v[24];
        if (!Numbers(toks, 4, 24, v, fmt::format("ARS granule of '{}'", ars_.prim.name))) {
            ars_.ok = false;
            return;
        }
        if (ars_.values.size() >= ars_.granules * 24) {
            Error(toks[0], fmt::format("ARS '{}' has more than its {} granules", ars_.prim.name,
                                       ars_.granules));
            ars_.ok = false;
            return;
        }
        ars_.values.insert(ars_.values.end(), v, v + 24);
    }

    void FinishArs() {
        inArs_ = false;
        if (!ars_.ok) return;
        if (ars_.values.size() != ars_.granules * 24) {
            Error(ars_.at, fmt::format("ARS '{}' has {} granules (B records), its A record says "
                                       "{}",
                                       ars_.prim.name, ars_.values.size() / 24, ars_.granules));
            return;
        }
        Primitive& p = ars_.prim;
        Vec3 base;
        for (std::size_t i = 0; i < ars_.curves; ++i) {
            std::vector<Vec3> curve;
            for (std::size_t j = 0; j < ars_.points; ++j) {
                const double* q = &ars_.values[(i * ars_.perCurve * 8 + j) * 3];
                Vec3 pt{q[0], q[1], q[2]};
                if (i == 0 && j == 0)
                    base = pt;
                else
                    pt = base + pt;
                curve.push_back(pt);
            }
            p.arsCurves.push_back(std::move(curve));
        }
        db_.AddPrimitive(std::move(p));
        ars_ = {};
    }

    TextMap map_;
    Database& db_;
    Diagnostics& diags_;
    std::vector<Line> lines_;
    std::size_t li_ = 0;
    bool inComb_ = false;
    bool inArs_ = false;
    struct PendingArs {
        bool ok = false;
        Primitive prim;
        Token at;
        std::size_t curves = 0, points = 0, perCurve = 0, granules = 0;
        std::vector<double> values;  // 24 a granule, in the order of the B records
    } ars_;
    Combination comb_;
    std::vector<Member> members_;
};

}  // namespace

// Builds the binary tree of a GIFT member list (db_mkgift_tree): the list is cut at each 'u'
// into union groups, each group a left-to-right chain of '+' (∩) and '-'.
void BuildGiftTree(Combination& comb, const std::vector<GiftMember>& members) {
    int unionRoot = -1;
    int group = -1;
    auto add = [&](TreeNode n) {
        comb.nodes.push_back(std::move(n));
        return static_cast<int>(comb.nodes.size()) - 1;
    };
    auto flush = [&]() {
        if (group < 0) return;
        if (unionRoot < 0) {
            unionRoot = group;
        } else {
            TreeNode u;
            u.op = TreeNode::Op::kUnion;
            u.left = unionRoot;
            u.right = group;
            u.loc = comb.nodes[group].loc;
            unionRoot = add(u);
        }
        group = -1;
    };
    for (std::size_t i = 0; i < members.size(); ++i) {
        const GiftMember& m = members[i];
        TreeNode leaf;
        leaf.name = m.name;
        leaf.matrix = m.matrix;
        leaf.loc = m.loc;
        int l = add(leaf);
        char op = i == 0 ? 'u' : m.op;  // the first operator is treated as union
        if (op == 'u' || group < 0) {
            flush();
            group = l;
        } else {
            TreeNode n;
            n.op = op == '+' ? TreeNode::Op::kIntersection : TreeNode::Op::kDifference;
            n.left = group;
            n.right = l;
            n.loc = m.loc;
            group = add(n);
        }
    }
    flush();
    comb.root = unionRoot;
}

bool ParseV4(std::string_view text, const std::string& file, Database& db, Diagnostics& diags) {
    return V4Reader(text, file, db, diags).Run();
}

}  // namespace quadrix::import::brlcad
