// The size of the pieces in which the MPI paths (sort_first.cpp, sort_last.cpp) send big buffers:
// MPI counts are int, and a Frame of an 8K image is larger than 2 GiB.
#pragma once

#include <cstddef>

namespace quadrix::batch {

inline constexpr std::size_t kMpiPiece = std::size_t{256} << 20;

}  // namespace quadrix::batch
