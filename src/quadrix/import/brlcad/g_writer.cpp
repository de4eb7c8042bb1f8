// Database → .g v5 bytes; see g_writer.h and the layout in g_format.h.
#include "quadrix/import/brlcad/g_writer.h"

#include <fmt/format.h>

#include <cstring>
#include <functional>

#include "quadrix/import/brlcad/g_format.h"

namespace quadrix::import::brlcad {

namespace {

using namespace g5;

class Bytes {
  public:
    void U(std::uint64_t v, int bytes) {
        for (int i = bytes - 1; i >= 0; --i) s_.push_back(static_cast<char>(v >> (8 * i) & 0xff));
    }
    void Double(double x) {
        std::uint64_t u = 0;
        std::memcpy(&u, &x, 8);
        U(u, 8);
    }
    void Vec(const Vec3& v) { Double(v.x), Double(v.y), Double(v.z); }
    void CString(const std::string& s) { s_.append(s), s_.push_back('\0'); }
    void Append(const std::string& s) { s_.append(s); }
    const std::string& str() const { return s_; }

  private:
    std::string s_;
};

// One object: header flags, the three optional sections, padding and magic2 (g_format.h).
std::string Object(int dli, int major, int minor, const std::string& name,
                   const std::vector<std::pair<std::string, std::string>>& attrs,
                   const std::string* body) {
    std::string nameBytes = name.empty() ? "" : name + std::string(1, '\0');
    std::string attrBytes;
    for (const auto& [k, v] : attrs) attrBytes += k + '\0' + v + '\0';
    if (!attrs.empty()) attrBytes += '\0';
    const int nw = WidthCodeFor(nameBytes.size()), aw = WidthCodeFor(attrBytes.size());
    const int bw = body ? WidthCodeFor(body->size()) : 0;
    std::size_t inner = (nameBytes.empty() ? 0 : WidthBytes(nw) + nameBytes.size()) +
                        (attrs.empty() ? 0 : WidthBytes(aw) + attrBytes.size()) +
                        (body ? WidthBytes(bw) + body->size() : 0);
    // The object-length field's width depends on the length it holds.
    int ow = 0;
    std::size_t total = 0;
    for (; ow < 4; ++ow) {
        total = (6 + WidthBytes(ow) + inner + 1 + 7) / 8 * 8;
        if (WidthCodeFor(total / 8) <= ow) break;
    }
    Bytes b;
    b.U(kMagic1, 1);
    b.U(static_cast<unsigned>(dli) | (nameBytes.empty() ? 0 : kNamePresent) |
            static_cast<unsigned>(nw) << 3 | static_cast<unsigned>(ow) << 6,
        1);
    b.U((attrs.empty() ? 0 : kSectionPresent) | static_cast<unsigned>(aw) << 6, 1);
    b.U((body ? kSectionPresent : 0) | static_cast<unsigned>(bw) << 6, 1);
    b.U(static_cast<unsigned>(major), 1);
    b.U(static_cast<unsigned>(minor), 1);
    b.U(total / 8, WidthBytes(ow));
    if (!nameBytes.empty()) b.U(nameBytes.size(), WidthBytes(nw)), b.Append(nameBytes);
    if (!attrs.empty()) b.U(attrBytes.size(), WidthBytes(aw)), b.Append(attrBytes);
    if (body) b.U(body->size(), WidthBytes(bw)), b.Append(*body);
    std::string out = b.str();
    out.resize(total - 1, '\0');
    out.push_back(static_cast<char>(kMagic2));
    return out;
}

int MinorOf(const std::string& type) {
    for (const MinorType& t : kMinorTypes)
        if (t.name == type) return t.id;
    return -1;
}

std::optional<std::string> SolidBody(const Primitive& p, std::string* error) {
    Bytes b;
    const std::string& t = p.type;
    if (t == "tor") {
        b.Vec(p.V), b.Vec(p.H), b.Double(p.r1), b.Double(p.r2);
    } else if (t == "tgc") {
        for (const Vec3* v : {&p.V, &p.H, &p.A, &p.B, &p.C, &p.D}) b.Vec(*v);
    } else if (t == "ell") {
        for (const Vec3* v : {&p.V, &p.A, &p.B, &p.C}) b.Vec(*v);
    } else if (t == "arb8") {
        for (const Vec3& v : p.pts) b.Vec(v);
    } else if (t == "half") {
        b.Vec(p.N), b.Double(p.d);
    } else if (t == "arbn") {
        b.U(p.planes.size(), 4);
        for (const Plane& q : p.planes) b.Double(q.a), b.Double(q.b), b.Double(q.c), b.Double(-q.d);
    } else if (t == "part") {
        b.Vec(p.V), b.Vec(p.H), b.Double(p.rv), b.Double(p.rh);
    } else if (t == "rpc" || t == "rhc") {
        b.Vec(p.V), b.Vec(p.H), b.Vec(p.B), b.Double(p.r);
        if (t == "rhc") b.Double(p.c);
    } else if (t == "epa" || t == "ehy") {
        b.Vec(p.V), b.Vec(p.H), b.Vec(p.A), b.Double(p.r1), b.Double(p.r2);
        if (t == "ehy") b.Double(p.c);
    } else if (t == "pipe") {
        b.U(p.pipe.size(), 4);
        for (const Primitive::PipePoint& q : p.pipe)
            b.Vec(q.at), b.Double(q.id), b.Double(q.od), b.Double(q.bend);
    } else if (t == "ars") {
        b.U(p.arsCurves.size(), 4);
        b.U(p.arsCurves.empty() ? 0 : p.arsCurves[0].size(), 4);
        for (const std::vector<Vec3>& curve : p.arsCurves)
            for (const Vec3& q : curve) b.Vec(q);
    } else if (t == "eto") {
        b.Vec(p.V), b.Vec(p.N), b.Vec(p.C), b.Double(p.r), b.Double(p.rd);
    } else if (t == "hyp") {
        b.Vec(p.V), b.Vec(p.H), b.Vec(p.A), b.Double(p.b), b.Double(p.bnr);
    } else if (t == "bot") {
        b.U(p.vertices.size(), 4), b.U(p.faces.size(), 4);
        b.U(static_cast<unsigned>(p.botOrientation), 1), b.U(static_cast<unsigned>(p.botMode), 1);
        b.U(0, 1);
        for (const Vec3& v : p.vertices) b.Vec(v);
        for (const auto& f : p.faces)
            for (int k : f) b.U(static_cast<std::uint64_t>(k), 4);
        if (p.botMode >= 3) {
            for (std::size_t i = 0; i < p.faces.size(); ++i)
                b.Double(i < p.thickness.size() ? p.thickness[i] : 0);
            std::string hex;
            for (std::size_t i = 0; i < (p.faces.size() + 3) / 4; ++i) {
                int v = 0;
                for (int k = 0; k < 4; ++k)
                    if (4 * i + k < p.faceAppended.size() && p.faceAppended[4 * i + k]) v |= 1 << k;
                hex.insert(hex.begin(), "0123456789abcdef"[v]);
            }
            b.CString(hex.empty() ? "0" : hex);
        }
    } else {
        if (error)
            *error = fmt::format(
                "primitive '{}' ({}): its parameters are not kept, so it cannot be "
                "written to a .g",
                p.name, t);
        return std::nullopt;
    }
    return b.str();
}

bool IsIdentity(const Mat4& m) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (m.m[r][c] != (r == c ? 1.0 : 0.0)) return false;
    return true;
}

std::string CombBody(const Combination& c) {
    bool allUnion = true;
    for (const TreeNode& n : c.nodes)
        allUnion = allUnion && (n.op == TreeNode::Op::kLeaf || n.op == TreeNode::Op::kUnion);
    // Postfix walk (left, right, operator) with the evaluation stack's height.
    std::vector<const TreeNode*> leaves;
    std::string rpn;
    std::size_t height = 0, maxHeight = 0;
    std::function<void(int)> walk = [&](int i) {
        const TreeNode& n = c.nodes[i];
        if (n.op == TreeNode::Op::kLeaf) {
            leaves.push_back(&n);
            rpn.push_back(static_cast<char>(kTokLeaf));
            maxHeight = std::max(maxHeight, ++height);
            return;
        }
        walk(n.left);
        walk(n.right);
        --height;
        rpn.push_back(static_cast<char>(n.op == TreeNode::Op::kUnion          ? kTokUnion
                                        : n.op == TreeNode::Op::kIntersection ? kTokIntersect
                                                                              : kTokSubtract));
    };
    if (c.root >= 0) walk(c.root);
    if (allUnion) rpn.clear();
    std::size_t nmat = 0, nameBytes = 0;
    for (const TreeNode* l : leaves) {
        nmat += IsIdentity(l->matrix) ? 0 : 1;
        nameBytes += l->name.size() + 1;
    }
    int w = 0;
    for (; w < 3; ++w) {
        std::uint64_t leafBytes = nameBytes + leaves.size() * WidthBytes(w);
        std::uint64_t all = nmat | leaves.size() | leafBytes | rpn.size() | maxHeight;
        if (WidthCodeFor(all) <= w) break;
    }
    const int wb = WidthBytes(w);
    Bytes b;
    b.U(static_cast<unsigned>(w), 1);
    b.U(nmat, wb), b.U(leaves.size(), wb), b.U(nameBytes + leaves.size() * wb, wb);
    b.U(rpn.size(), wb), b.U(maxHeight, wb);
    for (const TreeNode* l : leaves)
        if (!IsIdentity(l->matrix))
            for (int k = 0; k < 16; ++k) b.Double(l->matrix.m[k / 4][k % 4]);
    std::uint64_t mi = 0;
    for (const TreeNode* l : leaves) {
        b.CString(l->name);
        // -1 (identity) in two's complement of the width.
        b.U(IsIdentity(l->matrix) ? ~0ull : mi++, wb);
    }
    b.Append(rpn);
    return b.str();
}

std::vector<std::pair<std::string, std::string>> CombAttrs(const Combination& c) {
    std::vector<std::pair<std::string, std::string>> a;
    if (c.region) a.emplace_back("region", "R");
    if (c.regionId != 0) a.emplace_back("region_id", std::to_string(c.regionId));
    if (c.aircode != 0) a.emplace_back("aircode", std::to_string(c.aircode));
    if (c.rgb)
        a.emplace_back("rgb", fmt::format("{}/{}/{}", (*c.rgb)[0], (*c.rgb)[1], (*c.rgb)[2]));
    if (!c.shader.empty()) a.emplace_back("shader", c.shader);
    if (c.inherit) a.emplace_back("inherit", "1");
    return a;
}

}  // namespace

std::optional<std::string> WriteG(const Database& db, std::string* error) {
    std::string out(reinterpret_cast<const char*>(kHeader), 8);
    std::vector<std::pair<std::string, std::string>> global = {{"title", db.title}, {"units", "1"}};
    if (!db.colorTable.empty()) {
        std::string t;
        for (const ColorTableEntry& e : db.colorTable)
            t += fmt::format("{}{{{} {} {} {} {}}}", t.empty() ? "" : " ", e.low, e.high, e.rgb[0],
                             e.rgb[1], e.rgb[2]);
        global.emplace_back("regionid_colortable", t);
    }
    out += Object(kDliApplication, kMajorAttributeOnly, 0, "_GLOBAL", global, nullptr);
    auto current = [&](const std::string& name, bool isComb, std::size_t index) {
        auto it = db.objects.find(name);
        return it != db.objects.end() && it->second.first == isComb &&
               it->second.second == static_cast<int>(index);
    };
    for (std::size_t i = 0; i < db.primitives.size(); ++i) {
        const Primitive& p = db.primitives[i];
        if (!current(p.name, false, i)) continue;
        int minor = MinorOf(p.type);
        auto body = minor < 0 ? std::nullopt : SolidBody(p, error);
        if (!body) {
            if (error && minor < 0)
                *error = fmt::format("primitive '{}': type '{}' has no v5 binary form here", p.name,
                                     p.type);
            return std::nullopt;
        }
        out += Object(kDliApplication, kMajorGeometry, minor, p.name, {}, &*body);
    }
    for (std::size_t i = 0; i < db.combinations.size(); ++i) {
        const Combination& c = db.combinations[i];
        if (!current(c.name, true, i)) continue;
        std::string body = CombBody(c);
        out += Object(kDliApplication, kMajorGeometry, kComb, c.name, CombAttrs(c), &body);
    }
    return out;
}

}  // namespace quadrix::import::brlcad
