// STUB — to be replaced by the raycast implementation.
#include "quadrix/engines/raycast/raycast.h"

namespace quadrix {
namespace {
class RaycastEngine final : public Engine {
public:
    std::string_view Name() const override { return "raycast"; }
    RenderStats Render(const FlatScene& scene, const RenderOptions&, Frame& frame) override {
        frame.Reset(scene.width, scene.height);
        return {};
    }
};
}  // namespace
std::unique_ptr<Engine> MakeRaycastEngine() { return std::make_unique<RaycastEngine>(); }
}  // namespace quadrix
