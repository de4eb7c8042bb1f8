// Progress of a frame loop or batch run, on standard error (docs/batch.md "Progress"):
//   - on a terminal, one line redrawn in place: a bar, frames done of total, frames/s, ETA;
//   - otherwise one JSON object per line, for scripts and log files:
//       {"event":"frame","job":0,"frame":3,"output":"out_0003.png","seconds":0.012,
//        "done":4,"total":10,"failed":0,"frames_per_s":81.2,"eta_s":0.07}
//       {"event":"error","job":2,"label":"job 2 (jobs.jsonl:3)","error":"..."}
//       {"event":"summary", ...}            (see Summary in run.h)
//   A skipped frame (its outputs exist) is {"event":"skip",...} and counts as done.
// The rate is over the frames rendered in this run (skipped ones excluded), the ETA that rate
// applied to the frames left.
//
// Under MPI the counts are the whole run's (ShareCounts): every rank adds its frames to counters
// on rank 0 (one-sided, run.cpp), and rank 0, the only one that draws, shows the totals — after
// each of its own frames, and every 0.2 s once it has no more frames while others still render
// (Wait).
#pragma once

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>

namespace quadrix::batch {

struct FrameResult;

struct ProgressCounts {
    int done = 0, rendered = 0, failed = 0;
};
// Adds `delta` (this process's new frames) to the run's counts and returns the run's totals
// after it.
using CountExchange = std::function<ProgressCounts(const ProgressCounts& delta)>;

class Progress {
  public:
    // terminal: draw the bar; else JSON lines. quiet: only errors and the summary.
    Progress(std::FILE* out, int total, bool terminal, bool quiet = false);

    // A frame done, skipped or failed (result.error); a failure's error is printed when
    // printError (the first failure of a job: its other frames usually fail alike).
    void Frame(int job, int frame, const FrameResult& result, const std::string& label = {},
               bool printError = true);
    // A job that failed without a frame (an invalid entry); counts as one frame.
    void Error(int job, const std::string& label, const std::string& error);
    // Counts through `exchange` from now on (the run's totals instead of this process's).
    void ShareCounts(CountExchange exchange) { exchange_ = std::move(exchange); }
    // Until the run's done count reaches the total: redraws the totals (or prints a "progress"
    // line when they changed) every `period` seconds. Without ShareCounts it returns at once.
    void Wait(double period = 0.2);
    // Ends the bar's line (terminal) before the summary is printed.
    void Finish();
    // The counts so far.
    int done() const { return done_; }
    int failed() const { return failed_; }
    bool terminal() const { return terminal_; }

  private:
    void Bar();
    void Count(int done, int rendered, int failed);
    std::FILE* out_;
    int total_;
    bool terminal_, quiet_;
    int done_ = 0, rendered_ = 0, failed_ = 0;
    double renderedSeconds_ = 0;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    bool barShown_ = false;
    CountExchange exchange_;
};

// Whether standard error is a terminal (isatty), for choosing the progress form.
bool StderrIsTerminal();

}  // namespace quadrix::batch
