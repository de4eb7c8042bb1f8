// Reading back a drawing's SVG file the way an SVG renderer reads it, for the tests of
// `quadrix draw` (tests/draw_test.cpp): the subset that draw/svg_writer.h writes — <ellipse>
// with a rotate() transform, <path> with absolute M, L, A, Q and C commands, <line> — inside the
// groups <g id="hidden|edges|silhouettes|sheet">, and the stroke widths of the <style> classes.
// Arcs are converted from endpoint to centre form by the rules of the SVG specification (SVG 1.1
// Appendix F.6.5, radii scaled up when too small), independently of the writer. The shapes are
// replayed into Cairo: flattened (cairo_copy_path_flat) to sample the curves the file draws, and
// stroked at their written widths onto an alpha image of the render's size.
#pragma once

#include <cairo.h>

#include <map>
#include <string>
#include <vector>

namespace quadrix::testing {

struct SvgPoint {
    double x = 0, y = 0;
};

// One drawing command in absolute coordinates. kArc: the ellipse centre (cx, cy), radii rx, ry,
// rotation phi (radians), from angle theta1 through dtheta (signed).
struct SvgOp {
    enum Kind { kMove, kLine, kCubic, kArc } kind = kMove;
    SvgPoint p[3];  // kMove/kLine: p[0]; kCubic: controls p[0], p[1], end p[2]
    double cx = 0, cy = 0, rx = 0, ry = 0, phi = 0, theta1 = 0, dtheta = 0;
};

struct SvgShape {
    std::string group;  // id of the enclosing <g>
    std::string cls;    // class attribute
    std::vector<SvgOp> ops;
};

struct SvgDrawing {
    double width = 0, height = 0;  // viewBox size
    std::vector<SvgShape> shapes;
    std::map<std::string, double> strokeWidth;  // per class, from <style>
    std::vector<std::string> errors;            // what could not be read (a test fails on any)
};

SvgDrawing ReadSvgDrawing(const std::string& svg);

// The shape as a Cairo path in the current user space.
void AppendToCairo(cairo_t* cr, const SvgShape& shape);

// The shape flattened by Cairo to polylines (one per subpath) within `tolerance`.
std::vector<std::vector<SvgPoint>> FlattenShape(const SvgShape& shape, double tolerance);

// Alpha coverage in [0, 1], row-major width × height: the shapes for which keep(shape) holds,
// stroked with their class's written width, round caps and joins, no dashes, antialiased.
template <typename Keep>
std::vector<double> RasteriseShapes(const SvgDrawing& d, int width, int height, Keep keep);

std::vector<double> RasteriseSelected(const SvgDrawing& d, int width, int height,
                                      const std::vector<const SvgShape*>& shapes);

template <typename Keep>
std::vector<double> RasteriseShapes(const SvgDrawing& d, int width, int height, Keep keep) {
    std::vector<const SvgShape*> selected;
    for (const SvgShape& s : d.shapes)
        if (keep(s)) selected.push_back(&s);
    return RasteriseSelected(d, width, height, selected);
}

}  // namespace quadrix::testing
