#include "quadrix/viewer/file_watch.h"

#include <algorithm>
#include <system_error>

namespace quadrix::viewer {

FileWatch::Stamp FileWatch::StampOf(const std::string& path) {
    Stamp s;
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::is_regular_file(status)) return s;
    s.time = std::filesystem::last_write_time(path, ec);
    if (ec) return s;
    s.size = std::filesystem::file_size(path, ec);
    if (ec) return s;
    s.exists = true;
    return s;
}

void FileWatch::SetFiles(std::vector<std::string> paths) {
    std::sort(paths.begin(), paths.end());
    paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
    paths.erase(std::remove_if(paths.begin(), paths.end(),
                               [](const std::string& p) { return p.empty() || p == "-"; }),
                paths.end());
    paths_ = std::move(paths);
    stamps_.clear();
    for (const std::string& p : paths_) stamps_.push_back(StampOf(p));
}

bool FileWatch::Changed() {
    bool changed = false;
    std::optional<std::chrono::system_clock::time_point> newest;
    for (std::size_t i = 0; i < paths_.size(); ++i) {
        const Stamp now = StampOf(paths_[i]);
        if (!(now == stamps_[i])) {
            stamps_[i] = now;
            changed = true;
            if (now.exists) {
                const auto t = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
                    std::chrono::file_clock::to_sys(now.time));
                if (!newest || t > *newest) newest = t;
            }
        }
    }
    if (changed) lastChange_ = newest;
    return changed;
}

}  // namespace quadrix::viewer
