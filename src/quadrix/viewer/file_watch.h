// Live reload (issue 18 §4): the viewer polls the modification time and size of its input files
// (the files named on the command line and every file the scene's statements came from, so files
// reached by `read` too). Polling, not inotify: it is portable, needs no library, and at one
// stat() per file every 10 ms (each pass of the window's event loop; docs/viewer.md measures
// what it adds to the save-to-picture time) it costs nothing next to a frame.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace quadrix::viewer {

class FileWatch {
  public:
    // Watches these files from their state now (missing files are watched for appearing).
    void SetFiles(std::vector<std::string> paths);
    const std::vector<std::string>& Files() const { return paths_; }
    // True once for each change since the last call (or SetFiles): a time, size or existence.
    bool Changed();
    // The newest modification time among the files the last Changed() found changed (when the
    // file was saved, for the save-to-picture latency); empty when none exists now.
    std::optional<std::chrono::system_clock::time_point> LastChangeTime() const {
        return lastChange_;
    }

  private:
    struct Stamp {
        bool exists = false;
        std::filesystem::file_time_type time;
        std::uintmax_t size = 0;
        bool operator==(const Stamp&) const = default;
    };
    static Stamp StampOf(const std::string& path);
    std::vector<std::string> paths_;
    std::vector<Stamp> stamps_;
    std::optional<std::chrono::system_clock::time_point> lastChange_;
};

}  // namespace quadrix::viewer
