// Private to the public API's implementation (src/api/): what Scene and Renderer share, and the
// conversions between the public types (include/quadrix/quadrix.h) and the internal ones. Never
// installed; the public header includes nothing of this.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "quadrix/quadrix.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct Scene::Impl {
    scene::Scene scene;
    std::vector<Message> warnings;
    // A number that changes with every edit (and is kept by a copy, whose content is the same):
    // the Renderer hands the scene to its render context again only when it changed, so that
    // rendering the same scene twice reuses the flat scene.
    std::uint64_t revision = 0;
    void Touch();
};

namespace api {

Message ToMessage(const Diagnostic& d);
// Every diagnostic, in order.
std::vector<Message> ToMessages(const Diagnostics& diags);
// The warnings only.
std::vector<Message> WarningsOf(const Diagnostics& diags);
// Throws Error with every diagnostic of `diags` (which holds at least one error), or with
// `fallback` as a message when it holds none.
[[noreturn]] void ThrowDiagnostics(const Diagnostics& diags, const std::string& fallback);

scene::View ToSceneView(const View& view, const std::string& id);

}  // namespace api
}  // namespace quadrix
