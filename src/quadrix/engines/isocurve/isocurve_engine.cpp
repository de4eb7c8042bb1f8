#include "quadrix/engines/isocurve/isocurve_engine.h"

#include "quadrix/engines/isocurve/compare.h"

namespace quadrix::isocurve {

std::vector<FreeformDrawable> SceneDrawables(const FlatScene& scene) {
    std::vector<FreeformDrawable> drawables;
    for (std::size_t k = 0; k < scene.freeforms.size(); ++k) {
        FrameIds ids;
        ids.surface = static_cast<std::int32_t>(scene.halfSpaces.size() + k);
        ids.body = Frame::kNone;
        drawables.push_back({&scene.freeforms[k].surface, ids});
    }
    return drawables;
}

IsocurveEngine::IsocurveEngine(std::unique_ptr<Engine> quadrics,
                               std::vector<freeform::Surface> surfaces,
                               std::vector<std::int32_t> bodyIds)
    : quadrics_(std::move(quadrics)),
      surfaces_(std::move(surfaces)),
      bodyIds_(std::move(bodyIds)) {}

RenderStats IsocurveEngine::Draw(const FlatScene& scene, const EngineOptions& options,
                                 Frame& frame) {
    RenderStats stats;
    const IsocurveOptions o = ReadIsocurveOptions(options);
    if (quadrics_ && !scene.solids.empty()) {
        stats = quadrics_->Render(scene, RenderOptions{}, frame);
    } else {
        frame.Reset(scene.width, scene.height);
    }
    std::vector<FreeformDrawable> drawables = SceneDrawables(scene);
    for (std::size_t k = 0; k < surfaces_.size(); ++k) {
        FrameIds ids;
        ids.surface =
            static_cast<std::int32_t>(scene.halfSpaces.size() + scene.freeforms.size() + k);
        ids.body = k < bodyIds_.size() ? bodyIds_[k] : Frame::kNone;
        drawables.push_back({&surfaces_[k], ids});
    }
    IsocurveStats st = RenderFreeform(drawables, scene.projection, o, frame);
    FillRenderStats(st, stats);
    if (o.compare)
        stats.report +=
            CompareCoverage(drawables, scene.projection, o, scene.width, scene.height).Format();
    return stats;
}

std::unique_ptr<Engine> MakeIsocurveEngine() {
    return std::make_unique<IsocurveEngine>(nullptr, std::vector<freeform::Surface>{});
}

}  // namespace quadrix::isocurve
