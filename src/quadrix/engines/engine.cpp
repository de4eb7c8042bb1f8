#include "quadrix/engines/engine.h"

#include "quadrix/engines/raycast/raycast.h"

namespace quadrix {

std::unique_ptr<Engine> MakeEngine(std::string_view name) {
    if (name == "raycast") return MakeRaycastEngine();
    return nullptr;
}

std::vector<std::string> EngineNames() { return {"raycast"}; }

}  // namespace quadrix
