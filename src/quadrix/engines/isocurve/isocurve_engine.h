// Engine `isocurve` (DESIGN.md): quadric solids by an inner engine, freeform surfaces by adaptive
// isocurves drawn over them into the same Frame.
//
// The surfaces drawn are the FlatScene's freeforms (from the scene language and the freeform
// file formats), then any surfaces handed to the constructor (tests). Frame ids written for
// FlatScene freeform k: surface = scene.halfSpaces.size() + k (past every half-space id), body =
// solid = Frame::kNone (FlatScene::SurfaceColor gives the color); constructor surface k follows
// them, with body = bodyIds[k] when given.
#pragma once

#include <memory>
#include <vector>

#include "quadrix/engines/engine.h"
#include "quadrix/engines/isocurve/render.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

// The FlatScene's freeform surfaces with their Frame ids (see above).
std::vector<FreeformDrawable> SceneDrawables(const FlatScene& scene);

class IsocurveEngine : public Engine {
  public:
    // `quadrics` renders the FlatScene's solids first (nullptr: the Frame starts empty).
    IsocurveEngine(std::unique_ptr<Engine> quadrics, std::vector<freeform::Surface> surfaces,
                   std::vector<std::int32_t> bodyIds = {});

    std::string_view Name() const override { return "isocurve"; }
    // Accepts the isocurve options (render.h ParseIsocurveOptions); none go to the inner engine.
    std::string ValidateOptions(const RenderOptions& options) const override;
    // Resets `frame` to the scene size, renders the quadrics, then the freeform surfaces; --stats
    // gets the isocurve statistics and, with compare=1, the comparison table of item 5.
    RenderStats Render(const FlatScene& scene, const RenderOptions& options, Frame& frame) override;

  private:
    std::unique_ptr<Engine> quadrics_;
    std::vector<freeform::Surface> surfaces_;
    std::vector<std::int32_t> bodyIds_;
};

}  // namespace quadrix::isocurve
