// Views like rt (FORMAT.md §9.4): MakeAzElView and MakeRtView build orthographic scene::Views in
// Quadrix space from rt's parameters, which are given in the model's own coordinates
// (model_space.h maps them). Also rt's view scripts and its default lights.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "quadrix/math/mat4.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

// rt's explicit orthographic view (FORMAT.md §9.4), in MODEL coordinates: rows 0-2 of `viewrot`
// are the view's X (right), Y (up) and Z (toward the viewer) axes; the image spans `viewsize`
// across its width; pixel (i, j from the bottom) samples eye + (-vs/2 + i·cell) X +
// (-vs/2 + j·cell) Y, cell = viewsize/width, along -Z. Nothing behind the eye plane is drawn.
struct RtView {
    double viewsize = 0;
    Vec3 eye;
    Mat4 viewrot = Mat4::Identity();
    // A script whose view is rt's `ae AZ EL` (azimuth, elevation in degrees) with no eye_pt,
    // viewrot or orientation after it: rt fits that view to the model (centred on its box,
    // viewsize = the box's diagonal unless the script's `viewsize` gives it), which needs the
    // model, so the view is not made here. The caller turns it into the --az/--el request
    // (azimuth, elevation and, when viewsize > 0, the viewsize): the same view as --az/--el.
    std::optional<double> aeAzimuth, aeElevation;
    bool Fitted() const { return aeAzimuth.has_value(); }
};

// The view (id "rt") reproducing rt's frame pixel for pixel on a width×height image.
scene::View MakeRtView(const RtView& rt, int width, int height);

// rt's azimuth/elevation (degrees) in model coordinates: the viewer sits along
// (cos el cos az, cos el sin az, sin el), model Z projects to screen up. When `modelBox` (Quadrix
// space) is finite the view is fitted like rt: centred on the box, viewsize = its diagonal (or
// `viewsize` when given); otherwise the Flattener's auto-fit frames the scene.
RtView AzElRtView(double azimuth, double elevation, const Box3& modelBox,
                  std::optional<double> viewsize);
scene::View MakeAzElView(double azimuth, double elevation, const Box3& modelBox,
                         std::optional<double> viewsize, int width, int height);

// Reads rt's view commands (`viewsize s;` `eye_pt x y z;` `viewrot m0 .. m15;`
// `orientation x y z w;` `ae az el;`) from text, as rt reads them on standard input. `ae` sets
// the rotation as rt's do_ae does (the --az/--el rotation: the viewer along (cos el cos az,
// cos el sin az, sin el), model Z up); an `eye_pt` after it keeps that rotation with the given
// eye (then `viewsize` is needed), otherwise the view is fitted to the model (RtView::Fitted).
// A `viewrot`/`orientation` after `ae` replaces its rotation. rt's `ae` takes two numbers (MGED's
// third, a twist, is refused with a message). Errors name file:line:column.
std::optional<RtView> ParseRtViewScript(std::string_view text, const std::string& file,
                                        Diagnostics& diags);

// Lights for a view made from rt parameters when the scene has none: rt's 40 % ambient plus a
// light at the eye (FORMAT.md §9.2-9.4).
void AddRtLights(scene::Scene& scene, const scene::View& view);

}  // namespace quadrix::import
