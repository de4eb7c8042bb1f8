// A hidden-line drawing of a flattened scene (docs/drawings.md; seed 001 §7.2.3, "wire-frame
// images with hidden edges removed"): the stages in order,
//   1. curve_extraction.h  candidate edges and silhouettes (exact lines and conics, traced
//   quartics)
//   2. trim.h              pieces that lie on the solids' boundary after CSG
//   3. visibility.h        split where visibility changes (ray casts + bisection)
//   4. here                pieces as 2-D strokes: segments, elliptical, hyperbolic and parabolic
//                          arcs in closed form, polylines (traced quartics); coincident strokes
//                          (the same piece of line drawn twice, e.g. by two curves carried by one
//                          line) are written once
// and the writers (svg_writer.h, cairo_writer.h) take the strokes. Coordinates of strokes are
// device pixels (x right, y down), the same as the Frame's, so a drawing overlays the render of
// the same view exactly.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/flatten/flat_scene.h"

namespace quadrix::draw {

struct Point2 {
    double x = 0, y = 0;
};

enum class StrokeKind : std::uint8_t {
    kSegment,
    kEllipseArc,
    kHyperbolaArc,
    kParabolaArc,
    kPolyline
};

struct Stroke {
    StrokeKind kind = StrokeKind::kSegment;
    CurveRole role = CurveRole::kEdge;
    CurveKind source = CurveKind::kLine;
    bool visible = true;
    bool tangent = false;  // a tangent edge drawn thin (TangentEdges::kThin)
    int surfaceA = -1, surfaceB = -1;
    // The conic arcs, P(θ) for θ from a0 to a1 (a1 > a0), in closed form (the writers turn them
    // into exact SVG `A` and `Q` commands, or cubic Béziers within the page's tolerance):
    //   kEllipseArc    P(θ) = c + U cos θ + V sin θ (a1 − a0 = 2π is the whole ellipse; U, V are
    //                  conjugate semi-diameters, the image of the 3-D ones)
    //   kHyperbolaArc  P(θ) = c + U cosh θ + V sinh θ
    //   kParabolaArc   P(θ) = c + U θ + V θ²
    Point2 c, U, V;
    double a0 = 0, a1 = 0;
    std::vector<Point2> points;         // kSegment (two) and kPolyline
    Point2 ArcPoint(double t) const;    // the conic arcs
    Point2 ArcTangent(double t) const;  // dP/dθ
    bool IsConicArc() const {
        return kind == StrokeKind::kEllipseArc || kind == StrokeKind::kHyperbolaArc ||
               kind == StrokeKind::kParabolaArc;
    }
};

// Tangent edges, where two faces meet without a crease (trim.h): drawn with a thin line (what
// drafting practice does by default), left out, or drawn as ordinary edges.
enum class TangentEdges : std::uint8_t { kThin, kOff, kOn };

struct DrawOptions {
    double visibilityStep = 0.5;  // device px between ray tests along a curve
    bool hidden = true;           // compute (and keep) hidden pieces
    TangentEdges tangentEdges = TangentEdges::kThin;
};

struct DrawStats {
    int candidates = 0, pieces = 0, strokes = 0;
    // tangentPairs: plane–quadric pairs tangent along a line (double lines); tangentPieces:
    // boundary pieces that are tangent edges (0 under TangentEdges::kOff, which
    // drops them while trimming).
    int lines = 0, conics = 0, silhouettes = 0, quartics = 0, tangentPairs = 0;
    int tangentPieces = 0;
    int duplicates = 0;  // strokes dropped because another stroke draws the same line
    long long rayTests = 0;
    int visibilityChanges = 0;
    double seconds = 0;  // the whole of MakeDrawing, the sum of the phases below
    // Phases: candidate curves (surfaces and their pairs), trimming to the solids' boundary,
    // visibility (ray tests and bisection), strokes (2-D output).
    double curveSeconds = 0, trimSeconds = 0, visibilitySeconds = 0, strokeSeconds = 0;
};

struct Drawing {
    int width = 0, height = 0;  // device size (px)
    std::vector<Stroke> strokes;
    DrawStats stats;
};

Drawing MakeDrawing(const FlatScene& scene, const DrawOptions& options = {});

// Maps every stroke by p → s p + (dx, dy) (s > 0): used to place views on a sheet.
void TransformDrawing(Drawing& d, double s, double dx, double dy);

}  // namespace quadrix::draw
