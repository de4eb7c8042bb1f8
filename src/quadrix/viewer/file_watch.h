// Live reload (issue 18 §4): the viewer polls the modification time and size of its input files
// (the files named on the command line and every file the scene's statements came from, so files
// reached by `read` too). Polling, not inotify: it is portable, needs no library, and at one
// stat() per file every 50 ms it costs nothing next to a frame.
#pragma once

#include <filesystem>
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
};

}  // namespace quadrix::viewer
