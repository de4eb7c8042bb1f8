// `quadrix render --frames N | --turntable N | --views FILE [--frame-range a:b]`: the options of
// an animation and their hand-over to the batch module (src/quadrix/batch/, docs/batch.md), which
// renders the frames; `quadrix render` without them is unchanged.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "commands.h"
#include "quadrix/batch/job_file.h"
#include "quadrix/batch/run.h"
#include "quadrix/batch/sort_first.h"
#include "quadrix/batch/sort_last.h"
#include "quadrix/batch/view_list.h"
#include "quadrix/io/bounded_read.h"

namespace quadrix::cli {

void AddAnimationOptions(CLI::App& cmd, RenderArgs& args) {
    cmd.add_option("--frames", args.frames,
                   "Render N frames of an animation: `clock` goes from 0 to 1 over them; the "
                   "output is a pattern (out_%04d.png) or gets _NNNN before its extension")
        ->check(CLI::Range(1, 10'000'000));
    cmd.add_option("--frame-range", args.frameRange,
                   "Only frames FIRST:LAST (numbered from 0, inclusive) of the animation");
    cmd.add_option("--turntable", args.turntable,
                   "N frames orbiting the scene's centre once (start azimuth --az, elevation "
                   "--el, default 35 and 25 degrees)")
        ->check(CLI::Range(1, 10'000'000));
    cmd.add_flag("--sort-last", args.sortLast,
                 "Under mpirun: every rank draws a share of the solids, rank 0 composes them by "
                 "depth and writes the picture (docs/batch.md)");
    cmd.add_flag("--sort-first", args.sortFirst,
                 "Under mpirun: every rank draws bands of the picture's rows, rank 0 gathers "
                 "them and writes the picture (docs/batch.md)")
        ->excludes("--sort-last");
    cmd.add_flag("--resume", args.resume,
                 "With --frames/--turntable/--views: skip the frames whose outputs exist and are "
                 "complete (an interrupted run goes on where it stopped)");
    cmd.add_option("--views", args.views,
                   "One frame per view of FILE: UniQuadrix view statements, or an rt view script "
                   "(several views between `start N;` and `end;`)");
}

namespace {
// Whether the outputs (or --stats, which counts the covered pixels) need the whole Frame on the
// writing rank, not only the shaded picture.
bool NeedsFrame(const RenderArgs& args, const OutputRequest& outputs) {
    ImageFormat format;
    PnmKind pnm;
    const bool frameFormat = OutputFormat(outputs, format, pnm) &&
                             (format == ImageFormat::kFrameDump || format == ImageFormat::kExr);
    return frameFormat || !outputs.dumpFrame.empty() || !outputs.exr.empty() || args.stats;
}
}  // namespace

bool RenderMaybeShared(const RenderArgs& args, const OutputRequest& outputs, RenderContext& ctx,
                       const EngineRequest& engine, const ShadeOptions* shade, Frame& frame,
                       std::optional<Image>& image, RenderReport& report, Diagnostics& diags,
                       bool& writer) {
    writer = !(args.sortLast || args.sortFirst) || batch::MpiRank() == 0;
    if (args.sortFirst && shade) {
        image.emplace();
        return batch::RenderShadeSortFirst(ctx, engine, *shade, NeedsFrame(args, outputs), frame,
                                           *image, report, diags);
    }
    if (args.sortFirst) return batch::RenderSortFirst(ctx, engine, frame, report, diags);
    if (args.sortLast) return batch::RenderSortLast(ctx, engine, frame, report, diags);
    return ctx.Render(engine, frame, report, diags);
}

int RunAnimation(const RenderArgs& args, const PipelineOptions& po, const EngineRequest& engine,
                 const ShadeOptions& shade, const PictureDefaults& picture,
                 const OutputRequest& outputs) {
    batch::JobEntry entry;
    batch::Job& job = entry.job;
    job.label = "animation";
    job.input = po.Input();
    job.view = po.View();
    job.engine = engine;
    job.shade = shade;
    job.picture = picture;
    job.output = outputs;
    job.frames = args.frames;
    // Standard input can be read once: its text is kept and read again from memory per frame.
    if (std::count(job.input.paths.begin(), job.input.paths.end(), "-") > 0) {
        if (job.input.paths.size() != 1) {
            std::fprintf(stderr,
                         "quadrix: error: an animation reads standard input ('-') only "
                         "as its one input\n");
            return 2;
        }
        if (auto why = ReadBoundedFile("-", job.input.text); !why.empty()) {
            std::fprintf(stderr, "quadrix: error: cannot read standard input: %s\n", why.c_str());
            return 1;
        }
        job.input.textName = "<stdin>";
        job.input.paths.clear();
    }
    if (args.turntable > 0) {
        if (args.frames > 0 && args.frames != args.turntable) {
            std::fprintf(stderr,
                         "quadrix: error: --turntable N gives the number of frames; "
                         "--frames disagrees\n");
            return 2;
        }
        if (po.rtView || !args.view.empty()) {
            std::fprintf(stderr,
                         "quadrix: error: --turntable makes its own views: it cannot be "
                         "combined with --view or an rt view\n");
            return 2;
        }
        job.frames = args.turntable;
        batch::Turntable t;
        if (po.azimuth) t.azimuth0 = *po.azimuth;
        if (po.elevation) t.elevation = *po.elevation;
        job.view.azimuth.reset();
        job.view.elevation.reset();
        job.turntable = t;
    }
    if (!args.views.empty()) {
        Diagnostics diags;
        auto list = batch::ReadViewList(args.views, diags);
        diags.Print(stderr);
        if (!list) {
            std::fprintf(stderr, "quadrix: error: --views: the view list has errors\n");
            return 2;
        }
        job.views = std::move(*list);
    }
    if (!args.frameRange.empty()) {
        if (auto e = batch::ParseFrameRange(args.frameRange, job.first, job.last); !e.empty()) {
            std::fprintf(stderr, "quadrix: error: --%s\n", e.c_str());
            return 2;
        }
    }
    if (args.sortLast || args.sortFirst) {
        std::fprintf(stderr, "quadrix: error: --sort-%s renders one picture, not frames\n",
                     args.sortLast ? "last" : "first");
        return 2;
    }
    if (auto e = batch::CheckJob(job); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    batch::RunOptions ro;
    ro.threads = args.threads;
    ro.skipExisting = args.resume;
    const batch::Summary s = batch::RunJobs({entry}, ro);
    if (batch::MpiRank() == 0) {
        std::fprintf(stderr, "quadrix: %s\n", s.Text().c_str());
        if (args.stats && args.json) std::printf("%s\n", s.Json().c_str());
    }
    return s.failed > 0 ? 1 : 0;
}

}  // namespace quadrix::cli
