#include "quadrix/csg/normal_form.h"

#include <algorithm>
#include <cmath>

namespace quadrix::csg {

int Tree::AddPrimitive(int primitive) {
    TreeNode n;
    n.kind = TreeNode::Kind::kPrimitive;
    n.primitive = primitive;
    nodes.push_back(std::move(n));
    return static_cast<int>(nodes.size() - 1);
}

int Tree::AddOperator(TreeNode::Kind kind, std::vector<int> children) {
    TreeNode n;
    n.kind = kind;
    n.children = std::move(children);
    nodes.push_back(std::move(n));
    return static_cast<int>(nodes.size() - 1);
}

namespace {

// Deeper trees are refused: a guard against cyclic node graphs (the Flattener merges chains of
// one operator, so real trees are shallow).
constexpr int kMaxTreeDepth = 10000;

struct WorkProduct {
    Product factors;
    Box3 box;  // intersection of the boxes of the ∩ factors (Everything without boxes)
};
using Sum = std::vector<WorkProduct>;

bool Disjoint(const Box3& a, const Box3& b) { return a.Intersected(b).Empty(); }

class Normalizer {
  public:
    Normalizer(const Tree& tree, const NormalizeOptions& options)
        : tree_(tree), options_(options) {}

    bool Run(NormalForm& out) {
        ComputeBoxes();
        Sum sum;
        if (tree_.root < 0 || !Build(tree_.root, 0, sum)) {
            out.ok = false;
            out.error = error_.empty() ? "CSG tree has no root" : error_;
            out.stats = stats_;
            return false;
        }
        for (WorkProduct& p : sum) {
            // The product's box may have shrunk after a − factor was added: drop what misses it.
            Product kept;
            for (const Factor& f : p.factors) {
                if (f.subtracted && Disjoint(Box(f.primitive), p.box)) {
                    ++stats_.prunedFactors;
                    continue;
                }
                kept.push_back(f);
            }
            stats_.factors += kept.size();
            out.products.push_back(std::move(kept));
        }
        stats_.products = out.products.size();
        stats_.terms = stats_.factors;
        out.stats = stats_;
        return true;
    }

  private:
    Box3 Box(int primitive) const {
        if (options_.boxes.empty()) return Box3::Everything();
        if (primitive < 0 || static_cast<std::size_t>(primitive) >= options_.boxes.size())
            return Box3{};  // an unknown primitive is empty
        return options_.boxes[static_cast<std::size_t>(primitive)];
    }

    bool Fail(const std::string& what) {
        if (error_.empty()) error_ = what;
        return false;
    }

    // Checks the explosion limits after `sum` grew; `work` counts products visited.
    bool Check(const Sum& sum) {
        if (sum.size() > options_.maxProducts)
            return Fail("CSG normal form exceeds " + std::to_string(options_.maxProducts) +
                        " products (the union-of-products form grows exponentially with nested "
                        "differences of unions/intersections); simplify the tree or raise "
                        "--engine-opt max-products");
        if (++work_ > 64 * (options_.maxProducts + 1))
            return Fail("CSG normalisation gave up after " + std::to_string(work_) +
                        " rewriting steps; raise --engine-opt max-products");
        return true;
    }

    // Conservative box of every node: a union lies in the hull of its children, an
    // intersection in all of them, a difference in its minuend.
    void ComputeBoxes() {
        nodeBoxes_.assign(tree_.nodes.size(), Box3::Everything());
        std::vector<char> done(tree_.nodes.size(), 0);
        if (tree_.root >= 0 && static_cast<std::size_t>(tree_.root) < tree_.nodes.size())
            NodeBox(tree_.root, 0, done);
    }
    Box3 NodeBox(int n, int depth, std::vector<char>& done) {
        if (depth > kMaxTreeDepth || n < 0 || static_cast<std::size_t>(n) >= tree_.nodes.size())
            return Box3::Everything();
        std::size_t k = static_cast<std::size_t>(n);
        if (done[k]) return nodeBoxes_[k];
        const TreeNode& node = tree_.nodes[k];
        Box3 b;
        if (node.kind == TreeNode::Kind::kPrimitive) {
            b = Box(node.primitive);
            ++stats_.treePrimitives;
        } else if (!node.children.empty()) {
            stats_.treeOperators += node.children.size() - 1;
            b = NodeBox(node.children[0], depth + 1, done);
            for (std::size_t i = 1; i < node.children.size(); ++i) {
                Box3 c = NodeBox(node.children[i], depth + 1, done);
                if (node.kind == TreeNode::Kind::kUnion) b.Extend(c);
                if (node.kind == TreeNode::Kind::kIntersection) b = b.Intersected(c);
            }
        }
        done[k] = 1;
        nodeBoxes_[k] = b;
        return b;
    }

    const TreeNode* NodeAt(int n, int depth) {
        if (depth > kMaxTreeDepth) {
            Fail("CSG tree deeper than 10000 nodes (cycle?)");
            return nullptr;
        }
        if (n < 0 || static_cast<std::size_t>(n) >= tree_.nodes.size()) {
            Fail("CSG tree names a missing node");
            return nullptr;
        }
        return &tree_.nodes[static_cast<std::size_t>(n)];
    }
    const Box3& NodeBoxOf(int n) const { return nodeBoxes_[static_cast<std::size_t>(n)]; }

    bool Append(Sum& out, Sum& more) {
        for (WorkProduct& q : more) {
            out.push_back(std::move(q));
            if (!Check(out)) return false;
        }
        return true;
    }

    // The normal form of node n (Theorem A, by the recursion of seed 004 §IV).
    bool Build(int n, int depth, Sum& out) {
        out.clear();
        const TreeNode* node = NodeAt(n, depth);
        if (!node) return false;
        if (node->kind == TreeNode::Kind::kPrimitive) {
            Box3 b = Box(node->primitive);
            if (b.Empty()) {
                ++stats_.prunedProducts;
                return true;  // the empty set: no product
            }
            out.push_back({{Factor{node->primitive, false}}, b});
            return true;
        }
        if (node->children.empty()) return true;  // an operator of nothing: empty
        if (node->kind == TreeNode::Kind::kUnion) {
            Sum part;
            for (int c : node->children) {
                if (!Build(c, depth + 1, part) || !Append(out, part)) return false;
            }
            return true;
        }
        if (!Build(node->children[0], depth + 1, out)) return false;
        for (std::size_t i = 1; i < node->children.size() && !out.empty(); ++i) {
            Sum next;
            for (const WorkProduct& p : out) {
                Sum part;
                bool ok = node->kind == TreeNode::Kind::kIntersection
                              ? IntersectOne(p, node->children[i], depth + 1, part)
                              : SubtractOne(p, node->children[i], depth + 1, part);
                if (!ok || !Append(next, part)) return false;
            }
            out.swap(next);
        }
        return true;
    }

    // out = p ∩ node n, by Lemma 1 b (∪), c (∩), a (−).
    bool IntersectOne(const WorkProduct& p, int n, int depth, Sum& out) {
        out.clear();
        const TreeNode* node = NodeAt(n, depth);
        if (!node) return false;
        if (Disjoint(p.box, NodeBoxOf(n))) {
            ++stats_.prunedProducts;
            return true;
        }
        if (node->kind == TreeNode::Kind::kPrimitive) {
            WorkProduct r = p;
            bool unchanged = false;
            if (AddFactor(r, Factor{node->primitive, false}, unchanged))
                out.push_back(std::move(r));
            return Check(out);
        }
        if (node->children.empty()) return true;
        if (node->kind == TreeNode::Kind::kUnion) {  // b) distribute
            Sum part;
            for (int c : node->children) {
                if (!IntersectOne(p, c, depth + 1, part) || !Append(out, part)) return false;
            }
            return true;
        }
        // c) p ∩ (Y ∩ Z) = p ∩ Y ∩ Z;  a) p ∩ (Y − Z) = p ∩ Y − Z.
        if (!IntersectOne(p, node->children[0], depth + 1, out)) return false;
        for (std::size_t i = 1; i < node->children.size() && !out.empty(); ++i) {
            Sum next;
            for (const WorkProduct& q : out) {
                Sum part;
                bool ok = node->kind == TreeNode::Kind::kIntersection
                              ? IntersectOne(q, node->children[i], depth + 1, part)
                              : SubtractOne(q, node->children[i], depth + 1, part);
                if (!ok || !Append(next, part)) return false;
            }
            out.swap(next);
        }
        return true;
    }

    static bool IsUnchanged(const Sum& s, const WorkProduct& p) {
        return s.size() == 1 && s[0].factors.size() == p.factors.size();
    }

    // out = p − node n, by Lemma 1 e (∪), f (∩), d (−).
    bool SubtractOne(const WorkProduct& p, int n, int depth, Sum& out) {
        out.clear();
        const TreeNode* node = NodeAt(n, depth);
        if (!node) return false;
        if (Disjoint(p.box, NodeBoxOf(n))) {  // p − B = p
            ++stats_.prunedSubtrahends;
            out.push_back(p);
            return true;
        }
        if (node->kind == TreeNode::Kind::kPrimitive) {
            WorkProduct r = p;
            bool unchanged = false;
            if (AddFactor(r, Factor{node->primitive, true}, unchanged)) out.push_back(std::move(r));
            return Check(out);
        }
        if (node->children.empty()) {  // p − ∅ = p
            out.push_back(p);
            return true;
        }
        if (node->kind == TreeNode::Kind::kUnion) {  // e) p − (Y ∪ Z) = p − Y − Z
            out.push_back(p);
            for (std::size_t i = 0; i < node->children.size() && !out.empty(); ++i) {
                Sum next;
                for (const WorkProduct& q : out) {
                    Sum part;
                    if (!SubtractOne(q, node->children[i], depth + 1, part) || !Append(next, part))
                        return false;
                }
                out.swap(next);
            }
            return true;
        }
        // f) p − (Y ∩ Z) = (p − Y) ∪ (p − Z);
        // d) p − (Y − Z) = (p − Y) ∪ (p ∩ Z).
        // Every piece is a subset of p, so when one of them is p itself the union is p.
        Sum part;
        for (std::size_t i = 0; i < node->children.size(); ++i) {
            bool subtract = node->kind == TreeNode::Kind::kIntersection || i == 0;
            bool ok = subtract ? SubtractOne(p, node->children[i], depth + 1, part)
                               : IntersectOne(p, node->children[i], depth + 1, part);
            if (!ok) return false;
            if (subtract && IsUnchanged(part, p)) {
                out.clear();
                out.push_back(p);
                return true;
            }
            if (!Append(out, part)) return false;
        }
        return true;
    }

    // Adds factor f to p (in place). Returns false when p becomes empty (contradiction or
    // disjoint boxes); sets `unchanged` when p stays as it was.
    bool AddFactor(WorkProduct& p, const Factor& f, bool& unchanged) {
        unchanged = false;
        for (const Factor& g : p.factors) {
            if (g.primitive != f.primitive) continue;
            if (g.subtracted == f.subtracted) {
                ++stats_.duplicates;
                unchanged = true;
                return true;
            }
            ++stats_.contradictions;
            return false;
        }
        Box3 b = Box(f.primitive);
        if (!f.subtracted) {
            p.box = p.box.Intersected(b);
            if (p.box.Empty()) {
                ++stats_.prunedProducts;
                return false;
            }
        } else if (Disjoint(b, p.box)) {
            ++stats_.prunedFactors;
            unchanged = true;  // X − Y = X
            return true;
        }
        p.factors.push_back(f);
        return true;
    }

    const Tree& tree_;
    const NormalizeOptions& options_;
    std::vector<Box3> nodeBoxes_;
    NormalFormStats stats_;
    std::string error_;
    std::size_t work_ = 0;
};

bool ClassifyNode(const Tree& tree, int n, const std::function<bool(int)>& inside, int depth) {
    if (depth > kMaxTreeDepth || n < 0 || static_cast<std::size_t>(n) >= tree.nodes.size())
        return false;
    const TreeNode& node = tree.nodes[static_cast<std::size_t>(n)];
    if (node.kind == TreeNode::Kind::kPrimitive) return inside(node.primitive);
    if (node.children.empty()) return false;
    bool r = ClassifyNode(tree, node.children[0], inside, depth + 1);
    for (std::size_t i = 1; i < node.children.size(); ++i) {
        bool c = ClassifyNode(tree, node.children[i], inside, depth + 1);
        switch (node.kind) {
            case TreeNode::Kind::kUnion:
                r = r || c;
                break;
            case TreeNode::Kind::kIntersection:
                r = r && c;
                break;
            default:
                r = r && !c;
                break;
        }
    }
    return r;
}

int AddFlatNode(const FlatScene& scene, int n, Tree& tree, int depth) {
    if (depth > kMaxTreeDepth || n < 0 || static_cast<std::size_t>(n) >= scene.nodes.size())
        return tree.AddOperator(TreeNode::Kind::kUnion, {});  // empty
    const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
    if (node.isLeaf) return tree.AddPrimitive(node.body);
    std::vector<int> children;
    for (int c : node.children) children.push_back(AddFlatNode(scene, c, tree, depth + 1));
    TreeNode::Kind kind = TreeNode::Kind::kUnion;
    if (node.op == scene::CsgOp::kIntersection) kind = TreeNode::Kind::kIntersection;
    if (node.op == scene::CsgOp::kDifference) kind = TreeNode::Kind::kDifference;
    return tree.AddOperator(kind, std::move(children));
}

}  // namespace

NormalForm Normalize(const Tree& tree, const NormalizeOptions& options) {
    NormalForm out;
    Normalizer(tree, options).Run(out);
    return out;
}

bool ClassifyTree(const Tree& tree, const std::function<bool(int)>& inside) {
    return ClassifyNode(tree, tree.root, inside, 0);
}

bool ClassifyProducts(const std::vector<Product>& products,
                      const std::function<bool(int)>& inside) {
    for (const Product& p : products) {
        bool in = !p.empty();
        for (const Factor& f : p) {
            if (inside(f.primitive) == f.subtracted) {
                in = false;
                break;
            }
        }
        if (in) return true;
    }
    return false;
}

std::string FormatProducts(const std::vector<Product>& products,
                           const std::function<std::string(int)>& name) {
    std::string s;
    for (std::size_t i = 0; i < products.size(); ++i) {
        if (i) s += " | ";
        for (std::size_t j = 0; j < products[i].size(); ++j) {
            const Factor& f = products[i][j];
            if (j) s += f.subtracted ? " - " : " & ";
            s += name(f.primitive);
        }
    }
    return s.empty() ? "(empty)" : s;
}

Tree TreeOfSolid(const FlatScene& scene, int solid) {
    Tree tree;
    if (solid < 0 || static_cast<std::size_t>(solid) >= scene.solids.size()) {
        tree.root = tree.AddOperator(TreeNode::Kind::kUnion, {});
        return tree;
    }
    tree.root = AddFlatNode(scene, scene.solids[static_cast<std::size_t>(solid)].root, tree, 0);
    return tree;
}

std::vector<Box3> BodyBoxes(const FlatScene& scene) {
    std::vector<Box3> boxes;
    boxes.reserve(scene.bodies.size());
    for (const FlatBody& b : scene.bodies) {
        // NaN bounds are unknown: treat as everything (conservative).
        bool nan = std::isnan(b.bounds.lo.x) || std::isnan(b.bounds.lo.y) ||
                   std::isnan(b.bounds.lo.z) || std::isnan(b.bounds.hi.x) ||
                   std::isnan(b.bounds.hi.y) || std::isnan(b.bounds.hi.z);
        boxes.push_back(nan ? Box3::Everything() : b.bounds);
    }
    return boxes;
}

}  // namespace quadrix::csg
