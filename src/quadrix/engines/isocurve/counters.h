// The counters of engine `isocurve`, declared once (engines/counters.h): what Elber's adaptive
// isocurves (seed 002) extracted and drew. They are reported by the isocurve engine and, with the
// `isocurve.` prefix they carry, by any render whose freeform surfaces the isocurve drawer drew.
#pragma once

#include "quadrix/engines/counters.h"

namespace quadrix::isocurve {

#define QUADRIX_ISOCURVE_COUNTERS(X)                                                               \
    X(kIsocurveSurfaces, "isocurve.surfaces", "freeform surfaces drawn")                           \
    X(kIsocurveDelta, "isocurve.delta", "world tolerance: the largest gap left")                   \
    X(kIsocurveThickness, "isocurve.thickness", "curve width (pixels)")                            \
    X(kIsocurveCurves, "isocurve.curves", "isocurves extracted")                                   \
    X(kIsocurveLength, "isocurve.length", "their total length (world units)")                      \
    X(kIsocurveCrossings, "isocurve.crossings", "parameters where the gap equals delta")           \
    X(kIsocurveUnresolved, "isocurve.unresolved", "curve pairs that could not be refined further") \
    X(kIsocurveSamples, "isocurve.samples", "curve samples rasterised")                            \
    X(kIsocurvePixelsDrawn, "isocurve.pixels_drawn", "pixel writes")                               \
    X(kIsocurvePixelsDistinct, "isocurve.pixels_distinct", "distinct pixels written")              \
    X(kIsocurvePixelsMultiple, "isocurve.pixels_multiple", "pixels written more than once")        \
    X(kIsocurveRedundancy, "isocurve.redundancy", "pixel writes per distinct pixel")               \
    X(kIsocurveExtractSeconds, "isocurve.extract_seconds", "time extracting curves")               \
    X(kIsocurveDrawSeconds, "isocurve.draw_seconds", "time drawing them")

enum IsocurveCounter : std::size_t { QUADRIX_ISOCURVE_COUNTERS(QUADRIX_COUNTER_ID) };
inline constexpr CounterDecl kIsocurveCounters[] = {
    QUADRIX_ISOCURVE_COUNTERS(QUADRIX_COUNTER_DECL)};

}  // namespace quadrix::isocurve
