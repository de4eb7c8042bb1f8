#include "quadrix/engines/pixelpowers/pixelpowers_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "quadrix/engines/pixelpowers/compiler.h"
#include "quadrix/engines/pixelpowers/counters.h"
#include "quadrix/engines/pixelpowers/machine.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/frame/compare.h"
#include "quadrix/shade/shader.h"

namespace quadrix {
namespace pixelpowers {
namespace {

// Seed 004 Table 1: 1854 equations in 7.5 ms, 170 in .68 ms, 46 in .19 ms — about 4.05 µs per
// equation (a 30-bit bit-serial QEE evaluation at 10 MHz, seed 004 §I "under 4 microseconds").
constexpr double kMicrosecondsPerEquation = 7500.0 / 1854.0;

// Per-pixel memory (bits). The paper's machine: F1–F3, ZTEMP and ZMIN of 30 bits, COLOR 24 (seed
// 004 §II) = 87 of 128. This simulation keeps depths as doubles (64 bits each, needed for exact
// agreement with raycast) and COLOR as a 32-bit patch id resolved at scan-out.
constexpr int kPaperBits = 3 + 30 + 30 + 24;
constexpr int kSimulatedBits = 3 + 64 + 64 + 32;

struct Settings {
    CompileOptions compile;
    bool compare = false;
};

// Bits of the N0–N2 registers of paper shading in this simulation (three doubles).
constexpr int kNormalBits = 3 * 64;

const OptionSchema& PixelPowersSchema() {
    using O = OptionSpec;
    static const OptionSchema kSchema{
        O::Choice("mode", "exact", {"exact", "approx"},
                  "exact: the extended machine with a per-pixel square root; approx: the "
                  "paper's machine, depths from parabolic-strip envelopes"),
        O::Number("tolerance", "0.25", 0, HUGE_VAL, true,
                  "approx: depth tolerance of a strip envelope, device z units"),
        O::Choice("shading", "", {"exact", "paper"},
                  "exact normals at ZMIN, or the paper's approximate shading (default: paper "
                  "in approx mode, else exact)"),
        O::Int("depth-bits", "", 8, 52,
               "fixed-point ZTEMP/ZMIN words of N bits (default: doubles)"),
        O::Int("max-products", "20000", 1, 10000000,
               "normal-form explosion guard per solid (a solid past it goes to raycast)"),
        O::Int("max-instructions", "1000000", 1, 100000000,
               "program size guard per scene (a solid past it goes to raycast)"),
        O::Int("max-literals", "1024", 1, 100000000,
               "literals per product guard (paring ~literals^2; a solid past it goes to raycast)"),
        O::Int("max-strips", "64", 1, 4096, "approx: strips per sheet at most"),
        O::Bool("compare", "",
                "also render with raycast and report agreement and depth error (default: on in "
                "approx mode, off in exact mode)"),
    };
    return kSchema;
}

Settings ReadSettings(const EngineOptions& o) {
    Settings st;
    st.compile.mode = o.Choice("mode") == "approx" ? DepthMode::kApprox : DepthMode::kExact;
    st.compile.tolerance = o.Number("tolerance");
    st.compile.maxProducts = static_cast<std::size_t>(o.Int("max-products"));
    st.compile.maxInstructions = static_cast<std::size_t>(o.Int("max-instructions"));
    st.compile.maxLiterals = static_cast<std::size_t>(o.Int("max-literals"));
    st.compile.maxStrips = o.Int("max-strips");
    if (o.Given("depth-bits")) st.compile.depthBits = o.Int("depth-bits");
    const bool approx = st.compile.mode == DepthMode::kApprox;
    st.compile.paperShading = o.Given("shading") ? o.Choice("shading") == "paper" : approx;
    st.compare = o.Given("compare") ? o.Bool("compare") : approx;
    return st;
}

// Seed 004 Table 1 with this scene's row first, then the paper's rows.
StatsTable Table1(const CompileStats& cs, const Program& program, const std::string& name) {
    using C = StatsCell;
    StatsTable t;
    t.title = "Pixel-Powers estimate (layout of seed 004 Table 1; 10 MHz, ~4.05 us per equation)";
    t.columns = {"Part Name", "Source", "Primitives", "Opcodes", "Equations", "Time"};
    double ms = static_cast<double>(program.Equations()) * kMicrosecondsPerEquation / 1000.0;
    t.rows.push_back({C::Text(name.empty() ? std::string("this scene") : name), C::Text("quadrix"),
                      C::Integer(cs.primitives), C::Integer(program.Opcodes()),
                      C::Integer(program.Equations()), C::Real(ms, 2, "msec")});
    struct Row {
        const char* name;
        const char* source;
        int primitives, opcodes, equations;
        double ms;
    };
    static const Row rows[] = {{"Union", "local", 2, 54, 46, .19},
                               {"Difference", "local", 2, 182, 170, .68},
                               {"Intersection", "local", 2, 178, 170, .68},
                               {"Tube", "Okino 84", 11, 1205, 1065, 4.3},
                               {"Cut Tube", "Okino 84", 12, 1969, 1733, 7.0},
                               {"MBB", "Okino 84", 24, 2139, 1854, 7.5},
                               {"Tie Rod", "BRL", 17, 2660, 2309, 9.3}};
    for (const Row& r : rows)
        t.rows.push_back({C::Text(r.name), C::Text(r.source), C::Integer(r.primitives),
                          C::Integer(r.opcodes), C::Integer(r.equations),
                          C::Real(r.ms, 2, "msec")});
    t.notes = {"first row: this scene (our primitives: bodies); the others: the paper's figures"};
    return t;
}

class PixelPowersEngine final : public Engine {
  public:
    std::string_view Name() const override { return "pixelpowers"; }

    const OptionSchema& Schema() const override { return PixelPowersSchema(); }

  protected:
    RenderStats Draw(const FlatScene& scene, const EngineOptions& options, Frame& frame) override {
        auto start = std::chrono::steady_clock::now();
        RenderStats stats;
        const Settings st = ReadSettings(options);
        Program program;
        CompileStats cs;
        auto t0 = std::chrono::steady_clock::now();
        Compile(scene, st.compile, program, cs);
        auto t1 = std::chrono::steady_clock::now();
        MachineCounters mc = Execute(program, scene, frame);
        auto t2 = std::chrono::steady_clock::now();
        stats.seconds = std::chrono::duration<double>(t2 - start).count();

        CounterValues counters(kPixelPowersCounters);
        const csg::NormalFormStats& nf = cs.normalForm;
        counters.Set(kExactMode, st.compile.mode == DepthMode::kExact ? 1 : 0);
        counters.Set(kPaperShading, st.compile.paperShading ? 1 : 0);
        counters.Set(kPrimitives, cs.primitives);
        counters.Set(kHalfSpaces, cs.halfSpaces);
        counters.Set(kTreePrimitives, nf.treePrimitives);
        counters.Set(kTreeOperators, nf.treeOperators);
        counters.Set(kProducts, nf.products);
        counters.Set(kProductFactors, nf.factors);
        counters.Set(kPrunedProducts, nf.prunedProducts);
        counters.Set(kPrunedFactors, nf.prunedFactors + nf.prunedSubtrahends);
        counters.Set(kTerms, cs.terms);
        counters.Set(kPrunedTerms, cs.prunedTerms);
        counters.Set(kPrunedParings, cs.prunedParings);
        counters.Set(kPatches, cs.patches);
        counters.Set(kPrunedPatches, cs.prunedPatches);
        counters.Set(kOpcodes, program.Opcodes());
        counters.Set(kEquations, program.Equations());
        counters.Set(kEstimatedMs10mhz,
                     static_cast<double>(program.Equations()) * kMicrosecondsPerEquation / 1000.0);
        if (st.compile.mode == DepthMode::kApprox) {
            counters.Set(kStrips, cs.strips);
            counters.Set(kStripSheetsCapped, cs.stripsCapped);
            counters.Set(kExtendedFallbacks, cs.extendedFallbacks);
        }
        if (st.compile.paperShading) {
            counters.Set(kShadedPatches, cs.shadedPatches);
            counters.Set(kShadingFallbacks, cs.shadingFallbacks);
            counters.Set(kShadingSqrtBound, cs.shadingSqrtBound);
            counters.Set(kShadingDenominatorSpread, cs.shadingDenominatorSpread);
        }
        if (program.depthStep > 0) {
            counters.Set(kDepthBits, static_cast<std::uint64_t>(program.depthBits));
            counters.Set(kDepthStep, program.depthStep);
            counters.Set(kDepthOrigin, program.depthOrigin);
        }
        counters.Set(kTiles, mc.tiles);
        counters.Set(kBlockRuns, mc.blockRuns);
        counters.Set(kBlocksAbandoned, mc.blocksAbandoned);
        counters.Set(kInstructionsExecuted, mc.instructions);
        counters.Set(kPixelOperations, mc.pixelOps);
        counters.Set(kRootSolves, mc.rootSolves);
        counters.Set(kZWrites, mc.writes);
        counters.Set(kCoveredPixels, frame.CoveredCount());
        counters.Set(kBitsPerPixelPaper, kPaperBits);
        counters.Set(kBitsPerPixelSimulated,
                     static_cast<std::uint64_t>(kSimulatedBits +
                                                (st.compile.paperShading ? kNormalBits : 0)));
        counters.Set(kCompileSeconds, std::chrono::duration<double>(t1 - t0).count());
        counters.Set(kMachineSeconds, std::chrono::duration<double>(t2 - t1).count());
        counters.Set(kSolidsNotDrawn, cs.errors.size());

        // Table 1 names a part; ours is the solid's name, or the number of solids.
        std::string part = scene.solids.size() == 1
                               ? scene.solids[0].name
                               : std::to_string(scene.solids.size()) + " solids";
        stats.tables.push_back(Table1(cs, program, part));
        std::string report;
        char line[256];
        std::snprintf(line, sizeof line,
                      "normal form: %zu products, %zu factors (tree: %zu primitives, %zu "
                      "operators); display terms %zu, patches %zu\n",
                      nf.products, nf.factors, nf.treePrimitives, nf.treeOperators, cs.terms,
                      cs.patches);
        report += line;
        std::snprintf(line, sizeof line,
                      "per-pixel memory: paper %d of 128 bits (F1-F3, ZTEMP 30, ZMIN 30, COLOR 24);"
                      " simulated %d bits (F1-F3, ZTEMP 64, ZMIN 64, patch id 32)\n",
                      kPaperBits, kSimulatedBits);
        report += line;
        if (st.compile.paperShading) {
            std::snprintf(line, sizeof line,
                          "shading: the paper's (seed 004 III step 4): %zu patches broadcast their "
                          "approximate normal (3 equations each), %zu exact fallbacks; host "
                          "bounds in n.l: sqrt approximation %.4g, constant denominator %.4g\n",
                          cs.shadedPatches, cs.shadingFallbacks, cs.shadingSqrtBound,
                          cs.shadingDenominatorSpread);
            report += line;
        }
        if (program.depthStep > 0) {
            std::snprintf(line, sizeof line,
                          "depth words: %d-bit fixed point, step %.4g device z from %.6g\n",
                          program.depthBits, program.depthStep, program.depthOrigin);
            report += line;
        }
        // Every solid not drawn, and every accuracy guard that fired, also as a warning the CLI
        // prints without --stats.
        for (std::size_t k = 0; k < cs.errors.size(); ++k) {
            report += "not drawn (left to raycast): " + cs.errors[k] + "\n";
            stats.undrawn.push_back({cs.undrawnSolids[k], cs.errors[k]});
        }
        for (const std::string& w : cs.warnings) {
            report += "warning: " + w + "\n";
            stats.warnings.push_back(w);
        }

        if (st.compare) {
            Frame ref;
            auto reference = MakeRaycastEngine();
            reference->Render(scene, RenderOptions{}, ref);
            // Fixed-point words add up to half a step to every depth (rounding is monotone).
            const double tolerance = st.compile.mode == DepthMode::kApprox
                                         ? st.compile.tolerance + 0.5 * program.depthStep
                                         : 0.5 * program.depthStep;
            // Shading: the shader's Lambert intensity before color, in [0, 1] (×255 for 8-bit
            // gray levels). The depth tolerance is widened by 1e-9 of itself (its rounding).
            CompareOptions co;
            co.depthTolerance = tolerance * (1 + 1e-9);
            co.intensity = [&scene](const Vec3& n) { return LambertIntensity(scene, n); };
            const FrameComparison a = quadrix::CompareFrames(frame, ref, co);
            std::uint64_t union_ = a.coveredBoth + a.onlyA + a.onlyReference;
            double same = a.coveredBoth ? static_cast<double>(a.sameSolid) / a.coveredBoth : 1.0;
            const double mean = a.meanDepthError, meanI = a.meanIntensityError;
            counters.Set(kCmpCoveredBoth, a.coveredBoth);
            counters.Set(kCmpCoveredOnlyHere, a.onlyA);
            counters.Set(kCmpCoveredOnlyRaycast, a.onlyReference);
            counters.Set(kCmpSameSolidShare, same);
            counters.Set(kCmpDepthErrorMax, a.maxDepthError);
            counters.Set(kCmpDepthErrorMean, mean);
            counters.Set(kCmpDepthErrorP999, a.p999DepthError);
            counters.Set(kCmpDepthErrorOverTolerance, a.depthOverTolerance);
            counters.Set(kCmpIntensityErrorMax, a.maxIntensityError);
            counters.Set(kCmpIntensityErrorMean, meanI);
            counters.Set(kCmpIntensityErrorP99, a.p99IntensityError);
            std::snprintf(
                line, sizeof line,
                "vs raycast: %llu covered pixels, %.4f%% same solid, coverage differs on "
                "%llu; depth error (same surface) max %.4g p99.9 %.4g mean %.4g device z, "
                "%llu pixels over the tolerance %.4g\n",
                static_cast<unsigned long long>(union_), 100.0 * same,
                static_cast<unsigned long long>(a.onlyA + a.onlyReference), a.maxDepthError,
                a.p999DepthError, mean, static_cast<unsigned long long>(a.depthOverTolerance),
                tolerance);
            report += line;
            std::snprintf(line, sizeof line,
                          "vs raycast shading (%s): Lambert intensity error (same surface) max "
                          "%.4f p99 %.4f mean %.4f (x255: %.1f / %.1f / %.2f gray levels)\n",
                          st.compile.paperShading ? "paper" : "exact normals", a.maxIntensityError,
                          a.p99IntensityError, meanI, 255 * a.maxIntensityError,
                          255 * a.p99IntensityError, 255 * meanI);
            report += line;
        }
        counters.AppendTo(stats.counters);
        stats.report = report;
        return stats;
    }
};

}  // namespace
}  // namespace pixelpowers

std::unique_ptr<Engine> MakePixelPowersEngine() {
    return std::make_unique<pixelpowers::PixelPowersEngine>();
}

}  // namespace quadrix
