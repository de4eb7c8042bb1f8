// Engine `raycast`'s sub-tile path at points that are not pixel centres: the visible points of a
// batch of rays through device positions (x, y) — the anti-aliasing pass's sub-pixel samples
// (shade/antialias.h) — computed the way a sub-tile's pixels are (tiling.cpp), instead of one
// sample at a time by SampleTracer's tree walk (sample_tracer.h).
//
// For the points of one batch, all in a closed rectangle r of the image plane (their bounds):
//   1. the program is pruned to r (csg_program.h PruneProgram: by the bounds of the nodes);
//   2. each body's literals are reduced on r and bodies are proved empty there (tile_reduction.h
//      PrepareStrip/PrepareTile), on the band and square rectangles that contain r first;
//   3. the bodies are batched over the points (body_batch.h StartAt), and the batch is drawn as a
//      sub-tile: from the one body it reduces to, else by the kernel's lanes (kernel.h), else by
//      Trace per point (trace.h) — a sub-tile pixel's rule (worker.h SubTileHit), point by
//      point.
// Every proof of steps 1–3 is made on a rectangle, by bounds linear in (x, y) or by
// ClassifyQuadric's bound over the whole rectangle, never at pixel centres alone; the lanes and
// Trace take each point's own (x, y). So a point's visible point is the exact one, what
// SampleTracer::Trace gives there, bit for bit: depth, surface, body, solid and the normal
// computed from them the same way (the SampleBatch tests compare the two at random points of
// every example and test scene). Flat sub-tiles are not filled as such here (their pixels are
// drawn from the body's batch, the same values).
//
// Use: SetBand (a band of rows, pruned once and binned over its squares, as the engine bins a
// tile's program over its sub-tiles), then SetSquare (a rectangle inside one square of the band:
// pruned from its bin, the strip reduction), then Trace for the batches of points in it, each at
// most kMaxPoints.
#pragma once

#include <cstdint>

#include "quadrix/engines/raycast/sample_tracer.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/worker.h"
#include "quadrix/eval/csg_program.h"
#include "quadrix/flatten/flat_scene.h"

namespace quadrix::raycast {

class SampleBatcher {
  public:
    static constexpr int kMaxPoints = kLanePixels;
    // A node of more operands than this in a band or square makes it "wide" (SetSquare). The
    // machined part's difference has 9 subtrahends; a cluster of spheres, hundreds.
    static constexpr std::int32_t kWideOperands = 32;

    // For points of the image [0, width] × [0, height], which is cut into bands of `side` rows
    // and each band into squares `side` wide (the last ones shorter). The whole program is binned
    // over the bands once here.
    // `tables`: the scene's (SampleTracer::Tables), kept alive by the caller.
    SampleBatcher(const FlatScene& scene, const SceneTables& tables, int width, int height,
                  int side, Settings settings = {});

    // One per thread: the engine's per-thread state (worker.h) and the band's program.
    class Scratch {
      public:
        explicit Scratch(const SampleBatcher& batcher);

      private:
        friend class SampleBatcher;
        Worker worker;
        int bandIndex = 0;       // SetBand's band
        Rect bandRect;           // ... its rectangle
        bool bandWide = false;   // ... holds a wide node (SetBand)
        bool bandReady = false;  // `band` and `bins` made (PrepareBand)
        CsgProgram band;         // the program pruned to the band
        ProgramBins bins;        // band's, over the squares
        Rect square;             // SetSquare's rectangle
        std::size_t bin = 0;     // the band's square (bin) that holds it
        bool prepared = false;   // the program pruned to it, its bodies reduced (Prepare)
    };

    // The next points lie in band `band`: [0, width] × [band·side, (band + 1)·side].
    void SetBand(int band, Scratch& s) const;
    // ... and in the closed rectangle `r`, inside one of the band's squares. Returns whether the
    // program there has a wide node (a union, or a difference's subtrahends, of more than
    // kWideOperands operands, as the bins count them for the band or, else, for the square): the
    // kernel does not take it, and SampleTracer's depth windows trace such a cluster (10,000
    // spheres) faster than Trace's cuts do here. The band and the square are then pruned, and the
    // square's bodies reduced, only if Trace is called.
    bool SetSquare(const Rect& r, Scratch& s) const;
    // out[p] = the visible point of the ray through (xs[p], ys[p]), p < n <= kMaxPoints, every
    // point inside the square. Adds the literals it evaluates to tRayLiterals (util/ray_work.h).
    void Trace(const double* xs, const double* ys, int n, Sample* out, Scratch& s) const;

  private:
    Rect BandRect(int band) const;
    // The program pruned to the band and binned over its squares (SetBand, or Prepare in a wide
    // band).
    void PrepareBand(Scratch& s) const;
    // The program pruned to the square and its bodies reduced there (SetSquare, or the first
    // Trace after a SetSquare that found a wide node).
    void Prepare(Scratch& s) const;

    const FlatScene& scene_;
    Settings settings_;
    const SceneTables& tables_;
    CsgProgram full_;
    int width_, height_, side_;
    ProgramBins bands_;  // full_'s, over the bands
};

}  // namespace quadrix::raycast
