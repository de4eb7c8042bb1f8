// The v5 ASCII format (FORMAT.md §3): a Tcl script of title/units/attr/color/put commands.
// A command ends at a newline (or ';') outside braces, so a command may span lines. Words are
// bare, "quoted" or {braced} (nesting counted, braces kept inside). Vectors are {x y z} lists and
// combination trees are nested prefix lists ({u L R}, {n L R}, {- L R}, {l name [matrix]}).
// Every word keeps its offset in the file, so sub-lists (tree nodes, vector components) are
// reported at their own line and column.
#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <unordered_map>
#include <vector>

#include "quadrix/import/brlcad/readers.h"

namespace quadrix::import::brlcad {

namespace {

struct Word {
    std::string_view text;   // braces and quotes removed
    std::size_t offset = 0;  // offset of the word's first character (the brace, if any)
    bool braced = false;
};

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

class V5Reader {
  public:
    V5Reader(std::string_view text, const std::string& file, Database& db, Diagnostics& diags)
        : map_(text, file), db_(db), diags_(diags) {}

    bool Run() {
        db_.format = "v5";
        std::string_view t = map_.text();
        std::size_t i = 0;
        while (i < t.size() && diags_.ErrorCount() < 50) {
            std::vector<Word> words;
            if (!Command(i, words)) break;
            if (!words.empty()) Dispatch(words);
        }
        ApplyAttributes();
        return !diags_.HasErrors();
    }

  private:
    void Error(std::size_t offset, std::string message) {
        diags_.Error(map_.At(offset), std::move(message), map_.LineText(offset));
    }

    // Reads one word starting at t[i] (not a space); false after reporting an error.
    // `inList`: inside a braced list ';' is an ordinary character (at command level it ends the
    // command).
    bool ReadWord(std::string_view t, std::size_t base, std::size_t& i, Word& w,
                  bool inList = false) {
        w.offset = base + i;
        if (t[i] == '{') {
            // The matching brace: counted from here (a backslash escapes the next character),
            // recording the match of every brace opened on the way (braceEnd_), so that the
            // nested words List reads later find their ends at once. Without it a combination
            // tree, a chain of nested lists, was scanned again at every level (its text times its
            // depth: most of reading a model with long unions). The matches are kept by offset in
            // the file's text, which every word's text is a view of (`base` is the offset used in
            // messages, one short for the content of a quoted word).
            const std::size_t s = i;
            const auto origin = static_cast<std::size_t>(t.data() - map_.text().data());
            const auto known = braceEnd_.find(origin + s);
            if (known != braceEnd_.end() && known->second - origin < t.size()) {
                i = known->second - origin;
            } else {
                std::vector<std::size_t>& open = openBraces_;
                open.clear();
                for (; i < t.size(); ++i) {
                    if (t[i] == '\\') {
                        ++i;
                        continue;
                    }
                    if (t[i] == '{') open.push_back(i);
                    if (t[i] == '}' && !open.empty()) {
                        braceEnd_[origin + open.back()] = origin + i;
                        open.pop_back();
                        if (open.empty()) break;
                    }
                }
            }
            if (i >= t.size()) {
                Error(base + s, "unbalanced '{': the brace is never closed");
                return false;
            }
            w.text = t.substr(s + 1, i - s - 1);
            w.braced = true;
            ++i;
            return true;
        }
        if (t[i] == '"') {
            std::size_t s = ++i;
            while (i < t.size() && t[i] != '"') i += t[i] == '\\' ? 2 : 1;
            if (i >= t.size()) {
                Error(base + s - 1, "unterminated '\"'");
                return false;
            }
            w.text = t.substr(s, i - s);
            ++i;
            return true;
        }
        std::size_t s = i;
        while (i < t.size() && !IsSpace(t[i]) && (inList || t[i] != ';')) ++i;
        if (i == s) ++i;  // never stall on a character that cannot start a word
        w.text = t.substr(s, i - s);
        return true;
    }

    bool Command(std::size_t& i, std::vector<Word>& words) {
        std::string_view t = map_.text();
        while (i < t.size() && (IsSpace(t[i]) || t[i] == ';')) ++i;
        if (i < t.size() && t[i] == '#') {
            while (i < t.size() && t[i] != '\n') ++i;
            return true;
        }
        while (i < t.size()) {
            while (i < t.size() && (t[i] == ' ' || t[i] == '\t' || t[i] == '\r')) ++i;
            if (i >= t.size() || t[i] == '\n' || t[i] == ';') break;
            if (t[i] == '\\' && i + 1 < t.size() && t[i + 1] == '\n') {  // line continuation
                i += 2;
                continue;
            }
            Word w;
            if (!ReadWord(t, 0, i, w)) return false;
            words.push_back(w);
        }
        return true;
    }

    // Splits the content of a braced word into list elements.
    std::optional<std::vector<Word>> List(const Word& w) {
        std::vector<Word> out;
        std::size_t base = w.offset + (w.braced ? 1 : 0);
        std::string_view t = w.text;
        std::size_t i = 0;
        while (true) {
            while (i < t.size() && IsSpace(t[i])) ++i;
            if (i >= t.size()) break;
            Word e;
            if (!ReadWord(t, base, i, e, true)) return std::nullopt;
            out.push_back(e);
        }
        return out;
    }

    bool Number(const Word& w, double& v, const std::string& what) {
        std::string s(w.text);
        char* end = nullptr;
        v = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) {
            Error(w.offset, fmt::format("{}: '{}' is not a finite number", what, w.text));
            return false;
        }
        return true;
    }

    // `v` (already a finite number read from `w`) is a whole number in [lo, hi]; else an error at
    // `w`. Checked before a conversion to int, which is undefined beyond int's range.
    bool WholeNumberIn(const Word& w, double v, double lo, double hi, const std::string& what) {
        if (v == std::floor(v) && v >= lo && v <= hi) return true;
        Error(w.offset,
              fmt::format("{}: '{}' is not a whole number from {} to {}", what, w.text, lo, hi));
        return false;
    }

    bool Vector(const Word& w, Vec3& v, const std::string& what) {
        auto l = List(w);
        if (!l) return false;
        if (l->size() != 3) {
            Error(w.offset,
                  fmt::format("{}: expected a vector {{x y z}}, found {} values", what, l->size()));
            return false;
        }
        for (int k = 0; k < 3; ++k)
            if (!Number((*l)[k], v[k], what)) return false;
        return true;
    }

    void Dispatch(const std::vector<Word>& w) {
        std::string_view cmd = w[0].text;
        if (cmd == "title") {
            if (w.size() > 1) db_.title = std::string(w[1].text);
        } else if (cmd == "units") {
            // Display unit only: lengths in the file are always millimetres (FORMAT.md §3.1).
        } else if (cmd == "color") {
            ColorCmd(w);
        } else if (cmd == "attr") {
            Attr(w);
        } else if (cmd == "put") {
            Put(w);
        } else {
            Error(w[0].offset, fmt::format("unknown command '{}' (a v5 ASCII database holds only "
                                           "title, units, attr, color and put)",
                                           cmd));
        }
    }

    void ColorCmd(const std::vector<Word>& w) {
        if (w.size() != 6) {
            Error(w[0].offset, "color: expected 'color low high r g b'");
            return;
        }
        double v[5];
        for (int k = 0; k < 5; ++k)
            if (!Number(w[k + 1], v[k], "color")) return;
        // Range checks before any conversion to int (UBSan float-cast-overflow; issue 23).
        static const char* kField[] = {"low region id", "high region id", "red", "green", "blue"};
        for (int k = 0; k < 5; ++k)
            if (!WholeNumberIn(w[k + 1], v[k], 0, k < 2 ? 2147483647.0 : 255.0,
                               fmt::format("color: {}", kField[k])))
                return;
        db_.colorTable.push_back(
            {static_cast<int>(v[0]),
             static_cast<int>(v[1]),
             {static_cast<int>(v[2]), static_cast<int>(v[3]), static_cast<int>(v[4])}});
    }

    void Attr(const std::vector<Word>& w) {
        if (w.size() < 3 || w[1].text != "set") return;  // attr rm/append/...: no geometry
        if ((w.size() - 3) % 2 != 0) {
            Error(w.back().offset,
                  fmt::format("attr set {{{}}}: attribute without a value", w[2].text));
            return;
        }
        auto& attrs = attrs_[std::string(w[2].text)];
        for (std::size_t k = 3; k + 1 < w.size(); k += 2)
            attrs.push_back({std::string(w[k].text), w[k + 1]});
    }

    void Put(const std::vector<Word>& w) {
        if (w.size() < 3) {
            Error(w[0].offset, "put: expected 'put {name} type key value ...'");
            return;
        }
        std::string name(w[1].text), type(w[2].text);
        if ((w.size() - 3) % 2 != 0) {
            Error(w.back().offset,
                  fmt::format("put {{{}}}: key '{}' has no value", name, w.back().text));
            return;
        }
        std::map<std::string, Word> kv;
        for (std::size_t k = 3; k + 1 < w.size(); k += 2) kv[std::string(w[k].text)] = w[k + 1];
        if (type == "comb") {
            PutComb(w, name, kv);
            return;
        }
        Primitive p;
        p.type = type;
        p.name = name;
        p.loc = map_.At(w[0].offset);
        p.sourceLine = map_.LineText(w[0].offset);
        std::string what = fmt::format("primitive '{}' ({})", name, type);
        bool ok = true;
        auto vec = [&](const char* key, Vec3& out) {
            if (!ok) return;
            auto it = kv.find(key);
            if (it == kv.end()) {
                Error(w[0].offset, fmt::format("{}: missing parameter '{}'", what, key));
                ok = false;
                return;
            }
            ok = Vector(it->second, out, what + " " + key);
        };
        auto num = [&](const char* key, double& out) {
            if (!ok) return;
            auto it = kv.find(key);
            if (it == kv.end()) {
                Error(w[0].offset, fmt::format("{}: missing parameter '{}'", what, key));
                ok = false;
                return;
            }
            ok = Number(it->second, out, what + " " + key);
        };
        if (type.size() == 4 && type.substr(0, 3) == "arb" && type[3] >= '4' && type[3] <= '8') {
            p.type = "arb8";
            for (int k = 0; k < 8; ++k) {
                std::string key = fmt::format("V{}", k + 1);
                vec(key.c_str(), p.pts[k]);
            }
        } else if (type == "tgc") {
            vec("V", p.V), vec("H", p.H), vec("A", p.A), vec("B", p.B), vec("C", p.C),
                vec("D", p.D);
        } else if (type == "ell") {
            vec("V", p.V), vec("A", p.A), vec("B", p.B), vec("C", p.C);
        } else if (type == "half") {
            vec("N", p.N), num("d", p.d);
        } else if (type == "rpc" || type == "rhc") {
            vec("V", p.V), vec("H", p.H), vec("B", p.B), num("r", p.r);
            if (type == "rhc") num("c", p.c);
        } else if (type == "epa" || type == "ehy") {
            vec("V", p.V), vec("H", p.H), vec("A", p.A), num("r_1", p.r1), num("r_2", p.r2);
            if (type == "ehy") num("c", p.c);
        } else if (type == "hyp") {
            vec("V", p.V), vec("H", p.H), vec("A", p.A), num("b", p.b), num("bnr", p.bnr);
        } else if (type == "part") {
            vec("V", p.V), vec("H", p.H), num("r_v", p.rv), num("r_h", p.rh);
        } else if (type == "tor") {
            vec("V", p.V), vec("H", p.H), num("r_a", p.r1), num("r_h", p.r2);
        } else if (type == "eto") {
            vec("V", p.V), vec("N", p.N), vec("C", p.C), num("r", p.r), num("r_d", p.rd);
        } else if (type == "pipe") {
            // V<k> {x y z} O<k> od I<k> id R<k> bend, k = 0, 1, ... while V<k> is present.
            for (int k = 0; ok && kv.count(fmt::format("V{}", k)); ++k) {
                Primitive::PipePoint pt;
                const std::string v = fmt::format("V{}", k), o = fmt::format("O{}", k),
                                  i = fmt::format("I{}", k), r = fmt::format("R{}", k);
                vec(v.c_str(), pt.at), num(o.c_str(), pt.od), num(i.c_str(), pt.id),
                    num(r.c_str(), pt.bend);
                p.pipe.push_back(pt);
            }
        } else if (type == "bot") {
            ok = Bot(w, kv, what, p);
        } else if (type == "ars") {
            ok = Ars(w, kv, what, p);
        } else if (type == "arbn") {
            double n = 0;
            num("N", n);
            // Every plane is a key P0 … P(N-1) of this command, so N cannot exceed their count.
            if (ok) {
                auto nWord = kv.find("N");
                if (nWord != kv.end())
                    ok = WholeNumberIn(nWord->second, n, 0, static_cast<double>(kv.size()),
                                       what + " N");
            }
            for (int k = 0; ok && k < static_cast<int>(n); ++k) {
                std::string key = fmt::format("P{}", k);
                auto it = kv.find(key);
                if (it == kv.end()) {
                    Error(w[0].offset, fmt::format("{}: missing plane '{}'", what, key));
                    ok = false;
                    break;
                }
                auto l = List(it->second);
                double c[4];
                if (!l || l->size() != 4) {
                    Error(it->second.offset, fmt::format("{} {}: expected {{a b c d}}", what, key));
                    ok = false;
                    break;
                }
                for (int j = 0; ok && j < 4; ++j) ok = Number((*l)[j], c[j], what);
                if (ok) p.planes.push_back(Plane{c[0], c[1], c[2], -c[3]});
            }
        }
        if (ok) db_.AddPrimitive(std::move(p));
    }

    // ars (librt's rt_ars_get): NC curves, PPC points a curve, C0 … C(NC-1) each a list of PPC
    // points, written {x y z} each or as 3·PPC plain numbers.
    bool Ars(const std::vector<Word>& w, const std::map<std::string, Word>& kv,
             const std::string& what, Primitive& p) {
        // NC cannot exceed the number of keys (each curve is one); PPC is bounded by the text.
        auto count = [&](const char* key, double hi, double& v) {
            auto it = kv.find(key);
            if (it == kv.end()) {
                Error(w[0].offset, fmt::format("{}: missing parameter '{}'", what, key));
                return false;
            }
            return Number(it->second, v, what + " " + key) &&
                   WholeNumberIn(it->second, v, 0, hi, what + " " + key);
        };
        double nc = 0, ppc = 0;
        if (!count("NC", static_cast<double>(kv.size()), nc) || !count("PPC", 1e7, ppc))
            return false;
        for (int i = 0; i < static_cast<int>(nc); ++i) {
            const std::string key = fmt::format("C{}", i);
            auto it = kv.find(key);
            if (it == kv.end()) {
                Error(w[0].offset, fmt::format("{}: missing curve '{}'", what, key));
                return false;
            }
            auto l = List(it->second);
            if (!l) return false;
            std::vector<Vec3> curve;
            if (!l->empty() && (*l)[0].braced) {
                for (const Word& v : *l) {
                    Vec3 x;
                    if (!Vector(v, x, what + " " + key)) return false;
                    curve.push_back(x);
                }
            } else {
                if (l->size() % 3 != 0) {
                    Error(it->second.offset, fmt::format("{} {}: {} numbers are not whole points "
                                                         "(x y z)",
                                                         what, key, l->size()));
                    return false;
                }
                for (std::size_t k = 0; k < l->size(); k += 3) {
                    Vec3 x;
                    for (int c = 0; c < 3; ++c)
                        if (!Number((*l)[k + c], x[c], what + " " + key)) return false;
                    curve.push_back(x);
                }
            }
            if (curve.size() != static_cast<std::size_t>(ppc)) {
                Error(it->second.offset,
                      fmt::format("{} {}: {} points, PPC says {}", what, key, curve.size(), ppc));
                return false;
            }
            p.arsCurves.push_back(std::move(curve));
        }
        return true;
    }

    // bot: mode surf|volume|plate|plate_nocos (or 1-4), orient no|rh|lh (or 1-3), V {{x y z}
    // ...}, F {{a b c} ...}, in plate modes T {t ...} and fm (hex bit vector, bit i = face i
    // appended).
    bool Bot(const std::vector<Word>& w, const std::map<std::string, Word>& kv,
             const std::string& what, Primitive& p) {
        auto word = [&](const char* key) -> const Word* {
            auto it = kv.find(key);
            return it == kv.end() ? nullptr : &it->second;
        };
        const Word* mode = word("mode");
        const Word* orient = word("orient");
        const Word* verts = word("V");
        const Word* faces = word("F");
        if (!mode || !verts || !faces) {
            Error(w[0].offset, fmt::format("{}: a bot needs mode, V and F", what));
            return false;
        }
        static const std::map<std::string_view, int> kModes = {
            {"surf", 1}, {"volume", 2}, {"plate", 3}, {"plate_nocos", 4},
            {"1", 1},    {"2", 2},      {"3", 3},     {"4", 4}};
        static const std::map<std::string_view, int> kOrients = {{"no", 1}, {"rh", 2}, {"lh", 3},
                                                                 {"1", 1},  {"2", 2},  {"3", 3}};
        auto m = kModes.find(mode->text);
        if (m == kModes.end()) {
            Error(mode->offset, fmt::format("{}: unknown bot mode '{}' (surf, volume, plate or "
                                            "plate_nocos)",
                                            what, mode->text));
            return false;
        }
        p.botMode = m->second;
        if (orient) {
            auto o = kOrients.find(orient->text);
            if (o == kOrients.end()) {
                Error(orient->offset, fmt::format("{}: unknown bot orientation '{}' (no, rh or lh)",
                                                  what, orient->text));
                return false;
            }
            p.botOrientation = o->second;
        }
        auto vl = List(*verts);
        if (!vl) return false;
        for (const Word& v : *vl) {
            Vec3 x;
            if (!Vector(v, x, what + " V")) return false;
            p.vertices.push_back(x);
        }
        auto fl = List(*faces);
        if (!fl) return false;
        for (const Word& f : *fl) {
            Vec3 x;
            if (!Vector(f, x, what + " F")) return false;
            std::array<int, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                if (x[k] != std::floor(x[k]) || x[k] < 0 ||
                    x[k] >= static_cast<double>(p.vertices.size())) {
                    Error(f.offset, fmt::format("{}: face vertex {} is not one of the {} vertices",
                                                what, x[k], p.vertices.size()));
                    return false;
                }
                tri[k] = static_cast<int>(x[k]);
            }
            p.faces.push_back(tri);
        }
        if (p.botMode >= 3) {
            const Word* t = word("T");
            auto tl = t ? List(*t) : std::optional<std::vector<Word>>{};
            if (!tl || tl->size() != p.faces.size()) {
                Error(
                    t ? t->offset : w[0].offset,
                    fmt::format("{}: a plate-mode bot needs T with one thickness per face", what));
                return false;
            }
            for (const Word& x : *tl) {
                double th = 0;
                if (!Number(x, th, what + " T")) return false;
                p.thickness.push_back(th);
            }
            p.faceAppended.assign(p.faces.size(), 0);
            if (const Word* fm = word("fm")) {
                // bu_bitv hex: the last hex digit holds bits 0-3.
                std::string_view hex = fm->text;
                if (hex.substr(0, 2) == "0x" || hex.substr(0, 2) == "0X") hex.remove_prefix(2);
                for (std::size_t i = 0; i < hex.size(); ++i) {
                    char ch = hex[hex.size() - 1 - i];
                    int v = std::isdigit(static_cast<unsigned char>(ch)) ? ch - '0'
                            : (ch | 32) >= 'a' && (ch | 32) <= 'f'       ? (ch | 32) - 'a' + 10
                                                                         : -1;
                    if (v < 0) {
                        Error(fm->offset,
                              fmt::format("{}: fm '{}' is not hexadecimal", what, fm->text));
                        return false;
                    }
                    for (int b = 0; b < 4; ++b)
                        if (v >> b & 1 && 4 * i + b < p.faces.size()) p.faceAppended[4 * i + b] = 1;
                }
            }
        }
        return true;
    }

    // Deepest combination tree accepted. The parser below keeps its own stack (no recursion,
    // so no stack overflow at any depth, issue 23); the limit protects the importer, which walks
    // trees recursively (brlcad_import.cpp, kMaxTreeDepth over all combinations together).
    static constexpr int kMaxTreeDepth = 2000;

    // Parses a tree list into comb.nodes (children before their parent); returns the root's node
    // index or -1 on error. Iterative: an operator waiting for its operands sits on `pending`.
    int Tree(const Word& root, Combination& comb) {
        struct Pending {
            TreeNode node;
            Word left, right;
            int depth;
            bool leftDone = false;
        };
        std::vector<Pending> pending;
        // Starts the subtree at `w`: a leaf's node index, kOperator when an operator was pushed
        // on `pending`, or -1 on error.
        constexpr int kOperator = -2;
        auto start = [&](const Word& w, int depth) -> int {
            if (depth > kMaxTreeDepth) {
                Error(w.offset, fmt::format("combination '{}': tree nested deeper than {} levels",
                                            comb.name, kMaxTreeDepth));
                return -1;
            }
            TreeNode n;
            n.loc = map_.At(w.offset);
            Word left, right;
            const int r = TreeNodeOf(w, comb, n, left, right);
            if (r < 0) return -1;
            if (r == 1) {
                pending.push_back({std::move(n), left, right, depth});
                return kOperator;
            }
            comb.nodes.push_back(std::move(n));
            return static_cast<int>(comb.nodes.size()) - 1;
        };
        int r = start(root, 0);
        while (r != -1) {
            if (r == kOperator) {  // descend into the new operator's left operand
                const Word w = pending.back().left;
                r = start(w, pending.back().depth + 1);
                continue;
            }
            if (pending.empty()) return r;  // the root is complete
            Pending& p = pending.back();
            if (!p.leftDone) {
                p.node.left = r;
                p.leftDone = true;
                const Word w = p.right;
                r = start(w, p.depth + 1);
                continue;
            }
            p.node.right = r;
            comb.nodes.push_back(std::move(p.node));
            pending.pop_back();
            r = static_cast<int>(comb.nodes.size()) - 1;
        }
        return -1;
    }

    // One node of a tree list: fills `n` and returns 0 for a leaf; sets n.op and the two operand
    // words and returns 1 for an operator; -1 after reporting an error.
    int TreeNodeOf(const Word& w, Combination& comb, TreeNode& n, Word& left, Word& right) {
        auto l = List(w);
        if (!l) return -1;
        if (l->empty()) {
            Error(w.offset, fmt::format("combination '{}': empty tree node", comb.name));
            return -1;
        }
        const std::vector<Word>& e = *l;
        std::string_view op = e[0].text;
        if (op == "l") {
            if (e.size() < 2 || e.size() > 3) {
                Error(w.offset,
                      fmt::format("combination '{}': a leaf is {{l name [matrix]}}", comb.name));
                return -1;
            }
            n.name = std::string(e[1].text);
            n.loc = map_.At(e[1].offset);
            if (e.size() == 3 && e[2].text != "I") {
                auto m = List(e[2]);
                if (!m) return -1;
                if (m->size() != 16) {
                    Error(e[2].offset, fmt::format("combination '{}': member '{}' has a matrix "
                                                   "of {} numbers (expected 16)",
                                                   comb.name, n.name, m->size()));
                    return -1;
                }
                for (int k = 0; k < 16; ++k)
                    if (!Number((*m)[k], n.matrix.m[k / 4][k % 4], "matrix")) return -1;
            }
            return 0;
        }
        if (op == "u" || op == "n" || op == "+" || op == "-") {
            if (e.size() != 3) {
                Error(w.offset, fmt::format("combination '{}': operator '{}' needs two operands, "
                                            "found {}",
                                            comb.name, op, e.size() - 1));
                return -1;
            }
            n.op = op == "u"   ? TreeNode::Op::kUnion
                   : op == "-" ? TreeNode::Op::kDifference
                               : TreeNode::Op::kIntersection;
            left = e[1];
            right = e[2];
            return 1;
        }
        Error(e[0].offset, fmt::format("combination '{}': unsupported tree operator '{}' "
                                       "(supported: l u n - ; xor and not are not)",
                                       comb.name, op));
        return -1;
    }

    static std::optional<std::array<int, 3>> ParseRgb(std::string_view s) {
        std::string str(s);
        for (char& c : str)
            if (c == '/' || c == ',') c = ' ';
        int r = 0, g = 0, b = 0;
        char extra = 0;
        if (std::sscanf(str.c_str(), "%d %d %d %c", &r, &g, &b, &extra) != 3) return std::nullopt;
        return std::array<int, 3>{r, g, b};
    }

    void PutComb(const std::vector<Word>& w, const std::string& name,
                 const std::map<std::string, Word>& kv) {
        Combination c;
        c.name = name;
        c.loc = map_.At(w[0].offset);
        c.sourceLine = map_.LineText(w[0].offset);
        if (auto it = kv.find("region"); it != kv.end())
            c.region = it->second.text == "yes" || it->second.text == "1" || it->second.text == "R";
        auto tree = kv.find("tree");
        if (tree == kv.end()) {
            Error(w[0].offset, fmt::format("combination '{}' has no tree", name));
            return;
        }
        auto trimmed = tree->second.text;
        while (!trimmed.empty() && IsSpace(trimmed.front())) trimmed.remove_prefix(1);
        if (!trimmed.empty()) {
            c.root = Tree(tree->second, c);
            if (c.root < 0) return;
        }
        for (const auto& [k, v] : kv) SetCombAttr(c, k, v);
        db_.AddCombination(std::move(c));
    }

    void SetCombAttr(Combination& c, const std::string& key, const Word& v) {
        double num = 0;
        if (key == "region") {
            c.region = c.region || v.text == "R" || v.text == "yes" || v.text == "1";
        } else if (key == "region_id" || key == "id") {
            const std::string what = fmt::format("combination '{}' {}", c.name, key);
            if (Number(v, num, what) && WholeNumberIn(v, num, -2147483647.0, 2147483647.0, what))
                c.regionId = static_cast<int>(num);
        } else if (key == "aircode" || key == "air") {
            const std::string what = fmt::format("combination '{}' {}", c.name, key);
            if (Number(v, num, what) && WholeNumberIn(v, num, -2147483647.0, 2147483647.0, what))
                c.aircode = static_cast<int>(num);
        } else if (key == "rgb" || key == "color") {
            auto rgb = ParseRgb(v.text);
            if (!rgb) {
                Error(v.offset,
                      fmt::format("combination '{}': colour '{}' is not r/g/b", c.name, v.text));
                return;
            }
            c.rgb = rgb;
        } else if (key == "inherit") {
            c.inherit = v.text == "1" || v.text == "yes";
        } else if (key == "oshader" || key == "shader") {
            auto l = List(v);
            if (l && !l->empty()) c.shader = std::string((*l)[0].text);
        }
    }

    void ApplyAttributes() {
        for (const auto& [name, attrs] : attrs_) {
            auto it = db_.objects.find(name);
            if (it == db_.objects.end() || !it->second.first) continue;
            Combination& c = db_.combinations[it->second.second];
            for (const auto& [k, v] : attrs) SetCombAttr(c, k, v);
        }
    }

    TextMap map_;
    // ReadWord's matches: the file offset of a '{' to that of its '}', and its scratch stack.
    std::unordered_map<std::size_t, std::size_t> braceEnd_;
    std::vector<std::size_t> openBraces_;
    Database& db_;
    Diagnostics& diags_;
    std::map<std::string, std::vector<std::pair<std::string, Word>>> attrs_;
};

}  // namespace

bool ParseV5(std::string_view text, const std::string& file, Database& db, Diagnostics& diags) {
    return V5Reader(text, file, db, diags).Run();
}

}  // namespace quadrix::import::brlcad
