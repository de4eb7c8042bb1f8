// `quadrix batch JOBFILE`: many jobs (models, views, animations) from a file of JSON lines, with
// progress, failures reported and skipped over, a summary, and resumption (outputs that exist
// are not rendered again). The work is done by the batch module (src/quadrix/batch/run.h); under
// `mpirun -np N` the jobs' frames are shared among the ranks. docs/batch.md.
#include <cstdio>
#include <string>

#include "commands.h"
#include "quadrix/batch/job_file.h"
#include "quadrix/batch/output_clashes.h"
#include "quadrix/batch/run.h"
#include "quadrix/io/bounded_read.h"

namespace quadrix::cli {

void AddBatchCommand(CLI::App& app, BatchArgs& args) {
    CLI::App* cmd = app.add_subcommand(
        "batch", "Render the jobs of a file of JSON lines (docs/batch.md); runs under mpirun");
    cmd->add_option("jobfile", args.jobFile, "Job file: one JSON object per line ('-' = stdin)")
        ->required();
    cmd->add_option("--threads", args.threads,
                    "Worker threads per process (0 = all cores, or inline for a picture of at "
                    "most 128x128 pixels of a small scene; 1 = inline, without oneTBB)")
        ->check(CLI::Range(0, 1024));
    cmd->add_flag("--restart", args.restart,
                  "Render every frame again, even those whose outputs exist (default: resume)");
    cmd->add_flag("--quiet", args.quiet, "No progress: only errors and the summary");
    cmd->add_flag("--json", args.json, "Also print the summary as one JSON object on stdout");
    AddLimitOptions(*cmd, args);
}

int RunBatch(const BatchArgs& args) {
    if (auto e = ApplyLimits(args); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    std::string text;
    if (auto why = ReadBoundedFile(args.jobFile, text); !why.empty()) {
        std::fprintf(stderr, "quadrix: error: cannot read the job file '%s': %s\n",
                     args.jobFile.c_str(), why.c_str());
        return 1;
    }
    const std::vector<batch::JobEntry> jobs = batch::ParseJobFile(text, args.jobFile);
    if (jobs.empty()) {
        std::fprintf(stderr, "quadrix: error: the job file '%s' has no job\n",
                     args.jobFile.c_str());
        return 1;
    }
    // Outputs that two jobs (or two outputs of one job) share: refused before anything is
    // rendered (batch/output_clashes.h). Every rank finds the same; rank 0 says it.
    const std::vector<std::string> clashes = batch::OutputClashes(jobs);
    const bool speaker = batch::MpiRank() == 0;
    if (!clashes.empty()) {
        if (speaker) {
            for (const std::string& c : clashes)
                std::fprintf(stderr, "quadrix: error: %s\n", c.c_str());
            std::fprintf(stderr, "quadrix batch: nothing rendered\n");
        }
        return 1;
    }
    if (speaker)
        for (const batch::JobEntry& e : jobs)
            for (const std::string& w : e.warnings) std::fprintf(stderr, "%s\n", w.c_str());
    batch::RunOptions ro;
    ro.threads = args.threads;
    ro.skipExisting = !args.restart;
    ro.quiet = args.quiet;
    const batch::Summary s = batch::RunJobs(jobs, ro);
    if (batch::MpiRank() == 0) {
        if (!s.failures.empty()) {
            std::fprintf(stderr, "quadrix batch: failed:\n");
            for (const std::string& f : s.failures) std::fprintf(stderr, "  %s\n", f.c_str());
        }
        std::fprintf(stderr, "quadrix batch: %s\n", s.Text().c_str());
        if (args.json) std::printf("%s\n", s.Json().c_str());
    }
    return s.failed > 0 ? 1 : 0;
}

}  // namespace quadrix::cli
