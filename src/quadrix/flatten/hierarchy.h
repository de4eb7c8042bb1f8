// The Flattener's traversal of the scene hierarchy (seed 001 §3.3, §2.1.3-2.1.4) and of the CSG
// extension (docs/language.md): every drawn body, instance copy and CSG solid becomes FlatSolids
// whose trees are n-ary FlatCsgNodes over FlatBodies, with half-spaces transformed to the target
// space (the Flattener passes provisional device space).
//
// Transforms: a scope instance carries targetFromObject; copy k of an instance/array inside it
// gets targetFromObject · delta^k · init (init first, then k deltas: deltas accumulate). Planes
// and quadrics map with the composed Transform's stored inverse (p' = M⁻ᵀp, Q' = M⁻ᵀQM⁻¹), never
// re-inverting.
//
// What is drawn: the bodies, instances/arrays and CSG solids of the top scope not used as
// operands; an instance draws the same of its definition's scope. Each drawn body is a FlatSolid
// of one leaf; each drawn CSG solid is one FlatSolid.
//
// CSG trees: chains of one associative operator are merged (a | b | c → one kUnion with three
// children, also across references to other CSG solids); difference chains (a - b) - c become one
// kDifference [a, b, c], and a subtrahend that is a union is spliced (a - (b | c) = a - b - c).
// Differences in a union or intersection that subtract the same bodies are grouped,
// ∪ᵢ (aᵢ − s) → (∪ᵢ aᵢ) − s (common_subtrahends.h), so a solid costs the same however its tree
// is written. An instance/array used as an operand is the union of everything it draws. A union of
// nothing (an operand instance of zero copies) is an empty kUnion node: the empty set.
//
// Colors: a body's own color, else the innermost enclosing CSG solid or instance with one, else
// white. Names: paths such as "stack_of_bundles[1]/bundle_of_tubes[3]/tube" (instance ids with
// the copy index for arrays, CSG solid ids, then the body or half-space id).
//
// Guards: before building anything the numbers of bodies and literals are counted (in doubles,
// so arrays of arrays cannot overflow); beyond the limits the walk stops with an error naming the
// top-level statement responsible. Definition and CSG nesting deeper than kMaxNesting (cycles
// included) is an error too, so the recursion depth is bounded.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct HierarchyLimits {
    double maxBodies = 2'000'000;
    double maxLiterals = 20'000'000;  // including the clip literals appended to every body
    int clipLiteralsPerBody = 0;      // counted against maxLiterals
    // Also list every body's extent pieces in the target space (HierarchyResult): for the world
    // stage, whose boxes are made again for every view.
    bool keepExtentPieces = false;
    // FlatHalfSpace::name made (flattener.h FlattenOptions::halfSpaceNames).
    bool halfSpaceNames = true;
    // HierarchyResult::halfSpaceLocs made: for the world stage, whose half-spaces are mapped
    // again for every view (a one-shot walk reports a half-space's error as it maps it).
    bool keepHalfSpaceLocs = false;
};

inline constexpr int kMaxNesting = 256;

struct HierarchyResult {
    std::vector<SourceLoc> solidLocs;  // per FlatSolid: its body or csg statement
    std::vector<bool> solidIsCsg;      // per FlatSolid: drawn from a csg statement
    // With HierarchyLimits::keepHalfSpaceLocs, per FlatHalfSpace appended by the walk: its
    // half-space statement.
    std::vector<SourceLoc> halfSpaceLocs;
    // With HierarchyLimits::keepExtentPieces, per FlatBody: its extent (scene::Body::extent)
    // mapped to the target space, the pieces extentPieces[begin, end); empty where the body has
    // none or its map to the target space is not affine (a perspective view).
    struct ExtentRange {
        std::uint32_t begin = 0, end = 0;
    };
    std::vector<ExtentRange> bodyExtents;
    std::vector<ExtentPiece> extentPieces;
};

// Told by the walk about the half-spaces it appends to FlatScene::halfSpaces, in order (the
// Flattener's LiteralCacheBuilder works on them meanwhile). All calls come from the walk's thread.
class HalfSpaceObserver {
  public:
    // The array reserved for the walk, which expects to append up to `expected` half-spaces.
    virtual void Started(const std::vector<FlatHalfSpace>& halfSpaces, std::size_t expected) = 0;
    // halfSpaces[0, size) are final.
    virtual void Appended(std::size_t size) = 0;
    // The next append would move the array (its capacity is reached).
    virtual void Growing() = 0;
    // The walk has ended (whether or not it failed): nothing more is appended.
    virtual void Finished() = 0;

  protected:
    ~HalfSpaceObserver() = default;
};

// Appends the drawn solids of `scene` to `out` (halfSpaces, bodies, nodes, solids), transformed
// by targetFromWorld. A FlatBody's `bounds` is the box of its extent in the target space
// (scene::Body::extent, math/extent_piece.h) where it has one and its map there is affine, else
// Box3::Everything(). false (with errors in diags) on a limit, a cycle or a bad reference.
bool FlattenHierarchy(const scene::Scene& scene, const Transform& targetFromWorld,
                      const HierarchyLimits& limits, FlatScene& out, HierarchyResult& result,
                      Diagnostics& diags, HalfSpaceObserver* observer = nullptr);

}  // namespace quadrix
