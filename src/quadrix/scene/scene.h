// The scene model: what a scene file says, independent of any file format and with no
// transform applied (seed 001 §3.2: "Reader does no coordinate transformation").
//
// Readers (the UniQuadrix language, importers) build a Scene; the Flattener turns it into a
// FlatScene in device space. Everything here is plain data; ids are kept for diagnostics and for
// lookups by name (views, lights).
//
// Hierarchy (seed 001 §2.1.3-2.1.4): the top level of a scene and each definition are Scopes.
// A scope holds half-spaces (HSBs), bodies, instances/arrays and CSG solids. Half-space and solid
// ids are local to their scope. Definitions are global and are instanced by index.
//
// What is drawn: every body, instance/array and CSG solid of the top-level scope that is not used
// as an operand of a CSG solid; instancing a definition draws, likewise, its scope's non-operand
// solids under the instance's transform.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/freeform/surface.h"
#include "quadrix/math/extent_piece.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"
#include "quadrix/math/quartic_surface.h"
#include "quadrix/scene/source_loc.h"

namespace quadrix::scene {

struct Color {
    double r = 1, g = 1, b = 1;  // linear intensities in [0, 1]
    bool operator==(const Color&) const = default;
};

// The finish of a surface (the materials extension, docs/language.md §3.6): diffuse and specular
// coefficients, the specular exponent and the opacity. Every property is optional and resolved
// like the color (the body's own, else the innermost enclosing CSG solid's or instance's); what is
// still unset after that takes the shading model's default (shade/shader.h).
struct Finish {
    std::optional<double> diffuse;    // kd >= 0
    std::optional<double> specular;   // ks >= 0
    std::optional<double> shininess;  // Phong/Blinn exponent > 0
    std::optional<double> opacity;    // alpha in [0, 1]; 1 = opaque
    bool operator==(const Finish&) const = default;
    bool Empty() const { return *this == Finish{}; }
    // Each property of `inner` that is set, else `outer`'s.
    static Finish Over(const Finish& inner, const Finish& outer) {
        Finish f = inner;
        if (!f.diffuse) f.diffuse = outer.diffuse;
        if (!f.specular) f.specular = outer.specular;
        if (!f.shininess) f.shininess = outer.shininess;
        if (!f.opacity) f.opacity = outer.opacity;
        return f;
    }
};

// A half-space bound (HSB), seed 001 §2.1.1: a surface that is drawn (when opaque) and bounds the
// other surfaces of the bodies that name it. A quartic (torus, elliptical torus, general cone;
// math/quartic_surface.h) is in the scope's object coordinates like the others; MakeQuartic builds
// one. Code that switches on `kind` must handle kQuartic (never read it as a quadric).
struct HalfSpace {
    enum class Kind { kPlane, kQuadric, kQuartic };
    std::string id;
    Kind kind = Kind::kPlane;
    Plane plane;                                    // when kind == kPlane
    Quadric quadric;                                // when kind == kQuadric
    std::shared_ptr<const QuarticSurface> quartic;  // when kind == kQuartic
    bool transparent = false;                       // =t: bounds others but is not drawn
    SourceLoc loc;
};

// A quartic half-space (kind kQuartic) with the given id and position.
inline HalfSpace MakeQuartic(std::string id, const QuarticSurface& q, SourceLoc loc = {},
                             bool transparent = false) {
    HalfSpace h;
    h.id = std::move(id);
    h.kind = HalfSpace::Kind::kQuartic;
    h.quartic = std::make_shared<const QuarticSurface>(q);
    h.transparent = transparent;
    h.loc = loc;
    return h;
}

// One entry of a body's list: a half-space of the same scope, possibly complemented ("!").
struct Literal {
    int halfSpace = -1;  // index into Scope::halfSpaces
    bool complemented = false;
};

// The intersection of its literals (seed 001 §2.1.2).
struct Body {
    std::string id;
    std::vector<Literal> literals;
    // Where the reader knows the body's shape (an imported primitive of one body): pieces in
    // the scope's space whose convex hull has the body's bounding box (math/extent_piece.h), so
    // that its box under an affine placement and view is exact without a search. Empty: not
    // known. The set itself is the literals'; the pieces only describe its box.
    std::vector<ExtentPiece> extent;
    std::optional<Color> color;
    Finish finish;
    bool usedAsOperand = false;  // set by the reader when a CSG solid names this body
    SourceLoc loc;
};

// `instance` and `array` (seed 001 §2.1.4). An instance is an array of one copy. Copy k (0-based)
// is placed by delta^k * init (init applied first, then k deltas): deltas accumulate.
struct Instance {
    std::string id;
    int definition = -1;  // index into Scene::definitions
    Transform init;
    int count = 1;
    Transform delta;
    bool isArray = false;
    // Color given to the bodies of the instanced definition that have none of their own
    // (`=c r g b` after the parenthesised transforms).
    std::optional<Color> color;
    Finish finish;
    bool usedAsOperand = false;
    SourceLoc loc;
};

enum class CsgOp { kUnion, kIntersection, kDifference };

// What a CSG leaf names: a body, an instance/array or another CSG solid of the same scope.
struct SolidRef {
    enum class Kind { kBody, kInstance, kCsg };
    Kind kind = Kind::kBody;
    int index = -1;
};

// A CSG expression tree stored as nodes; node 0 is not special, Csg::root is.
struct CsgNode {
    bool isLeaf = true;
    SolidRef ref;               // when isLeaf
    CsgOp op = CsgOp::kUnion;   // when !isLeaf
    int left = -1, right = -1;  // when !isLeaf: indices into Csg::nodes
    SourceLoc loc;
};

// The CSG extension statement (docs/language.md): a solid combining bodies, instances and other
// CSG solids with union, intersection and difference.
//
// Color precedence (docs/language.md): a body's own color; else the innermost enclosing CSG solid
// or instance that has one; else white.
struct Csg {
    std::string id;
    std::vector<CsgNode> nodes;
    int root = -1;
    std::optional<Color> color;
    Finish finish;
    bool usedAsOperand = false;
    SourceLoc loc;
};

// A freeform surface (Bézier, B-spline or NURBS; docs/language.md "Freeform surfaces") in object
// coordinates of its scope, so that definitions, instances and arrays replicate it. It has no
// inside: it is drawn (by adaptive isocurves, seed 002) but never bounds or combines with solids,
// and a body or csg naming it is an error.
struct FreeformSurface {
    std::string id;
    freeform::Surface surface;
    std::optional<Color> color;
    Finish finish;
    SourceLoc loc;
};

struct Scope {
    std::string id;  // definition id; empty for the top level
    std::vector<HalfSpace> halfSpaces;
    std::vector<Body> bodies;
    std::vector<Instance> instances;
    std::vector<Csg> csgs;
    std::vector<FreeformSurface> freeforms;
    SourceLoc loc;
};

// Lights (seed 001 §2.1.5, and the point/spot extension of docs/language.md §3.7). Ambient lights
// are isotropic; parallel lights shine from `direction` (the vector *to* the light, world space);
// point lights shine from `position` in every direction, spot lights from `position` toward
// `aim` within a cone: full intensity up to `coneDegrees` from the axis, falling smoothly to 0 at
// `falloffDegrees`. Point and spot lights are not attenuated with distance (as POV-Ray's default
// `fade_power 0`). Intensities are already truncated to [0, 1].
struct Light {
    enum class Kind { kAmbient, kParallel, kPoint, kSpot };
    std::string id;
    Kind kind = Kind::kAmbient;
    double intensity = 0;
    Vec3 direction;                                // kParallel: toward the light
    Vec3 position;                                 // kPoint, kSpot: world space
    Vec3 aim;                                      // kSpot: the point the spot is aimed at
    double coneDegrees = 30, falloffDegrees = 40;  // kSpot: half-angles, cone <= falloff < 90
    Color color;                                   // the light's color (white unless given)
    bool isDefault = false;                        // the automatic `light default 1 0 0 -1`
    bool isRig = false;  // one of the default rig's lights (no light declared)
    SourceLoc loc;
};

// A view (seed 001 §2.1.6) with `=p`/`=r` options already resolved against the vrp given before
// them, so every vector here is a direction and cop is absolute. Missing parameters stay nullopt;
// the Flattener applies the defaults of §2.1.6.
//
// Orientation convention (docs/language.md): vpn points from the viewer into the scene; dop is the
// direction from the scene toward the viewer (so `dop 0 1 1` looks down from above, as the paper's
// `view top_down dop 0 1 1`). Screen right is vup × vpn, screen up is vpn × right: for the default
// vpn (0 0 1) and vup (0 1 0), x is right, y up and the eye looks along +z (a left-handed viewing
// frame, as in Foley and van Dam's 1982 SGP and POV-Ray).
struct View {
    std::string id;
    std::optional<Vec3> vrp, vpn, vup, dop, cop;
    std::optional<double> whh, whw;
    std::optional<double> front, back;  // fbp d1 d2, distances from vrp along vpn
    bool isDefault = false;             // the automatic `view default dop .3 .3 -1`
    SourceLoc loc;
};

struct Scene {
    Scope top;
    std::vector<Scope> definitions;
    std::vector<Light> lights;
    std::vector<View> views;
    // `background r g b [r g b]` (docs/language.md §3.8): the picture's background, a plain color
    // or a vertical gradient from the top color to the bottom one. Unset = black.
    std::optional<Color> background, backgroundBottom;

    // Lookups by id; -1 when absent.
    int FindDefinition(const std::string& id) const;
    int FindView(const std::string& id) const;
    int FindLight(const std::string& id) const;

    // The view used for rendering: `name` if given, else the last view defined, else the default
    // view `dop .3 .3 -1`. nullopt when `name` is not a view.
    std::optional<View> ViewToUse(const std::string& name = {}) const;
    // The lights used for shading when the scene declares lights: all of them; when none of them
    // is a parallel, point or spot light, the default `light default 1 0 0 -1` is added
    // (UniQuadrix's semantics). A scene that declares no light at all is lit by the default rig
    // instead (shade/light_rig.h), which the Flattener builds from the view; this returns an empty
    // list then.
    std::vector<Light> LightsToUse() const;
    // The UniQuadrix rule applied to a given list of lights (a front end's current lights): the
    // default light added when none is directed; never the rig, even for an empty list.
    static std::vector<Light> WithDefaultLight(std::vector<Light> lights);
    // True when nothing would be drawn (no drawable solid in the top scope).
    bool Empty() const;
};

View DefaultView();
Light DefaultLight();

}  // namespace quadrix::scene
