// STUB — to be replaced by the Flattener implementation.
#include "quadrix/flatten/flattener.h"

namespace quadrix {
std::optional<FlatScene> Flatten(const scene::Scene&, const FlattenOptions&, Diagnostics& diags) {
    diags.Error({}, "flattener not implemented");
    return std::nullopt;
}
}  // namespace quadrix
