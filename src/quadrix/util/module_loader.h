// Loading Quadrix's optional modules: shared objects that hold the code linked with a large
// third-party library that most commands never use.
//
// A process that starts pays for every shared library it is linked with: the dynamic loader
// maps, relocates and initialises each one before main. Cairo (PDF and EPS drawings), OpenEXR
// (.exr output) and Open MPI (`mpirun quadrix batch`) bring about 30 libraries between them and
// cost every quadrix process about 9 ms of start-up on the test machines, for output formats and
// a launcher most runs never use (docs/performance.md "Page faults and start-up"). Each is
// therefore a module of its own (modules/<name>/, one folder per library, built as
// quadrix-<name>.so), loaded with dlopen the first time a command needs it, like the window of
// `quadrix view` (quadrix-view.so) and the line editor of the `uq>` prompt (quadrix-lineedit.so,
// apps/quadrix/line_edit_module.h; libedit and three more libraries, 0.2 ms of every start).
//
// The modules are self-contained: each links its library and the C++ runtime only, and exchanges
// plain data with Quadrix through the table of functions its interface header declares
// (draw/cairo_module.h, io/exr_module.h, batch/mpi_module.h). Targets that would rather link the
// library than load a module (the shared library of the public API, the Python module, the tests)
// link the module's source directly (CMake target quadrix_modules_linked); its table is then found
// without dlopen, through a weak reference (see QUADRIX_LINKED_MODULE in the module headers).
//
// Where a module is looked for: in $QUADRIX_MODULE_DIR alone when it is set, else in order (the
// first file that exists is loaded):
//   1. the directory of the object that holds this code (the program, libquadrix.so or the
//      Python module; dladdr), which is where the build tree puts the modules next to quadrix;
//   2. that directory + QUADRIX_MODULE_DIR_FROM_BIN (CMake: the relative path from <bindir> to
//      <libdir>/quadrix, for an installed program), and that directory + "/quadrix" (for an
//      installed libquadrix.so in <libdir>);
//   3. QUADRIX_MODULE_DIR_INSTALLED (CMake: <libdir>/quadrix, absolute), then
//      QUADRIX_MODULE_DIR_BUILD (the build tree's module directory) when it exists.
#pragma once

#include <string>

namespace quadrix {

// The address of `symbol` in module `file` (e.g. "quadrix-cairo.so"), loading the module on
// first use (thread-safe; a module is loaded once and never unloaded). Null when the module is
// missing or cannot be loaded or lacks the symbol; then `*error` says which and why, naming the
// places looked in.
void* LoadModuleSymbol(const char* file, const char* symbol, std::string* error);

// The directories LoadModuleSymbol looks in, in order (for messages and tests).
std::string ModuleSearchPath();

}  // namespace quadrix
