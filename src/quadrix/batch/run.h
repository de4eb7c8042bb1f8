// The scheduler of the batch module: renders every frame of a list of jobs, in one process or
// shared among the ranks of an MPI run (mpi_run.cpp), and sums up (issue 22, docs/batch.md).
//
// Work units are (job, frame) pairs in job order, frames in order. One process renders them in
// order with one JobRenderer (so a job's scene is read once and its flat scene reused). Under
// MPI the units are handed out dynamically: rank 0 holds a counter in an MPI window and every
// rank, rank 0 included, takes the next unit with MPI_Fetch_and_op when it is idle — a rank that
// draws fast frames simply takes more of them, and no rank waits for a reply from a busy one.
// Each rank keeps its own JobRenderer (its engines use all its cores through oneTBB), so
// consecutive units of one job on one rank share the read; each rank writes the frames it
// renders (a shared file system). At the end the ranks' counts and failures are gathered on
// rank 0, which prints the summary; every rank returns the same exit code.
//
// A job whose entry is invalid (a bad job line) fails without frames; a frame that fails is
// reported with its error and the run goes on. With skipExisting a frame whose outputs all exist
// is skipped: outputs are written atomically (io/output_file.h), so an existing file is complete
// and an interrupted run is resumed by running it again; an output that exists but is not
// complete or not of the job's size (io/output_check.h) is rendered again.
//
// Fault injection (the resumption tests, docs/batch.md): with QUADRIX_FAULT_KILL_AFTER=N in the
// environment a process kills itself (SIGKILL) right after rendering its N-th frame; with
// QUADRIX_FAULT_KILL_AFTER=N:R only MPI rank R does. Nothing else reads it.
#pragma once

#include <string>
#include <vector>

#include "quadrix/batch/job.h"
#include "quadrix/batch/mpi.h"  // UnderMpiLauncher, MpiRank, MpiSize

namespace quadrix::batch {

struct JobEntry {
    Job job;
    std::string error;  // set: the entry is invalid and fails without rendering
    // Warnings about the entry itself ("FILE:LINE:COLUMN: warning: ..."), printed once before the
    // run; the job still runs.
    std::vector<std::string> warnings;
    std::string file;  // where the entry was written (job files; empty for a command line)
    int line = 0;
};

struct RunOptions {
    int threads = 0;            // per process; 0 = all cores
    bool skipExisting = false;  // resume: skip frames whose outputs exist
    bool quiet = false;         // only errors and the summary
    // -1 = decide by isatty(stderr); 0 = JSON lines; 1 = a bar.
    int terminal = -1;
    bool useMpi = true;  // when built with MPI and launched by mpirun
};

// Seconds spent in each stage of a frame (FrameResult in job_renderer.h), summed over frames.
struct StageSeconds {
    double read = 0, flatten = 0, render = 0, shade = 0, write = 0;
};

struct Summary {
    int jobs = 0, failedJobs = 0;
    int frames = 0, rendered = 0, skipped = 0, failed = 0;
    // Over every rank: reads of the scene, flattens of a view (the view stage), and runs of the
    // world stage (the geometry: flattener.h FlattenWorld).
    int reads = 0, flattens = 0, geometryFlattens = 0;
    int ranks = 1;
    double seconds = 0;       // wall clock of the whole run
    double frameSeconds = 0;  // sum of the rendered frames' times (all ranks)
    double minFrame = 0, maxFrame = 0;
    StageSeconds stages;                // over the rendered frames (all ranks)
    std::vector<std::string> failures;  // "label: error" of each failed job (first error)
    // One line for people, and one JSON object (event "summary").
    std::string Text() const;
    std::string Json() const;
};

// Renders every frame of every job; progress and errors on standard error; returns the summary
// (on every rank the same counts under MPI).
Summary RunJobs(const std::vector<JobEntry>& jobs, const RunOptions& options);

}  // namespace quadrix::batch
