// True Phong post-shading of a Frame (seed 000 §1.3 and §1.6: "Shading (true Phong shading can be
// used [9]) and Z-buffer operations are post-processed", "used with a post shading unit"). The
// patch processor outputs a normal per pixel, so the shading unit evaluates the Phong reflection
// model per pixel from that normal, with no interpolation: with the Frame's world-space unit
// normal n, the unit vector v toward the viewer and, per parallel light, the unit vector l toward
// it and the mirror direction r = 2(n·l)n - l,
//   I = min(1, Σ ambient + Σ_parallel intensity·(kd·max(0, n·l) + ks·max(0, r·v)^shininess))
// and the pixel is I·color for diffuse reflection plus the white highlight (kd = 1, ks = 0 is the
// Lambert shader of shade/shader.h). For a parallel projection v is Projection::towardViewer;
// for a perspective one, the direction from the pixel's world point to the eye.
//
// This is a post-process over any engine's Frame (the patch engine's fixed-point mode fills the
// Frame's normals from the emulated 16-bit normals), not part of an engine.
#pragma once

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

namespace quadrix::patch {

struct PhongOptions {
    double diffuse = 0.8;   // kd
    double specular = 0.4;  // ks
    double shininess = 24;  // Phong exponent
    scene::Color background{0, 0, 0};
};

// Diffuse and specular terms for one pixel, before color: {diffuse sum incl. ambient, specular}.
struct PhongTerms {
    double diffuse = 0;
    double specular = 0;
};
PhongTerms PhongAt(const FlatScene& scene, const Vec3& normal, const Vec3& towardViewer,
                   const PhongOptions& options);

// Unit vector from the world point seen at device point (x, y, z) toward the viewer.
Vec3 TowardViewer(const FlatScene& scene, const Vec3& devicePoint);

// An RGB image of the Frame.
Image PhongShade(const Frame& frame, const FlatScene& scene, const PhongOptions& options = {});

}  // namespace quadrix::patch
