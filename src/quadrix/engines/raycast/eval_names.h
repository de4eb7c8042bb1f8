// Engine `raycast` is built on the shared exact evaluation layer (src/quadrix/eval/): the
// ray/half-space kernel (eval/ray_literal.h) and the CSG program with its pruning against a screen
// rectangle (eval/csg_program.h). Its fast paths (body batches, kernels, tile reduction) use those
// types throughout, so they are named here without the eval:: prefix, in raycast's namespace only.
#pragma once

#include "quadrix/eval/csg_program.h"
#include "quadrix/eval/ray_literal.h"

namespace quadrix::raycast {
using namespace quadrix::eval;  // NOLINT(google-build-using-namespace): see above
}  // namespace quadrix::raycast
