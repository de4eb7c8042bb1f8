// The one bounded reader for every input of Quadrix (docs/output.md "Limits"): scene files named
// on the command line, `read` statements, standard input, --rt-view files, pipe files and the
// importers (BRL-CAD, OpenSCAD, freeform models) all read through these functions, so that an
// endless or huge input (/dev/zero, a pipe that never closes, a 300 MB file) ends in a clear error
// instead of exhausting memory.
//
// The limit is kMaxInputBytes (256 MiB) per file and for standard input in total. Text is never
// allowed to grow past the limit (the check comes before each append), so reading costs at most
// the limit in memory. Every regular file read is recorded with NoteInputFile (io/output_file.h),
// so that no output of the same process replaces it.
#pragma once

#include <cstddef>
#include <string>

namespace quadrix {

inline constexpr std::size_t kMaxInputBytes = std::size_t{256} << 20;

// Reads the whole of `path` ("-" = standard input) into `text`. Returns empty on success, else
// the reason in words that follow "cannot read PATH: " ("it is a directory", "it is larger than
// 256 MiB", "No such file or directory", ...).
std::string ReadBoundedFile(const std::string& path, std::string& text,
                            std::size_t limit = kMaxInputBytes);

// Reads one line of standard input into `text` (appended, with its '\n' when it had one), for
// readers that run statement by statement. False at the end of input or on an error; then
// StdinError() says which (empty at a clean end). All lines together count against
// kMaxInputBytes.
bool ReadBoundedStdinLine(std::string& text);
std::string StdinError();

// Human-readable size: "256 MiB", "1.5 GiB", "300 bytes".
std::string ByteSizeText(double bytes);

}  // namespace quadrix
