// The one comparison of two Frames (DESIGN.md "The Frame"): how far a Frame `a` is from a
// reference Frame (usually raycast's) of the same size. Used by the tests of every engine, by
// `quadrix compare`, and by engines that compare themselves with raycast (--engine-opt compare).
//
// Per pixel: coverage (covered in both / only in a / only in the reference), same surface id,
// same solid id; for same-surface pixels the depth error |za − zr| (device z) and the angle
// between the normals (degrees). A difference in coverage or surface id is "off edge" when the
// reference's 3×3 neighbourhood of the pixel shows one surface only: there no rounding can decide
// either way, so an exact engine must agree. The diff image colours each pixel by its class.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

namespace quadrix {

struct FrameComparison {
    int width = 0, height = 0;
    bool sizeMismatch = false;
    std::uint64_t coveredBoth = 0, onlyA = 0, onlyReference = 0;
    std::uint64_t sameSurface = 0, sameSolid = 0;
    std::uint64_t surfaceDiffers = 0;              // covered in both, different surface id
    std::uint64_t sameSurfaceOtherBody = 0;        // same surface id, different body id
    std::uint64_t offEdgeDifferences = 0;          // coverage or surface differs away from any edge
    std::uint64_t offEdgeCoverageDifferences = 0;  // of those, covered in one frame only
    std::uint64_t depthOverTolerance =
        0;  // same surface, |Δz| above CompareOptions::depthTolerance
    double maxDepthError = 0, meanDepthError = 0, p999DepthError = 0;
    double maxNormalErrorDegrees = 0;
    // Largest minus smallest depth over the reference's covered pixels (0 when fewer than two):
    // the scale of depth tolerances relative to the scene.
    double referenceDepthRange = 0;
    // Shading error on same-surface pixels, when CompareOptions::intensity is given:
    // |intensity(normal in A) − intensity(normal in the reference)|.
    double maxIntensityError = 0, meanIntensityError = 0, p99IntensityError = 0;
    std::string firstDifference;  // the first off-edge difference, described

    // Share of pixels covered in both that show the same surface (1 when none are).
    double SameSurfaceShare() const;
    // Pixels whose surface id differs, coverage included (onlyA + onlyReference + surfaceDiffers).
    std::uint64_t SurfaceMismatches() const { return onlyA + onlyReference + surfaceDiffers; }
    // A few lines for people.
    std::string Summary() const;
};

struct CompareOptions {
    double depthTolerance = 1e-6;  // device z units, for depthOverTolerance
    // A shader's intensity of a normal (e.g. Lambert under the scene's lights, in [0, 1]); when
    // set, the comparison also reports the intensity error.
    std::function<double(const Vec3& normal)> intensity;
};

FrameComparison CompareFrames(const Frame& a, const Frame& reference,
                              const CompareOptions& options = {});

// Empty when the two Frames are identical bit for bit (depth, normal and ids of every pixel;
// NaN-free frames), else the first difference, described. The test of "bit-identical" refactors
// and of fast paths against their reference.
std::string FirstBitDifference(const Frame& a, const Frame& b);

// A picture of the comparison: black = background in both, gray = same surface (brighter where
// the depth error is larger), yellow = different surface, red = only in a, blue = only in the
// reference; off-edge differences are drawn at full brightness, edge ones dimmed.
Image FrameDiffImage(const Frame& a, const Frame& reference, const CompareOptions& options = {});

}  // namespace quadrix
