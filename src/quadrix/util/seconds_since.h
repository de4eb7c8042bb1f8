// Wall-clock seconds elapsed since a steady_clock time point: the stage timers of the engines and
// the batch runner read their clocks through this one function.
#pragma once

#include <chrono>

namespace quadrix {

inline double SecondsSince(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace quadrix
