#include "quadrix/frame/frame.h"

namespace quadrix {

void ComposeMin(Frame& into, const Frame& other) {
    for (std::size_t i = 0; i < into.depth.size() && i < other.depth.size(); ++i)
        into.Offer(i, other.depth[i], other.normal[i], other.surface[i], other.body[i],
                   other.solid[i]);
}

}  // namespace quadrix
