// The host side of Pixel-Powers: from a FlatScene to a program of broadcasts (seed 004 §III–IV).
//
//   1. every solid's CSG tree (primitives = FlatBody, an intersection of literals) is normalised
//      into a union of simple products (csg/normal_form.h), pruned by device-space boxes;
//   2. each product X0 op1 X1 … opk Xk gives, by the display theorem (seed 004 Theorem 2,
//      seed 003 §2), the terms  D_p(Xi) pared by the other factors, D_p = front (entry) face for
//      ∩ factors and X0, back (exit) face for − factors;
//   3. the face of a primitive is a set of patches, one per opaque literal: that literal's entry
//      (exit) sheet, kept where it lies inside the primitive's other literals (for a convex body
//      this is exactly the paper's scan conversion by bounding curves, done here per pixel against
//      the bounding surfaces instead of their projected curves, which are quartics for two
//      quadrics);
//   4. each patch becomes a block: load ZTEMP and F1 (exists), pare F1 with each other factor
//      (∩: F1 ∧= inside; −: F2 = inside, F1 ∧= ¬F2), z-buffer test against ZMIN, write.
// A − factor whose box misses the term's box is not sent, and a term whose ∩ factors' boxes miss
// each other is dropped (seed 003 §3 "CSG operation", seed 004 §VI).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "quadrix/csg/normal_form.h"
#include "quadrix/engines/pixelpowers/isa.h"
#include "quadrix/flatten/flat_scene.h"

namespace quadrix::pixelpowers {

enum class DepthMode {
    kExact,   // extended machine: per-pixel square root (kRoot / kInside)
    kApprox,  // the paper's machine: parabolic-strip envelopes within `tolerance`
};

struct CompileOptions {
    DepthMode mode = DepthMode::kExact;
    double tolerance = 0.25;          // kApprox: largest depth error of a sheet, device z units
    std::size_t maxProducts = 20000;  // normal-form explosion guard, per solid
    int maxStrips = 64;               // kApprox: parabolic strips per sheet at most
    // Program size guard: a solid whose instructions would pass this total is not drawn (a normal
    // form below maxProducts can still hold millions of paring tests).
    std::size_t maxInstructions = 1000000;
    // Literals of one product (its bodies' literals summed) above which the solid goes to
    // raycast: the paring pass costs ~literals² per product (issue 23; 2,000 literals: 0.46 s,
    // 10⁴: 11.5 s CPU at 64×64, while the program stays under maxInstructions).
    std::size_t maxLiterals = 1024;
    // The paper's shading (seed 004 §III step 4): each patch broadcasts its approximate normal
    // (kNLoad ×3) instead of leaving the exact normal to scan-out. Docs: "Shading".
    bool paperShading = false;
    // Fixed-point depth words of this many bits (0 = doubles): Program::depthStep.
    int depthBits = 0;
};

struct CompileStats {
    std::size_t primitives = 0;       // distinct bodies used by the drawn solids
    std::size_t halfSpaces = 0;       // distinct half-spaces used by them
    csg::NormalFormStats normalForm;  // summed over the solids
    std::size_t terms = 0;            // display-theorem terms compiled
    std::size_t prunedTerms = 0;      // dropped: the term's ∩ boxes miss each other or the screen
    std::size_t prunedParings = 0;    // − factors not sent for a term (disjoint boxes)
    std::size_t patches = 0;          // blocks
    std::size_t prunedPatches = 0;    // plane patches whose face polygon is empty
    std::size_t strips = 0;           // kApprox: parabolic strips (tangents) broadcast
    std::size_t stripsCapped = 0;     // kApprox: sheets that hit maxStrips
    std::size_t extendedFallbacks = 0;  // kApprox: sheets with C = 0 done by the root unit
    std::size_t shadedPatches = 0;      // paperShading: blocks with kNLoad
    std::size_t shadingFallbacks = 0;   // paperShading: quadric patches with C = 0 (exact normal)
    // paperShading: the host's own bound on |a·l − n·l| from the sqrt approximation alone
    // (max over patches of |numerator error| / denominator, for a unit l along the worst axis).
    double shadingSqrtBound = 0;
    // paperShading: max over patches of (wMax − wMin)/(wMax + wMin) for the sampled |n|, the
    // largest relative error of the constant denominator w0 (0 for spheres and circular
    // cylinders under a parallel view). |paper − exact| ≤ sqrt bound + this, per unit light.
    double shadingDenominatorSpread = 0;
    std::vector<std::string> errors;    // solids not drawn (normal form too large, program size)
    std::vector<int> undrawnSolids;     // their FlatScene::solids indices, parallel to errors
    std::vector<std::string> warnings;  // drawn, but less accurately than asked
};

void Compile(const FlatScene& scene, const CompileOptions& options, Program& program,
             CompileStats& stats);

// The re-centring point raycast uses for half-space h (ray_literal.h), so that kRoot/kInside
// compute the very same roots as the reference engine.
Vec3 RaycastReferencePoint(const FlatScene& scene, std::size_t h);

}  // namespace quadrix::pixelpowers
