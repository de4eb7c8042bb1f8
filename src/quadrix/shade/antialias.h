// Anti-aliasing that keeps the picture exact (issue 17, deliverable 1), and silhouette and crease
// lines (deliverable 7), both from the Frame.
//
// 1. Edge pixels. Two 4-neighbour pixels p, q are separated by an edge when the Frame says so:
//    their surface, body or solid ids differ (silhouettes against the background or another
//    solid, intersection curves, creases between half-spaces), or, on one surface, their normals
//    differ by more than kCreaseDegrees (a sheet seen behind another sheet of the same quadric),
//    or their depths jump (a discontinuity, not a steep slope: the test of edge_pixels.h, against
//    4 times the slope to the next pixels outward along the same line). Both pixels of such a
//    pair are edge pixels. A straight edge crossing a pixel's square always separates its centre
//    from a 4-neighbour's (the edge is at distance < ½·√2 from the centre, and some axis
//    neighbour lies at signed distance ≥ max(|nx|, |ny|) ≥ ½·√2 across the edge's normal n), so
//    only features thinner than a pixel that touch no centre are missed.
//    With shadows on, a pair on one surface of one body whose shaded brightness jumps (the same
//    test on luminance, with a floor of one 8-bit level) is a pair of edge pixels too: a shadow's
//    boundary is not an edge of the Frame, but its samples are exact like any other (shadow rays
//    from each sample's own point).
//    Pixels near freeform surfaces (drawn by isocurves, which cannot be traced at a point) are
//    left as they are.
// 2. Samples. An edge pixel (i, j) is re-rendered at N sub-pixel positions (i + u, j + v) by
//    engine raycast, exactly: the samples of the edge pixels of an 8 × 8 square together by the
//    engine's sub-tile path (engines/raycast/sample_batch.h), or one by one by its sample tracer
//    (sample_tracer.h, the definition of a sample) where the square holds a wide union; each
//    sample is shaded like a pixel (PixelShader). Positions are stratified: N = k² (4, 16, 64), one
//    sample in each of the k × k cells and, within the cells, one in each of the N columns and N
//    rows of the fine grid (a Latin square, "multi-jittered" in Chiu, Shirley and Wang's terms;
//    here the sample sits at the centre of its fine cell). The fine-column order inside each coarse
//    column and the fine-row order inside each coarse row are permutations drawn per pixel from a
//    hash of (i, j), so the picture is deterministic and edges at any angle see no regular pattern.
//    An axis-aligned edge is resolved to 1/N of a pixel.
// 3. Filter. Box (the mean of the samples: the pixel's area coverage) or Mitchell–Netravali
//    (B = C = ⅓) weights of each sample's offset from the pixel centre, the filter truncated to
//    the pixel's square (it is positive there), so a pixel's value depends on its own samples
//    only. Averaging is done in linear light on clamped colours (what the pixel would store),
//    before the writers' sRGB encoding.
// Interior pixels are not resampled: their value is the one Shade() gave them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/shade/edge_pixels.h"
#include "quadrix/shade/shader.h"

namespace quadrix {

// kCreaseDegrees, kEdgePixel and kEdgeLine: edge_pixels.h (the one-pixel line of DrawEdgeLines is
// the kEdgeLine pixels).
std::vector<std::uint8_t> FindEdges(const Frame& frame);
// FindEdges, plus kEdgePixel on the pairs of 4-neighbours of one surface and body whose
// brightness in the shaded `image` (of the Frame's size) jumps: shadow boundaries (see the file
// comment). The pixels Antialias re-renders when shadows are on.
std::vector<std::uint8_t> FindEdgesAndShadingJumps(const Frame& frame, const Image& image);

// The N = k·k sub-pixel positions (u, v) in [0, 1)² of pixel (i, j) (see the file comment).
struct SubPixel {
    double u, v;
};
std::vector<SubPixel> SamplePositions(int samples, int i, int j);
// The same positions in a caller's list, without an allocation (the anti-aliasing asks for them
// once per edge pixel): out.at[0, out.n). samples <= 64.
struct SamplePositionList {
    std::array<SubPixel, 64> at{};
    int n = 0;
};
void SamplePositionsInto(int samples, int i, int j, SamplePositionList& out);

// Whether `samples` is a level --aa accepts (0 or 1 = off, 4, 16, 64).
bool ValidAaSamples(int samples);

struct AntialiasStats {
    std::size_t edgePixels = 0;  // pixels re-rendered
    std::size_t samples = 0;     // rays traced
    double seconds = 0;
};

// Re-renders the edge pixels of `image` (made by Shade(frame, scene, options)) with
// options.aaSamples samples each. No-op when aaSamples < 2.
// `wide`: the flat scene's wide-node trees (PixelShader), or null.
AntialiasStats Antialias(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                         Image& image, std::shared_ptr<const WideNodeTrees> wide = nullptr);

// Paints the kEdgeLine pixels of the Frame in options.edgeColor: exact silhouette, intersection
// and crease lines one pixel wide, on the front side of each edge. Returns how many.
std::size_t DrawEdgeLines(const Frame& frame, const ShadeOptions& options, Image& image);

}  // namespace quadrix
