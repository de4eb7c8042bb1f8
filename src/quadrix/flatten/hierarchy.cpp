// Traversal of the scene hierarchy and CSG solids; see hierarchy.h.
#include "quadrix/flatten/hierarchy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "quadrix/flatten/coefficient_scale.h"
#include "quadrix/lang/big_arrays.h"

namespace quadrix {

namespace {

using scene::Color;
using scene::CsgOp;
using scene::SolidRef;

std::string BodyName(const scene::Body& b, int index) {
    return b.id.empty() ? fmt::format("body#{}", index) : b.id;
}
std::string CsgName(const scene::Csg& c, int index) {
    return c.id.empty() ? fmt::format("csg#{}", index) : c.id;
}
std::string InstanceName(const scene::Scene& s, const scene::Instance& inst) {
    if (!inst.id.empty()) return inst.id;
    if (inst.definition >= 0 && inst.definition < static_cast<int>(s.definitions.size()))
        return s.definitions[inst.definition].id;
    return "instance";
}

// ---------------------------------------------------------------------------------------------
// Counting pass (the explosion guard). Scope key: -1 = top, else the definition index.

struct Counts {
    double bodies = 0, literals = 0;
    // Half-spaces of the scope instances visited (each maps its own at most once): an upper
    // bound of the half-spaces the walk appends, for reserving.
    double halfSpaces = 0;
    Counts& operator+=(const Counts& o) {
        bodies += o.bodies;
        literals += o.literals;
        halfSpaces += o.halfSpaces;
        return *this;
    }
    Counts operator*(double k) const { return {bodies * k, literals * k, halfSpaces * k}; }
};

class Counter {
  public:
    Counter(const scene::Scene& scene, int clipPerBody, Diagnostics& diags)
        : scene_(scene), clip_(clipPerBody), diags_(diags) {
        int n = static_cast<int>(scene.definitions.size());
        defState_.assign(n, 0);
        defCounts_.resize(n);
        csgState_.resize(n + 1);
        csgCounts_.resize(n + 1);
        for (int key = -1; key < n; ++key) {
            csgState_[key + 1].assign(ScopeOf(key).csgs.size(), 0);
            csgCounts_[key + 1].resize(ScopeOf(key).csgs.size());
        }
    }

    bool ok() const { return ok_; }

    const scene::Scope& ScopeOf(int key) const {
        return key < 0 ? scene_.top : scene_.definitions[key];
    }

    // Everything a scope draws.
    Counts Drawn(int key, int depth) {
        const scene::Scope& s = ScopeOf(key);
        Counts c;
        for (std::size_t i = 0; i < s.bodies.size() && ok_; ++i)
            if (!s.bodies[i].usedAsOperand) c += Ref(key, {SolidRef::Kind::kBody, int(i)}, depth);
        for (std::size_t i = 0; i < s.instances.size() && ok_; ++i)
            if (!s.instances[i].usedAsOperand)
                c += Ref(key, {SolidRef::Kind::kInstance, int(i)}, depth);
        for (std::size_t i = 0; i < s.csgs.size() && ok_; ++i)
            if (!s.csgs[i].usedAsOperand) c += Ref(key, {SolidRef::Kind::kCsg, int(i)}, depth);
        return c;
    }

    Counts Ref(int key, const SolidRef& ref, int depth) {
        const scene::Scope& s = ScopeOf(key);
        switch (ref.kind) {
            case SolidRef::Kind::kBody:
                if (ref.index < 0 || ref.index >= int(s.bodies.size())) return Bad(s.loc);
                return {1, double(s.bodies[ref.index].literals.size()) + clip_, 0};
            case SolidRef::Kind::kInstance: {
                if (ref.index < 0 || ref.index >= int(s.instances.size())) return Bad(s.loc);
                const scene::Instance& inst = s.instances[ref.index];
                if (inst.count <= 0) return {};
                return Definition(inst, depth) * double(inst.count);
            }
            case SolidRef::Kind::kCsg:
                if (ref.index < 0 || ref.index >= int(s.csgs.size())) return Bad(s.loc);
                return Csg(key, ref.index, depth);
        }
        return {};
    }

  private:
    Counts Bad(const SourceLoc& loc) {
        if (ok_) diags_.Error(loc, "internal error: a solid reference is out of range");
        ok_ = false;
        return {};
    }

    Counts Definition(const scene::Instance& inst, int depth) {
        int def = inst.definition;
        if (def < 0 || def >= int(scene_.definitions.size())) {
            if (ok_) diags_.Error(inst.loc, fmt::format("'{}' names no definition", inst.id));
            ok_ = false;
            return {};
        }
        if (defState_[def] == 2) return defCounts_[def];
        if (defState_[def] == 1 || depth >= kMaxNesting) {
            if (ok_)
                diags_.Error(
                    inst.loc,
                    defState_[def] == 1
                        ? fmt::format("definition '{}' instances itself (directly or "
                                      "through other definitions)",
                                      scene_.definitions[def].id)
                        : fmt::format("definitions are nested more than {} deep", kMaxNesting));
            ok_ = false;
            return {};
        }
        defState_[def] = 1;
        Counts c = Drawn(def, depth + 1);
        c.halfSpaces += double(scene_.definitions[def].halfSpaces.size());
        defState_[def] = 2;
        defCounts_[def] = c;
        return c;
    }

    Counts Csg(int key, int index, int depth) {
        int& state = csgState_[key + 1][index];
        const scene::Csg& csg = ScopeOf(key).csgs[index];
        if (state == 2) return csgCounts_[key + 1][index];
        if (state == 1 || depth >= kMaxNesting) {
            if (ok_)
                diags_.Error(csg.loc, state == 1
                                          ? fmt::format("csg '{}' refers to itself", csg.id)
                                          : fmt::format("CSG solids are nested more than {} deep",
                                                        kMaxNesting));
            ok_ = false;
            return {};
        }
        state = 1;
        Counts c;
        // Iterative walk over the expression's nodes (a long chain must not recurse), on the
        // shared stack above the entries of the walks this one is nested in.
        std::vector<int>& stack = stack_;
        const std::size_t base = stack.size();
        stack.push_back(csg.root);
        std::size_t visited = 0;
        while (stack.size() > base && ok_) {
            int n = stack.back();
            stack.pop_back();
            if (n < 0 || n >= int(csg.nodes.size()) || ++visited > csg.nodes.size()) {
                Bad(csg.loc);
                break;
            }
            const scene::CsgNode& node = csg.nodes[n];
            if (node.isLeaf) {
                c += Ref(key, node.ref, depth + 1);
            } else {
                stack.push_back(node.right);
                stack.push_back(node.left);
            }
        }
        stack.resize(base);
        state = 2;
        csgCounts_[key + 1][index] = c;
        return c;
    }

    const scene::Scene& scene_;
    double clip_;
    Diagnostics& diags_;
    bool ok_ = true;
    std::vector<int> defState_;
    std::vector<Counts> defCounts_;
    std::vector<std::vector<int>> csgState_;
    std::vector<std::vector<Counts>> csgCounts_;
    std::vector<int> stack_;  // Csg's walks (one allocation for all)
};

// ---------------------------------------------------------------------------------------------
// The walk.

// One visit of a scope under a transform: its half-spaces are transformed lazily, once.
struct ScopeInst {
    const scene::Scope* scope = nullptr;
    Transform t;       // target from object
    std::string path;  // name prefix, "" or "a[1]/b/"
    std::vector<int> hsMap;
    std::uint64_t serial = 0;  // unique in the walk (addresses of finished copies are reused)
};

// The state of an array used as a CSG operand, expanded copy by copy.
struct InstanceIter {
    ScopeInst* parent = nullptr;
    const scene::Instance* inst = nullptr;
    int k = 0;
    Transform deltaK;  // delta^k
};

inline const std::string kNoPath;

// a + b + c in one allocation (names are built once per body and half-space).
std::string Joined(std::string_view a, std::string_view b, std::string_view c = {}) {
    std::string s;
    s.reserve(a.size() + b.size() + c.size());
    s.append(a).append(b).append(c);
    return s;
}

// An item of work while collecting the operands of an n-ary node.
struct Term {
    enum class Kind { kRef, kNode, kInstanceCopy, kPopScope, kChildren };
    Kind kind = Kind::kRef;
    ScopeInst* si = nullptr;
    SolidRef ref;                // kRef
    int csg = -1;                // kNode: csg index in si->scope
    int node = -1;               // kNode: node index in that csg
    std::optional<Color> color;  // innermost enclosing csg/instance color
    scene::Finish finish;        // likewise, property by property
    // CSG ids inside the scope instance, "" or "c/": an entry of Walker::paths_ (copying a Term
    // copies no string).
    const std::string* path = &kNoPath;
    std::shared_ptr<InstanceIter> iter;  // kInstanceCopy
    // kChildren: nodes of csg `csg` still to collect in this context, the next one last (the
    // right operands of a chain: 4 bytes each instead of a Term).
    std::vector<int> nodes;
};

class Walker {
  public:
    Walker(const scene::Scene& scene, FlatScene& out, HierarchyResult& result, Diagnostics& diags,
           const HierarchyLimits& limits, HalfSpaceObserver* observer)
        : scene_(scene),
          out_(out),
          result_(result),
          diags_(diags),
          observer_(observer),
          clipLiterals_(limits.clipLiteralsPerBody),
          halfSpaceNames_(limits.halfSpaceNames),
          keepExtentPieces_(limits.keepExtentPieces),
          keepHalfSpaceLocs_(limits.keepHalfSpaceLocs) {}

    bool Run(const Transform& targetFromWorld) {
        worldFromTarget_ = targetFromWorld.Inverted();
        ScopeInst top{&scene_.top, targetFromWorld, "", {}, nextSerial_++};
        top.hsMap.assign(scene_.top.halfSpaces.size(), -1);
        DrawScope(top, std::nullopt, {});
        return !failed_;
    }

  private:
    static constexpr int kMaxDepth = 1000;  // CSG expression recursion (alternating operators)
    static constexpr std::size_t kMaxFreeforms = 100000;

    void Fail(const SourceLoc& loc, std::string message) {
        if (!failed_) diags_.Error(loc, std::move(message));
        failed_ = true;
    }

    void DrawScope(ScopeInst& si, const std::optional<Color>& color, const scene::Finish& finish) {
        const scene::Scope& s = *si.scope;
        for (std::size_t i = 0; i < s.bodies.size() && !failed_; ++i) {
            if (s.bodies[i].usedAsOperand) continue;
            Term t = RefTerm(si, {SolidRef::Kind::kBody, int(i)}, color, finish);
            AddSolid(t, Joined(si.path, BodyName(s.bodies[i], int(i))), s.bodies[i].loc);
        }
        for (std::size_t i = 0; i < s.instances.size() && !failed_; ++i) {
            const scene::Instance& inst = s.instances[i];
            if (inst.usedAsOperand || inst.count <= 0) continue;
            const scene::Scope& def = scene_.definitions[inst.definition];
            std::optional<Color> c = inst.color ? inst.color : color;
            const scene::Finish fin = scene::Finish::Over(inst.finish, finish);
            Transform deltaK;
            for (int k = 0; k < inst.count && !failed_; ++k) {
                ScopeInst child{
                    &def, si.t * deltaK * inst.init, CopyPath(si.path, inst, k), {}, nextSerial_++};
                child.hsMap.assign(def.halfSpaces.size(), -1);
                DrawScope(child, c, fin);
                deltaK = inst.delta * deltaK;
            }
        }
        for (const scene::FreeformSurface& f : s.freeforms) {
            if (failed_) break;
            if (out_.freeforms.size() >= kMaxFreeforms) {
                Fail(f.loc, fmt::format("more than {} freeform surfaces to draw (instances and "
                                        "arrays multiply them)",
                                        kMaxFreeforms));
                break;
            }
            FlatFreeform ff;
            // The walk composes target-from-object; freeform surfaces stay in world space.
            ff.surface = f.surface.Transformed((worldFromTarget_ * si.t).Matrix());
            ff.color = f.color ? *f.color : color ? *color : Color{};
            ff.finish = scene::Finish::Over(f.finish, finish);
            ff.name = si.path + f.id;
            ff.loc = f.loc;
            out_.freeforms.push_back(std::move(ff));
        }
        for (std::size_t i = 0; i < s.csgs.size() && !failed_; ++i) {
            if (s.csgs[i].usedAsOperand) continue;
            Term t = RefTerm(si, {SolidRef::Kind::kCsg, int(i)}, color, finish);
            AddSolid(t, Joined(si.path, CsgName(s.csgs[i], int(i))), s.csgs[i].loc);
        }
    }

    static Term RefTerm(ScopeInst& si, SolidRef ref, const std::optional<Color>& color,
                        const scene::Finish& finish) {
        Term t;
        t.kind = Term::Kind::kRef;
        t.si = &si;
        t.ref = ref;
        t.color = color;
        t.finish = finish;
        return t;
    }

    // The name prefix of copy k: the enclosing prefix (scope instance path plus CSG ids), the
    // instance's id and, for arrays, the copy index.
    std::string CopyPath(const std::string& prefix, const scene::Instance& inst, int k) const {
        std::string name = InstanceName(scene_, inst);
        if (inst.isArray) name += fmt::format("[{}]", k);
        return prefix + name + "/";
    }

    void AddSolid(const Term& t, std::string name, const SourceLoc& loc) {
        currentSolid_ = static_cast<int>(out_.solids.size());
        std::size_t scopes = scopes_.size();
        int root = Emit(t, 0);
        scopes_.resize(scopes);  // operand instance copies are done with
        if (failed_) return;
        FlatSolid solid;
        solid.root = root;
        solid.name = std::move(name);
        out_.solids.push_back(std::move(solid));
        result_.solidLocs.push_back(loc);
        result_.solidIsCsg.push_back(t.ref.kind == SolidRef::Kind::kCsg);
    }

    // Follows leaves and references to CSG solids until t is a body or instance reference or an
    // internal node.
    void Normalize(Term& t) {
        for (int guard = 0; guard < 100000; ++guard) {
            const scene::Scope& s = *t.si->scope;
            if (t.kind == Term::Kind::kNode) {
                const scene::CsgNode& node = s.csgs[t.csg].nodes[t.node];
                if (!node.isLeaf) return;
                t.kind = Term::Kind::kRef;
                t.ref = node.ref;
                continue;
            }
            if (t.kind != Term::Kind::kRef || t.ref.kind != SolidRef::Kind::kCsg) return;
            const scene::Csg& c = s.csgs[t.ref.index];
            t.kind = Term::Kind::kNode;
            t.csg = t.ref.index;
            t.node = c.root;
            if (c.color) t.color = c.color;
            t.finish = scene::Finish::Over(c.finish, t.finish);
            t.path = &paths_.emplace_back(Joined(*t.path, CsgName(c, t.csg), "/"));
        }
        Fail(t.si->scope->loc, "internal error: CSG references loop");
    }

    Term Child(const Term& t, int node) const {
        Term c;
        c.kind = Term::Kind::kNode;
        c.si = t.si;
        c.csg = t.csg;
        c.node = node;
        c.color = t.color;
        c.finish = t.finish;
        c.path = t.path;
        return c;
    }

    const scene::CsgNode& NodeOf(const Term& t) const {
        return t.si->scope->csgs[t.csg].nodes[t.node];
    }

    int AddNode(CsgOp op, std::vector<int> children) {
        FlatCsgNode n;
        n.isLeaf = false;
        n.op = op;
        n.children = std::move(children);
        out_.nodes.push_back(std::move(n));
        return static_cast<int>(out_.nodes.size()) - 1;
    }

    int Emit(Term t, int depth) {
        if (failed_) return -1;
        if (depth > kMaxDepth) {
            Fail(t.si->scope->loc,
                 fmt::format("CSG expressions are nested more than {} deep", kMaxDepth));
            return -1;
        }
        Normalize(t);
        if (failed_) return -1;
        if (t.kind == Term::Kind::kRef) {
            if (t.ref.kind == SolidRef::Kind::kBody) return Leaf(t);
            std::vector<int> children;
            Collect(CsgOp::kUnion, {t}, children, depth);
            return children.size() == 1 ? children[0] : AddNode(CsgOp::kUnion, std::move(children));
        }
        const scene::CsgNode& node = NodeOf(t);
        if (node.op != CsgOp::kDifference) {
            std::vector<int> children;
            Collect(node.op, {Child(t, node.left), Child(t, node.right)}, children, depth);
            return children.size() == 1 ? children[0] : AddNode(node.op, std::move(children));
        }
        Term minuend;
        std::vector<Term> subtrahends;
        if (!Spine(t, minuend, subtrahends)) return -1;
        return EmitDifference(std::move(minuend), std::move(subtrahends), depth);
    }

    // (a − b) − c → a, [b, c]: the minuend and the subtrahends in order, down the left spine of
    // a normalised difference term t. False when normalising failed.
    bool Spine(const Term& t, Term& minuend, std::vector<Term>& subtrahends) {
        subtrahends.clear();
        minuend = t;
        for (;;) {
            Normalize(minuend);
            if (failed_) return false;
            if (minuend.kind != Term::Kind::kNode || NodeOf(minuend).op != CsgOp::kDifference)
                break;
            subtrahends.push_back(Child(minuend, NodeOf(minuend).right));
            minuend = Child(minuend, NodeOf(minuend).left);
        }
        std::reverse(subtrahends.begin(), subtrahends.end());
        return true;
    }

    // The node of a difference's spine, at Emit's depth (which Emit has checked).
    int EmitDifference(Term minuend, std::vector<Term> subtrahends, int depth) {
        std::vector<int> children{Emit(std::move(minuend), depth + 1)};
        // a - (b | c) = a - b - c: subtrahends that are unions are spliced.
        Collect(CsgOp::kUnion, std::move(subtrahends), children, depth);
        if (children.size() == 1) return children[0];
        return AddNode(CsgOp::kDifference, std::move(children));
    }

    // A subtracted body of a difference being grouped: what its leaf is made from.
    struct Subtrahend {
        std::uint64_t scope = 0;  // ScopeInst::serial
        int body = -1;
        std::optional<Color> color;
        scene::Finish finish;
        const std::string* path = &kNoPath;  // compared by its characters
        bool operator==(const Subtrahend& o) const {
            return scope == o.scope && body == o.body && color == o.color && finish == o.finish &&
                   *path == *o.path;
        }
    };
    // Differences of one Collect that subtract the same bodies: (∪ᵢ minuendᵢ) − leaves.
    struct DifferenceGroup {
        std::vector<Subtrahend> key;
        std::vector<int> leaves;    // the subtrahends' leaves, made once
        std::vector<int> minuends;  // the operands of the group's union or intersection
        std::size_t slot = 0;       // its place in Collect's output: its first member's
    };
    struct DifferenceGroups {
        std::vector<DifferenceGroup> groups;
        std::unordered_map<std::uint64_t, std::vector<int>> byHash;
    };

    static std::uint64_t Mix(std::uint64_t h, std::uint64_t v) {
        return h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 12) + (h >> 4));
    }
    static std::uint64_t Bits(double d) {
        std::uint64_t u;
        std::memcpy(&u, &d, sizeof u);
        return u;
    }
    static std::uint64_t Hash(const std::vector<Subtrahend>& key) {
        std::uint64_t h = key.size();
        for (const Subtrahend& s : key) {
            h = Mix(Mix(h, s.scope), std::uint64_t(std::uint32_t(s.body)));
            if (s.color) h = Mix(Mix(Mix(h, Bits(s.color->r)), Bits(s.color->g)), Bits(s.color->b));
            h = Mix(h, std::hash<std::string>{}(*s.path));
        }
        return h;
    }

    // Differences as operands of a union or intersection: ∪ᵢ (aᵢ − s) = (∪ᵢ aᵢ) − s and
    // ∩ᵢ (aᵢ − s) = (∩ᵢ aᵢ) − s, exact for point sets. Differences of one operator node that
    // subtract the same bodies (every subtrahend a single body, the same ones in the same order,
    // from the same scope instance with the same inherited color, finish and path, so the same
    // leaves) are made into one: each minuend is collected into the group and the subtrahends'
    // leaves are made once, at the first member, which is where the group stands. Written either
    // way the solid then has the same tree and costs the same (issue 24: ∪ᵢ (sphereᵢ − drill)
    // within 1.2× of (∪ᵢ sphereᵢ) − drill); the picture is the same pixel for pixel, the Frame's
    // body id of a subtracted face being the one leaf's. A difference with another kind of
    // subtrahend is not grouped (false, nothing made). t is a normalised difference node.
    bool GroupDifference(CsgOp op, const Term& minuend, std::vector<Term>& subtrahends,
                         DifferenceGroups& g, std::vector<int>& out, int depth) {
        if (depth > kMaxDepth) return false;  // Emit reports it
        std::vector<Subtrahend> key;
        key.reserve(subtrahends.size());
        for (Term& s : subtrahends) {
            Normalize(s);
            if (failed_ || s.kind != Term::Kind::kRef || s.ref.kind != SolidRef::Kind::kBody)
                return false;
            key.push_back({s.si->serial, s.ref.index, s.color, s.finish, s.path});
        }
        std::vector<int>& candidates = g.byHash[Hash(key)];
        for (int c : candidates)
            if (g.groups[c].key == key) {
                Collect(op, {minuend}, g.groups[c].minuends, depth + 1);
                return true;
            }
        candidates.push_back(static_cast<int>(g.groups.size()));
        DifferenceGroup& group = g.groups.emplace_back();  // (the Collect below has its own)
        group.key = std::move(key);
        group.slot = out.size();
        out.push_back(-1);  // filled in by FinishGroups
        // The minuend's bodies before the subtrahends', as Emit makes them.
        Collect(op, {minuend}, group.minuends, depth + 1);
        for (const Term& s : subtrahends) group.leaves.push_back(Leaf(s));
        return true;
    }

    void FinishGroups(CsgOp op, DifferenceGroups& g, std::vector<int>& out) {
        for (DifferenceGroup& group : g.groups) {
            std::vector<int> children{group.minuends.size() == 1
                                          ? group.minuends[0]
                                          : AddNode(op, std::move(group.minuends))};
            children.insert(children.end(), group.leaves.begin(), group.leaves.end());
            out[group.slot] = AddNode(CsgOp::kDifference, std::move(children));
        }
    }

    // Appends the operands of an `op` node to `out`, splicing terms of the same associative
    // operator and, for unions, instances (the union of what they draw), and grouping the
    // differences that subtract the same bodies (GroupDifference). `firsts` are the node's
    // operands in order. Iterative, so long chains and big arrays do not recurse.
    void Collect(CsgOp op, std::vector<Term> firsts, std::vector<int>& out, int depth) {
        std::vector<Term> stack(std::make_move_iterator(firsts.rbegin()),
                                std::make_move_iterator(firsts.rend()));
        DifferenceGroups groups;
        while (!stack.empty() && !failed_) {
            Term t;
            if (Term& rest = stack.back(); rest.kind == Term::Kind::kChildren) {
                t = Child(rest, rest.nodes.back());
                rest.nodes.pop_back();
                if (rest.nodes.empty()) stack.pop_back();
            } else {
                t = std::move(stack.back());
                stack.pop_back();
            }
            if (t.kind == Term::Kind::kPopScope) {
                scopes_.pop_back();
                continue;
            }
            if (t.kind == Term::Kind::kInstanceCopy) {
                ExpandCopy(t, stack);
                continue;
            }
            Normalize(t);
            if (failed_) return;
            if (t.kind == Term::Kind::kNode && NodeOf(t).op == op && op != CsgOp::kDifference) {
                // Down the chain's left spine while it stays an `op` node of this csg (a long
                // a | b | c … is left-deep): the right operands wait as node indices, in one
                // kChildren term, instead of as a Term each (100,000 Terms were 35 MB of fresh
                // pages, docs/performance.md).
                const std::vector<scene::CsgNode>& nodes = t.si->scope->csgs[t.csg].nodes;
                Term rest = Child(t, -1);
                rest.kind = Term::Kind::kChildren;
                int n = t.node;
                for (std::size_t guard = 0; guard <= nodes.size(); ++guard) {
                    rest.nodes.push_back(nodes[n].right);
                    const scene::CsgNode& left = nodes[nodes[n].left];
                    if (left.isLeaf || left.op != op) break;
                    n = nodes[n].left;
                }
                const int leftmost = nodes[n].left;
                stack.push_back(std::move(rest));
                stack.push_back(Child(t, leftmost));
                continue;
            }
            if (t.kind == Term::Kind::kRef && t.ref.kind == SolidRef::Kind::kInstance &&
                op == CsgOp::kUnion) {
                const scene::Instance& inst = t.si->scope->instances[t.ref.index];
                if (inst.count <= 0) continue;
                Term copy;
                copy.kind = Term::Kind::kInstanceCopy;
                copy.si = t.si;
                copy.color = inst.color ? inst.color : t.color;
                copy.finish = scene::Finish::Over(inst.finish, t.finish);
                copy.path = t.path;
                copy.iter = std::make_shared<InstanceIter>();
                copy.iter->parent = t.si;
                copy.iter->inst = &inst;
                stack.push_back(std::move(copy));
                continue;
            }
            if (t.kind == Term::Kind::kNode && NodeOf(t).op == CsgOp::kDifference &&
                depth + 1 <= kMaxDepth) {
                // The spine once, for the grouping and, when it declines, for the node.
                Term minuend;
                std::vector<Term> subtrahends;
                if (!Spine(t, minuend, subtrahends)) return;
                if (GroupDifference(op, minuend, subtrahends, groups, out, depth)) continue;
                if (failed_) return;
                out.push_back(
                    EmitDifference(std::move(minuend), std::move(subtrahends), depth + 1));
                continue;
            }
            out.push_back(Emit(std::move(t), depth + 1));
        }
        if (!failed_) FinishGroups(op, groups, out);
    }

    // Pushes copy k of an operand instance: the next copy (processed after this one), the
    // scope's end marker and the copy's drawn items (LIFO: items first, in statement order).
    void ExpandCopy(const Term& t, std::vector<Term>& stack) {
        InstanceIter& it = *t.iter;
        const scene::Instance& inst = *it.inst;
        if (it.k >= inst.count) return;
        const scene::Scope& def = scene_.definitions[inst.definition];
        scopes_.push_back(std::make_unique<ScopeInst>());
        ScopeInst& si = *scopes_.back();
        si.scope = &def;
        si.serial = nextSerial_++;
        si.t = it.parent->t * it.deltaK * inst.init;
        si.path = CopyPath(Joined(it.parent->path, *t.path), inst, it.k);
        si.hsMap.assign(def.halfSpaces.size(), -1);
        Term next = t;
        next.iter = std::make_shared<InstanceIter>(it);
        next.iter->k = it.k + 1;
        next.iter->deltaK = inst.delta * it.deltaK;
        stack.push_back(std::move(next));
        Term pop;
        pop.kind = Term::Kind::kPopScope;
        stack.push_back(std::move(pop));
        std::vector<Term> items;
        auto add = [&](SolidRef::Kind kind, int index) {
            Term item;
            item.kind = Term::Kind::kRef;
            item.si = &si;
            item.ref = {kind, index};
            item.color = t.color;
            item.finish = t.finish;
            items.push_back(std::move(item));
        };
        for (std::size_t i = 0; i < def.bodies.size(); ++i)
            if (!def.bodies[i].usedAsOperand) add(SolidRef::Kind::kBody, int(i));
        for (std::size_t i = 0; i < def.instances.size(); ++i)
            if (!def.instances[i].usedAsOperand) add(SolidRef::Kind::kInstance, int(i));
        for (std::size_t i = 0; i < def.csgs.size(); ++i)
            if (!def.csgs[i].usedAsOperand) add(SolidRef::Kind::kCsg, int(i));
        for (auto r = items.rbegin(); r != items.rend(); ++r) stack.push_back(std::move(*r));
    }

    int Leaf(const Term& t) {
        ScopeInst& si = *t.si;
        const scene::Body& body = si.scope->bodies[t.ref.index];
        FlatBody fb;
        // Room for the clip literals the Flattener appends to every body.
        fb.literals.reserve(body.literals.size() + static_cast<std::size_t>(clipLiterals_));
        for (const scene::Literal& l : body.literals) {
            int hs = HalfSpaceIndex(si, l.halfSpace, body.loc);
            if (failed_) return -1;
            fb.literals.push_back({hs, l.complemented});
        }
        fb.color = body.color ? *body.color : (t.color ? *t.color : Color{});
        fb.finish = scene::Finish::Over(body.finish, t.finish);
        fb.solid = currentSolid_;
        fb.name = body.id.empty() ? Joined(si.path, *t.path, BodyName(body, t.ref.index))
                                  : Joined(si.path, *t.path, body.id);
        // The box of the body's extent, where it has one (in the FlatBody it writes anyway: no
        // fresh memory for it).
        HierarchyResult::ExtentRange extent;
        extent.begin = extent.end = static_cast<std::uint32_t>(result_.extentPieces.size());
        fb.bounds = Box3::Everything();
        if (!body.extent.empty() && IsAffine(si.t.Matrix())) {
            fb.bounds = PiecesBox(body.extent, si.t.Matrix());
            if (keepExtentPieces_)
                for (const ExtentPiece& piece : body.extent)
                    result_.extentPieces.push_back(MappedPiece(piece, si.t.Matrix()));
            extent.end = static_cast<std::uint32_t>(result_.extentPieces.size());
        }
        if (keepExtentPieces_) result_.bodyExtents.push_back(extent);
        out_.bodies.push_back(std::move(fb));
        FlatCsgNode leaf;
        leaf.isLeaf = true;
        leaf.body = static_cast<int>(out_.bodies.size()) - 1;
        out_.nodes.push_back(std::move(leaf));
        return static_cast<int>(out_.nodes.size()) - 1;
    }

    int HalfSpaceIndex(ScopeInst& si, int local, const SourceLoc& bodyLoc) {
        if (local < 0 || local >= static_cast<int>(si.hsMap.size())) {
            Fail(bodyLoc, "internal error: a body names a half-space out of range");
            return -1;
        }
        if (si.hsMap[local] >= 0) return si.hsMap[local];
        const scene::HalfSpace& hs = si.scope->halfSpaces[local];
        if (observer_ && out_.halfSpaces.size() == out_.halfSpaces.capacity()) {
            observer_->Growing();
            observer_ = nullptr;
        }
        // Made in place, past the size the observer was told (it reads none of it before
        // Appended), and taken back if it fails.
        FlatHalfSpace& f = out_.halfSpaces.emplace_back();
        f.isPlane = hs.kind == scene::HalfSpace::Kind::kPlane;
        bool finite;
        // Rescaled before and after the transform (coefficient_scale.h). A quartic keeps its
        // local frame: only its localFromSpace map composes (no coefficients to rescale).
        if (hs.kind == scene::HalfSpace::Kind::kQuartic) {
            QuarticSurface q = *hs.quartic;
            q.TransformBy(si.t);
            finite = q.AllFinite();
            f.SetQuartic(q);
        } else if (f.isPlane) {
            Plane source = hs.plane;
            RescaleCoefficients(source);
            f.plane = source.Transformed(si.t);
            RescaleCoefficients(f.plane);
            finite = f.plane.AllFinite();
        } else {
            Quadric source = hs.quadric;
            RescaleCoefficients(source);
            f.quadric = source.Transformed(si.t);
            RescaleCoefficients(f.quadric);
            finite = f.quadric.AllFinite();
        }
        f.transparent = hs.transparent;
        if (halfSpaceNames_) f.name = Joined(si.path, hs.id);
        if (!finite) {
            Fail(hs.loc, fmt::format("half-space '{}' has non-finite coefficients after its "
                                     "transforms and the view transformation",
                                     Joined(si.path, hs.id)));
            out_.halfSpaces.pop_back();
            return -1;
        }
        if (observer_) observer_->Appended(out_.halfSpaces.size());
        if (keepHalfSpaceLocs_) result_.halfSpaceLocs.push_back(hs.loc);
        si.hsMap[local] = static_cast<int>(out_.halfSpaces.size()) - 1;
        return si.hsMap[local];
    }

    const scene::Scene& scene_;
    FlatScene& out_;
    HierarchyResult& result_;
    Diagnostics& diags_;
    HalfSpaceObserver* observer_;  // null once told the array is growing
    Transform worldFromTarget_;
    bool failed_ = false;
    int currentSolid_ = -1;
    std::uint64_t nextSerial_ = 0;
    std::vector<std::unique_ptr<ScopeInst>> scopes_;  // operand instance copies being expanded
    std::deque<std::string> paths_;   // Term::path strings (a deque: they stay where they are)
    int clipLiterals_ = 0;            // HierarchyLimits::clipLiteralsPerBody
    bool halfSpaceNames_ = true;      // HierarchyLimits::halfSpaceNames
    bool keepExtentPieces_ = false;   // HierarchyLimits::keepExtentPieces
    bool keepHalfSpaceLocs_ = false;  // HierarchyLimits::keepHalfSpaceLocs
};

}  // namespace

bool FlattenHierarchy(const scene::Scene& scene, const Transform& targetFromWorld,
                      const HierarchyLimits& limits, FlatScene& out, HierarchyResult& result,
                      Diagnostics& diags, HalfSpaceObserver* observer) {
    // The guard first: nothing is built for a scene that would explode.
    Counter counter(scene, limits.clipLiteralsPerBody, diags);
    Counts total;
    const scene::Scope& top = scene.top;
    Counts worst;
    SourceLoc worstLoc = top.loc;
    auto consider = [&](const SolidRef& ref, bool operand, const SourceLoc& loc) {
        if (operand || !counter.ok()) return;
        Counts c = counter.Ref(-1, ref, 0);
        total += c;
        if (c.bodies + c.literals > worst.bodies + worst.literals) {
            worst = c;
            worstLoc = loc;
        }
    };
    for (std::size_t i = 0; i < top.bodies.size(); ++i)
        consider({SolidRef::Kind::kBody, int(i)}, top.bodies[i].usedAsOperand, top.bodies[i].loc);
    for (std::size_t i = 0; i < top.instances.size(); ++i)
        consider({SolidRef::Kind::kInstance, int(i)}, top.instances[i].usedAsOperand,
                 top.instances[i].loc);
    for (std::size_t i = 0; i < top.csgs.size(); ++i)
        consider({SolidRef::Kind::kCsg, int(i)}, top.csgs[i].usedAsOperand, top.csgs[i].loc);
    if (!counter.ok()) return false;
    if (total.bodies > limits.maxBodies || total.literals > limits.maxLiterals) {
        diags.Error(
            worstLoc,
            fmt::format("the flattened scene would have {:.4g} bodies and {:.4g} "
                        "half-space literals (limits {:.4g} and {:.4g}); arrays of "
                        "arrays multiply their counts: reduce them",
                        total.bodies, total.literals, limits.maxBodies, limits.maxLiterals));
        return false;
    }
    // The lists reserved, so that each is written once instead of copied as it grows, and a big
    // one in transparent huge pages (lang/big_arrays.h): on a virtual machine a fresh 4 KiB page
    // costs ~15 us, more than the walk's arithmetic on it (docs/performance.md, "Third round").
    // Half-spaces: at most the scope instances' own, and at most the literals. Nodes: a leaf per
    // body and fewer operator nodes than leaves, but for unions of nothing (a hint).
    const double halfSpaces = std::min(total.halfSpaces + double(top.halfSpaces.size()),
                                       total.literals - total.bodies * limits.clipLiteralsPerBody);
    const auto nHalf = static_cast<std::size_t>(halfSpaces);
    const auto nBody = static_cast<std::size_t>(total.bodies);
    lang::ReserveAdvised(out.halfSpaces, out.halfSpaces.size() + nHalf);
    if (limits.keepHalfSpaceLocs)
        lang::ReserveAdvised(result.halfSpaceLocs, result.halfSpaceLocs.size() + nHalf);
    lang::ReserveAdvised(out.bodies, out.bodies.size() + nBody);
    if (limits.keepExtentPieces)
        lang::ReserveAdvised(result.bodyExtents, result.bodyExtents.size() + nBody);
    lang::ReserveAdvised(out.nodes, out.nodes.size() + 2 * nBody);
    if (observer) observer->Started(out.halfSpaces, nHalf);
    Walker walker(scene, out, result, diags, limits, observer);
    const bool ok = walker.Run(targetFromWorld);
    if (observer) observer->Finished();
    return ok;
}

}  // namespace quadrix
