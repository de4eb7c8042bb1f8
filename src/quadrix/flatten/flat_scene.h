// The Flattener's output: every drawn solid with its half-spaces in DEVICE space (DESIGN.md).
//
// Device space: x = column in pixels, y = row in pixels (row 0 at the top), pixel centres at
// (i+½, j+½), rays parallel to +z, z grows away from the viewer. Perspective is folded in as a
// projective map, so quadrics stay quadrics and planes planes; the region behind the eye is removed
// by transparent clipping planes appended to every body (seed 001 §3.3).
//
// Solids are CSG trees over bodies; a plain body is a solid whose tree is one leaf. Trees are
// n-ary (chains of one operator are merged) so that a union of 10,000 spheres is one node with
// 10,000 children, not a 10,000-deep chain.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadrix/freeform/surface.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/plane_or_quadric.h"
#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

// The surface (PlaneOrQuadric: isPlane, plane, quadric) is in device space.
struct FlatHalfSpace : PlaneOrQuadric {
    bool transparent = false;
    bool isClip = false;  // a clipping plane added by the Flattener (front/back/near/far)
    // Path for pickers and the library, e.g. "stack_of_bundles[1]/bundle_of_tubes[3]/outer_tube";
    // empty when the flatten was asked for none (FlattenOptions::halfSpaceNames), except for
    // the clip and section planes the Flattener adds.
    std::string name;
};

struct FlatLiteral {
    int halfSpace = -1;  // index into FlatScene::halfSpaces
    bool complemented = false;
};

struct FlatBody {
    std::vector<FlatLiteral> literals;
    scene::Color color;    // resolved: the body's color, else its CSG solid's, else white
    int solid = -1;        // the FlatSolid this body belongs to
    std::string name;      // path like FlatHalfSpace::name
    Box3 bounds;           // conservative device-space bounds (may be infinite)
    scene::Finish finish;  // resolved like color, property by property (unset = model default)
};

struct FlatCsgNode {
    bool isLeaf = true;
    int body = -1;                           // when isLeaf
    scene::CsgOp op = scene::CsgOp::kUnion;  // when !isLeaf
    // Children when !isLeaf. For kDifference the first child is the minuend and every other child
    // is subtracted; kUnion/kIntersection are n-ary.
    std::vector<int> children;
    Box3 bounds;  // conservative device-space bounds
};

struct FlatSolid {
    int root = -1;  // index into FlatScene::nodes
    std::string name;
    Box3 bounds;  // conservative device-space bounds, clipped to the image in x and y
};

// A freeform surface to draw (scene::FreeformSurface under its instance transforms). It stays in
// WORLD coordinates: the isocurve renderer projects it with `Projection` (exactly, through
// homogeneous control points). Frame ids for freeform k: surface = halfSpaces.size() + k,
// body = solid = Frame::kNone (FlatScene::SurfaceColor gives its color).
struct FlatFreeform {
    freeform::Surface surface;  // world coordinates
    scene::Color color;         // resolved like a body's
    std::string name;
    scene::Finish finish;  // resolved like a body's
    SourceLoc loc;         // where it was defined (for messages)
};

// How the world was projected; the shader needs it to express normals in world space.
struct Projection {
    bool perspective = false;
    Transform deviceFromWorld;  // projective when perspective
    Vec3 eye;                   // world-space cop (perspective)
    Vec3 towardViewer;          // world-space unit direction toward the viewer (parallel)
};

struct FlatScene {
    int width = 0, height = 0;
    std::vector<FlatHalfSpace> halfSpaces;
    std::vector<FlatBody> bodies;
    std::vector<FlatCsgNode> nodes;
    std::vector<FlatSolid> solids;
    std::vector<FlatFreeform> freeforms;
    std::vector<scene::Light> lights;  // world space, defaults (or the default rig) applied
    // Background of the picture: `background` at the top row blending linearly to
    // `backgroundBottom` at the bottom row (equal = a plain color). From the scene's
    // `background` statement; ShadeOptions may override it.
    scene::Color background{0, 0, 0}, backgroundBottom{0, 0, 0};
    Projection projection;
    // The section plane (FlattenOptions::section) exactly as given, in WORLD coordinates, and its
    // half-space (named kSectionName, device space); -1 without one. The shader's hatching of the
    // cut faces (shade/section_hatch.h) is anchored to this plane, not to its device image.
    std::optional<Plane> section;
    int sectionHalfSpace = -1;
    std::string viewName;
    // One tolerance for the scene, in device units of depth (see docs/engines.md): used for
    // ties between coincident surfaces.
    double depthTolerance = 1e-9;

    // World-space unit normal of half-space `hs` at device point `p`, oriented toward the viewer.
    // Normals are covectors: n_world = (deviceFromWorld)ᵀ g where g is the device gradient.
    Vec3 WorldNormal(int hs, const Vec3& devicePoint) const;

    // The base color of a pixel with Frame ids (surface, body): the body's, else the freeform
    // surface's (surface ids past the half-spaces), else white.
    scene::Color SurfaceColor(int surface, int body) const;
    // Its finish, looked up likewise (an empty Finish for neither).
    scene::Finish SurfaceFinish(int surface, int body) const;

    // The structure's invariants, checked once after flattening (the render context does): every
    // index in range, children before their parents. Empty when they hold, else the first
    // violation (an internal error: user input never breaks them).
    std::string Validate() const;
};

}  // namespace quadrix
