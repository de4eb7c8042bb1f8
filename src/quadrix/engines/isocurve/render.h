// The isocurve engine's entry points: freeform surfaces → adaptive isocurves → a Frame
// (seed 002; DESIGN.md "isocurve").
//
// RenderFreeform draws into a Frame that may already hold quadric solids (depth-tested by
// Frame::Offer), so freeform surfaces and quadrics compose in one picture. Surfaces are given in
// world coordinates with the Frame ids to write for them; the projection is the FlatScene's.
//
// The tolerance δ (world units) is either given or derived from the image: δ = pixelSpacing / s,
// s the largest number of device pixels per world unit over the surfaces (exact for parallel
// projections: the spectral norm of the xy rows of deviceFromWorld; sampled on a 17×17 grid per
// patch with a 10 % margin for perspective). Adjacent curves are then at most pixelSpacing pixels
// apart on the screen, and curves of width `thickness` > pixelSpacing leave no hole.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "quadrix/engines/engine.h"
#include "quadrix/engines/isocurve/curve_raster.h"
#include "quadrix/engines/isocurve/extraction.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

struct FreeformDrawable {
    const freeform::Surface* surface = nullptr;  // world coordinates
    FrameIds ids;                                // written into the Frame where it is seen
};

struct IsocurveOptions {
    double delta = 0;         // world tolerance; 0 = from pixelSpacing and the projection
    double pixelSpacing = 1;  // screen gap between adjacent isocurves when delta = 0 (pixels)
    double thickness = 0;     // curve width in pixels; 0 = 1.5 · pixelSpacing + 0.25
    Direction direction = Direction::kAuto;
    int minLevel = 2;
    int maxLevel = 24;
    int baseCount = 1;          // ExtractOptions::baseCount: 1 = Algorithm 1, 0 = auto, N
    bool uniform = false;       // draw uniformly spaced curves instead of adaptive ones
    int progressiveLevels = 1;  // RenderFreeformProgressive: coarse levels before the final one
    bool compare = false;       // also measure uniform curves and a polygon mesh (compare.h)
};

struct IsocurveStats {
    int surfaces = 0;
    double delta = 0;      // world tolerance used
    double thickness = 0;  // pixels
    int curves = 0;
    double length = 0;  // world units
    int pairs = 0;
    int crossings = 0;
    int unresolved = 0;
    int deepestLevel = 0;
    RasterCounts raster;
    double extractSeconds = 0;
    double drawSeconds = 0;
};

// Device pixels per world unit, the largest over the surfaces (see the file comment).
double PixelsPerWorldUnit(const std::vector<FreeformDrawable>& drawables,
                          const Projection& projection);
double DeltaForImage(const std::vector<FreeformDrawable>& drawables, const Projection& projection,
                     double pixelSpacing);

// Extracts and draws. `frame` must already have the image size (it is not reset).
IsocurveStats RenderFreeform(const std::vector<FreeformDrawable>& drawables,
                             const Projection& projection, const IsocurveOptions& options,
                             Frame& frame);

// The curves of one surface, extracted with the options' direction and levels.
Extraction ExtractFor(const freeform::Surface& surface, double delta,
                      const IsocurveOptions& options, bool keepStrips = false);
// Draws given extractions (one per drawable) with curves `thickness` pixels wide.
RasterCounts DrawExtractions(const std::vector<FreeformDrawable>& drawables,
                             const std::vector<Extraction>& extractions,
                             const Projection& projection, double thickness, Frame& frame);

// Progressive (coarse-to-fine) rendering, seed 002 §3.1 and Figure 4: level k = 0..L−1 (L =
// progressiveLevels + 1) uses δ_k = δ · 2^(L−1−k) and thickness_k = thickness · 2^(L−1−k); each
// level starts from `base` (e.g. the quadric solids) and is handed to `show` when done. The last
// level is the full-quality image.
void RenderFreeformProgressive(
    const std::vector<FreeformDrawable>& drawables, const Projection& projection,
    const IsocurveOptions& options, const Frame& base,
    const std::function<void(int level, int levels, const Frame&, const IsocurveStats&)>& show);

// Engine options (CLI --engine-opt key=value), declared once in IsocurveSchema: delta, spacing,
// thickness, direction (u|v|auto), min-level, max-level, base (auto|N), uniform, progressive
// (levels), compare. ParseIsocurveOptions checks a raw map against the schema (an error message
// for an unknown key or a bad value, else "") and fills `options`.
const OptionSchema& IsocurveSchema();
std::string CheckIsocurveOptions(const EngineOptions& options);
IsocurveOptions ReadIsocurveOptions(const EngineOptions& options);
std::string ParseIsocurveOptions(const std::map<std::string, std::string>& values,
                                 IsocurveOptions& options);

// Counters and the free-form report of --stats.
void FillRenderStats(const IsocurveStats& stats, RenderStats& out);
std::string FormatIsocurveStats(const IsocurveStats& stats);

}  // namespace quadrix::isocurve
