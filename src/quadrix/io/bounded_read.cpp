// The bounded reader; see bounded_read.h.
#include "quadrix/io/bounded_read.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <mutex>

#include "quadrix/io/output_file.h"
#include "quadrix/util/huge_pages.h"

namespace quadrix {

namespace {

// Standard input is one stream for the whole process: its budget and its last error are shared
// by every reader of it.
std::atomic<std::size_t> gStdinBytes{0};
std::mutex gStdinErrorMutex;
std::string gStdinError;

void SetStdinError(std::string e) {
    std::lock_guard<std::mutex> lock(gStdinErrorMutex);
    gStdinError = std::move(e);
}

std::string TooLarge(std::size_t limit) {
    return fmt::format("it is larger than {} (the input size limit)", ByteSizeText(limit));
}

// Reads `fd` to its end; `shared` (when given) counts the bytes against the limit across calls,
// else the size of `text` does.
std::string ReadAll(int fd, std::string& text, std::size_t limit,
                    std::atomic<std::size_t>* shared) {
    char buffer[1 << 16];
    for (;;) {
        ssize_t n = read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) continue;
            return std::strerror(errno);
        }
        if (n == 0) return {};
        std::size_t used = shared ? shared->fetch_add(static_cast<std::size_t>(n)) : text.size();
        if (used + static_cast<std::size_t>(n) > limit) return TooLarge(limit);
        text.append(buffer, static_cast<std::size_t>(n));
    }
}

}  // namespace

std::string ByteSizeText(double bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (bytes >= 1024 && u < 4) {
        bytes /= 1024;
        ++u;
    }
    if (u == 0) return fmt::format("{:.0f} bytes", bytes);
    return bytes == static_cast<double>(static_cast<long long>(bytes))
               ? fmt::format("{:.0f} {}", bytes, units[u])
               : fmt::format("{:.1f} {}", bytes, units[u]);
}

std::string ReadBoundedFile(const std::string& path, std::string& text, std::size_t limit) {
    if (path == "-") {
        std::fflush(stdout);
        std::string e = ReadAll(STDIN_FILENO, text, limit, &gStdinBytes);
        return e;
    }
    int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return std::strerror(errno);
    struct stat st {};
    if (fstat(fd, &st) != 0) {
        std::string e = std::strerror(errno);
        close(fd);
        return e;
    }
    if (S_ISDIR(st.st_mode)) {
        close(fd);
        return "it is a directory";
    }
    if (S_ISREG(st.st_mode)) {
        if (static_cast<unsigned long long>(st.st_size) > limit) {
            close(fd);
            return TooLarge(limit);
        }
        NoteInputFile(fd);
        // One byte more: the read that finds the end of the file. A big text is read into huge
        // pages (util/huge_pages.h; std::string allocates one byte more for its terminator).
        const std::size_t want = text.size() + static_cast<std::size_t>(st.st_size) + 1;
        if (text.empty() && want >= kHugePageBytes) {
            text.reserve(HugePageRequest(want + 1) - 1);
            AdviseHugePages(text.data(), text.capacity() + 1);
        } else {
            text.reserve(want);
        }
    }
    const std::size_t before = text.size();
    std::string e = ReadAll(fd, text, limit + before, nullptr);
    close(fd);
    return e;
}

namespace {

// The buffer std::cin had at start-up: while it is still in place, standard input is read through
// stdio (fast, and with its error flag); a program or test that swapped in another buffer
// (std::cin.rdbuf(x)) is read through that one.
std::streambuf* const gOriginalCinBuffer = std::cin.rdbuf();

bool ReadLineFromStreambuf(std::streambuf& in, std::string& text) {
    const std::size_t room = kMaxInputBytes - std::min(kMaxInputBytes, gStdinBytes.load());
    std::string line;
    using Traits = std::streambuf::traits_type;
    for (int c = in.sbumpc(); !Traits::eq_int_type(c, Traits::eof()); c = in.sbumpc()) {
        if (line.size() >= room) {
            gStdinBytes += line.size();
            SetStdinError(TooLarge(kMaxInputBytes));
            return false;
        }
        line.push_back(Traits::to_char_type(c));
        if (line.back() == '\n') break;
    }
    gStdinBytes += line.size();
    if (line.empty()) return false;
    text += line;
    return true;
}

}  // namespace

bool ReadBoundedStdinLine(std::string& text) {
    if (std::streambuf* buffer = std::cin.rdbuf(); buffer != gOriginalCinBuffer)
        return buffer && ReadLineFromStreambuf(*buffer, text);
    std::FILE* in = stdin;
    flockfile(in);
    bool any = false;
    int c = 0;
    std::string line;
    const std::size_t room = kMaxInputBytes - std::min(kMaxInputBytes, gStdinBytes.load());
    while ((c = getc_unlocked(in)) != EOF) {
        any = true;
        if (line.size() >= room) {
            funlockfile(in);
            gStdinBytes += line.size();
            SetStdinError(TooLarge(kMaxInputBytes));
            return false;
        }
        line.push_back(static_cast<char>(c));
        if (c == '\n') break;
    }
    gStdinBytes += line.size();
    const bool failed = c == EOF && ferror_unlocked(in);
    const int err = errno;
    funlockfile(in);
    if (failed) {
        SetStdinError(std::strerror(err));
        return false;
    }
    if (!any) return false;
    text += line;
    return true;
}

std::string StdinError() {
    std::lock_guard<std::mutex> lock(gStdinErrorMutex);
    return gStdinError;
}

}  // namespace quadrix
