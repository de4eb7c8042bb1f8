// Running the OpenSCAD program to evaluate a .scad file into its CSG tree (`openscad -o x.csg`),
// for the models that use the language beyond the literal CSG subset our reader takes (variables,
// modules, functions, loops, include/use; docs/import.md "OpenSCAD").
//
// How it runs (no shell, no half-written output):
//   - the program: $QUADRIX_OPENSCAD when set (a path, or a name looked up on PATH; set it empty
//     to act as if OpenSCAD were not installed), else `openscad` on PATH;
//   - argv is passed directly (posix_spawn, never a shell), so no path can inject a command; the
//     input is given as an absolute path (a name starting with '-' is not read as an option);
//     standard input is /dev/null;
//   - a private temporary directory (mkdtemp under $TMPDIR or /tmp) receives the CSG output and
//     OpenSCAD's standard output and error; it is removed when the run ends, whatever happened;
//   - a time limit (kDefaultSeconds, or $QUADRIX_OPENSCAD_TIMEOUT seconds): past it the process
//     is killed and the run fails;
//   - the run fails when OpenSCAD exits non-zero, is killed by a signal, prints an "ERROR:" line
//     (2021.01 exits 0 after a failed assert(), writing an empty CSG file) or writes no output;
//   - every ERROR/WARNING/DEPRECATED line it prints becomes a diagnostic at its "in file F,
//     line N" position (mapped to the user's spelling of the path when F is the input), ECHO
//     lines become notes; when a failure prints no such line, the end of its standard error is
//     quoted in the error.
// An input that is not a regular file (a FIFO, process substitution) was already read once:
// that text is written into the temporary directory and OpenSCAD reads the copy (include/use
// relative to it then cannot be found, which OpenSCAD reports).
#pragma once

#include <string>
#include <string_view>

#include "quadrix/scene/diagnostics.h"

namespace quadrix::import::scad {

inline constexpr double kDefaultSeconds = 60;

// The program to run: an executable path, or empty when OpenSCAD is not available.
std::string FindOpenScad();

// Evaluates `path` (whose contents are `text`) with `program`. On success returns true with
// the CSG text in `csg`; on failure adds errors to diags and returns false. Warnings and echoes
// are added either way.
bool EvaluateWithOpenScad(const std::string& program, const std::string& path,
                          std::string_view text, std::string& csg, Diagnostics& diags);

}  // namespace quadrix::import::scad
