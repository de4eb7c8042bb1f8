#include "quadrix/engines/engine.h"

#include "quadrix/engines/isocurve/isocurve_engine.h"
#include "quadrix/engines/patch/patch_engine.h"
#include "quadrix/engines/pixelpowers/pixelpowers_engine.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/engines/scanline/scanline_engine.h"

namespace quadrix {

std::unique_ptr<Engine> MakeEngine(std::string_view name) {
    if (name == "raycast") return MakeRaycastEngine();
    if (name == "patch") return MakePatchEngine();
    if (name == "pixelpowers") return MakePixelPowersEngine();
    if (name == "scanline") return MakeScanlineEngine();
    if (name == "isocurve")
        return std::make_unique<isocurve::IsocurveEngine>(MakeRaycastEngine(),
                                                          std::vector<freeform::Surface>{});
    return nullptr;
}

std::vector<std::string> EngineNames() { return {"raycast", "patch", "isocurve", "scanline", "pixelpowers"}; }

}  // namespace quadrix
