// The wall-clock time limit of a command (--time-limit, docs/output.md "Limits"): for servers and
// batch runs that must not hang on a scene whose cost explodes (issue 23). When the limit
// passes, a SIGALRM handler removes the temporary output files in the making
// (RemoveTemporaryOutputFiles), prints one line to standard error and ends the process with
// exit status kTimeLimitExitCode — all async-signal-safe calls, wherever the process was.
#pragma once

namespace quadrix {

inline constexpr int kTimeLimitExitCode = 124;  // as timeout(1)

// Arms the limit (seconds from now; > 0); a second call replaces the first. Returns false for a
// value that is not a positive finite number of at most a year.
bool SetTimeLimit(double seconds);

}  // namespace quadrix
