// CSG normal form: any CSG tree rewritten as a union of simple products (seed 003 §1, seed 004
// §IV).
//
// A simple product is  X0 op1 X1 op2 … opk Xk  with op ∈ {∩, −}, associated from the left, every
// Xi a primitive. With the convention op0 = ∩ a product is the set of points inside every factor
// with op = ∩ and outside every factor with op = −, so the order of its factors does not matter
// (seed 004 §IV uses this). The rewriting uses the identities of Lemma 1 (seed 003):
//     a) X ∩ (Y − Z) = X ∩ Y − Z          d) X − (Y − Z) = (X − Y) ∪ (X ∩ Z)
//     b) X ∩ (Y ∪ Z) = (X ∩ Y) ∪ (X ∩ Z)  e) X − (Y ∪ Z) = X − Y − Z
//     c) X ∩ (Y ∩ Z) = X ∩ Y ∩ Z          f) X − (Y ∩ Z) = (X − Y) ∪ (X − Z)
// which give, for products p and q = Y0 op1 Y1 … opk Yk (Lemma 2):
//     p ∩ q = p ∩ Y0 op1 Y1 … opk Yk
//     p − q = ∪_i (p op'_i Y_i),   op'_i = − when op_i = ∩ (and for i = 0), ∩ when op_i = −.
// The second multiplies the number of products: the normal form can be exponentially larger than
// the tree, so Normalize stops with a clear message past a limit instead of running away.
//
// Exact simplifications applied on the way (they keep the point set, hence the picture):
//   - a factor already in the product with the same op is dropped (X ∩ X = X, −Y −Y = −Y);
//   - a product holding X both with ∩ and − is empty and dropped;
//   - p − q = p when one of the products p op'_i Y_i equals p (they are all subsets of p).
// Bounding-box pruning (seed 004 §VI "future work", seed 003 §3 "CSG operation"), with conservative
// per-primitive boxes: a product whose ∩ factors have disjoint boxes is empty and dropped; a −
// factor whose box misses the product's box is dropped (X − Y = X); p − q = p when their boxes
// are disjoint.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"

namespace quadrix::csg {

// A CSG tree over primitives 0..n-1, with n-ary operators. kDifference: the first child minus
// every other child.
struct TreeNode {
    enum class Kind : unsigned char { kPrimitive, kUnion, kIntersection, kDifference };
    Kind kind = Kind::kPrimitive;
    int primitive = -1;         // when kPrimitive
    std::vector<int> children;  // otherwise: indices into Tree::nodes
};

struct Tree {
    std::vector<TreeNode> nodes;
    int root = -1;

    int AddPrimitive(int primitive);
    int AddOperator(TreeNode::Kind kind, std::vector<int> children);
};

struct Factor {
    int primitive = -1;
    bool subtracted = false;  // op = − (else ∩)
    bool operator==(const Factor&) const = default;
};

// A simple product; its first factor is never subtracted.
using Product = std::vector<Factor>;

struct NormalizeOptions {
    std::size_t maxProducts = 20000;  // past this, Normalize fails (the explosion guard)
    std::size_t maxFactors = 400000;  // total factor occurrences over all products
    // Conservative box of each primitive (containing it); empty vector = no pruning. A primitive
    // whose box is empty is the empty set.
    std::vector<Box3> boxes;
};

// Sizes reported with the normal form.
struct NormalFormStats {
    std::size_t treePrimitives = 0;  // leaf occurrences in the tree
    std::size_t treeOperators = 0;   // binary operator count (an n-ary node with m children = m-1)
    std::size_t products = 0;        // simple products in the result
    std::size_t factors = 0;         // factor occurrences over all products
    std::size_t terms = 0;           // display-theorem terms = factors (one per factor)
    std::size_t prunedProducts = 0;  // products dropped as empty by their boxes
    std::size_t prunedFactors = 0;   // − factors dropped because their box misses the product
    std::size_t prunedSubtrahends = 0;  // p − q = p by disjoint boxes
    std::size_t contradictions = 0;     // products dropped holding X with both ∩ and −
    std::size_t duplicates = 0;         // repeated factors dropped
};

struct NormalForm {
    bool ok = true;
    std::string error;  // when !ok: what exceeded which limit
    std::vector<Product> products;
    NormalFormStats stats;
};

NormalForm Normalize(const Tree& tree, const NormalizeOptions& options = {});

// Point classification, for tests and checks: `inside(primitive)` says whether the point is in it.
bool ClassifyTree(const Tree& tree, const std::function<bool(int)>& inside);
bool ClassifyProducts(const std::vector<Product>& products, const std::function<bool(int)>& inside);

// "A - B & C | D" style text of a normal form, primitives named by `name`.
std::string FormatProducts(const std::vector<Product>& products,
                           const std::function<std::string(int)>& name);

// The tree of FlatScene solid `solid` over its bodies (primitive = body index), and the boxes of
// all bodies (FlatBody::bounds) for pruning.
Tree TreeOfSolid(const FlatScene& scene, int solid);
std::vector<Box3> BodyBoxes(const FlatScene& scene);

}  // namespace quadrix::csg
