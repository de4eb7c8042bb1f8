#include "quadrix/engines/raycast/sample_batch.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "quadrix/util/ray_work.h"

namespace quadrix::raycast {

namespace {

std::uint64_t Literals(const Counters& c) {
    return c.literals.planes + c.literals.quadrics + c.literals.quartics;
}

// Whether bin k of `bins` holds more than SampleBatcher::kWideOperands operands of one binned
// node.
bool WideBin(const ProgramBins& bins, std::size_t k) {
    const std::size_t nb = bins.Bins();
    const std::size_t binned = bins.starts.size() / (nb + 1);
    for (std::size_t b = 0; b < binned; ++b) {
        const std::int32_t* starts = bins.starts.data() + b * (nb + 1);
        if (starts[k + 1] - starts[k] > SampleBatcher::kWideOperands) return true;
    }
    return false;
}

}  // namespace

SampleBatcher::SampleBatcher(const FlatScene& scene, const SceneTables& tables, int width,
                             int height, int side, Settings settings)
    : scene_(scene),
      settings_(settings),
      tables_(tables),
      width_(std::max(width, 1)),
      height_(std::max(height, 1)),
      side_(std::max(side, 1)) {
    BuildProgram(scene, full_);
    std::vector<Rect> bands;
    for (int y0 = 0; y0 < height_; y0 += side_) bands.push_back(BandRect(y0 / side_));
    BinProgram(full_, bands, false, bands_);
}

Rect SampleBatcher::BandRect(int band) const {
    const int y0 = band * side_;
    return {0, static_cast<double>(width_), static_cast<double>(y0),
            static_cast<double>(std::min(height_, y0 + side_))};
}

SampleBatcher::Scratch::Scratch(const SampleBatcher& batcher)
    : worker(&batcher.tables_, batcher.full_.maxDepth, batcher.settings_) {}

void SampleBatcher::SetBand(int band, Scratch& s) const {
    const auto last = static_cast<int>(bands_.Bins()) - 1;
    s.bandIndex = std::clamp(band, 0, last);
    s.bandRect = BandRect(s.bandIndex);
    s.bandReady = s.prepared = false;
    // A band with a wide node (the full program's bins count its operands there) has its squares
    // traced by SampleTracer (SetSquare): it is pruned and binned only if Trace is called.
    s.bandWide = WideBin(bands_, static_cast<std::size_t>(s.bandIndex));
    if (!s.bandWide) PrepareBand(s);
}

void SampleBatcher::PrepareBand(Scratch& s) const {
    PruneProgram(full_, bands_, static_cast<std::size_t>(s.bandIndex), s.bandRect, s.band,
                 s.worker.stack);
    std::vector<Rect>& squares = s.worker.subTileRects;
    squares.clear();
    for (int x0 = 0; x0 < width_; x0 += side_)
        squares.push_back({static_cast<double>(x0),
                           static_cast<double>(std::min(width_, x0 + side_)), s.bandRect.y0,
                           s.bandRect.y1});
    BinProgram(s.band, squares, true, s.bins);
    s.bandReady = true;
}

bool SampleBatcher::SetSquare(const Rect& r, Scratch& s) const {
    // The square that holds r: its bin lists every operand that may meet it, so the program
    // pruned from it is the one pruned from the whole band (csg_program.h ProgramBins).
    const int squares = (width_ + side_ - 1) / side_;
    s.bin = static_cast<std::size_t>(
        std::clamp(std::floor(r.x0 / side_), 0.0, static_cast<double>(squares - 1)));
    s.square = r;
    s.prepared = false;
    // A wide node in the band, or in this square's bin of the band's program (read from the
    // bins, before anything is pruned).
    if (s.bandWide || WideBin(s.bins, s.bin)) return true;
    Prepare(s);
    return false;
}

void SampleBatcher::Prepare(Scratch& s) const {
    if (!s.bandReady) PrepareBand(s);
    Worker& w = s.worker;
    PruneProgram(s.band, s.bins, s.bin, s.square, w.tileProgram, w.stack);
    w.reduction.PrepareStrip(w.tileProgram, s.square);
    s.prepared = true;
}

void SampleBatcher::Trace(const double* xs, const double* ys, int n, Sample* out,
                          Scratch& s) const {
    Worker& w = s.worker;
    if (!s.prepared) Prepare(s);  // a square with a wide node, traced here all the same
    const std::uint64_t before = Literals(w.counters);
    for (int p = 0; p < n; ++p) out[p] = Sample{};
    if (n <= 0) return;
    // The points' bounds: every proof below is made on this closed rectangle.
    Rect r{xs[0], xs[0], ys[0], ys[0]};
    for (int p = 1; p < n; ++p) {
        r.x0 = xs[p] < r.x0 ? xs[p] : r.x0;
        r.x1 = xs[p] > r.x1 ? xs[p] : r.x1;
        r.y0 = ys[p] < r.y0 ? ys[p] : r.y0;
        r.y1 = ys[p] > r.y1 ? ys[p] : r.y1;
    }
    CsgProgram& program = w.subTileProgram;
    PruneProgram(w.tileProgram, r, program, w.stack);
    if (program.solids.empty()) return;
    w.tracer.SetCuts(program);
    w.reduction.PrepareTile(program, r);
    if (w.reduction.AllEmpty(program, r)) return;
    // A sub-tile's rule (worker.h SubTileHit), point by point.
    w.batches.StartAt(program, r, xs, ys, n);
    const BodyBatch* single = w.batches.SingleBodyBatch(program, r);
    const bool kernel = !single && w.kernel.Compile(program, r);
    Hit kernelHits[kLanePixels];
    if (kernel) w.kernel.RunTile(kernelHits);
    for (int p = 0; p < n; ++p) {
        const double x = xs[p], y = ys[p];
        w.batches.SetPixelIndex(static_cast<std::size_t>(p));
        const Hit hit = SubTileHit(w, program, single, kernel ? kernelHits : nullptr,
                                   static_cast<std::size_t>(p), x, y);
        if (hit.tag < 0) continue;
        // SampleTracer::Trace's Sample of the same visible point.
        const Tag& tag = tables_.TagOf(hit.tag);
        const auto h = static_cast<std::size_t>(tag.halfSpace);
        Sample& o = out[p];
        o.depth = hit.t;
        o.normal = tables_.constantNormal[h] ? tables_.planeNormal[h]
                                             : scene_.WorldNormal(tag.halfSpace, {x, y, hit.t});
        o.surface = tag.halfSpace;
        o.body = tag.body;
        o.solid = hit.solid;
    }
    tRayLiterals += Literals(w.counters) - before;
}

}  // namespace quadrix::raycast
