#include "quadrix/engines/patch/patch_engine.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>

#include "quadrix/engines/patch/cost_model.h"
#include "quadrix/engines/patch/counters.h"
#include "quadrix/engines/patch/float_engine.h"
#include "quadrix/engines/patch/host_setup.h"
#include "quadrix/engines/patch/integer_reference.h"
#include "quadrix/engines/patch/patch.h"
#include "quadrix/engines/patch/patch_processor.h"
#include "quadrix/engines/patch/timing_model.h"
#include "quadrix/util/parallel.h"

namespace quadrix {
namespace {

using namespace patch;

constexpr int kBandRows = 16;       // rows per parallel task; bands never share a pixel
constexpr int kHistogramBins = 12;  // error bins [0,1), [1,2), [2,4), ... LSB, the last open

struct Settings {
    bool fixed = false;
    DatapathWidths widths;
    CapPolicy caps = CapPolicy::kSkip;
    double clockHz = kPaperClockHz;
    bool compare = true;
    bool verify = false;
};

const OptionSchema& PatchSchema() {
    using O = OptionSpec;
    static const OptionSchema kSchema{
        O::Choice("mode", "float", {"float", "fixed"},
                  "the algorithm in double precision, or the bit-exact fixed-point emulator"),
        O::Int("depth-bits", "24", DatapathWidths::kMinDepthBits, DatapathWidths::kMaxDepthBits,
               "fixed mode: depth word width d (the EP2 and square-root extractor use 2d)"),
        O::Int("normal-bits", "16", DatapathWidths::kMinNormalBits, DatapathWidths::kMaxDepthBits,
               "fixed mode: normal and multiplier width n (8..d)"),
        O::Choice("caps", "skip", {"skip", "open"},
                  "bodies cut by opaque planes: left to raycast (skip) or drawn open"),
        O::Number("clock-mhz", "50", 0, 1e6, true, "clock of the timing model (the paper's)"),
        O::Bool("compare", "on",
                "fixed mode: also run the float algorithm and report the depth error histogram"),
        O::Bool("verify", "off",
                "fixed mode: also run the integer reference and count mismatching pixels"),
    };
    return kSchema;
}

Settings ReadSettings(const EngineOptions& o) {
    Settings st;
    st.fixed = o.Choice("mode") == "fixed";
    st.widths.depthBits = o.Int("depth-bits");
    st.widths.normalBits = o.Int("normal-bits");
    st.caps = o.Choice("caps") == "open" ? CapPolicy::kOpen : CapPolicy::kSkip;
    st.clockHz = o.Number("clock-mhz") * 1e6;
    st.compare = o.Bool("compare");
    st.verify = o.Bool("verify");
    return st;
}

// What one band of rows contributes to the statistics (summed in band order: deterministic).
struct BandStats {
    FloatStats flt;
    std::int64_t fixedSurfacePixels = 0;
    std::int64_t normalsFacingAway = 0;  // emulated NZ > 0 (rounding at silhouettes)
    // Comparison with the float algorithm (fixed mode).
    std::int64_t compared = 0;
    std::int64_t sheetMismatch = 0;     // both draw, different sheets
    std::int64_t coverageMismatch = 0;  // one draws, the other does not
    std::array<std::int64_t, kHistogramBins> histogram{};
    double maxErrorLsb = 0, sumErrorLsb = 0;
    double maxErrorOverBound = 0;
    // Integer reference (verify=on).
    std::int64_t verified = 0, verifyMismatch = 0;

    void Add(const BandStats& o) {
        flt.windowPixels += o.flt.windowPixels;
        flt.surfacePixels += o.flt.surfacePixels;
        flt.backSheetPixels += o.flt.backSheetPixels;
        fixedSurfacePixels += o.fixedSurfacePixels;
        normalsFacingAway += o.normalsFacingAway;
        compared += o.compared;
        sheetMismatch += o.sheetMismatch;
        coverageMismatch += o.coverageMismatch;
        for (int b = 0; b < kHistogramBins; ++b) histogram[b] += o.histogram[b];
        maxErrorLsb = std::max(maxErrorLsb, o.maxErrorLsb);
        sumErrorLsb += o.sumErrorLsb;
        maxErrorOverBound = std::max(maxErrorOverBound, o.maxErrorOverBound);
        verified += o.verified;
        verifyMismatch += o.verifyMismatch;
    }
};

int HistogramBin(double lsb) {
    if (lsb < 1) return 0;
    const int b = 1 + static_cast<int>(std::floor(std::log2(lsb)));
    return std::min(b, kHistogramBins - 1);
}

struct FixedJob {
    const QuadricPatch* patch = nullptr;
    HostPatch host;
    double boundLsb = 0;
};

void ScanFixedBand(const FixedJob& job, const FlatScene& scene, const Settings& st,
                   const DepthFormat& format, int yBegin, int yEnd, Frame& frame, BandStats& bs) {
    const FixedPatch& fp = job.host.program;
    const PixelWindow& w = fp.window;
    const int y0 = std::max(yBegin, w.y0), y1 = std::min(yEnd, w.y1);
    if (y0 >= y1) return;
    PatchProcessor proc(st.widths);
    proc.Load(fp);
    proc.SkipLines(y0 - w.y0);
    std::vector<PixelSignals> line;
    const std::int64_t zmax = Zmax(st.widths);
    for (int py = y0; py < y1; ++py) {
        const int j = py - w.y0;
        proc.ScanLine(line);
        bs.flt.windowPixels += w.Width();
        for (int i = 0; i < w.Width(); ++i) {
            const PixelSignals& s = line[static_cast<std::size_t>(i)];
            const int pxi = w.x0 + i;
            const double x = pxi + 0.5, y = py + 0.5;
            if (st.verify) {
                ++bs.verified;
                if (!(ReferencePixel(fp, st.widths, i, j) == s)) ++bs.verifyMismatch;
            }
            const bool drawn = s.zout != zmax;
            const double z = format.ToDevice(s.zout);
            if (st.compare) {
                const FloatPixel fpx = EvaluatePixelFloat(*job.patch, x, y);
                const bool floatDrawn = fpx.sheet != Sheet::kNone;
                if (drawn != floatDrawn) {
                    ++bs.coverageMismatch;
                } else if (drawn) {
                    const Sheet sheet = s.ef ? Sheet::kFront : Sheet::kBack;
                    if (sheet != fpx.sheet) {
                        ++bs.sheetMismatch;
                    } else {
                        const double err = std::fabs(z - fpx.zout) / format.ulp;
                        ++bs.compared;
                        ++bs.histogram[static_cast<std::size_t>(HistogramBin(err))];
                        bs.maxErrorLsb = std::max(bs.maxErrorLsb, err);
                        bs.sumErrorLsb += err;
                        bs.maxErrorOverBound = std::max(bs.maxErrorOverBound, err / job.boundLsb);
                    }
                }
            }
            if (!drawn) continue;
            ++bs.fixedSurfacePixels;
            if (s.nz > 0) ++bs.normalsFacingAway;
            const std::size_t idx = frame.Index(pxi, py);
            if (!frame.Nearer(idx, z)) continue;
            const double u = job.host.normalUnit;
            const Vec3 g{static_cast<double>(s.nx) * u, static_cast<double>(s.ny) * u,
                         static_cast<double>(s.nz) * u};
            frame.Offer(idx, z, WorldNormalFromDeviceGradient(scene, {x, y, z}, g),
                        job.patch->surface, job.patch->body);
        }
    }
}

// Runs `bandFn(band, stats)` over the bands of rows, in parallel, and sums the stats in order.
template <class Fn>
BandStats ForEachBand(int height, Fn&& bandFn) {
    const int bands = (height + kBandRows - 1) / kBandRows;
    std::vector<BandStats> perBand(static_cast<std::size_t>(bands));
    ParallelFor(tbb::blocked_range<int>(0, bands), [&](const tbb::blocked_range<int>& r) {
        for (int b = r.begin(); b < r.end(); ++b)
            bandFn(b * kBandRows, std::min(height, (b + 1) * kBandRows),
                   perBand[static_cast<std::size_t>(b)]);
    });
    BandStats total;
    for (const BandStats& b : perBand) total.Add(b);
    return total;
}

class PatchEngine final : public Engine {
  public:
    std::string_view Name() const override { return "patch"; }
    const OptionSchema& Schema() const override { return PatchSchema(); }
    std::string CheckOptions(const EngineOptions& options) const override {
        if (std::string why = ReadSettings(options).widths.Validate(); !why.empty())
            return "engine 'patch': " + why;
        return {};
    }

  protected:
    RenderStats Draw(const FlatScene& scene, const EngineOptions& options, Frame& frame) override;
};

RenderStats PatchEngine::Draw(const FlatScene& scene, const EngineOptions& options, Frame& frame) {
    const auto t0 = std::chrono::steady_clock::now();
    RenderStats stats;
    frame.Reset(scene.width, scene.height);
    const Settings st = ReadSettings(options);

    // Solids made of one body become patches; CSG trees of several bodies are skipped.
    std::vector<QuadricPatch> patches;
    std::map<Rejection, std::int64_t> rejected;
    std::int64_t csgSkipped = 0, drawnOpen = 0, planesDropped = 0;
    for (std::size_t s = 0; s < scene.solids.size(); ++s) {
        const FlatSolid& solid = scene.solids[s];
        if (solid.root < 0 || solid.root >= static_cast<int>(scene.nodes.size())) continue;
        const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(solid.root)];
        if (!node.isLeaf) {
            ++csgSkipped;
            stats.undrawn.push_back({static_cast<int>(s),
                                     "a CSG solid (the patch processor "
                                     "draws one quadric within four planes)"});
            continue;
        }
        if (node.body < 0 || node.body >= static_cast<int>(scene.bodies.size())) continue;
        Conversion c = ConvertBody(scene, node.body, st.caps);
        planesDropped += c.planesDropped;
        if (!c.patch) {
            ++rejected[c.why];
            if (c.why != Rejection::kEmpty && c.why != Rejection::kInvisible)
                stats.undrawn.push_back({static_cast<int>(s), std::string(RejectionName(c.why))});
            continue;
        }
        drawnOpen += c.drawnOpen;
        patches.push_back(*c.patch);
    }

    FrameTiming timing;
    timing.clockHz = st.clockHz;
    const int latency = PipelineLatency(st.widths);
    BandStats bs;
    std::string fixedReport;
    std::int64_t hostOverflow = 0, hostEmpty = 0, planesPerpendicular = 0, planesNeverCut = 0;
    double depthUlp = 0;

    if (!st.fixed) {
        for (const QuadricPatch& p : patches) timing.AddPatch(p.window.Pixels(), latency);
        bs = ForEachBand(scene.height, [&](int y0, int y1, BandStats& b) {
            for (const QuadricPatch& p : patches) {
                if (p.window.y1 <= y0 || p.window.y0 >= y1) continue;
                RenderPatchRowsFloat(p, scene, y0, y1, frame, b.flt);
            }
        });
    } else {
        std::vector<HostAnalysis> analyses;
        DepthFormatBuilder builder;
        for (const QuadricPatch& p : patches) {
            analyses.push_back(AnalyzePatch(p));
            builder.Add(analyses.back());
        }
        const DepthFormat format = builder.Build(st.widths);
        depthUlp = format.ulp;
        std::vector<FixedJob> jobs;
        for (std::size_t k = 0; k < patches.size(); ++k) {
            const HostAnalysis& a = analyses[k];
            planesPerpendicular += a.planesMadePerpendicular;
            planesNeverCut += a.planesDropped;
            if (a.empty) {
                ++hostEmpty;
                continue;
            }
            std::optional<HostPatch> hp = PrepareFixedPatch(patches[k], a, format, st.widths);
            if (!hp) {
                ++hostOverflow;
                continue;
            }
            timing.AddPatch(patches[k].window.Pixels(), latency);
            jobs.push_back({&patches[k], *hp, DepthErrorBoundLsb(patches[k].window)});
        }
        bs = ForEachBand(scene.height, [&](int y0, int y1, BandStats& b) {
            for (const FixedJob& job : jobs) {
                const PixelWindow& w = job.host.program.window;
                if (w.y1 <= y0 || w.y0 >= y1) continue;
                ScanFixedBand(job, scene, st, format, y0, y1, frame, b);
            }
        });

        fixedReport += fmt::format(
            "Fixed-point datapath: depth {} bits (EP2 and SRE input {} bits, root {} bits), "
            "normals {} bits\n",
            st.widths.depthBits, st.widths.Ep2Bits(), st.widths.RootBits(), st.widths.normalBits);
        fixedReport += fmt::format(
            "  depth format: z = {:.9g} + word x {:.6g} (range +-{:.6g} device units)\n",
            format.origin, format.ulp, format.ulp * std::ldexp(1.0, st.widths.depthBits - 1));
        fixedReport += fmt::format(
            "  host: {} planes never cutting dropped, {} nearly edge-on planes loaded as "
            "perpendicular, {} patches empty, {} patches not fitting the words\n",
            planesNeverCut, planesPerpendicular, hostEmpty, hostOverflow);
        fixedReport += fmt::format("  surface pixels {}, emulated normals facing away {}\n",
                                   bs.fixedSurfacePixels, bs.normalsFacingAway);
        if (st.compare) {
            fixedReport += fmt::format(
                "  vs float: {} pixels compared, {} coverage and {} sheet mismatches (pixels on "
                "silhouettes and plane cuts)\n",
                bs.compared, bs.coverageMismatch, bs.sheetMismatch);
            const double mean = bs.compared > 0 ? bs.sumErrorLsb / bs.compared : 0;
            fixedReport += fmt::format(
                "  depth error: max {:.3f} LSB = {:.3g} device units, mean {:.3f} LSB, max/bound "
                "{:.3f}\n",
                bs.maxErrorLsb, bs.maxErrorLsb * format.ulp, mean, bs.maxErrorOverBound);
            fixedReport += "  depth error histogram (LSB):";
            for (int b = 0; b < kHistogramBins; ++b) {
                if (bs.histogram[static_cast<std::size_t>(b)] == 0) continue;
                const std::string label =
                    b == 0
                        ? "[0,1)"
                        : (b == kHistogramBins - 1 ? fmt::format(">={}", 1 << (b - 1))
                                                   : fmt::format("[{},{})", 1 << (b - 1), 1 << b));
                fixedReport +=
                    fmt::format(" {}:{}", label, bs.histogram[static_cast<std::size_t>(b)]);
            }
            fixedReport += "\n";
        }
        if (st.verify)
            fixedReport += fmt::format("  integer reference: {} of {} pixels differ\n",
                                       bs.verifyMismatch, bs.verified);
    }

    // Statistics.
    const CostModel cost = ComputeCost(st.widths);
    CounterValues counters(patch::kPatchCounters);
    counters.Set(patch::kPatches, patches.size());
    counters.Set(patch::kBodiesDrawnOpen, drawnOpen);
    counters.Set(patch::kRedundantPlanesDropped, planesDropped);
    counters.Set(patch::kCsgSolidsSkipped, csgSkipped);
    std::int64_t notDrawable = 0;
    for (const auto& [why, count] : rejected) {
        counters.Set(patch::kSkippedEmpty + (static_cast<std::size_t>(why) -
                                             static_cast<std::size_t>(Rejection::kEmpty)),
                     count);
        if (why != Rejection::kEmpty && why != Rejection::kInvisible) notDrawable += count;
    }
    counters.Set(patch::kWindowPixels, bs.flt.windowPixels);
    counters.Set(patch::kSurfacePixels, st.fixed ? bs.fixedSurfacePixels : bs.flt.surfacePixels);
    counters.Set(patch::kCycles, timing.cycles);
    counters.Set(patch::kStreamedCycles, timing.streamedCycles);
    counters.Set(patch::kEstimatedSeconds, timing.Seconds());
    counters.Set(patch::kTransistors, cost.Total());
    if (st.fixed && st.verify) counters.Set(patch::kReferenceMismatches, bs.verifyMismatch);
    if (st.fixed && st.compare) counters.Set(patch::kMaxDepthErrorLsb, bs.maxErrorLsb);
    if (st.fixed) counters.Set(patch::kDepthUlp, depthUlp);
    counters.AppendTo(stats.counters);

    std::string& r = stats.report;
    r += fmt::format("Engine patch (seed 000, quadric patch processor), mode={}\n",
                     st.fixed ? "fixed" : "float");
    r += fmt::format(
        "  patches drawn {} ({} open: opaque plane faces missing); CSG solids skipped "
        "{} (the patch processor cannot do CSG); bodies not drawable {}\n",
        patches.size(), drawnOpen, csgSkipped, notDrawable);
    for (const auto& [why, count] : rejected)
        r += fmt::format("    skipped, {}: {}\n", RejectionName(why), count);
    r += fmt::format(
        "Timing: {} patches, {} window pixels at 1 pixel/clock, pipeline latency {} cycles\n",
        timing.patches, timing.pixels, latency);
    r += fmt::format(
        "  {} cycles = {:.6f} s at {:g} MHz ({} cycles = {:.6f} s with patches "
        "streamed back to back)\n",
        timing.cycles, timing.Seconds(), st.clockHz / 1e6, timing.streamedCycles,
        timing.StreamedSeconds());
    stats.tables.push_back(ScheduleTable(st.widths));
    for (StatsTable& t : CostTables(cost)) stats.tables.push_back(std::move(t));
    if (!(st.widths == DatapathWidths{}))
        r += fmt::format("  (the paper's widths 24/16 give {} transistors)\n",
                         ComputeCost(DatapathWidths{}).Total());
    r += fixedReport;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return stats;
}

}  // namespace

std::unique_ptr<Engine> MakePatchEngine() { return std::make_unique<PatchEngine>(); }

}  // namespace quadrix
