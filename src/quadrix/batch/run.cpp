#include "quadrix/batch/run.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "quadrix/batch/job_renderer.h"
#include "quadrix/batch/progress.h"
#include "quadrix/util/seconds_since.h"

namespace quadrix::batch {

namespace {

struct Unit {
    int job = -1, frame = 0;  // frame -1: an invalid entry
};

std::vector<Unit> Units(const std::vector<JobEntry>& jobs) {
    std::vector<Unit> units;
    for (int j = 0; j < static_cast<int>(jobs.size()); ++j) {
        if (!jobs[j].error.empty()) {
            units.push_back({j, -1});
            continue;
        }
        for (int f = jobs[j].job.FirstFrame(); f <= jobs[j].job.LastFrame(); ++f)
            units.push_back({j, f});
    }
    return units;
}

// What one rank did: counts and the first error of each job it saw fail.
struct RankTally {
    int rendered = 0, skipped = 0, failed = 0, reads = 0, flattens = 0, geometryFlattens = 0;
    double frameSeconds = 0, minFrame = 1e300, maxFrame = 0;
    StageSeconds stages;
    std::map<int, std::string> failures;  // job → first error
};

std::string Label(const std::vector<JobEntry>& jobs, int j) {
    const std::string& l = jobs[j].job.label;
    return l.empty() ? fmt::format("job {}", j) : l;
}

// What a resumed run (--resume, or a job file run again) still has to do, said before it starts:
// "resuming: 6 of 8 frames not complete: spin.png frames 2-7" (the frames of a killed run, or of
// a rank killed mid-run, that it did not finish), one job after another, at most 12 jobs named.
// Empty when every frame is to be rendered (nothing was done before) or when nothing is left.
std::string ResumeReport(const std::vector<JobEntry>& jobs, const std::vector<Unit>& units) {
    int todo = 0, frames = 0;
    std::map<int, std::vector<int>> missing;  // job → frames not complete
    for (const Unit& u : units) {
        if (u.frame < 0) continue;
        ++frames;
        if (!FrameComplete(jobs[u.job].job, u.frame)) {
            ++todo;
            missing[u.job].push_back(u.frame);
        }
    }
    if (todo == frames || todo == 0) return {};
    std::string s = fmt::format("resuming: {} of {} frame{} not complete:", todo, frames,
                                frames == 1 ? "" : "s");
    int named = 0;
    for (const auto& [job, list] : missing) {
        if (++named > 12) {
            s += fmt::format(" and {} more jobs", missing.size() - 12);
            break;
        }
        s += fmt::format("{} {}", named > 1 ? ";" : "", Label(jobs, job));
        if (!jobs[job].job.Animated()) continue;
        std::string ranges;
        for (std::size_t i = 0; i < list.size();) {
            std::size_t j = i;
            while (j + 1 < list.size() && list[j + 1] == list[j] + 1) ++j;
            ranges += fmt::format(
                "{}{}", ranges.empty() ? "" : ",",
                j == i ? fmt::format("{}", list[i]) : fmt::format("{}-{}", list[i], list[j]));
            i = j + 1;
        }
        s += fmt::format(" frame{} {}", list.size() == 1 ? "" : "s", ranges);
    }
    return s;
}

// The fault-injection hook of the resumption tests (run.h): the number of frames after which
// this process kills itself, 0 = never.
int KillAfterFrames(int rank) {
    const char* v = std::getenv("QUADRIX_FAULT_KILL_AFTER");
    if (!v) return 0;
    int frames = 0, onRank = -1;
    if (std::sscanf(v, "%d:%d", &frames, &onRank) < 1 || frames < 1) return 0;
    return onRank < 0 || onRank == rank ? frames : 0;
}

// Renders the units that `next` hands out (-1 = none left).
template <typename Next>
RankTally RenderUnits(const std::vector<JobEntry>& jobs, const std::vector<Unit>& units,
                      const RunOptions& options, Progress& progress, Next next) {
    RankTally t;
    JobRenderer renderer(options.threads);
    const int killAfter = KillAfterFrames(MpiRank());
    for (int u = next(); u >= 0 && u < static_cast<int>(units.size()); u = next()) {
        const Unit& unit = units[u];
        const std::string label = Label(jobs, unit.job);
        if (unit.frame < 0) {
            ++t.failed;
            t.failures.emplace(unit.job, jobs[unit.job].error);
            progress.Error(unit.job, label, jobs[unit.job].error);
            continue;
        }
        const Job& job = jobs[unit.job].job;
        FrameResult r = renderer.Render(job, unit.job, unit.frame, options.skipExisting);
        const std::string frameLabel =
            job.Animated() ? fmt::format("{}, frame {}", label, unit.frame) : label;
        if (!r.error.empty()) {
            ++t.failed;
            const bool first = t.failures.emplace(unit.job, r.error).second;
            progress.Frame(unit.job, unit.frame, r, frameLabel, first);
            continue;
        }
        if (r.skipped) {
            ++t.skipped;
        } else {
            ++t.rendered;
            t.frameSeconds += r.seconds;
            t.minFrame = std::min(t.minFrame, r.seconds);
            t.maxFrame = std::max(t.maxFrame, r.seconds);
            t.stages.read += r.readSeconds;
            t.stages.flatten += r.flattenSeconds;
            t.stages.render += r.renderSeconds;
            t.stages.shade += r.shadeSeconds;
            t.stages.write += r.writeSeconds;
        }
        progress.Frame(unit.job, unit.frame, r, frameLabel);
        if (killAfter > 0 && t.rendered == killAfter) std::raise(SIGKILL);
    }
    t.reads = renderer.reads;
    t.flattens = renderer.flattens;
    t.geometryFlattens = renderer.GeometryFlattens();
    return t;
}

Summary Summed(const std::vector<JobEntry>& jobs, const std::vector<RankTally>& tallies, int frames,
               double seconds) {
    Summary s;
    s.jobs = static_cast<int>(jobs.size());
    s.frames = frames;
    s.ranks = static_cast<int>(tallies.size());
    s.seconds = seconds;
    std::map<int, std::string> failures;
    s.minFrame = 1e300;
    for (const RankTally& t : tallies) {
        s.rendered += t.rendered;
        s.skipped += t.skipped;
        s.failed += t.failed;
        s.reads += t.reads;
        s.flattens += t.flattens;
        s.geometryFlattens += t.geometryFlattens;
        s.frameSeconds += t.frameSeconds;
        s.minFrame = std::min(s.minFrame, t.minFrame);
        s.maxFrame = std::max(s.maxFrame, t.maxFrame);
        s.stages.read += t.stages.read;
        s.stages.flatten += t.stages.flatten;
        s.stages.render += t.stages.render;
        s.stages.shade += t.stages.shade;
        s.stages.write += t.stages.write;
        for (const auto& [j, e] : t.failures) failures.emplace(j, e);
    }
    if (s.rendered == 0) s.minFrame = 0;
    s.failedJobs = static_cast<int>(failures.size());
    for (const auto& [j, e] : failures) {
        std::string text = e;
        while (!text.empty() && text.back() == '\n') text.pop_back();
        s.failures.push_back(fmt::format("{}: {}", Label(jobs, j), text));
    }
    return s;
}

nlohmann::json StagesJson(const StageSeconds& s) {
    nlohmann::json j;
    j["read"] = s.read;
    j["flatten"] = s.flatten;
    j["render"] = s.render;
    j["shade"] = s.shade;
    j["write"] = s.write;
    return j;
}

nlohmann::json TallyJson(const RankTally& t) {
    nlohmann::json j;
    j["rendered"] = t.rendered;
    j["skipped"] = t.skipped;
    j["failed"] = t.failed;
    j["reads"] = t.reads;
    j["flattens"] = t.flattens;
    j["geometry_flattens"] = t.geometryFlattens;
    j["frame_s"] = t.frameSeconds;
    j["min_s"] = t.minFrame;
    j["max_s"] = t.maxFrame;
    j["stages_s"] = StagesJson(t.stages);
    nlohmann::json f = nlohmann::json::object();
    for (const auto& [job, e] : t.failures) f[std::to_string(job)] = e;
    j["failures"] = f;
    return j;
}

RankTally TallyFromJson(const nlohmann::json& j) {
    RankTally t;
    t.rendered = j["rendered"];
    t.skipped = j["skipped"];
    t.failed = j["failed"];
    t.reads = j["reads"];
    t.flattens = j["flattens"];
    t.geometryFlattens = j["geometry_flattens"];
    t.frameSeconds = j["frame_s"];
    t.minFrame = j["min_s"];
    t.maxFrame = j["max_s"];
    const nlohmann::json& st = j["stages_s"];
    t.stages = {st["read"].get<double>(), st["flatten"].get<double>(), st["render"].get<double>(),
                st["shade"].get<double>(), st["write"].get<double>()};
    for (const auto& [k, v] : j["failures"].items()) t.failures.emplace(std::stoi(k), v);
    return t;
}

// Every rank's tally on every rank (a JSON text each).
std::vector<RankTally> AllTallies(const RankTally& mine) {
    std::vector<RankTally> tallies;
    for (const std::string& text : Mpi().allGather(TallyJson(mine).dump()))
        tallies.push_back(TallyFromJson(nlohmann::json::parse(text)));
    return tallies;
}

Summary RunMpi(const std::vector<JobEntry>& jobs, const std::vector<Unit>& units,
               const RunOptions& options, bool terminal) {
    const auto t0 = std::chrono::steady_clock::now();
    const int rank = MpiRank();
    if (rank == 0 && options.skipExisting && !options.quiet)
        if (std::string r = ResumeReport(jobs, units); !r.empty())
            std::fprintf(stderr, "%s\n", r.c_str());
    // The next unit's index is counter 0 on rank 0; a rank takes one with an atomic add
    // (passive target, no reply from a busy rank needed).
    // Next to it the run's progress counts (done, rendered, failed), which every rank adds its
    // frames to, so that rank 0 shows the whole run's progress.
    const MpiModule& mpi = Mpi();
    MpiCounter* counter = mpi.counterCreate(4);
    const long long one = 1;
    auto next = [&]() -> int {
        long long got = 0;
        mpi.counterAdd(counter, 0, 1, &one, &got);
        return got < static_cast<long long>(units.size()) ? static_cast<int>(got) : -1;
    };
    // Only rank 0 draws progress (the whole run's counts, progress.h); every rank reports its own
    // errors as they happen.
    Progress progress(stderr, static_cast<int>(units.size()), terminal, options.quiet || rank != 0);
    progress.ShareCounts([&](const ProgressCounts& delta) {
        const long long add[3] = {delta.done, delta.rendered, delta.failed};
        long long before[3] = {0, 0, 0};
        mpi.counterAdd(counter, 1, 3, add, before);
        return ProgressCounts{static_cast<int>(before[0] + add[0]),
                              static_cast<int>(before[1] + add[1]),
                              static_cast<int>(before[2] + add[2])};
    });
    RankTally mine = RenderUnits(jobs, units, options, progress, next);
    if (rank == 0) progress.Wait();
    mpi.counterFree(counter);
    progress.Finish();
    std::vector<RankTally> tallies = AllTallies(mine);
    return Summed(jobs, tallies, static_cast<int>(units.size()), SecondsSince(t0));
}

}  // namespace

Summary RunJobs(const std::vector<JobEntry>& jobs, const RunOptions& options) {
    const std::vector<Unit> units = Units(jobs);
    const bool terminal = options.terminal < 0 ? StderrIsTerminal() : options.terminal == 1;
    if (options.useMpi && MpiSize() > 1) return RunMpi(jobs, units, options, terminal);
    if (options.skipExisting && !options.quiet)
        if (std::string r = ResumeReport(jobs, units); !r.empty())
            std::fprintf(stderr, "%s\n", r.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    Progress progress(stderr, static_cast<int>(units.size()), terminal, options.quiet);
    int at = 0;
    RankTally t = RenderUnits(jobs, units, options, progress, [&] { return at++; });
    progress.Finish();
    return Summed(jobs, {t}, static_cast<int>(units.size()), SecondsSince(t0));
}

std::string Summary::Text() const {
    const double rate = seconds > 0 ? rendered / seconds : 0;
    std::string s = fmt::format(
        "{} job{}, {} failed; {} frame{}: {} rendered, {} skipped (outputs exist), {} failed; "
        "{:.3f} s, {:.1f} frames/s",
        jobs, jobs == 1 ? "" : "s", failedJobs, frames, frames == 1 ? "" : "s", rendered, skipped,
        failed, seconds, rate);
    if (rendered > 0)
        s += fmt::format("; per frame {:.2f} ms mean, {:.2f} min, {:.2f} max",
                         1e3 * frameSeconds / rendered, 1e3 * minFrame, 1e3 * maxFrame);
    if (rendered > 0)
        s += fmt::format(
            " (stages, mean: read {:.2f} ms, flatten {:.2f}, render {:.2f}, shade {:.2f}, write "
            "{:.2f})",
            1e3 * stages.read / rendered, 1e3 * stages.flatten / rendered,
            1e3 * stages.render / rendered, 1e3 * stages.shade / rendered,
            1e3 * stages.write / rendered);
    s += fmt::format("; scene read {} time{}, geometry flattened {} time{}, views {} time{}", reads,
                     reads == 1 ? "" : "s", geometryFlattens, geometryFlattens == 1 ? "" : "s",
                     flattens, flattens == 1 ? "" : "s");
    if (ranks > 1) s += fmt::format("; {} MPI ranks", ranks);
    return s;
}

std::string Summary::Json() const {
    nlohmann::json j;
    j["event"] = "summary";
    j["jobs"] = jobs;
    j["failed_jobs"] = failedJobs;
    j["frames"] = frames;
    j["rendered"] = rendered;
    j["skipped"] = skipped;
    j["failed"] = failed;
    j["seconds"] = seconds;
    j["frames_per_s"] = seconds > 0 ? rendered / seconds : 0.0;
    j["mean_frame_s"] = rendered > 0 ? frameSeconds / rendered : 0.0;
    j["min_frame_s"] = minFrame;
    j["max_frame_s"] = maxFrame;
    j["stages_s"] = StagesJson(stages);  // sums over the rendered frames
    j["reads"] = reads;
    j["flattens"] = flattens;
    j["geometry_flattens"] = geometryFlattens;
    j["ranks"] = ranks;
    j["failures"] = failures;
    return j.dump();
}

}  // namespace quadrix::batch
