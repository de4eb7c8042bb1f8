// EngineLimitError: thrown by Engine::Render (engine.h) when a complexity guard stops an engine
// that has no other engine to hand the work to — raycast's max-evaluations
// (engines/raycast/work_budget.h). The message names the limit and how to raise it. The render
// context (pipeline/render_context.cpp) turns it into an error: no image, never a partial one.
// Engines throw nothing else for any scene (degenerate geometry included); Engine::Render
// documents "never throws for degenerate geometry".
#pragma once

#include <stdexcept>

namespace quadrix {

class EngineLimitError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace quadrix
