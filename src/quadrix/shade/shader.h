// The shader: a Frame (per pixel normal, depth and ids) and the flat scene's lights and
// materials become an Image in linear light. One entry point, Shade(), used by every front end.
//
// Models (ShadeOptions::model; the reflection formulas are in phong.h):
//   kLambert    seed 001 §6.1: i = min(1, Σ ambient + Σ intensity·kd·max(0, n·l))·color; a
//               surface whose finish declares a specular coefficient adds its highlight
//               (Blinn–Phong). With the defaults (kd 1, ks 0) and white lights this is
//               bit-for-bit the historical shader, which the paper defines with one parallel
//               light (the last); Quadrix sums every light, which is the same when there is one.
//   kFast       the -f option (§2.1.5): every (surface, body) pair gets one constant intensity,
//               computed from the mean of its visible normals: the flat look used for debugging.
//   kPhong      seed 000's post-shading unit: diffuse plus a Phong highlight (defaults kd .8,
//   kBlinnPhong ks .4, shininess 24 for surfaces whose finish does not say); Blinn–Phong uses
//               the half vector.
// Lights: ambient, parallel, point and spot (lighting.h); the scene's, or the default rig when it
// declares none (scene/light_rig.h). Materials: the body's color and finish
// (scene::Finish, resolved by the Flattener); unset finish properties take the model's defaults.
//
// Transparency (=alpha a, a < 1) is limited to what ONE Frame holds: the first surface along each
// ray. The pixel is a · shaded + (1 - a) · background, so a transparent solid shows the
// background through it but not the solids behind it (those are not in the Frame); the CAD
// "glass" look with hidden parts showing needs the engines to keep more than the first hit.
//
// Background: ShadeOptions::background when given, else the scene's `background` statement (a
// color or a vertical gradient, FlatScene::background/backgroundBottom), else black.
//
// Output: 8-bit gray when every color involved is gray, else RGB; Image::linear carries the
// unquantised values for the writers' sRGB encoding (io/writers.h).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/shade/phong.h"
#include "quadrix/shade/shadows.h"

namespace quadrix {

enum class ShadingModel { kLambert, kFast, kPhong, kBlinnPhong };

struct ShadeOptions {
    ShadingModel model = ShadingModel::kLambert;
    // The front ends' historical spelling of model = kFast (UniQuadrix's -f); either selects it.
    bool fast = false;
    std::optional<scene::Color> background;  // overrides the scene's background
    bool forceColor = false;                 // RGB output even when every solid is white
    // Shadows from every parallel, point and spot light by shadow rays through the CSG
    // (shadows.h), under parallel and perspective views. Off by default here (quadrix render
    // turns it on for scenes that declare lights).
    bool shadows = false;
    // The box trees of the shadow and sample rays (math/box_tree.h); false only to measure
    // their gain (bench/): the picture is the same.
    bool spatialIndex = true;
    // Finish defaults of kPhong and kBlinnPhong (seed 000's post-shading unit).
    double phongDiffuse = 0.8, phongSpecular = 0.4, phongShininess = 24;
    // Anti-aliasing (antialias.h), applied by RenderContext::Shade after Shade(): samples per
    // edge pixel (0 or 1 = off; 4, 16, 64), and the reconstruction filter.
    int aaSamples = 0;
    bool aaMitchell = false;  // false: box filter over the pixel; true: Mitchell–Netravali
    // A small job run inline (RenderContext: the threads were not given and the job is small)
    // may anti-alias on two threads, the second a plain std::thread (util/parallel.h
    // OnTwoThreads), when the process may run on two processors. The picture is the same.
    bool aaHelperThread = false;
    // Silhouette and crease lines from the Frame (antialias.h DrawEdgeLines), over the shading.
    bool edges = false;
    scene::Color edgeColor{0, 0, 0};
    // Hatch lines on the section plane's cut faces (section_hatch.h), applied by
    // RenderContext::Shade after the anti-aliasing and before the edge lines: their target
    // spacing in pixels (the world spacing is a power of two near it) and their colour.
    bool hatch = false;
    double hatchSpacing = 8;
    scene::Color hatchColor{0, 0, 0};
    // Fill Image::linear (the unquantised values). Only 16-bit PNG output and the precise 8-bit
    // encoding read it; a front end that writes 8-bit files may turn it off (11 MB less to write
    // at 1280×720).
    bool linear = true;
};

// The shading of one visible point, as Shade() computes it for a pixel centre: used by Shade()
// for every pixel and by the anti-aliasing pass for sub-pixel samples. (x, y) is the device
// position (a pixel centre is (i + ½, j + ½)), the rest what a Frame pixel holds. Built once
// per frame (the fast model's mean normals are taken from `frame`); At() is thread-safe.
class PixelShader {
  public:
    // `wide`: the flat scene's wide-node trees for the shadow rays, made once for every pass
    // over one flat scene (the render context keeps them); null: made here when needed.
    PixelShader(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                std::shared_ptr<const WideNodeTrees> wide = nullptr);
    // What At() looks up per (surface, body) — finish, reflectance, colour — kept between calls
    // by a caller that shades runs of pixels (a row mostly repeats its neighbour's surface). One
    // per thread.
    struct MaterialCache {
        std::int32_t surface = Frame::kNone - 1, body = Frame::kNone - 1;
        scene::Finish finish;
        Reflectance reflectance;
        scene::Color base;
    };
    // The reach of each light's shadow rays from a run of pixels (ShadowTester::MayMeet), made by
    // Reach for the pixels x0 .. x1 − 1 of row y and passed to At and ShadowMask for them: the
    // same answers, fewer boxes tested (shadows.h). Lights without one ray for every pixel (point
    // and spot lights, perspective) keep kReachAll.
    struct ShadowReach {
        std::vector<std::uint64_t> light;
    };
    void Reach(const Frame& frame, int y, int x0, int x1, ShadowReach& reach) const;
    // The same for rays that start anywhere in the device box [lo, hi] (the anti-aliasing pass:
    // the visible points of a square's samples). An empty box (lo > hi) leaves kReachAll.
    void ReachOfBox(const Vec3& lo, const Vec3& hi, ShadowReach& reach) const;
    // Pixels per run of Reach in the shading loops. 16, 64 and 128 shaded the machined part at
    // 1280 × 720 on one thread within the noise (±1 ms of about 25 ms) of 32.
    static constexpr int kReachRun = 32;
    scene::Color At(double x, double y, std::int32_t surface, std::int32_t body, double depth,
                    const Vec3& normal, const scene::Color& background,
                    MaterialCache* cache = nullptr, const ShadowReach* reach = nullptr) const;
    // Whether a pixel's colour depends only on its (surface, body), its normal, the background
    // and, with shadows, which lights are blocked there: no world point (point or spot lights,
    // highlights or shadows under perspective), not the fast model, and with shadows only
    // ambient and parallel lights (at most 64). ShadeRowKinds then repeats the previous pixel's
    // bytes where all of those repeat (asking ShadowMask per pixel with shadows).
    bool LocalShading() const { return localShading_; }
    // Bit k: light k is blocked at the pixel, asked only for the lights At asks (those whose
    // light reaches the surface's side, n·l > 0). Only with shadows and LocalShading().
    std::uint64_t ShadowMask(double x, double y, std::int32_t surface, std::int32_t body,
                             double depth, const Vec3& normal,
                             const ShadowReach* reach = nullptr) const;
    // At, with the lights' shadow answers of ShadowMask instead of asking them.
    scene::Color AtWithMask(std::int32_t surface, std::int32_t body, const Vec3& normal,
                            std::uint64_t mask, const scene::Color& background,
                            MaterialCache* cache) const;
    // The background of row y of `height` (a vertical gradient, or one color).
    scene::Color Background(int y, int height) const;
    // Whether the image is RGB (some color involved) rather than gray.
    bool Color() const { return color_; }

  private:
    // At's colour once the normal and the shadow test are known.
    scene::Color Lit(std::int32_t surface, std::int32_t body, const Vec3& n, const Vec3& point,
                     const scene::Color& background, MaterialCache* cache,
                     const ShadowTest& inShadow) const;
    // The shadow origin of a pixel on (surface, body): shadows.h.
    ShadowOrigin OriginOf(std::int32_t surface, std::int32_t body) const;

    const FlatScene& scene_;
    ShadeOptions options_;
    ShadingModel model_, reflection_;
    ViewerGeometry viewer_;
    bool needPoint_, shadows_;
    std::optional<ShadowTester> shadowTester_;  // with shadows only
    Mat4 deviceFromWorld_;
    bool color_;
    std::vector<Incident> fixedLight_;
    // The shadow ray of each parallel light under a parallel view (an affine device map): the
    // same device ray at every pixel (DeviceShadowRay), made once. Empty optional otherwise.
    std::vector<std::optional<DeviceRay>> fixedRay_;
    std::map<std::pair<int, int>, Vec3> meanNormal_;
    bool localShading_ = false;
};

// Writes a linear color into pixel (x, y) of an image: its bytes (value·255, rounded) and its
// unquantised `linear` entry, RGB or gray by image.channels.
void StorePixel(Image& image, int x, int y, const scene::Color& c);
// The same, but the unquantised entry only when the image has Image::linear (it is not made):
// the passes over a shaded image (anti-aliasing, edge lines) for an 8-bit output, which reads
// only the bytes.
void StoreColor(Image& image, int x, int y, const scene::Color& c);

Image Shade(const Frame& frame, const FlatScene& scene, const ShadeOptions& options = {},
            std::shared_ptr<const WideNodeTrees> wide = nullptr);

// Intensity of a surface with world normal n under the scene's ambient and parallel lights
// (Lambert, before color, in [0,1]; point and spot lights, which need the surface point, are
// not counted). Used by the engines' shading comparisons.
double LambertIntensity(const FlatScene& scene, const Vec3& n);

}  // namespace quadrix
