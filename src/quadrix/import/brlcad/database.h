// The in-memory form of a BRL-CAD database as the readers leave it, before conversion to a Scene.
//
// The readers (v4 records, v5 `put` script, COMGEOM deck) only parse; every geometric decision
// (which primitives are quadric, how regions and colors are resolved) is made by the converter
// (brlcad_import.cpp) on this neutral form. Units: millimetres, as in every BRL-CAD file
// (shared/data/brlcad/FORMAT.md §2.1, §3.1). Coordinates are BRL-CAD's own (right-handed, Z up).
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"
#include "quadrix/scene/source_loc.h"

namespace quadrix::import::brlcad {

// One primitive with the parameters of FORMAT.md §2.3 / §3.1 (only those its type uses are set).
struct Primitive {
    std::string type;  // v5 type name: arb8, arbn, half, ell, tgc, rpc, rhc, epa, ehy, hyp, part,
                       // tor, eto, pipe, bot, or any other name (dsp, ...), kept for the census
    std::string name;
    std::array<Vec3, 8> pts{};  // arb8 vertices 1..8, absolute
    Vec3 V, H, A, B, C, D, N;
    double r = 0, r1 = 0, r2 = 0, c = 0, d = 0, b = 0, bnr = 0, rv = 0, rh = 0;
    std::vector<Plane> planes;  // arbn, already as Quadrix planes (inside <= 0)
    // tor: V, H (unit normal), r1 = r_a (ring radius), r2 = r_h (tube radius).
    // eto: V, N, C, r, rd.
    double rd = 0;
    // pipe (FORMAT.md §3.1 `V0 O0 I0 R0 V1 ...`): the points in order, each with the outer and
    // inner diameters and the bend radius used at that point (pipe_solid.h).
    struct PipePoint {
        Vec3 at;
        double od = 0, id = 0, bend = 0;
    };
    std::vector<PipePoint> pipe;
    // ars (FORMAT.md §2.1 `A`/`B`, v5 `NC PPC C0 …`): curves of the same number of points, all
    // absolute; each curve is a closed loop, consecutive curves are joined by quadrilaterals
    // (librt's rt_ars_tess). Drawn as the closed mesh they bound (primitives.cpp).
    std::vector<std::vector<Vec3>> arsCurves;
    // bot (triangle mesh, FORMAT.md §3.1): vertices, 0-based triangles, mode (1 surface, 2 solid,
    // 3 plate, 4 plate without obliquity), orientation (1 unoriented, 2 counter-clockwise seen
    // from outside, 3 clockwise), and in plate modes one thickness and one "appended" flag
    // (thickness on one side instead of centred) per face.
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> faces;
    int botMode = 2, botOrientation = 1;
    std::vector<double> thickness;
    std::vector<char> faceAppended;
    SourceLoc loc;
    std::string sourceLine;
    long long byteOffset = -1;  // binary .g: where the object starts (loc has no line there)
};

// A node of a combination's boolean tree (v5 form; v4 GIFT lists are converted to it).
struct TreeNode {
    enum class Op { kLeaf, kUnion, kIntersection, kDifference };
    Op op = Op::kLeaf;
    std::string name;                // kLeaf
    Mat4 matrix = Mat4::Identity();  // kLeaf: row-major, p' = M p, m15 = inverse uniform scale
    int left = -1, right = -1;       // indices into Combination::nodes
    SourceLoc loc;
};

struct Combination {
    std::string name;
    bool region = false;
    int regionId = 0;
    int aircode = 0;
    std::optional<std::array<int, 3>> rgb;  // 0..255
    bool inherit = false;
    std::string shader;  // first word of the shader, e.g. "plastic", "light", "envmap"
    std::vector<TreeNode> nodes;
    int root = -1;  // -1: an empty combination
    SourceLoc loc;
    std::string sourceLine;
    long long byteOffset = -1;
};

struct ColorTableEntry {
    int low = 0, high = 0;
    std::array<int, 3> rgb{};
};

struct Database {
    std::string title;
    std::string format;  // "v4", "v5" or "comgeom"
    std::vector<Primitive> primitives;
    std::vector<Combination> combinations;
    std::vector<ColorTableEntry> colorTable;
    // name -> (isCombination, index); later definitions replace earlier ones (as asc2g does).
    std::map<std::string, std::pair<bool, int>> objects;

    void AddPrimitive(Primitive p) {
        objects[p.name] = {false, static_cast<int>(primitives.size())};
        primitives.push_back(std::move(p));
    }
    void AddCombination(Combination c) {
        objects[c.name] = {true, static_cast<int>(combinations.size())};
        combinations.push_back(std::move(c));
    }
};

}  // namespace quadrix::import::brlcad
