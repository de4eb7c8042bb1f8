// Phase times of one process (issue 24 item 6: the benchmark's whole-process phase table).
//
// A one-shot command marks the end of each of its phases (the command line parsed, read,
// flatten, render, shade, encode, write, exit) with MarkPhase; when the environment variable
// QUADRIX_PHASE_TIMES is set (to anything but "0" or ""), PrintPhaseTimes writes one line to
// standard error just before the process exits:
//
//     quadrix phases: main=T0 start=T1 read=T2 ... exit=Tn
//     quadrix faults: main=F0 start=F1 ... exit=Fn
//     quadrix peak KiB: main=R0 start=R1 ... exit=Rn
//
// every T the steady clock (CLOCK_MONOTONIC on Linux, the same clock in every process of the
// machine) in nanoseconds, so that a parent that noted the clock before spawning the process and
// after reaping it (bench/bench_main.cpp) gets the start-up (spawn → main → start) and the exit
// (the last mark → reaped) too. F is the process's minor page faults so far and R its peak
// resident set so far (getrusage, every thread), so that a phase's first-touched memory shows. A
// phase that did not happen is absent (e.g. encode for a .qxf). Without the variable MarkPhase
// costs one load and a branch; nothing is printed. Marks are kept in a fixed table (no allocation,
// the last mark of a name wins), so the library's own marks (the PNG encoder marks "encode") cost
// nothing in a long-running process either.
#pragma once

#include <cstdio>

namespace quadrix {

// Whether QUADRIX_PHASE_TIMES asks for the phase line (read once).
bool PhaseTimesEnabled();
// Notes the clock under `name` (a string literal: kept by pointer), when enabled.
void MarkPhase(const char* name);
// Writes the line to `out` (standard error by default), when enabled and any phase was marked.
void PrintPhaseTimes(std::FILE* out = stderr);

}  // namespace quadrix
