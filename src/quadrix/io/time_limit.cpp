// The time limit; see time_limit.h.
#include "quadrix/io/time_limit.h"

#include <signal.h>
#include <sys/time.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "quadrix/io/output_file.h"

namespace quadrix {

namespace {

char gMessage[160];
std::size_t gMessageLength = 0;

extern "C" void TimeLimitReached(int) {
    RemoveTemporaryOutputFiles();
    ssize_t ignored = write(STDERR_FILENO, gMessage, gMessageLength);
    (void)ignored;
    _exit(kTimeLimitExitCode);
}

}  // namespace

bool SetTimeLimit(double seconds) {
    if (!std::isfinite(seconds) || !(seconds > 0) || seconds > 366.0 * 86400) return false;
    std::snprintf(gMessage, sizeof gMessage, "quadrix: error: time limit of %g s exceeded\n",
                  seconds);
    gMessageLength = std::strlen(gMessage);
    struct sigaction sa {};
    sa.sa_handler = TimeLimitReached;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGALRM, &sa, nullptr);
    struct itimerval timer {};
    const double whole = std::floor(seconds);
    timer.it_value.tv_sec = static_cast<time_t>(whole);
    timer.it_value.tv_usec = static_cast<suseconds_t>((seconds - whole) * 1e6);
    if (timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
    return setitimer(ITIMER_REAL, &timer, nullptr) == 0;
}

}  // namespace quadrix
