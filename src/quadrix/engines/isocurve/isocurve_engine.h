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
    // The isocurve options (render.h IsocurveSchema); none go to the inner engine.
    const OptionSchema& Schema() const override { return IsocurveSchema(); }
    std::string CheckOptions(const EngineOptions& options) const override {
        return CheckIsocurveOptions(options);
    }

  protected:
    // Resets `frame` to the scene size, renders the quadrics (when there is an inner engine),
    // then the freeform surfaces; --stats gets the isocurve statistics and, with compare=on, the
    // comparison table of item 5.
    RenderStats Draw(const FlatScene& scene, const EngineOptions& options, Frame& frame) override;

  private:
    std::unique_ptr<Engine> quadrics_;
    std::vector<freeform::Surface> surfaces_;
    std::vector<std::int32_t> bodyIds_;
};

// The registry's engine: freeform surfaces only (the render context draws the solids with
// raycast and composes the Frames).
std::unique_ptr<Engine> MakeIsocurveEngine();

}  // namespace quadrix::isocurve
