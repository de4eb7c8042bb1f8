// The host's side of the fixed-point mode: choosing the number formats and computing the RAM
// contents (FixedPatch) of each patch, and mapping the processor's outputs back to device depth
// and world normals. Seed 000 leaves the host unspecified ("we have to study the host
// requirements"); these are Quadrix's choices, documented in docs/patch-engine.md.
//
// Depth format (one per frame, since the z-buffer compares patches): a depth word Z stands for
// the device depth origin + Z·ulp. The frame's range is the union over patches of every depth
// quantity the datapath can hold inside the window (F1, ZF, ZB, ZP, and sqrt|F2|), and it is
// mapped onto ±0.75·2^(d-2), so that every word and every difference ZP - ZF fits in d bits
// with room for the forward-differencing drift. F2 is in units of ulp², so its square root is a
// depth word.
//
// Plane preparation (per patch, before the format is chosen):
//   - a plane that keeps every root the window can have is dropped (its unit is loaded with a
//     never-cutting perpendicular plane); a plane that cuts them all makes the patch empty;
//   - a plane so steep that its cut line moves by at most 1/16 pixel across the patch's depth
//     range (|C|·Δz <= |(A, B)|/16) is loaded as perpendicular, evaluated at the middle depth:
//     the hardware has no floating point, and a nearly edge-on plane would otherwise force a
//     huge depth range on the whole frame.
//
// Quantisation: every step word is the nearest integer to the exact value in its unit (ties away
// from zero). Start words are for the first pixel centre (x0 + ½, y0 + ½) of the window, moved by
// the middle of the steps' rounding drift over the window so that the drift is centred. The normals
// use one unit per patch (directions need no common scale), chosen so that NX, NY, NZ over the
// window and depth range, and e, f, 2c in the multipliers' format, fit.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>

#include "quadrix/engines/patch/patch.h"
#include "quadrix/engines/patch/patch_polynomials.h"
#include "quadrix/engines/patch/patch_processor.h"

namespace quadrix::patch {

// What the host knows about a patch before choosing the depth format.
struct HostAnalysis {
    bool empty = false;       // no pixel of the window can show the surface
    PatchPolynomials poly;    // with the prepared planes
    Range rootDepths;         // every ZF, ZB the window can have (where F2 >= 0)
    Range depthWords;         // every depth quantity held by the datapath (F1, roots, ZP)
    double sqrtMaxAbsF2 = 0;  // sqrt of max |F2| over the window
    int planesDropped = 0;    // never cut inside the window
    int planesMadePerpendicular = 0;
};

HostAnalysis AnalyzePatch(const QuadricPatch& patch);

struct DepthFormat {
    double origin = 0;
    double ulp = 1;
    int bits = 24;
    double ToDevice(std::int64_t word) const { return origin + static_cast<double>(word) * ulp; }
};

// The format fitting all the analysed patches (ignoring empty ones). A frame with no patch gets
// the range [0, 1].
class DepthFormatBuilder {
  public:
    void Add(const HostAnalysis& analysis);
    DepthFormat Build(const DatapathWidths& widths) const;

  private:
    double lo_ = HUGE_VAL, hi_ = -HUGE_VAL, halfF2_ = 0;
};

struct HostPatch {
    FixedPatch program;
    double normalUnit = 1;  // device gradient units per normal word LSB
};

// The RAM contents; nullopt when a word does not fit its width (cannot happen with a format built
// from this patch's analysis, but a caller may pass any format).
std::optional<HostPatch> PrepareFixedPatch(const QuadricPatch& patch, const HostAnalysis& analysis,
                                           const DepthFormat& format, const DatapathWidths& widths);

// A priori bound, in depth LSBs, of |ZOUT - exact depth| at a pixel of a window of this size where
// the fixed-point and the exact algorithm pick the same sheet: the EP1 drift of F1 (its steps are
// off by at most ½ LSB each and counted i and j times; the start word centres the drift, so
// ½ + (i + j)/4), plus the square root of the EP2's drift (its six words, off by ½ LSB² each,
// counted 1, j, j(j+1)/2, i, i·j and i(i+1)/2 times; |sqrt(a + δ) - sqrt(a)| <= sqrt|δ|), plus 1
// for the square root's floor; i, j up to the window's width and height minus one.
double DepthErrorBoundLsb(const PixelWindow& window);

// Nearest integer, ties away from zero; nullopt when not finite or beyond ±2^62.
std::optional<std::int64_t> Quantize(double value);

}  // namespace quadrix::patch
