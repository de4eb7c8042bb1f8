// The BRL-CAD binary v5 database (".g") → Database; the layout is written out in g_format.h.
//
// Every read is bounds-checked against the object it belongs to, so a truncated or corrupt file
// gives an error naming the byte offset (and the object, once its name is known), never a read
// past the end. Positions: a binary file has no lines, so diagnostics name "file" and the message
// names the byte offset; Primitive/Combination::byteOffset keep it for the converter's messages.
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <map>

#include "quadrix/import/brlcad/g_format.h"
#include "quadrix/import/brlcad/readers.h"

namespace quadrix::import::brlcad {

namespace {

using namespace g5;

// A bounds-checked big-endian cursor over [begin, end) of the file.
class Cursor {
  public:
    Cursor(std::string_view data, std::size_t begin, std::size_t end)
        : d_(data), pos_(begin), end_(end) {}
    std::size_t pos() const { return pos_; }
    std::size_t left() const { return end_ - pos_; }
    bool Has(std::size_t n) const { return n <= left(); }

    bool U(int bytes, std::uint64_t& v) {
        if (!Has(bytes)) return false;
        v = 0;
        for (int i = 0; i < bytes; ++i) v = v << 8 | static_cast<unsigned char>(d_[pos_++]);
        return true;
    }
    bool Signed(int bytes, std::int64_t& v) {
        std::uint64_t u = 0;
        if (!U(bytes, u)) return false;
        if (bytes < 8 && (u >> (8 * bytes - 1) & 1)) u |= ~0ull << (8 * bytes);
        v = static_cast<std::int64_t>(u);
        return true;
    }
    bool Double(double& x) {
        std::uint64_t u = 0;
        if (!U(8, u)) return false;
        std::memcpy(&x, &u, 8);
        return true;
    }
    bool Vec(Vec3& v) { return Double(v.x) && Double(v.y) && Double(v.z); }
    // A NUL-terminated string inside the range.
    bool CString(std::string& s) {
        std::size_t e = pos_;
        while (e < end_ && d_[e] != 0) ++e;
        if (e >= end_) return false;
        s.assign(d_.substr(pos_, e - pos_));
        pos_ = e + 1;
        return true;
    }
    std::string_view Bytes(std::size_t n) {
        std::string_view v = d_.substr(pos_, n);
        pos_ += n;
        return v;
    }

  private:
    std::string_view d_;
    std::size_t pos_, end_;
};

struct RawObject {
    std::size_t offset = 0, length = 0;
    int dli = 0, major = 0, minor = 0;
    std::string name;
    std::vector<std::pair<std::string, std::string>> attrs;
    std::size_t bodyBegin = 0, bodyEnd = 0;
    bool hasBody = false;
};

std::string_view TypeName(int minor) {
    for (const MinorType& t : kMinorTypes)
        if (t.id == minor) return t.name;
    return {};
}

class GReader {
  public:
    GReader(std::string_view data, const std::string& file, Database& db, Diagnostics& diags)
        : d_(data), file_(std::make_shared<const std::string>(file)), db_(db), diags_(diags) {}

    bool Run() {
        db_.format = "v5 binary";
        if (!IsV5Binary(d_)) return Fail(0, "not a BRL-CAD v5 binary database (no v5 header)");
        std::size_t pos = 8;
        while (pos < d_.size() && !diags_.HasErrors()) {
            RawObject o;
            if (!Object(pos, o)) return false;
            pos += o.length;
            Dispatch(o);
        }
        return !diags_.HasErrors();
    }

  private:
    SourceLoc Loc() const {
        SourceLoc l;
        l.file = file_;
        return l;
    }
    bool Fail(std::size_t at, std::string message) {
        diags_.Error(Loc(), fmt::format("byte {}: {}", at, message));
        return false;
    }
    bool Fail(const RawObject& o, std::string message) {
        return Fail(o.offset, fmt::format("object '{}': {}", o.name, message));
    }

    // One object header and its sections; o.length is its total size in bytes.
    bool Object(std::size_t pos, RawObject& o) {
        o.offset = pos;
        Cursor c(d_, pos, d_.size());
        std::uint64_t magic = 0, hflags = 0, aflags = 0, bflags = 0, major = 0, minor = 0;
        if (!c.U(1, magic) || !c.U(1, hflags) || !c.U(1, aflags) || !c.U(1, bflags) ||
            !c.U(1, major) || !c.U(1, minor))
            return Fail(pos, "truncated object header");
        if (magic != kMagic1)
            return Fail(pos, fmt::format("bad object magic 0x{:02x} (expected 0x76): the file is "
                                         "corrupt or not a v5 database",
                                         magic));
        o.dli = static_cast<int>(hflags & 3);
        o.major = static_cast<int>(major);
        o.minor = static_cast<int>(minor);
        std::uint64_t units = 0;
        if (!c.U(WidthBytes(static_cast<int>(hflags >> 6 & 3)), units))
            return Fail(pos, "truncated object length");
        if (units == 0 || units > (d_.size() - pos) / 8)
            return Fail(pos, fmt::format("object length {} × 8 bytes runs past the end of the "
                                         "file ({} bytes)",
                                         units, d_.size()));
        o.length = static_cast<std::size_t>(units) * 8;
        const std::size_t end = pos + o.length;
        if (static_cast<unsigned char>(d_[end - 1]) != kMagic2)
            return Fail(pos, "the object does not end with the v5 magic byte 0x35");
        Cursor in(d_, c.pos(), end - 1);
        auto section = [&](int widthCode, std::size_t& b, std::size_t& e) {
            std::uint64_t len = 0;
            if (!in.U(WidthBytes(widthCode), len) || len > in.left()) return false;
            b = in.pos();
            e = b + static_cast<std::size_t>(len);
            in.Bytes(static_cast<std::size_t>(len));
            return true;
        };
        if (hflags & kNamePresent) {
            std::size_t b = 0, e = 0;
            if (!section(static_cast<int>(hflags >> 3 & 3), b, e))
                return Fail(pos, "the name runs past the end of its object");
            Cursor n(d_, b, e);
            if (!n.CString(o.name)) return Fail(pos, "the object name has no terminating NUL");
        }
        if ((aflags & 7) || (bflags & 7))
            return Fail(o, "compressed sections are not supported (BRL-CAD never writes them)");
        if (aflags & kSectionPresent) {
            std::size_t b = 0, e = 0;
            if (!section(static_cast<int>(aflags >> 6 & 3), b, e))
                return Fail(o, "the attributes run past the end of the object");
            Cursor a(d_, b, e);
            while (a.left() > 0) {
                std::string k, v;
                if (!a.CString(k)) return Fail(o, "an attribute name has no terminating NUL");
                if (k.empty()) break;  // the final NUL
                if (!a.CString(v)) return Fail(o, fmt::format("attribute '{}' has no value", k));
                o.attrs.emplace_back(std::move(k), std::move(v));
            }
        }
        if (bflags & kSectionPresent) {
            if (!section(static_cast<int>(bflags >> 6 & 3), o.bodyBegin, o.bodyEnd))
                return Fail(o, "the body runs past the end of the object");
            o.hasBody = true;
        }
        return true;
    }

    void Dispatch(const RawObject& o) {
        if (o.dli == kDliFree) return;  // free storage
        if (o.dli == kDliHeader) return;
        if (o.name == "_GLOBAL") {
            Global(o);
            return;
        }
        if (o.major == kMajorAttributeOnly || o.major != kMajorGeometry) return;  // binary data
        if (o.name.empty()) {
            Fail(o.offset, "a geometry object without a name");
            return;
        }
        if (o.minor == kComb) {
            Comb(o);
            return;
        }
        Solid(o);
    }

    void Global(const RawObject& o) {
        for (const auto& [k, v] : o.attrs) {
            if (k == "title") db_.title = v;
            if (k == "regionid_colortable") ColorTable(o, v);
        }
    }

    // "{low high r g b} {low high r g b} ..."
    void ColorTable(const RawObject& o, const std::string& v) {
        std::string s = v;
        for (char& ch : s)
            if (ch == '{' || ch == '}') ch = ' ';
        const char* p = s.c_str();
        while (true) {
            long x[5];
            int k = 0;
            for (; k < 5; ++k) {
                char* e = nullptr;
                x[k] = std::strtol(p, &e, 10);
                if (e == p) break;
                p = e;
            }
            if (k == 0) break;
            if (k < 5) {
                Fail(o, "regionid_colortable entries need 5 numbers: {low high r g b}");
                return;
            }
            db_.colorTable.push_back(
                {static_cast<int>(x[0]),
                 static_cast<int>(x[1]),
                 {static_cast<int>(x[2]), static_cast<int>(x[3]), static_cast<int>(x[4])}});
        }
    }

    bool Doubles(Cursor& c, const RawObject& o, int n, double* out) {
        for (int i = 0; i < n; ++i)
            if (!c.Double(out[i]) || !std::isfinite(out[i]))
                return Fail(o, fmt::format("the body is too short or holds a non-finite number "
                                           "(value {} of {})",
                                           i + 1, n));
        return true;
    }

    void Solid(const RawObject& o) {
        Primitive p;
        p.name = o.name;
        p.loc = Loc();
        p.byteOffset = static_cast<long long>(o.offset);
        std::string_view tn = TypeName(o.minor);
        p.type = tn.empty() ? fmt::format("type{}", o.minor) : std::string(tn);
        Cursor c(d_, o.bodyBegin, o.hasBody ? o.bodyEnd : o.bodyBegin);
        double v[24] = {};
        auto vec = [&](int i) { return Vec3{v[3 * i], v[3 * i + 1], v[3 * i + 2]}; };
        bool ok = true;
        switch (o.minor) {
            case 1:  // tor
                if ((ok = Doubles(c, o, 8, v)))
                    p.V = vec(0), p.H = vec(1), p.r1 = v[6], p.r2 = v[7];
                break;
            case 2:
            case 7:  // tgc, rec
                p.type = "tgc";
                if ((ok = Doubles(c, o, 18, v)))
                    p.V = vec(0), p.H = vec(1), p.A = vec(2), p.B = vec(3), p.C = vec(4),
                    p.D = vec(5);
                break;
            case 3:
            case 10:  // ell, sph
                p.type = "ell";
                if ((ok = Doubles(c, o, 12, v)))
                    p.V = vec(0), p.A = vec(1), p.B = vec(2), p.C = vec(3);
                break;
            case 4:
                if ((ok = Doubles(c, o, 24, v)))
                    for (int k = 0; k < 8; ++k) p.pts[k] = vec(k);
                break;
            case 6:
                if ((ok = Doubles(c, o, 4, v))) p.N = vec(0), p.d = v[3];
                break;
            case 14:
                ok = Arbn(c, o, p);
                break;
            case 16:
                if ((ok = Doubles(c, o, 8, v)))
                    p.V = vec(0), p.H = vec(1), p.rv = v[6], p.rh = v[7];
                break;
            case 17:
            case 18:
                if ((ok = Doubles(c, o, o.minor == 17 ? 10 : 11, v)))
                    p.V = vec(0), p.H = vec(1), p.B = vec(2), p.r = v[9],
                    p.c = o.minor == 18 ? v[10] : 0;
                break;
            case 19:
            case 20:
                if ((ok = Doubles(c, o, o.minor == 19 ? 11 : 12, v)))
                    p.V = vec(0), p.H = vec(1), p.A = vec(2), p.r1 = v[9], p.r2 = v[10],
                    p.c = o.minor == 20 ? v[11] : 0;
                break;
            case 21:
                if ((ok = Doubles(c, o, 11, v)))
                    p.V = vec(0), p.N = vec(1), p.C = vec(2), p.r = v[9], p.rd = v[10];
                break;
            case 38:
                if ((ok = Doubles(c, o, 11, v)))
                    p.V = vec(0), p.H = vec(1), p.A = vec(2), p.b = v[9], p.bnr = v[10];
                break;
            case 30:
                ok = Bot(c, o, p);
                break;
            case 15:
                ok = Pipe(c, o, p);
                break;
            case 5:
                ok = Ars(c, o, p);
                break;
            default:  // kept by name for the census; the converter reports it if reached
                break;
        }
        if (ok) db_.AddPrimitive(std::move(p));
    }

    bool Arbn(Cursor& c, const RawObject& o, Primitive& p) {
        std::uint64_t n = 0;
        if (!c.U(4, n) || n > c.left() / 32) return Fail(o, "arbn: bad plane count");
        for (std::uint64_t i = 0; i < n; ++i) {
            double q[4] = {0, 0, 0, 0};
            if (!Doubles(c, o, 4, q)) return false;
            p.planes.push_back(Plane{q[0], q[1], q[2], -q[3]});
        }
        return true;
    }

    // pipe: u32 count, then per point x y z id od bend (g_format.h).
    bool Pipe(Cursor& c, const RawObject& o, Primitive& p) {
        std::uint64_t n = 0;
        if (!c.U(4, n) || n > c.left() / 48) return Fail(o, "pipe: bad point count");
        for (std::uint64_t i = 0; i < n; ++i) {
            double q[6] = {0, 0, 0, 0, 0, 0};
            if (!Doubles(c, o, 6, q)) return false;
            p.pipe.push_back({{q[0], q[1], q[2]}, q[4], q[3], q[5]});
        }
        return true;
    }

    // ars (librt's rt_ars_export5): u32 curves, u32 points a curve, then every point x y z.
    bool Ars(Cursor& c, const RawObject& o, Primitive& p) {
        std::uint64_t nc = 0, ppc = 0;
        if (!c.U(4, nc) || !c.U(4, ppc)) return Fail(o, "ars: truncated header");
        if (ppc != 0 && nc > c.left() / 24 / ppc)
            return Fail(o,
                        fmt::format("ars: {} curves of {} points do not fit in the body", nc, ppc));
        for (std::uint64_t i = 0; i < nc; ++i) {
            std::vector<Vec3> curve;
            for (std::uint64_t j = 0; j < ppc; ++j) {
                double q[3] = {0, 0, 0};
                if (!Doubles(c, o, 3, q)) return false;
                curve.push_back({q[0], q[1], q[2]});
            }
            p.arsCurves.push_back(std::move(curve));
        }
        return true;
    }

    bool Bot(Cursor& c, const RawObject& o, Primitive& p) {
        std::uint64_t nv = 0, nf = 0, orient = 0, mode = 0, flags = 0;
        if (!c.U(4, nv) || !c.U(4, nf) || !c.U(1, orient) || !c.U(1, mode) || !c.U(1, flags))
            return Fail(o, "bot: truncated header");
        if (nv > c.left() / 24 || nf > c.left() / 12)
            return Fail(
                o, fmt::format("bot: {} vertices and {} faces do not fit in the body", nv, nf));
        if (mode < 1 || mode > 4 || orient < 1 || orient > 3)
            return Fail(o, fmt::format("bot: unknown mode {} or orientation {}", mode, orient));
        p.botMode = static_cast<int>(mode);
        p.botOrientation = static_cast<int>(orient);
        for (std::uint64_t i = 0; i < nv; ++i) {
            Vec3 x;
            if (!c.Vec(x) || !(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z)))
                return Fail(o, "bot: bad vertex");
            p.vertices.push_back(x);
        }
        for (std::uint64_t i = 0; i < nf; ++i) {
            std::array<int, 3> t{};
            for (int k = 0; k < 3; ++k) {
                std::uint64_t idx = 0;
                if (!c.U(4, idx)) return Fail(o, "bot: truncated faces");
                if (idx >= nv)
                    return Fail(o, fmt::format("bot: face {} names vertex {} of {}", i, idx, nv));
                t[k] = static_cast<int>(idx);
            }
            p.faces.push_back(t);
        }
        if (mode >= 3) {
            for (std::uint64_t i = 0; i < nf; ++i) {
                double t = 0;
                if (!Doubles(c, o, 1, &t)) return false;
                p.thickness.push_back(t);
            }
            std::string hex;
            if (!c.CString(hex)) return Fail(o, "bot: the face-mode string has no NUL");
            p.faceAppended.assign(nf, 0);
            for (std::size_t i = 0; i < hex.size(); ++i) {
                char ch = hex[hex.size() - 1 - i];
                int v = ch >= '0' && ch <= '9' ? ch - '0' : (ch | 32) - 'a' + 10;
                if (v < 0 || v > 15) {
                    if (ch == 'x' || ch == 'X') break;  // "0x" prefix
                    return Fail(o, "bot: the face-mode string is not hexadecimal");
                }
                for (int b = 0; b < 4; ++b)
                    if (v >> b & 1 && 4 * i + b < nf) p.faceAppended[4 * i + b] = 1;
            }
        }
        return true;  // surface normals (flag 1), if any, are not needed for the solid
    }

    void Comb(const RawObject& o) {
        Combination comb;
        comb.name = o.name;
        comb.loc = Loc();
        comb.byteOffset = static_cast<long long>(o.offset);
        if (!o.hasBody) {
            Fail(o, "a combination without a body");
            return;
        }
        Cursor c(d_, o.bodyBegin, o.bodyEnd);
        std::uint64_t wcode = 0, nmat = 0, nleaf = 0, leafBytes = 0, rpnLen = 0, depth = 0;
        if (!c.U(1, wcode) || wcode > 3) {
            Fail(o, "combination: bad width code");
            return;
        }
        const int w = WidthBytes(static_cast<int>(wcode));
        if (!c.U(w, nmat) || !c.U(w, nleaf) || !c.U(w, leafBytes) || !c.U(w, rpnLen) ||
            !c.U(w, depth)) {
            Fail(o, "combination: truncated header");
            return;
        }
        if (nmat > c.left() / 128 || leafBytes > c.left() - nmat * 128 ||
            rpnLen > c.left() - nmat * 128 - leafBytes || nleaf > leafBytes) {
            Fail(o, "combination: the section sizes do not fit in the body");
            return;
        }
        std::vector<Mat4> mats(static_cast<std::size_t>(nmat));
        for (Mat4& m : mats)
            for (int k = 0; k < 16; ++k)
                if (!c.Double(m.m[k / 4][k % 4]) || !std::isfinite(m.m[k / 4][k % 4])) {
                    Fail(o, "combination: a matrix holds a non-finite number");
                    return;
                }
        Cursor leaves(d_, c.pos(), c.pos() + static_cast<std::size_t>(leafBytes));
        Cursor rpn(d_, c.pos() + static_cast<std::size_t>(leafBytes),
                   c.pos() + static_cast<std::size_t>(leafBytes + rpnLen));
        std::uint64_t leavesRead = 0;
        auto leaf = [&]() -> int {
            TreeNode n;
            std::int64_t mi = 0;
            if (leavesRead++ >= nleaf || !leaves.CString(n.name) || !leaves.Signed(w, mi)) {
                Fail(o, "combination: the leaf list is shorter than its count");
                return -1;
            }
            if (mi >= 0) {
                if (static_cast<std::uint64_t>(mi) >= nmat) {
                    Fail(o, fmt::format("combination: member '{}' names matrix {} of {}", n.name,
                                        mi, nmat));
                    return -1;
                }
                n.matrix = mats[static_cast<std::size_t>(mi)];
            }
            n.loc = comb.loc;
            comb.nodes.push_back(std::move(n));
            return static_cast<int>(comb.nodes.size()) - 1;
        };
        auto op = [&](TreeNode::Op kind, int l, int r) {
            TreeNode n;
            n.op = kind;
            n.left = l;
            n.right = r;
            n.loc = comb.loc;
            comb.nodes.push_back(std::move(n));
            return static_cast<int>(comb.nodes.size()) - 1;
        };
        if (rpnLen == 0) {
            // All unions: the leaves paired into a balanced tree, as librt reads them.
            std::vector<int> level;
            for (std::uint64_t i = 0; i < nleaf; ++i) {
                int li = leaf();
                if (li < 0) return;
                level.push_back(li);
            }
            while (level.size() > 1) {
                std::vector<int> next;
                for (std::size_t i = 0; i < level.size(); i += 2)
                    next.push_back(i + 1 < level.size()
                                       ? op(TreeNode::Op::kUnion, level[i], level[i + 1])
                                       : level[i]);
                level.swap(next);
            }
            comb.root = level.empty() ? -1 : level[0];
        } else {
            std::vector<int> stack;
            for (std::uint64_t i = 0; i < rpnLen; ++i) {
                std::uint64_t tok = 0;
                rpn.U(1, tok);
                if (tok == kTokLeaf) {
                    int li = leaf();
                    if (li < 0) return;
                    stack.push_back(li);
                    continue;
                }
                if (tok == kTokXor || tok == kTokNot) {
                    Fail(o, fmt::format("combination: the {} operator is not supported",
                                        tok == kTokXor ? "xor" : "not"));
                    return;
                }
                if (tok < kTokUnion || tok > kTokSubtract || stack.size() < 2) {
                    Fail(o, fmt::format("combination: bad boolean expression (token {} at {})", tok,
                                        i));
                    return;
                }
                int r = stack.back();
                stack.pop_back();
                int l = stack.back();
                stack.pop_back();
                stack.push_back(op(tok == kTokUnion       ? TreeNode::Op::kUnion
                                   : tok == kTokIntersect ? TreeNode::Op::kIntersection
                                                          : TreeNode::Op::kDifference,
                                   l, r));
            }
            if (stack.size() != 1 || leavesRead != nleaf) {
                Fail(o, "combination: the boolean expression does not reduce to one tree");
                return;
            }
            comb.root = stack[0];
        }
        for (const auto& [k, v] : o.attrs) CombAttr(comb, k, v);
        db_.AddCombination(std::move(comb));
    }

    static void CombAttr(Combination& c, const std::string& k, const std::string& v) {
        if (k == "region") {
            c.region = !v.empty() && v != "0" && v != "no";
        } else if (k == "region_id" || k == "id") {
            c.regionId = std::atoi(v.c_str());
        } else if (k == "aircode" || k == "air") {
            c.aircode = std::atoi(v.c_str());
        } else if (k == "rgb" || k == "color") {
            int r = 0, g = 0, b = 0;
            std::string s = v;
            for (char& ch : s)
                if (ch == '/' || ch == ',') ch = ' ';
            if (std::sscanf(s.c_str(), "%d %d %d", &r, &g, &b) == 3) c.rgb = {r, g, b};
        } else if (k == "inherit") {
            c.inherit = v == "1" || v == "yes";
        } else if (k == "oshader" || k == "shader") {
            std::size_t s = v.find_first_not_of(" \t{");
            std::size_t e = s == std::string::npos ? s : v.find_first_of(" \t{}", s);
            c.shader = s == std::string::npos ? "" : v.substr(s, e - s);
        }
    }

    std::string_view d_;
    std::shared_ptr<const std::string> file_;
    Database& db_;
    Diagnostics& diags_;
};

}  // namespace

bool IsV5Binary(std::string_view bytes) {
    // The header object: magic1, DLI = header, and magic2 closing its 8 bytes.
    return bytes.size() >= 8 && static_cast<unsigned char>(bytes[0]) == g5::kMagic1 &&
           (static_cast<unsigned char>(bytes[1]) & 3) == g5::kDliHeader &&
           static_cast<unsigned char>(bytes[7]) == g5::kMagic2;
}

bool ParseG(std::string_view bytes, const std::string& file, Database& db, Diagnostics& diags) {
    return GReader(bytes, file, db, diags).Run();
}

}  // namespace quadrix::import::brlcad
