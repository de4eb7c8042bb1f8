#include "quadrix/batch/job.h"

#include <fmt/format.h>

#include <cctype>

namespace quadrix::batch {

int Job::FrameCount() const {
    if (!views.empty()) return static_cast<int>(views.size());
    return frames > 0 ? frames : 1;
}

int Job::LastFrame() const {
    const int end = FrameCount() - 1;
    return last < 0 || last > end ? end : last;
}

double Job::Clock(int frame) const {
    const int n = FrameCount();
    return n > 1 ? static_cast<double>(frame) / (n - 1) : 0.0;
}

namespace {
// The frame-number conversion in `path`: its position and length, and its width; npos when none.
// Only %d with an optional 0 flag and width (at most 2 digits) is a conversion.
struct Conversion {
    std::size_t pos = std::string::npos, length = 0;
    int width = 0;
    bool zero = false;
};
std::vector<Conversion> Conversions(const std::string& path, bool& malformed) {
    std::vector<Conversion> found;
    malformed = false;
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i] != '%') continue;
        if (i + 1 < path.size() && path[i + 1] == '%') {
            ++i;
            continue;
        }
        Conversion c;
        c.pos = i;
        std::size_t j = i + 1;
        if (j < path.size() && path[j] == '0') {
            c.zero = true;
            ++j;
        }
        std::size_t digits = 0;
        while (j < path.size() && std::isdigit(static_cast<unsigned char>(path[j])) && digits < 3) {
            c.width = c.width * 10 + (path[j] - '0');
            ++j;
            ++digits;
        }
        if (j >= path.size() || path[j] != 'd' || digits > 2) {
            malformed = true;
            continue;
        }
        c.length = j + 1 - i;
        found.push_back(c);
    }
    return found;
}
}  // namespace

bool HasFramePattern(const std::string& path) {
    bool malformed = false;
    return !Conversions(path, malformed).empty();
}

std::string FramePath(const std::string& path, int frame, bool animated) {
    if (!animated || path.empty() || path == "-") return path;
    bool malformed = false;
    const std::vector<Conversion> cs = Conversions(path, malformed);
    if (cs.empty()) {
        // out.png → out_0000.png: before the extension of the last path component.
        const std::size_t slash = path.find_last_of('/');
        std::size_t dot = path.find_last_of('.');
        if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
            dot == (slash == std::string::npos ? 0 : slash + 1))
            dot = path.size();
        return fmt::format("{}_{:04d}{}", path.substr(0, dot), frame, path.substr(dot));
    }
    std::string out;
    std::size_t at = 0;
    for (const Conversion& c : cs) {
        out += path.substr(at, c.pos - at);
        std::string digits = std::to_string(frame);
        if (static_cast<int>(digits.size()) < c.width)
            digits.insert(0, c.width - digits.size(), c.zero ? '0' : ' ');
        out += digits;
        at = c.pos + c.length;
    }
    out += path.substr(at);
    // "%%" stays "%%" in the copied pieces; make it one '%'.
    std::string result;
    for (std::size_t i = 0; i < out.size(); ++i) {
        result += out[i];
        if (out[i] == '%' && i + 1 < out.size() && out[i + 1] == '%') ++i;
    }
    return result;
}

std::string CheckJob(const Job& job) {
    if (job.frames < 0)
        return fmt::format("the number of frames must be positive, found {}", job.frames);
    if (!job.views.empty() && (job.frames > 0 || job.turntable))
        return "a list of views gives the frames itself: it cannot be combined with frames or a "
               "turntable";
    if (job.turntable && job.frames <= 0) return "a turntable needs a number of frames";
    const int n = job.FrameCount();
    if (job.first < 0 || job.first >= n)
        return fmt::format("frame range: the first frame {} is not one of the {} frames (0..{})",
                           job.first, n, n - 1);
    if (job.last >= 0 && job.last < job.first)
        return fmt::format("frame range: the last frame {} is before the first {}", job.last,
                           job.first);
    if (job.last >= n)
        return fmt::format("frame range: the last frame {} is not one of the {} frames (0..{})",
                           job.last, n, n - 1);
    bool malformed = false;
    for (const std::string* p : {&job.output.image, &job.output.dumpFrame, &job.output.exr}) {
        Conversions(*p, malformed);
        if (malformed)
            return fmt::format("output '{}': a '%' that is not a frame number (%d, %04d) or %%",
                               *p);
        if (!job.Animated() && HasFramePattern(*p))
            return fmt::format("output '{}' has a frame number but the job has no frames", *p);
    }
    if (job.Animated() && job.output.image == "-")
        return "an animation cannot write its frames to standard output";
    return {};
}

}  // namespace quadrix::batch
