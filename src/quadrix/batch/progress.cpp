#include "quadrix/batch/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "quadrix/batch/job_renderer.h"

namespace quadrix::batch {

Progress::Progress(std::FILE* out, int total, bool terminal, bool quiet)
    : out_(out), total_(total), terminal_(terminal), quiet_(quiet) {}

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

namespace {
std::string Clock(double seconds) {
    if (!(seconds >= 0) || seconds > 1e7) return "--:--";
    const long s = static_cast<long>(seconds + 0.5);
    return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60)
                     : fmt::format("{}:{:02d}", s / 60, s % 60);
}
}  // namespace

void Progress::Bar() {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = elapsed > 0 ? rendered_ / elapsed : 0;
    const double eta = rate > 0 ? (total_ - done_) / rate : -1;
    constexpr int kWidth = 30;
    const int filled = total_ > 0 ? kWidth * done_ / total_ : kWidth;
    std::string bar(filled, '#');
    bar.append(kWidth - filled, '.');
    fmt::print(out_, "\r[{}] {}/{} frames  {:.1f} frames/s  ETA {}{}\x1b[K", bar, done_, total_,
               rate, Clock(eta), failed_ ? fmt::format("  {} failed", failed_) : "");
    std::fflush(out_);
    barShown_ = true;
}

void Progress::Count(int done, int rendered, int failed) {
    if (!exchange_) {
        done_ += done;
        rendered_ += rendered;
        failed_ += failed;
        return;
    }
    const ProgressCounts totals = exchange_({done, rendered, failed});
    done_ = totals.done;
    rendered_ = totals.rendered;
    failed_ = totals.failed;
}

void Progress::Wait(double period) {
    if (!exchange_) return;
    ProgressCounts last{done_, rendered_, failed_};
    while (done_ < total_) {
        std::this_thread::sleep_for(std::chrono::duration<double>(period));
        Count(0, 0, 0);
        if (done_ == last.done && failed_ == last.failed) continue;
        last = {done_, rendered_, failed_};
        if (quiet_) continue;
        if (terminal_) {
            Bar();
            continue;
        }
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        const double rate = elapsed > 0 ? rendered_ / elapsed : 0;
        nlohmann::json j;
        j["event"] = "progress";
        j["done"] = done_;
        j["total"] = total_;
        j["failed"] = failed_;
        j["frames_per_s"] = rate;
        j["eta_s"] = rate > 0 ? (total_ - done_) / rate : 0.0;
        fmt::print(out_, "{}\n", j.dump());
        std::fflush(out_);
    }
}

void Progress::Frame(int job, int frame, const FrameResult& r, const std::string& label,
                     bool printError) {
    if (!r.error.empty()) {
        if (printError)
            Error(job, label, r.error);
        else
            Count(1, 0, 1);
        return;
    }
    Count(1, r.skipped ? 0 : 1, 0);
    if (!r.skipped) renderedSeconds_ += r.seconds;
    std::string notes = r.warnings;
    while (!notes.empty() && notes.back() == '\n') notes.pop_back();
    if (quiet_) return;
    if (terminal_) {
        if (!notes.empty()) fmt::print(out_, "\r\x1b[K{}\n", notes);
        Bar();
        return;
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = elapsed > 0 ? rendered_ / elapsed : 0;
    nlohmann::json j;
    j["event"] = r.skipped ? "skip" : "frame";
    j["job"] = job;
    j["frame"] = frame;
    j["output"] = r.image;
    if (!r.skipped) {
        j["seconds"] = r.seconds;
        j["read_s"] = r.readSeconds;
        j["flatten_s"] = r.flattenSeconds;
        j["render_s"] = r.renderSeconds;
        j["shade_s"] = r.shadeSeconds;
        j["write_s"] = r.writeSeconds;
    }
    if (!notes.empty()) j["notes"] = notes;
    j["done"] = done_;
    j["total"] = total_;
    j["failed"] = failed_;
    j["frames_per_s"] = rate;
    j["eta_s"] = rate > 0 ? (total_ - done_) / rate : 0.0;
    fmt::print(out_, "{}\n", j.dump());
    std::fflush(out_);
}

void Progress::Error(int job, const std::string& label, const std::string& error) {
    Count(1, 0, 1);
    if (barShown_) fmt::print(out_, "\r\x1b[K");
    std::string text = error;
    while (!text.empty() && text.back() == '\n') text.pop_back();
    if (terminal_ || quiet_) {
        fmt::print(out_, "quadrix: {} failed:\n{}\n", label, text);
    } else {
        nlohmann::json j;
        j["event"] = "error";
        j["job"] = job;
        j["label"] = label;
        j["error"] = text;
        fmt::print(out_, "{}\n", j.dump());
    }
    if (terminal_ && !quiet_) Bar();
    std::fflush(out_);
}

void Progress::Finish() {
    if (barShown_) fmt::print(out_, "\n");
    barShown_ = false;
    std::fflush(out_);
}

}  // namespace quadrix::batch
