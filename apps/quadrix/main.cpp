// quadrix: the command-line tool. Subcommands live in their own files (render_command.cpp, ...);
// this file only wires them into one CLI11 application.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <new>
#include <stdexcept>

#include "commands.h"

namespace {

int Run(int argc, char** argv) {
    CLI::App app{
        "Quadrix draws solids made of quadric surfaces and planes, and CSG combinations of them,\n"
        "exactly: no tessellation.\n\n"
        "Examples:\n"
        "  quadrix render examples/machined_part.uq -o part.png\n"
        "  quadrix render examples/stack_of_bundles.uq -o stack.png --size 800x600 --fast\n"
        "  quadrix render - -o out.ppm < scene.uq\n"
        "  quadrix export --to pov examples/machined_part.uq -o part.pov\n"
        "  quadrix pipe examples/gallery/hilbert3.pipe -o hilbert3_tubes.uq\n"
        "  quadrix compare --engines scanline,raycast examples/machined_part.uq\n"
        "  quadrix draw examples/machined_part.uq -o part.svg --views front,top,right,iso\n",
        "quadrix"};
    app.set_version_flag("--version", std::string("quadrix ") + QUADRIX_VERSION);
    app.require_subcommand(1);
    app.fallthrough(false);

    quadrix::cli::RenderArgs renderArgs;
    quadrix::cli::AddRenderCommand(app, renderArgs);
    quadrix::cli::ExportArgs exportArgs;
    quadrix::cli::AddExportCommand(app, exportArgs);
    quadrix::cli::AddUqCommand(app);
    quadrix::cli::PipeArgs pipeArgs;
    quadrix::cli::AddPipeCommand(app, pipeArgs);
    quadrix::cli::CompareArgs compareArgs;
    quadrix::cli::AddCompareCommand(app, compareArgs);
    bool enginesMarkdown = false;
    quadrix::cli::AddEnginesCommand(app, enginesMarkdown);
    quadrix::cli::DrawArgs drawArgs;
    quadrix::cli::AddDrawCommand(app, drawArgs);

    if (int uqCode = 0; quadrix::cli::MaybeRunUq(argc, argv, uqCode)) return uqCode;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "quadrix: error: %s\n(run 'quadrix --help' for usage)\n", e.what());
        return 2;
    }
    if (app.got_subcommand("render")) {
        renderArgs.exitWhenDone = true;  // a one-shot process: no freeing pass (render_command)
        return quadrix::cli::RunRender(renderArgs);
    }
    if (app.got_subcommand("export")) return quadrix::cli::RunExport(exportArgs);
    if (app.got_subcommand("pipe")) return quadrix::cli::RunPipe(pipeArgs);
    if (app.got_subcommand("compare")) return quadrix::cli::RunCompare(compareArgs);
    if (app.got_subcommand("engines")) return quadrix::cli::RunEngines(enginesMarkdown);
    if (app.got_subcommand("draw")) return quadrix::cli::RunDraw(drawArgs);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    // Allocation failure anywhere is a clear error with a non-zero exit, not SIGABRT
    // (docs/output.md "Limits"). Output files in the making are removed by their destructors
    // while the exception unwinds.
    try {
        return Run(argc, argv);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr,
                     "quadrix: error: out of memory (the input or image is too large for the "
                     "memory available; see docs/output.md)\n");
        return 1;
    } catch (const std::length_error& e) {
        std::fprintf(stderr, "quadrix: error: out of memory (%s)\n", e.what());
        return 1;
    }
}
