// Limits on the size of a Frame or an image: a request beyond them is a user error with a clear
// message, never an allocation failure. Used by every front end (the CLI's --size, uq's devices,
// the render context) before any buffer is made.
#pragma once

#include <string>

namespace quadrix {

// Largest image accepted (pixels) and largest side.
inline constexpr long long kMaxPixels = 8192LL * 8192LL;
inline constexpr int kMaxSide = 16384;

// Checks a requested image size; returns an error message or empty.
std::string CheckImageSize(long long width, long long height);

}  // namespace quadrix
