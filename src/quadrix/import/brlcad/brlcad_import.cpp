// Database → Scene conversion; the rules are summarised in brlcad_import.h.
#include "quadrix/import/brlcad/brlcad_import.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>
#include <set>

#include "quadrix/import/brlcad/primitives.h"
#include "quadrix/import/brlcad/readers.h"
#include "quadrix/import/model_space.h"
#include "quadrix/math/srgb.h"
#include "quadrix/util/hash_slots.h"

namespace quadrix::import {

using namespace brlcad;

namespace {

// Limits that keep a hostile or exploding file from exhausting memory.
constexpr std::size_t kMaxBodies = 2'000'000;
constexpr std::size_t kMaxTerms = 200'000;
// Boolean nodes of the expanded trees (a DAG of combinations that reuse each other expands
// exponentially when walked path by path, as rt walks it).
constexpr std::size_t kMaxExprs = 2'000'000;
constexpr int kMaxDepth = 1000;
// Depth of a boolean tree walked recursively (a 10,000-member v4 list is a chain that deep).
constexpr int kMaxTreeDepth = 10'000;
constexpr std::size_t kMaxCsgNodes = 8'000'000;

// Types that are not solids at all: ignored silently (FORMAT.md §6.2 last row).
bool IsNotASolid(const std::string& type) {
    return type == "grip" || type == "joint" || type == "annot" || type == "datum" ||
           type == "script";
}

struct Expr {
    bool leaf = true;
    int firstBody = 0, bodyCount = 0;  // leaf: union of scene bodies [firstBody, +bodyCount)
    scene::CsgOp op = scene::CsgOp::kUnion;
    int left = -1, right = -1;
    Box3 box;
};

// The finish of an rt shader name, from the defaults of BRL-CAD's liboptical (plastic: shine 10,
// specular .7, diffuse .3; mirror: shine 4, specular .6; glass: shine 4, specular .7,
// transmission .8). The specular weights are halved and the diffuse left to the shading model:
// Quadrix's lights are weaker than rt's, and rt's diffuse .3 would darken every region.
// Parameters written after the name (`plastic {sh 20}`) are not read. Unknown names: no finish.
scene::Finish ShaderFinish(const std::string& shader) {
    scene::Finish f;
    if (shader == "plastic") {
        f.specular = 0.35;
        f.shininess = 10;
    } else if (shader == "mirror") {
        f.specular = 0.3;
        f.shininess = 4;
    } else if (shader == "glass") {
        f.specular = 0.35;
        f.shininess = 4;
        f.opacity = 0.2;
    }
    return f;
}

struct ColorCtx {
    std::optional<std::array<int, 3>> rgb;
    bool locked = false;
};

struct Term {
    int expr = -1;
    std::string name;
    std::optional<std::array<int, 3>> rgb;
    SourceLoc loc;
    std::string shader;  // the region's shader name ("plastic", "glass", ...), empty if none
};

class Converter {
  public:
    Converter(const Database& db, const ImportOptions& options, scene::Scene& scene,
              Diagnostics& diags, ImportReport& report)
        : db_(db), options_(options), scene_(scene), diags_(diags), report_(report) {
        combOnPath_.assign(db.combinations.size(), 0);
        converted_.resize(db.primitives.size());
    }

    bool Run() {
        Census();
        if (!CheckCycles()) return false;
        std::vector<std::string> tops = TopObjects();
        Reserve(tops);
        std::vector<Term> terms;
        for (const std::string& name : tops) {
            auto t = Terms(name, Mat4::Identity(), {}, 0, nullptr);
            for (Term& x : t) terms.push_back(std::move(x));
            if (aborted_) return false;
        }
        report_.topObjects = tops;
        if (aborted_) return false;
        Emit(terms);
        ReportSkipped();
        return !aborted_;
    }

  private:
    void Census() {
        for (const Primitive& p : db_.primitives) {
            std::string type = p.type;
            if (type == "tgc") type = ConvertPrimitive(p).censusName;
            ++report_.census[type];
        }
    }

    // Every combination, reachable or not, must be free of cycles (an iterative depth-first
    // search: 0 = unvisited, 1 = on the stack, 2 = done).
    bool CheckCycles() {
        std::vector<char> state(db_.combinations.size(), 0);
        for (std::size_t start = 0; start < db_.combinations.size(); ++start) {
            if (state[start]) continue;
            std::vector<std::pair<int, std::size_t>> stack{{static_cast<int>(start), 0}};
            state[start] = 1;
            while (!stack.empty()) {
                auto& [ci, next] = stack.back();
                const Combination& c = db_.combinations[ci];
                if (next == c.nodes.size()) {
                    state[ci] = 2;
                    stack.pop_back();
                    continue;
                }
                const TreeNode& n = c.nodes[next++];
                if (n.op != TreeNode::Op::kLeaf) continue;
                auto it = db_.objects.find(n.name);
                if (it == db_.objects.end() || !it->second.first) continue;
                int child = it->second.second;
                if (state[child] == 1) {
                    std::string path;
                    bool on = false;
                    for (const auto& [k, unused] : stack) {
                        on = on || k == child;
                        if (on) path += db_.combinations[k].name + " → ";
                    }
                    diags_.Error(
                        n.loc,
                        fmt::format("combination '{}' contains itself: {}{}", n.name, path, n.name),
                        c.sourceLine);
                    return false;
                }
                if (state[child] == 0) {
                    state[child] = 1;
                    stack.push_back({child, 0});
                }
            }
        }
        return true;
    }

    // Room in the lists the walk appends to, from an upper bound of what it reaches: every leaf
    // node of every combination on every path, each primitive with its bodies and half-spaces
    // (the leaf cache and skipped regions make the walk reach less). Bounds beyond the caps
    // (a DAG reused along many paths may give far more than the walk makes: at most about
    // 50 + 200 MB of address space are reserved ahead) are not reserved, nor is anything when
    // the reservation fails: the lists then grow as they would.
    void Reserve(const std::vector<std::string>& tops) {
        constexpr double kCapBodies = 1 << 18, kCapHalfSpaces = 1 << 20;
        std::vector<Reach> memo(db_.combinations.size());
        std::vector<char> known(db_.combinations.size(), 0);
        Reach total;
        for (const std::string& name : tops) {
            auto it = db_.objects.find(name);
            if (it != db_.objects.end()) total += ReachOf(it->second, memo, known, 0);
            if (total.bodies > kCapBodies || total.halfSpaces > kCapHalfSpaces) return;
        }
        try {
            scene_.top.bodies.reserve(scene_.top.bodies.size() + std::size_t(total.bodies));
            scene_.top.halfSpaces.reserve(scene_.top.halfSpaces.size() +
                                          std::size_t(total.halfSpaces));
            exprs_.reserve(std::size_t(2 * total.leaves));
            leafCache_.Reserve(std::size_t(total.leaves));
        } catch (const std::bad_alloc&) {
        }
    }

    struct Reach {
        double leaves = 0, bodies = 0, halfSpaces = 0;
        Reach& operator+=(const Reach& o) {
            leaves += o.leaves;
            bodies += o.bodies;
            halfSpaces += o.halfSpaces;
            return *this;
        }
    };

    // Cycles are refused before (CheckCycles); nesting deeper than the walk allows counts as
    // nothing more (the walk stops there with an error).
    Reach ReachOf(std::pair<bool, int> object, std::vector<Reach>& memo, std::vector<char>& known,
                  int depth) {
        Reach r;
        if (!object.first) {
            const Primitive& p = db_.primitives[object.second];
            if (!converted_[object.second]) converted_[object.second] = ConvertPrimitive(p);
            r.leaves = 1;
            for (const ShapeBody& sb : converted_[object.second]->shape.bodies) {
                r.bodies += 1;
                r.halfSpaces += double(sb.size());
            }
            return r;
        }
        const auto ci = static_cast<std::size_t>(object.second);
        if (known[ci] || depth > kMaxDepth) return memo[ci];
        for (const TreeNode& n : db_.combinations[ci].nodes) {
            if (n.op != TreeNode::Op::kLeaf) continue;
            auto it = db_.objects.find(n.name);
            if (it != db_.objects.end()) r += ReachOf(it->second, memo, known, depth + 1);
        }
        memo[ci] = r;
        known[ci] = 1;
        return r;
    }

    std::vector<std::string> TopObjects() {
        std::vector<std::string> out;
        auto allTops = [&]() {
            std::set<std::string> referenced;
            for (const Combination& c : db_.combinations)
                for (const TreeNode& n : c.nodes)
                    if (n.op == TreeNode::Op::kLeaf) referenced.insert(n.name);
            std::vector<std::string> tops;
            // File order: combinations first (the usual top objects), then bare primitives.
            for (const Combination& c : db_.combinations)
                if (!referenced.count(c.name) &&
                    db_.objects.at(c.name).second == &c - db_.combinations.data())
                    tops.push_back(c.name);
            for (const Primitive& p : db_.primitives)
                if (!referenced.count(p.name) && !db_.objects.at(p.name).first &&
                    db_.objects.at(p.name).second == &p - db_.primitives.data())
                    tops.push_back(p.name);
            return tops;
        };
        // A COMGEOM deck is its regions: solids no region uses are not drawn (comgeom-g's "all").
        if (options_.topObjects.empty() && db_.format == "comgeom") return {"all"};
        if (options_.topObjects.empty()) return allTops();
        for (const std::string& name : options_.topObjects) {
            if (db_.objects.count(name)) {
                out.push_back(name);
            } else if (name == "all") {
                for (auto& t : allTops()) out.push_back(t);
            } else {
                report_.missingTops.push_back(name);
            }
        }
        return out;
    }

    int AddExpr(Expr e) {
        if (exprs_.size() >= kMaxExprs) {
            if (!aborted_)
                diags_.Error(file_ ? SourceLoc{file_, 0, 0} : SourceLoc{},
                             fmt::format("the combination trees expand to more than {} boolean "
                                         "nodes; refusing to go on",
                                         kMaxExprs));
            aborted_ = true;
            return -1;
        }
        exprs_.push_back(std::move(e));
        return static_cast<int>(exprs_.size()) - 1;
    }

    int Combine(scene::CsgOp op, int l, int r) {
        // Empty operands (missing members, skipped primitives, air) follow rt's NOP rules:
        // A ∪ ∅ = A, A ∩ ∅ = ∅, A − ∅ = A, ∅ − B = ∅.
        switch (op) {
            case scene::CsgOp::kUnion:
                if (l < 0) return r;
                if (r < 0) return l;
                break;
            case scene::CsgOp::kIntersection:
                if (l < 0 || r < 0) return -1;
                break;
            case scene::CsgOp::kDifference:
                if (l < 0) return -1;
                if (r < 0) return l;
                break;
        }
        Expr e;
        e.leaf = false;
        e.op = op;
        e.left = l;
        e.right = r;
        const Box3 &a = exprs_[l].box, &b = exprs_[r].box;
        if (op == scene::CsgOp::kUnion) {
            e.box = a;
            if (IsEverything(b) || IsEverything(a))
                e.box = Box3::Everything();
            else
                e.box.Extend(b);
        } else if (op == scene::CsgOp::kIntersection) {
            e.box = a.Intersected(b);
        } else {
            e.box = a;
        }
        return AddExpr(std::move(e));
    }

    static bool IsEverything(const Box3& b) { return !b.Empty() && !b.Finite(); }

    // The path matrix normalised so that m15 = 1 (FORMAT.md §2.4: m15 is an inverse scale).
    std::optional<Mat4> Normalised(const Mat4& m, const SourceLoc& loc, const std::string& who) {
        double w = m.m[3][3];
        if (!(std::fabs(w) > 1e-300) || !m.AllFinite()) {
            diags_.Error(loc,
                         fmt::format("the matrix of '{}' has m15 = {} (must be non-zero)", who, w));
            return std::nullopt;
        }
        Mat4 out = m;
        for (auto& row : out.m)
            for (double& x : row) x /= w;
        return out;
    }

    // "name.n" (what fmt::format("{}.{}", name, n) makes) in one allocation.
    static std::string NumberedId(const std::string& name, std::size_t n) {
        char digits[24];
        const auto end = std::to_chars(digits, digits + sizeof digits, n).ptr;
        std::string id;
        id.reserve(name.size() + 1 + static_cast<std::size_t>(end - digits));
        id.append(name).append(1, '.').append(digits, end);
        return id;
    }

    int Leaf(int primIndex, const Mat4& pathMatrix, const SourceLoc& refLoc) {
        const Primitive& p = db_.primitives[primIndex];
        if (!converted_[primIndex]) converted_[primIndex] = ConvertPrimitive(p);
        const ConvertResult& cr = *converted_[primIndex];
        if (IsNotASolid(p.type)) return -1;
        if (cr.status != ConvertResult::Status::kOk) {
            if (reachedSkipped_.insert(primIndex).second) {
                std::string label = cr.status == ConvertResult::Status::kInvalid
                                        ? cr.censusName + " (degenerate)"
                                        : cr.censusName;
                ++report_.skipped[label];
                if (cr.status == ConvertResult::Status::kNonQuadric)
                    missing_.push_back({primIndex, cr.censusName, cr.problem});
                if (cr.status == ConvertResult::Status::kInvalid)
                    diags_.Warning(p.loc,
                                   fmt::format("primitive '{}' ({}) is degenerate: {}; "
                                               "it is left out",
                                               p.name, p.type, cr.problem),
                                   p.sourceLine);
            }
            return -1;
        }
        auto norm = Normalised(pathMatrix, refLoc, p.name);
        if (!norm) {
            aborted_ = true;
            return -1;
        }
        Mat4 total = QuadrixFromZUp() * *norm;
        std::array<double, 17> key{};
        for (int i = 0; i < 16; ++i) key[i] = total.m[i / 4][i % 4];
        key[16] = primIndex;
        const std::size_t hash = LeafKeyHash{}(key);
        if (const int* found = leafCache_.Find(key, hash)) return *found;
        const std::optional<Transform>& t = TransformOf(total);
        if (!t) {
            diags_.Error(refLoc, fmt::format("the matrices on the path to '{}' cannot be inverted: "
                                             "singular, not finite, or scales more than 1e14 apart",
                                             p.name));
            aborted_ = true;
            return -1;
        }
        if (scene_.top.bodies.size() > kMaxBodies) {
            diags_.Error(refLoc, fmt::format("the model expands to more than {} primitive "
                                             "instances; refusing to go on",
                                             kMaxBodies));
            aborted_ = true;
            return -1;
        }
        Expr e;
        // A primitive of one body keeps its placed extent (and its box is that extent's).
        std::vector<ExtentPiece> extent = BodyExtent(cr.shape, total);
        e.box = cr.shape.unbounded ? Box3::Everything() : ShapeBox(cr.shape, total, extent);
        for (const ShapeBody& sb : cr.shape.bodies) {
            scene::Body body;
            body.id = p.name;
            body.loc = p.loc;
            body.usedAsOperand = true;
            body.extent = std::move(extent);  // empty unless the shape is this one body
            body.literals.reserve(sb.size());
            for (const ShapeHalfSpace& h : sb) {
                scene::HalfSpace hs;
                hs.id = NumberedId(p.name, scene_.top.halfSpaces.size());
                hs.loc = p.loc;
                hs.transparent = h.transparent;
                SetSceneSurface(Placed(h, *t), hs);
                body.literals.push_back(
                    {static_cast<int>(scene_.top.halfSpaces.size()), h.complement});
                scene_.top.halfSpaces.push_back(std::move(hs));
            }
            if (e.bodyCount++ == 0) e.firstBody = static_cast<int>(scene_.top.bodies.size());
            scene_.top.bodies.push_back(std::move(body));
        }
        int idx = AddExpr(std::move(e));
        if (idx >= 0) leafCache_.Insert(key, hash, idx);
        return idx;
    }

    // Transform::FromMatrix(total), made once for a run of leaves under the same matrix (the
    // primitives of one region placed once; the same bits, as the matrix is the same bit for bit).
    const std::optional<Transform>& TransformOf(const Mat4& total) {
        if (!lastTransform_ || std::memcmp(&lastTotal_, &total, sizeof total) != 0) {
            lastTotal_ = total;
            lastTransform_ = Transform::FromMatrix(total);
        }
        return *lastTransform_;
    }

    void WarnMissing(const std::string& parent, const std::string& name, const SourceLoc& loc) {
        if (!warnedMissing_.insert(parent + "\n" + name).second) return;
        diags_.Warning(loc, fmt::format("'{}' names '{}', which is not defined in this file; it is "
                                        "treated as empty (as rt does)",
                                        parent, name));
    }

    bool Enter(int combIndex, const SourceLoc& loc, int depth) {
        if (depth > kMaxDepth) {
            diags_.Error(loc, "combinations nested more than 1000 deep");
            aborted_ = true;
            return false;
        }
        if (combOnPath_[combIndex]) {
            const Combination& c = db_.combinations[combIndex];
            diags_.Error(c.loc,
                         fmt::format("combination '{}' contains itself (a cycle in the "
                                     "combination tree)",
                                     c.name),
                         c.sourceLine);
            aborted_ = true;
            return false;
        }
        combOnPath_[combIndex] = 1;
        return true;
    }

    // The CSG expression of a tree node inside a region (region flags below are ignored).
    bool TooDeep(int depth, const SourceLoc& loc) {
        if (depth <= kMaxTreeDepth) return false;
        if (!aborted_) diags_.Error(loc, fmt::format("boolean tree deeper than {}", kMaxTreeDepth));
        aborted_ = true;
        return true;
    }

    int TreeExpr(const Combination& c, int node, const Mat4& m, int depth) {
        if (node < 0 || aborted_ || TooDeep(depth, c.loc)) return -1;
        const TreeNode& n = c.nodes[node];
        if (n.op == TreeNode::Op::kLeaf)
            return ObjectExpr(c.name, n.name, m * n.matrix, n.loc, depth + 1);
        int l = TreeExpr(c, n.left, m, depth + 1);
        if (aborted_) return -1;
        int r = TreeExpr(c, n.right, m, depth + 1);
        return Combine(OpOf(n.op), l, r);
    }

    static scene::CsgOp OpOf(TreeNode::Op op) {
        return op == TreeNode::Op::kUnion          ? scene::CsgOp::kUnion
               : op == TreeNode::Op::kIntersection ? scene::CsgOp::kIntersection
                                                   : scene::CsgOp::kDifference;
    }

    int ObjectExpr(const std::string& parent, const std::string& name, const Mat4& m,
                   const SourceLoc& loc, int depth) {
        auto it = db_.objects.find(name);
        if (it == db_.objects.end()) {
            WarnMissing(parent, name, loc);
            return -1;
        }
        if (!it->second.first) return Leaf(it->second.second, m, loc);
        int ci = it->second.second;
        if (!Enter(ci, loc, depth)) return -1;
        const Combination& c = db_.combinations[ci];
        int e = TreeExpr(c, c.root, m, depth);
        combOnPath_[ci] = 0;
        return e;
    }

    std::optional<std::array<int, 3>> TableColor(int regionId) const {
        for (const ColorTableEntry& e : db_.colorTable)
            if (regionId >= e.low && regionId <= e.high) return e.rgb;
        return std::nullopt;
    }

    // Terms of an object above the region level (FORMAT.md §5.1-5.2).
    std::vector<Term> Terms(const std::string& name, const Mat4& m, ColorCtx ctx, int depth,
                            const TreeNode* ref) {
        std::vector<Term> out;
        if (aborted_) return out;
        auto it = db_.objects.find(name);
        SourceLoc loc = ref ? ref->loc : SourceLoc{};
        if (it == db_.objects.end()) {
            if (ref) WarnMissing(refParent_, name, loc);
            return out;
        }
        if (!it->second.first) {  // a bare primitive: a region of its own
            const Primitive& p = db_.primitives[it->second.second];
            int e = Leaf(it->second.second, m, ref ? loc : p.loc);
            if (e >= 0) out.push_back({e, p.name, ctx.rgb, p.loc, {}});
            return out;
        }
        int ci = it->second.second;
        const Combination& c = db_.combinations[ci];
        if (c.region) {
            if (c.aircode != 0 || c.shader == "envmap") return out;
            if (!Enter(ci, ref ? loc : c.loc, depth)) return out;
            Term t;
            t.expr = TreeExpr(c, c.root, m, depth);
            combOnPath_[ci] = 0;
            t.name = c.name;
            t.loc = c.loc;
            t.shader = c.shader;
            if (ctx.locked && ctx.rgb)
                t.rgb = ctx.rgb;
            else if (c.rgb)
                t.rgb = c.rgb;
            else if (ctx.rgb)
                t.rgb = ctx.rgb;
            else
                t.rgb = TableColor(c.regionId);
            if (t.expr >= 0) out.push_back(std::move(t));
            return out;
        }
        if (!ctx.locked && c.rgb) {
            ctx.rgb = c.rgb;
            ctx.locked = c.inherit;
        }
        if (!Enter(ci, ref ? loc : c.loc, depth)) return out;
        out = TreeTerms(c, c.root, m, ctx, depth + 1);
        combOnPath_[ci] = 0;
        return out;
    }

    std::vector<Term> TreeTerms(const Combination& c, int node, const Mat4& m, const ColorCtx& ctx,
                                int depth) {
        std::vector<Term> out;
        if (node < 0 || aborted_ || TooDeep(depth, c.loc)) return out;
        const TreeNode& n = c.nodes[node];
        if (n.op == TreeNode::Op::kLeaf) {
            refParent_ = c.name;
            return Terms(n.name, m * n.matrix, ctx, depth + 1, &n);
        }
        std::vector<Term> l = TreeTerms(c, n.left, m, ctx, depth + 1);
        if (aborted_) return {};
        std::vector<Term> r = TreeTerms(c, n.right, m, ctx, depth + 1);
        if (aborted_) return {};
        switch (n.op) {
            case TreeNode::Op::kUnion:
                out = std::move(l);
                for (Term& t : r) out.push_back(std::move(t));
                break;
            case TreeNode::Op::kIntersection:  // (A∪B)∩(C∪D) = ∪ A∩C ...
                if (l.size() * r.size() > kMaxTerms) {
                    diags_.Error(n.loc, fmt::format("combination '{}' expands to more than {} "
                                                    "rendered regions",
                                                    c.name, kMaxTerms));
                    aborted_ = true;
                    return {};
                }
                for (const Term& a : l)
                    for (const Term& b : r) {
                        int e = Combine(scene::CsgOp::kIntersection, a.expr, b.expr);
                        if (e >= 0) out.push_back({e, a.name, a.rgb, a.loc, a.shader});
                    }
                break;
            default: {  // (A∪B) − (C∪D) = (A − C − D) ∪ (B − C − D)
                for (const Term& a : l) {
                    int e = a.expr;
                    for (const Term& b : r) e = Combine(scene::CsgOp::kDifference, e, b.expr);
                    if (e >= 0) out.push_back({e, a.name, a.rgb, a.loc, a.shader});
                }
                break;
            }
        }
        if (out.size() > kMaxTerms) {
            diags_.Error(n.loc, fmt::format("combination '{}' expands to more than {} rendered "
                                            "regions",
                                            c.name, kMaxTerms));
            aborted_ = true;
            out.clear();
        }
        return out;
    }

    int EmitNode(scene::Csg& csg, int expr) {
        if (++emitted_ > kMaxCsgNodes) {
            if (emitted_ == kMaxCsgNodes + 1)
                diags_.Error(csg.loc, fmt::format("the model expands to more than {} CSG nodes; "
                                                  "refusing to go on",
                                                  kMaxCsgNodes));
            aborted_ = true;
            return -1;
        }
        const Expr& e = exprs_[expr];
        auto add = [&](scene::CsgNode n) {
            csg.nodes.push_back(n);
            return static_cast<int>(csg.nodes.size()) - 1;
        };
        if (e.leaf) {
            int root = -1;
            for (int b = e.firstBody; b < e.firstBody + e.bodyCount; ++b) {
                scene::CsgNode leaf;
                leaf.isLeaf = true;
                leaf.ref = {scene::SolidRef::Kind::kBody, b};
                leaf.loc = scene_.top.bodies[b].loc;
                int li = add(leaf);
                if (root < 0) {
                    root = li;
                } else {
                    scene::CsgNode u;
                    u.isLeaf = false;
                    u.op = scene::CsgOp::kUnion;
                    u.left = root;
                    u.right = li;
                    root = add(u);
                }
            }
            return root;
        }
        int l = EmitNode(csg, e.left);
        int r = EmitNode(csg, e.right);
        if (l < 0 || r < 0) return -1;
        scene::CsgNode n;
        n.isLeaf = false;
        n.op = e.op;
        n.left = l;
        n.right = r;
        return add(n);
    }

    // LinearFromSrgb(v / 255), from a table for 0..255 (the same values; a model has thousands
    // of regions and a handful of colours).
    double Linear(int v) {
        if (v < 0 || v > 255) return LinearFromSrgb(v / 255.0);
        if (linear_.empty()) {
            linear_.resize(256);
            for (int i = 0; i < 256; ++i) linear_[std::size_t(i)] = LinearFromSrgb(i / 255.0);
        }
        return linear_[std::size_t(v)];
    }

    void Emit(const std::vector<Term>& terms) {
        scene_.top.csgs.reserve(scene_.top.csgs.size() + terms.size());
        std::map<std::string, int> used;
        for (const Term& t : terms) {
            scene::Csg csg;
            int k = used[t.name]++;
            csg.id = k == 0 ? t.name : fmt::format("{}#{}", t.name, k + 1);
            csg.loc = t.loc;
            // rt's colors are display (sRGB) values: decoded to linear light (math/srgb.h).
            if (t.rgb)
                csg.color =
                    scene::Color{Linear((*t.rgb)[0]), Linear((*t.rgb)[1]), Linear((*t.rgb)[2])};
            csg.finish = ShaderFinish(t.shader);
            csg.root = EmitNode(csg, t.expr);
            if (aborted_) return;
            const Box3& b = exprs_[t.expr].box;
            if (b.Finite()) report_.bounds.Extend(b);
            scene_.top.csgs.push_back(std::move(csg));
            ++report_.solids;
        }
    }

    // Deliverable "nothing dropped silently" (brlcad_import.h ImportOptions): one error per
    // primitive that is not drawn (the first kMaxNamed, then a count), or with allowMissing one
    // warning with the counts by type.
    void ReportSkipped() {
        if (report_.skipped.empty()) return;
        SourceLoc loc;
        loc.file = file_;
        int total = 0;
        for (const auto& [type, n] : report_.skipped) total += n;
        if (missing_.empty()) return;  // only degenerate primitives: warned one by one
        if (options_.MissingIsError()) {
            constexpr std::size_t kMaxNamed = 20;
            for (std::size_t i = 0; i < missing_.size() && i < kMaxNamed; ++i) {
                const Primitive& p = db_.primitives[missing_[i].prim];
                std::string where =
                    p.byteOffset >= 0 ? fmt::format(" (object at byte {})", p.byteOffset) : "";
                diags_.Error(p.loc,
                             fmt::format("primitive '{}' ({}){} cannot be drawn: {}; the render "
                                         "stops (--allow-missing draws the model without it)",
                                         p.name, missing_[i].label, where,
                                         missing_[i].why.empty()
                                             ? std::string("it is not made of quadrics and planes")
                                             : missing_[i].why),
                             p.sourceLine);
            }
            if (missing_.size() > kMaxNamed)
                diags_.Error(loc, fmt::format("... and {} more primitives that cannot be drawn",
                                              missing_.size() - kMaxNamed));
            return;
        }
        diags_.Warning(loc, fmt::format("{} primitive{} left out (--allow-missing): {}; the model "
                                        "is drawn without them",
                                        total, total == 1 ? "" : "s", report_.SkippedText()));
    }

  public:
    std::shared_ptr<const std::string> file_;

  private:
    const Database& db_;
    const ImportOptions& options_;
    scene::Scene& scene_;
    Diagnostics& diags_;
    ImportReport& report_;
    std::vector<Expr> exprs_;
    std::vector<char> combOnPath_;
    std::vector<std::optional<ConvertResult>> converted_;
    std::set<int> reachedSkipped_;
    struct Missing {
        int prim;
        std::string label, why;
    };
    std::vector<Missing> missing_;  // reached, not drawable, in the order they were reached
    std::set<std::string> warnedMissing_;
    // A primitive under a placement (the 16 entries of the total matrix, then the primitive's
    // index) to its leaf. Keys are equal when their entries compare equal (-0 = +0); a key with
    // a NaN entry (a matrix whose product overflowed) equals none, and Transform::FromMatrix
    // then refuses it.
    using LeafKey = std::array<double, 17>;
    struct LeafKeyHash {
        std::size_t operator()(const LeafKey& k) const {
            std::uint64_t h = 0x243f6a8885a308d3ULL;
            for (double x : k) {
                const double y = x + 0.0;  // -0 and +0 hash alike, as they compare equal
                std::uint64_t u;
                std::memcpy(&u, &y, sizeof u);
                h = (h ^ u) * 0x100000001b3ULL;
                h ^= h >> 29;
            }
            return static_cast<std::size_t>(h);
        }
    };
    // The placements already converted (HashSlots: one array, no node per entry; a model's
    // leaves are mostly distinct placements, one insert each), keys in insertion order.
    class LeafTable {
      public:
        const int* Find(const LeafKey& k, std::size_t hash) const {
            const int at = slots_.Find(hash, [&](int i) { return keys_[std::size_t(i)] == k; });
            return at < 0 ? nullptr : &exprs_[std::size_t(at)];
        }
        void Insert(const LeafKey& k, std::size_t hash, int expr) {
            slots_.Insert(hash, static_cast<int>(keys_.size()));
            keys_.push_back(k);
            exprs_.push_back(expr);
        }
        void Reserve(std::size_t n) {
            keys_.reserve(n);
            exprs_.reserve(n);
            slots_.Reserve(n);
        }

      private:
        HashSlots slots_;
        std::vector<LeafKey> keys_;
        std::vector<int> exprs_;
    };
    LeafTable leafCache_;
    std::vector<double> linear_;                             // Linear's table, made on first use
    Mat4 lastTotal_;                                         // TransformOf's last matrix
    std::optional<std::optional<Transform>> lastTransform_;  // and its transform, once made
    std::string refParent_;
    std::size_t emitted_ = 0;
    bool aborted_ = false;
};

}  // namespace

bool ImportBrlcad(std::string_view text, const std::string& file, const ImportOptions& options,
                  scene::Scene& scene, Diagnostics& diags, ImportReport& report) {
    Database db;
    bool ok = false;
    if (IsV5Binary(text)) {
        ok = ParseG(text, file, db, diags);
        report.format = "BRL-CAD v5 binary";
        report.title = db.title;
        if (!ok) return false;
        Converter conv(db, options, scene, diags, report);
        conv.file_ = std::make_shared<const std::string>(file);
        return conv.Run() && !diags.HasErrors();
    }
    if (!text.empty() && text[0] == 'I' &&
        text.substr(0, 128).find('\0') != std::string_view::npos) {
        // A v4 binary ident record ('I', a units byte, "v4", NUL padding): text never has NULs.
        SourceLoc loc;
        loc.file = std::make_shared<const std::string>(file);
        diags.Error(loc,
                    "a BRL-CAD v4 binary database: only v5 binary files are read; upgrade it "
                    "with BRL-CAD's dbupgrade, or dump it with g2asc");
        return false;
    }
    switch (DetectFormat(text)) {
        case TextFormat::kV4:
            ok = ParseV4(text, file, db, diags);
            report.format = "BRL-CAD v4";
            break;
        case TextFormat::kV5:
            ok = ParseV5(text, file, db, diags);
            report.format = "BRL-CAD v5";
            break;
        case TextFormat::kComgeom:
            ok = ParseComgeom(text, file, db, diags);
            report.format = "COMGEOM";
            break;
        case TextFormat::kUnknown: {
            SourceLoc loc;
            loc.file = std::make_shared<const std::string>(file);
            loc.line = 1;
            loc.column = 1;
            diags.Error(loc,
                        "not a BRL-CAD database: expected 'I <units> v4' (v4), a "
                        "title/units/put command (v5), a COMGEOM deck or the v5 binary header "
                        "(a .g file)");
            return false;
        }
    }
    report.title = db.title;
    if (!ok) return false;
    Converter conv(db, options, scene, diags, report);
    conv.file_ = std::make_shared<const std::string>(file);
    return conv.Run() && !diags.HasErrors();
}

}  // namespace quadrix::import
