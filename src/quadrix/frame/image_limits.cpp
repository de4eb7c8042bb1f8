#include "quadrix/frame/image_limits.h"

#include <fmt/format.h>

#include "quadrix/frame/memory_budget.h"

namespace quadrix {

std::string CheckImageSize(long long width, long long height) {
    if (width <= 0 || height <= 0)
        return fmt::format("image size {}x{} is not positive", width, height);
    if (width > kMaxSide || height > kMaxSide || width * height > kMaxPixels)
        return fmt::format("image size {}x{} is too large (at most {} pixels a side and {} pixels)",
                           width, height, kMaxSide, kMaxPixels);
    // Before the Frame is allocated (frame/memory_budget.h): a clear error, not std::bad_alloc.
    return CheckMemory(RenderBytes(width, height),
                       fmt::format("an image of {}x{} pixels", width, height));
}

}  // namespace quadrix
