// The shading stage's complexity guard; see shade_budget.h.
#include "quadrix/shade/shade_budget.h"

#include <fmt/format.h>

#include <algorithm>

namespace quadrix {

ShadeBudget::ShadeBudget(const char* what, const char* avoid, std::uint64_t rays)
    : what_(what),
      avoid_(avoid),
      limit_(std::max(kShadeLiteralsFloor, kShadeLiteralsPerRay * rays)) {}

void ShadeBudget::ThrowIfExhausted(const FlatScene& scene) const {
    if (!Exhausted()) return;
    std::size_t most = 0;
    const FlatBody* big = nullptr;
    for (const FlatBody& b : scene.bodies)
        if (b.literals.size() > most) most = b.literals.size(), big = &b;
    const std::string culprit =
        big ? fmt::format("; body '{}' has {} literals, each evaluated on every ray that meets it",
                          big->name, most)
            : std::string();
    throw ShadeLimitError(fmt::format(
        "{}: the rays would evaluate more than {} literals (the shading budget: {} per ray, at "
        "least {}){}; use {} (docs/performance.md \"Complexity guards\")",
        what_, limit_, kShadeLiteralsPerRay, kShadeLiteralsFloor, culprit, avoid_));
}

}  // namespace quadrix
