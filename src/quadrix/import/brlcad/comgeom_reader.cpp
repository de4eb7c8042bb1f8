// COMGEOM / GIFT card decks (FORMAT.md §4), the fixed-column form read by comgeom-g:
//   line 1       title
//   line 2       number of solids, number of regions
//   solid table  columns 1-5 the solid number, 6-10 the type, then six 10-column numbers per card
//                from column 11; a solid continues on as many cards as its parameters need
//                (continuation cards leave columns 1-10 blank); trailing columns are comments
//   region table columns 1-5 the region number (blank on continuation cards), then nine
//                7-column fields from column 6, each a 2-character operator ("OR" starts a new
//                union term) and a signed solid number (positive: intersect, negative: subtract);
//                ended by a card "-1"
//   idents       region number, region id, air code, material, los, name
// Regions become combinations "r<N>" (air codes from the ident table); every region is also a
// member of the group "all", the default top object.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>

#include "quadrix/import/brlcad/readers.h"

namespace quadrix::import::brlcad {

namespace {

struct Card {
    std::string_view text;
    std::size_t offset;
};

std::string_view Field(std::string_view line, std::size_t start, std::size_t width) {
    if (start >= line.size()) return {};
    return line.substr(start, std::min(width, line.size() - start));
}

std::string Trim(std::string_view s) {
    std::size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string_view::npos) return {};
    std::size_t b = s.find_last_not_of(" \t\r");
    return std::string(s.substr(a, b - a + 1));
}

class ComgeomReader {
  public:
    ComgeomReader(std::string_view text, const std::string& file, Database& db, Diagnostics& d)
        : map_(text, file), db_(db), diags_(d) {
        std::size_t pos = 0;
        while (pos < text.size()) {
            std::size_t e = text.find('\n', pos);
            if (e == std::string_view::npos) e = text.size();
            std::string_view l = text.substr(pos, e - pos);
            if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
            cards_.push_back({l, pos});
            pos = e + 1;
        }
    }

    bool Run() {
        db_.format = "comgeom";
        if (cards_.size() < 2) return Fail(0, "truncated COMGEOM deck: no counts line");
        db_.title = Trim(cards_[0].text);
        int nSolids = 0, nRegions = 0;
        std::string counts(cards_[1].text);
        if (std::sscanf(counts.c_str(), "%d %d", &nSolids, &nRegions) != 2 || nSolids < 0)
            return Fail(cards_[1].offset, "expected the counts line 'solids regions'");
        std::size_t ci = 2;
        for (int s = 0; s < nSolids; ++s)
            if (!Solid(ci)) return false;
        if (!Regions(ci)) return false;
        Idents(ci);
        Combination all;
        all.name = "all";
        all.loc = map_.At(0);
        std::vector<GiftMember> members;
        for (const auto& [num, name] : regionNames_) {
            GiftMember m;
            m.name = name;
            m.loc = all.loc;
            members.push_back(m);
        }
        BuildGiftTree(all, members);
        db_.AddCombination(std::move(all));
        return !diags_.HasErrors();
    }

  private:
    bool Fail(std::size_t offset, std::string message) {
        diags_.Error(map_.At(offset), std::move(message), map_.LineText(offset));
        return false;
    }

    bool Number(std::string_view field, std::size_t offset, double& v) {
        std::string s = Trim(field);
        if (s.empty()) {
            v = 0;
            return true;
        }
        char* end = nullptr;
        v = std::strtod(s.c_str(), &end);
        if (*end != 0 || !std::isfinite(v))
            return Fail(offset, fmt::format("'{}' is not a number", s));
        return true;
    }

    bool Solid(std::size_t& ci) {
        if (ci >= cards_.size()) return Fail(map_.text().size(), "truncated solid table");
        const Card& c = cards_[ci];
        std::string num = Trim(Field(c.text, 0, 5)), type = Trim(Field(c.text, 5, 5));
        if (num.empty() || type.empty())
            return Fail(c.offset, "expected a solid card (number in columns 1-5, type in 6-10)");
        int nParams = 0;
        if (type == "RPP" || type == "HAF")
            nParams = type == "RPP" ? 6 : 4;
        else if (type == "RCC" || type == "SPH")
            nParams = type == "RCC" ? 7 : 4;
        else if (type == "TRC")
            nParams = 8;
        else if (type == "BOX" || type == "RAW" || type == "REC")
            nParams = 12;
        else if (type == "TEC")
            nParams = 13;
        else if (type == "ARB8")
            nParams = 24;
        else if (type == "ARB7")
            nParams = 21;
        else if (type == "ARB6")
            nParams = 18;
        else if (type == "ARB5")
            nParams = 15;
        else if (type == "ARB4")
            nParams = 12;
        else if (type == "ELL" || type == "ELL1" || type == "TOR")
            nParams = type == "TOR" ? 8 : 7;
        else
            return Fail(c.offset + 5, fmt::format("unknown COMGEOM solid type '{}'", type));
        int nCards = (nParams + 5) / 6;
        std::vector<double> v;
        for (int k = 0; k < nCards; ++k) {
            if (ci >= cards_.size())
                return Fail(map_.text().size(), fmt::format("truncated solid {} ({})", num, type));
            const Card& cc = cards_[ci++];
            if (k > 0 && !Trim(Field(cc.text, 0, 10)).empty())
                return Fail(cc.offset, fmt::format("solid {} ({}) needs {} cards; this card "
                                                   "starts a new solid",
                                                   num, type, nCards));
            for (int f = 0; f < 6; ++f) {
                double x = 0;
                if (!Number(Field(cc.text, 10 + 10 * f, 10), cc.offset + 10 + 10 * f, x))
                    return false;
                v.push_back(x);
            }
        }
        Primitive p;
        p.name = "s" + num;
        p.loc = map_.At(c.offset);
        p.sourceLine = map_.LineText(c.offset);
        auto vec = [&](int i) { return Vec3{v[i], v[i + 1], v[i + 2]}; };
        if (type == "RPP") {
            Vec3 lo{v[0], v[2], v[4]}, hi{v[1], v[3], v[5]};
            p.type = "arb8";
            p.pts = {Vec3{lo.x, lo.y, lo.z}, Vec3{hi.x, lo.y, lo.z}, Vec3{hi.x, hi.y, lo.z},
                     Vec3{lo.x, hi.y, lo.z}, Vec3{lo.x, lo.y, hi.z}, Vec3{hi.x, lo.y, hi.z},
                     Vec3{hi.x, hi.y, hi.z}, Vec3{lo.x, hi.y, hi.z}};
        } else if (type == "BOX" || type == "RAW") {
            Vec3 o = vec(0), a = vec(3), b = vec(6), cc = vec(9);
            p.type = "arb8";
            p.pts = {o, o + a, o + a + b, o + b, o + cc, o + a + cc, o + a + b + cc, o + b + cc};
        } else if (type == "RCC" || type == "TRC") {
            Vec3 h = vec(3);
            double r1 = v[6], r2 = type == "TRC" ? v[7] : v[6];
            Vec3 hh = Normalize(h);
            Vec3 t = std::fabs(hh.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            Vec3 a = Normalize(Cross(hh, t)), b = Cross(hh, a);
            p.type = "tgc";
            p.V = vec(0), p.H = h, p.A = a * r1, p.B = b * r1, p.C = a * r2, p.D = b * r2;
        } else if (type == "REC" || type == "TEC") {
            p.type = "tgc";
            p.V = vec(0), p.H = vec(3), p.A = vec(6), p.B = vec(9);
            double ratio = type == "TEC" ? v[12] : 1;
            p.C = p.A * ratio, p.D = p.B * ratio;
        } else if (type == "SPH") {
            p.type = "ell";
            p.V = vec(0), p.A = {v[3], 0, 0}, p.B = {0, v[3], 0}, p.C = {0, 0, v[3]};
        } else if (type == "ELL" || type == "ELL1") {
            // Ellipsoids of revolution (comgeom-g's GIFT forms): ELL gives the two foci F1, F2
            // and the length L of the major axis; ELL1 the centre V, the semi-major axis vector A
            // and the radius r of the circle of revolution. For ELL the centre is the foci's
            // midpoint, the semi-major axis L/2 along F2 − F1, and the minor radius
            // √((L/2)² − c²) with c half the foci's distance.
            Vec3 centre, axis;
            double minor = 0;
            if (type == "ELL") {
                const Vec3 f1 = vec(0), f2 = vec(3);
                const double half = 0.5 * v[6], focal = 0.5 * Length(f2 - f1);
                if (!(half > focal) || !(half > 0))
                    return Fail(c.offset, fmt::format("solid {} (ELL): the major axis length {} "
                                                      "must exceed the foci's distance {}",
                                                      num, v[6], 2 * focal));
                centre = (f1 + f2) * 0.5;
                axis = focal > 0 ? Normalize(f2 - f1) * half : Vec3{half, 0, 0};
                minor = std::sqrt(half * half - focal * focal);
            } else {
                centre = vec(0);
                axis = vec(3);
                minor = v[6];
                if (!(Length(axis) > 0) || !(minor > 0))
                    return Fail(c.offset, fmt::format("solid {} (ELL1): the axis vector and the "
                                                      "radius must be non-zero",
                                                      num));
            }
            const Vec3 u = Normalize(axis);
            const Vec3 t = std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            const Vec3 b = Normalize(Cross(u, t)), cc = Cross(u, b);
            p.type = "ell";
            p.V = centre, p.A = axis, p.B = b * minor, p.C = cc * minor;
        } else if (type == "HAF") {
            p.type = "half";
            p.N = vec(0), p.d = v[3];
        } else if (type.substr(0, 3) == "ARB") {
            // arb4..arb7 vertex lists expand to eight as mged's arb<n> do.
            int n = type[3] - '0';
            std::vector<Vec3> q;
            for (int k = 0; k < n; ++k) q.push_back(vec(3 * k));
            static const int kExpand[5][8] = {{0, 1, 2, 0, 3, 3, 3, 3},   // arb4
                                              {0, 1, 2, 3, 4, 4, 4, 4},   // arb5
                                              {0, 1, 2, 3, 4, 4, 5, 5},   // arb6
                                              {0, 1, 2, 3, 4, 5, 6, 4},   // arb7
                                              {0, 1, 2, 3, 4, 5, 6, 7}};  // arb8
            p.type = "arb8";
            for (int k = 0; k < 8; ++k) p.pts[k] = q[kExpand[n - 4][k]];
        } else {
            p.type = Trim(type);  // TOR: reported, not drawn
            for (char& ch : p.type) ch = static_cast<char>(std::tolower(ch));
        }
        db_.AddPrimitive(std::move(p));
        return true;
    }

    bool Regions(std::size_t& ci) {
        Combination* cur = nullptr;
        std::vector<GiftMember> members;
        auto finish = [&]() {
            if (!cur) return;
            BuildGiftTree(*cur, members);
            members.clear();
            db_.AddCombination(std::move(*cur));
            pending_.reset();
            cur = nullptr;
        };
        for (; ci < cards_.size(); ++ci) {
            const Card& c = cards_[ci];
            if (Trim(c.text).empty()) continue;
            std::string num = Trim(Field(c.text, 0, 5));
            if (num == "-1") {
                finish();
                ++ci;
                return true;
            }
            if (!num.empty()) {
                finish();
                pending_.emplace();
                cur = &*pending_;
                cur->name = "r" + num;
                cur->region = true;
                cur->loc = map_.At(c.offset);
                cur->sourceLine = map_.LineText(c.offset);
                regionNames_.emplace_back(std::atoi(num.c_str()), cur->name);
                regionIndex_[std::atoi(num.c_str())] = cur->name;
            } else if (!cur) {
                return Fail(c.offset, "region continuation card before any region card");
            }
            // The nine 7-column fields hold "OR" and signed solid numbers; decks differ in how
            // they align them inside the fields (ADA073408 left-aligns), so the field area
            // (columns 6-68) is read as whitespace-separated tokens.
            bool newTerm = members.empty();
            std::string_view area = Field(c.text, 5, 63);
            std::size_t k = 0;
            while (k < area.size()) {
                while (k < area.size() && area[k] == ' ') ++k;
                std::size_t s0 = k;
                while (k < area.size() && area[k] != ' ') ++k;
                if (k == s0) break;
                std::string tok(area.substr(s0, k - s0));
                std::size_t at = 5 + s0;
                if (tok.rfind("OR", 0) == 0) {
                    newTerm = true;
                    tok = tok.substr(2);
                    at += 2;
                    if (tok.empty()) continue;
                }
                char* end = nullptr;
                long solid = std::strtol(tok.c_str(), &end, 10);
                if (*end != 0)
                    return Fail(c.offset + at,
                                fmt::format("'{}' is not a solid number or OR", tok));
                if (solid == 0) continue;
                GiftMember m;
                m.op = newTerm ? 'u' : (solid > 0 ? '+' : '-');
                m.name = fmt::format("s{}", std::labs(solid));
                m.loc = map_.At(c.offset + at);
                if (newTerm && solid < 0)
                    return Fail(c.offset + at, "a union term cannot start with a subtraction");
                newTerm = false;
                members.push_back(std::move(m));
            }
        }
        finish();
        return Fail(map_.text().size(), "truncated region table: no '-1' card");
    }

    void Idents(std::size_t ci) {
        for (; ci < cards_.size(); ++ci) {
            std::string line(cards_[ci].text);
            int region = 0, id = 0, air = 0, mat = 0, los = 0;
            if (std::sscanf(line.c_str(), "%d %d %d %d %d", &region, &id, &air, &mat, &los) != 5)
                continue;
            auto it = regionIndex_.find(region);
            if (it == regionIndex_.end()) continue;
            auto obj = db_.objects.find(it->second);
            if (obj == db_.objects.end() || !obj->second.first) continue;
            Combination& c = db_.combinations[obj->second.second];
            c.regionId = id;
            c.aircode = air;
        }
    }

    TextMap map_;
    Database& db_;
    Diagnostics& diags_;
    std::vector<Card> cards_;
    std::optional<Combination> pending_;
    std::vector<std::pair<int, std::string>> regionNames_;
    std::map<int, std::string> regionIndex_;
};

}  // namespace

bool ParseComgeom(std::string_view text, const std::string& file, Database& db,
                  Diagnostics& diags) {
    return ComgeomReader(text, file, db, diags).Run();
}

}  // namespace quadrix::import::brlcad
