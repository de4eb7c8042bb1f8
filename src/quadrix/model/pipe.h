// Pipes and worms: tubes of circular section along polylines, written as UniQuadrix text
// (seed 001 §7.2.1: mkworm "produces automatically the specifications for all cylinders and the
// terminating planes or spheres at every joint from a piecewise linear specification of the axes",
// and ugpipe "permits the proper mitering of more than two elements and also accepts the
// specification of a spherical ball at each joint").
//
// Geometry. Points of all polylines that coincide (within a weld tolerance) are one joint; every
// segment is an element, a cylinder of its path's radius. At a joint, direction a_i points from
// the joint along element i. Element i keeps the points x with (x − P)·(a_i − a_j) >= 0 for every
// other element j at that joint: the plane bisecting a_i and a_j. Two cylinders of equal radius
// whose axes meet at P cut that plane in the same ellipse, so neighbouring tubes meet without gap
// or overlap; with more than two elements the bisectors split space around P into convex sectors
// (points go to the element whose direction is nearest), which is the "proper mitering" of any
// number of elements. With a ball, elements are instead cut square at the joint and a sphere of
// radius >= the tubes' fills it. A free end (one element) is capped by a square plane, drawn or
// transparent (open).
//
// Text format (docs/gallery.md "Pipe files"): one directive per line, '#' starts a comment.
//   radius R          tube radius of the paths that follow (default 1)
//   ball R | ball off a sphere of radius R (>= the tube radius) at every joint of later paths
//   caps on | off     close free ends (default on) or leave them open
//   color r g b | color off
//   path | loop       starts an open / closed polyline; its points follow, one "x y z" a line
//   end               ends the current polyline (optional)
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/math/quadric.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::model {

struct PipePath {
    std::vector<Vec3> points;
    bool closed = false;
    double radius = 1;
    double ball = 0;  // 0: mitered joints
    bool caps = true;
    std::optional<std::array<double, 3>> color;
    SourceLoc loc;
};

struct PipeSpec {
    std::vector<PipePath> paths;
};

// Reads the text format above. Returns false with errors (file:line:column) in diags.
bool ReadPipeText(std::string_view text, const std::string& name, PipeSpec& spec,
                  Diagnostics& diags);

// One tube: its cylinder and the planes that bound it at each end.
struct PipeElement {
    int path = -1;
    int joint0 = -1, joint1 = -1;  // indices into PipeModel::joints
    Vec3 p0, p1;
    double radius = 1;
    Quadric side;
    std::vector<Plane> ends;  // all bounding planes (end 0 first)
    std::vector<bool> endTransparent;
    std::optional<std::array<double, 3>> color;
};

struct PipeJoint {
    Vec3 point;
    std::vector<int> elements;  // elements that end here
    double ball = 0;            // radius of the sphere here, 0 = none
};

struct PipeModel {
    std::vector<PipeJoint> joints;
    std::vector<PipeElement> elements;
    int mitered = 0, balls = 0, freeEnds = 0;  // joints by kind (a joint of one element is an end)
};

// Builds the tubes; false with errors in diags (overlapping elements, a ball smaller than its
// tubes, a path with fewer than 2 distinct points). Warnings: dropped repeated points, duplicate
// elements, tubes of different radii mitered together.
bool BuildPipes(const PipeSpec& spec, PipeModel& model, Diagnostics& diags);

struct PipeWriteOptions {
    std::string source;      // named in the header comment
    std::string definition;  // when set, everything is wrapped in `definition <name>; ... enddef;`
    std::string prefix = "e";  // element ids e1, e2, ...; joint spheres j1, ...
};

// UniQuadrix text: per element a quadric, its planes and a body; per ball a quadric and a body.
std::string WriteUniQuadrix(const PipeModel& model, const PipeWriteOptions& options);

// Polyline generators for the gallery.
// The Hilbert curve of order n in the square [0, 2ⁿ − 1]² of the plane z = 0: 4ⁿ points.
std::vector<Vec3> HilbertCurve(int order);
// A trefoil knot (x = sin t + 2 sin 2t, y = cos t − 2 cos 2t, z = −sin 3t) sampled at n points.
std::vector<Vec3> TrefoilKnot(int samples);
// The triangles of a Sierpinski gasket of the given order (3^order triangles, side 2^order).
std::vector<std::array<Vec3, 3>> SierpinskiTriangles(int order);
// Strokes spelling `text` (letters A-Z as supported by the stroke font; others are skipped):
// polylines whose junctions share vertices, so that joints are mitered or balled.
std::vector<std::vector<Vec3>> StrokeText(std::string_view text, std::string* unsupported);

}  // namespace quadrix::model
