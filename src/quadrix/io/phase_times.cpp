#include "quadrix/io/phase_times.h"

#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>

namespace quadrix {

namespace {

struct Mark {
    const char* name = nullptr;
    long long ns = 0;
    long faults = 0;     // minor page faults of the process so far (every thread)
    long maxRssKiB = 0;  // the peak resident set so far
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
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const long faults = usage.ru_minflt, rss = usage.ru_maxrss;
    // Marks come from the main thread, one phase after the other; a name marked again (a second
    // picture) overwrites its first mark.
    const int n = markCount.load(std::memory_order_relaxed);
    for (int i = 0; i < n; ++i)
        if (std::strcmp(marks[i].name, name) == 0) {
            marks[i].ns = ns;
            marks[i].faults = faults;
            marks[i].maxRssKiB = rss;
            return;
        }
    if (n == kMaxMarks) return;
    marks[n] = {name, ns, faults, rss};
    markCount.store(n + 1, std::memory_order_relaxed);
}

void PrintPhaseTimes(std::FILE* out) {
    const int n = markCount.load(std::memory_order_relaxed);
    if (!PhaseTimesEnabled() || n == 0) return;
    std::fputs("quadrix phases:", out);
    for (int i = 0; i < n; ++i) std::fprintf(out, " %s=%lld", marks[i].name, marks[i].ns);
    std::fputc('\n', out);
    std::fputs("quadrix faults:", out);
    for (int i = 0; i < n; ++i) std::fprintf(out, " %s=%ld", marks[i].name, marks[i].faults);
    std::fputc('\n', out);
    std::fputs("quadrix peak KiB:", out);
    for (int i = 0; i < n; ++i) std::fprintf(out, " %s=%ld", marks[i].name, marks[i].maxRssKiB);
    std::fputc('\n', out);
    std::fflush(out);
}

}  // namespace quadrix
