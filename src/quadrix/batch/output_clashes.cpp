#include "quadrix/batch/output_clashes.h"

#include <fmt/format.h>

#include <filesystem>
#include <unordered_map>

namespace quadrix::batch {

namespace {

namespace fs = std::filesystem;

// Where a job line is, for messages: "FILE:LINE", or the job's label when it has no line.
std::string Position(const JobEntry& e) {
    return e.line > 0 ? fmt::format("{}:{}", e.file, e.line) : e.job.label;
}

// One output of one frame of one job.
struct Writer {
    int entry = 0;
    int frame = 0;
    const char* key = "";  // the job-file key of the output
};

std::string Describe(const JobEntry& e, const Writer& w) {
    return e.job.Animated() ? fmt::format("\"{}\", frame {}", w.key, w.frame)
                            : fmt::format("\"{}\"", w.key);
}

}  // namespace

std::vector<std::string> OutputClashes(const std::vector<JobEntry>& jobs, std::size_t limit) {
    // The canonical form of each directory met, computed once (an animation's frames share it).
    std::unordered_map<std::string, std::string> directories;
    auto fileKey = [&](const std::string& path) {
        const fs::path p(path);
        const std::string dir = p.parent_path().string();
        auto it = directories.find(dir);
        if (it == directories.end()) {
            std::error_code ec;
            fs::path abs = fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec);
            fs::path canon = fs::weakly_canonical(abs, ec);
            if (ec) canon = abs.lexically_normal();
            it = directories.emplace(dir, canon.string()).first;
        }
        return it->second + "/" + p.filename().string();
    };
    std::unordered_map<std::string, Writer> owners;
    std::vector<std::string> clashes;
    std::size_t more = 0;
    for (std::size_t n = 0; n < jobs.size(); ++n) {
        const JobEntry& e = jobs[n];
        if (!e.error.empty()) continue;
        const Job& job = e.job;
        const std::pair<const char*, const std::string*> outputs[] = {
            {"output", &job.output.image},
            {"dump_frame", &job.output.dumpFrame},
            {"exr", &job.output.exr}};
        for (int frame = job.FirstFrame(); frame <= job.LastFrame(); ++frame) {
            for (const auto& [key, pattern] : outputs) {
                if (pattern->empty() || *pattern == "-") continue;
                const std::string path = FramePath(*pattern, frame, job.Animated());
                const Writer w{static_cast<int>(n), frame, key};
                auto [it, fresh] = owners.emplace(fileKey(path), w);
                if (fresh) continue;
                if (clashes.size() >= limit) {
                    ++more;
                    continue;
                }
                const JobEntry& first = jobs[static_cast<std::size_t>(it->second.entry)];
                const std::string owner =
                    it->second.entry == w.entry
                        ? fmt::format("this job's {},", Describe(first, it->second))
                        : fmt::format("job {} ({}), {},", it->second.entry, Position(first),
                                      Describe(first, it->second));
                clashes.push_back(fmt::format(
                    "{}: {} writes '{}', which {} writes too: the outputs of a batch must be "
                    "different files",
                    Position(e), Describe(e, w) + (job.Animated() ? "," : ""), path, owner));
            }
        }
    }
    if (more > 0) clashes.push_back(fmt::format("... and {} more", more));
    return clashes;
}

}  // namespace quadrix::batch
