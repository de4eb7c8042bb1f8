#include "quadrix/io/phase_times.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>

namespace quadrix {

namespace {

struct Mark {
    const char* name = nullptr;
    long long ns = 0;
};

constexpr int kMaxMarks = 24;
Mark marks[kMaxMarks];
std::atomic<int> markCount{0};

bool ReadEnabled() {
    const char* v = std::getenv("QUADRIX_PHASE_TIMES");
    return v && *v && std::strcmp(v, "0") != 0;
}

}  // namespace

bool PhaseTimesEnabled() {
    static const bool enabled = ReadEnabled();
    return enabled;
}

void MarkPhase(const char* name) {
    if (!PhaseTimesEnabled()) return;
    const long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::steady_clock::now().time_since_epoch())
                             .count();
    // Marks come from the main thread, one phase after the other; a name marked again (a second
    // picture) overwrites its first mark.
    const int n = markCount.load(std::memory_order_relaxed);
    for (int i = 0; i < n; ++i)
        if (std::strcmp(marks[i].name, name) == 0) {
            marks[i].ns = ns;
            return;
        }
    if (n == kMaxMarks) return;
    marks[n] = {name, ns};
    markCount.store(n + 1, std::memory_order_relaxed);
}

void PrintPhaseTimes(std::FILE* out) {
    const int n = markCount.load(std::memory_order_relaxed);
    if (!PhaseTimesEnabled() || n == 0) return;
    std::fputs("quadrix phases:", out);
    for (int i = 0; i < n; ++i) std::fprintf(out, " %s=%lld", marks[i].name, marks[i].ns);
    std::fputc('\n', out);
    std::fflush(out);
}

}  // namespace quadrix
