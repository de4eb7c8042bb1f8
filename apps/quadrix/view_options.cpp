// The scene and view options of render and export; see SceneViewArgs in commands.h.
#include <fmt/format.h>

#include <optional>
#include <string>

#include "commands.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/pipeline/camera.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::cli {

void AddSceneViewOptions(CLI::App& cmd, SceneViewArgs& args, const std::string& verb) {
    cmd.add_option("--view", args.view, "Name of the view to use (default: the last one defined)");
    cmd.add_option("--top", args.top,
                   "Objects to draw from BRL-CAD/OpenSCAD files (repeatable or comma-separated; "
                   "default: every top-level object)")
        ->delimiter(',')
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd.add_flag(
        "--allow-missing", args.allowMissing,
        fmt::format(
            "{} an imported model without the primitives that cannot be drawn "
            "(superell, dsp, ebm, nmg, ...): a warning and a count in --stats instead of an error",
            verb));
    cmd.add_option("--camera", args.camera,
                   "Look-at camera eye_x,eye_y,eye_z,center_x,center_y,center_z in the model's "
                   "coordinates (Z-up for BRL-CAD/OpenSCAD files), as OpenSCAD");
    cmd.add_option("--projection", args.projection, "With --camera: ortho|persp (default persp)");
    cmd.add_option("--fov", args.fov, "With --camera: vertical field of view in degrees (22.5)")
        ->expected(1);
    cmd.add_flag("--viewall", args.viewAll, "Fit the window to the whole scene");
    cmd.add_flag("--autocenter", args.autoCenter, "Centre the scene in the picture");
    cmd.add_option("--az", args.az, "Azimuth in degrees (rt convention), orthographic fit")
        ->expected(1);
    cmd.add_option("--el", args.el, "Elevation in degrees (rt convention)")->expected(1);
    cmd.add_option("--viewsize", args.viewsize, "rt view size in mm (with --az/--el or --eye-pt)")
        ->expected(1);
    cmd.add_option("--eye-pt", args.eyePt, "rt eye point X Y Z in model mm")->expected(3);
    cmd.add_option("--viewrot", args.viewrot, "rt view rotation: 16 numbers, row-major")
        ->expected(16);
    cmd.add_option("--rt-view", args.rtView,
                   "File of rt view commands (viewsize; eye_pt; viewrot or orientation)");
}

namespace {

// The camera options → CameraRequest; an error message or empty.
std::string CameraOptions(const SceneViewArgs& args, CameraRequest& camera) {
    if (!args.camera.empty())
        if (auto e = ParseCamera(args.camera, camera); !e.empty()) return e;
    if (!args.projection.empty()) {
        if (args.camera.empty()) return "--projection needs --camera";
        if (auto e = ParseProjection(args.projection, camera); !e.empty()) return e;
    }
    if (!args.fov.empty()) camera.fovDegrees = args.fov[0];
    camera.viewAll = args.viewAll;
    camera.autoCenter = args.autoCenter;
    return {};
}

// The rt-style view options → PipelineOptions; returns an error message or empty.
std::string RtViewOptions(const SceneViewArgs& args, PipelineOptions& po, Diagnostics& diags) {
    if (!args.az.empty()) po.azimuth = args.az[0];
    if (!args.el.empty()) po.elevation = args.el[0];
    if (!args.viewsize.empty()) {
        if (!(args.viewsize[0] > 0)) return "--viewsize must be positive";
        po.viewsize = args.viewsize[0];
    }
    bool explicitView = !args.eyePt.empty() || !args.viewrot.empty();
    if (explicitView) {
        if (args.eyePt.size() != 3 || args.viewrot.size() != 16 || !po.viewsize)
            return "an explicit rt view needs --viewsize, --eye-pt (3 numbers) and --viewrot (16)";
        import::RtView rt;
        rt.viewsize = *po.viewsize;
        rt.eye = {args.eyePt[0], args.eyePt[1], args.eyePt[2]};
        for (int k = 0; k < 16; ++k) rt.viewrot.m[k / 4][k % 4] = args.viewrot[k];
        po.rtView = rt;
    }
    if (!args.rtView.empty()) {
        std::string text;
        if (auto why = ReadBoundedFile(args.rtView, text); !why.empty())
            return fmt::format("--rt-view: cannot read '{}': {}", args.rtView, why);
        auto rt = import::ParseRtViewScript(text, args.rtView, diags);
        if (!rt) return "--rt-view: the view file has errors";
        if (rt->Fitted()) {  // rt's `ae`: the same view as --az/--el (import/rt_view.h)
            if (po.azimuth || po.elevation)
                return "--az/--el cannot be combined with an rt view script's 'ae'";
            po.azimuth = rt->aeAzimuth;
            po.elevation = rt->aeElevation;
            if (rt->viewsize > 0) po.viewsize = rt->viewsize;
        } else {
            po.rtView = *rt;
        }
    }
    if ((po.rtView || po.azimuth || po.elevation) && !args.view.empty())
        return "--view cannot be combined with --az/--el or an rt view";
    return {};
}

}  // namespace

std::string SceneViewOptions(const SceneViewArgs& args, PipelineOptions& po, CameraRequest& camera,
                             Diagnostics& diags) {
    po.viewName = args.view;
    po.topObjects = args.top;
    po.allowMissing = args.allowMissing;
    if (auto e = RtViewOptions(args, po, diags); !e.empty()) return e;
    if (auto e = CameraOptions(args, camera); !e.empty()) return e;
    if (camera.Any() && (po.rtView || po.azimuth || po.elevation))
        return "the camera options cannot be combined with --az/--el or an rt view";
    return {};
}

bool ApplyCamera(RenderContext& ctx, CameraRequest camera, ViewRequest& view, Diagnostics& diags) {
    camera.zUp = !ctx.Inputs().imports.empty();
    const std::optional<scene::View> own = ctx.Scene().ViewToUse(view.viewName);
    if (!own) return true;  // Flatten reports the unknown view
    std::string error;
    std::optional<scene::View> v = CameraView(camera, *own, error);
    if (!v) {
        diags.Error({}, error, {}, "command line");
        return false;
    }
    if (camera.autoCenter) {
        ViewRequest fit = view;
        fit.view = *v;
        fit.view->whh = fit.view->whw = std::nullopt;
        if (!ctx.Flatten(fit, diags)) return false;
        v = CentreOnScene(*v, ctx.Flat());
    }
    view.view = v;
    view.viewName.clear();
    return true;
}

}  // namespace quadrix::cli
