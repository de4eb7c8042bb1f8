#include "quadrix/engines/engine.h"

#include "quadrix/engines/patch/patch_engine.h"
#include "quadrix/engines/raycast/raycast.h"

namespace quadrix {

std::unique_ptr<Engine> MakeEngine(std::string_view name) {
    if (name == "raycast") return MakeRaycastEngine();
    if (name == "patch") return MakePatchEngine();
    return nullptr;
}

std::vector<std::string> EngineNames() { return {"raycast", "patch"}; }

}  // namespace quadrix
