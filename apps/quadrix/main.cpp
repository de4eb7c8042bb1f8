// quadrix: the command-line tool. Subcommands live in their own files (render_command.cpp, ...);
// this file only wires them into one CLI11 application.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "commands.h"
#include "quadrix/engines/engine_limit.h"
#include "quadrix/io/phase_times.h"
#include "quadrix/util/heap_huge_pages.h"

namespace {

// Levenshtein distance, for "did you mean" (short words: the quadratic table is nothing).
std::size_t EditDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

std::vector<std::string> SubcommandNames(CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        names.push_back(sub->get_name());
    return names;
}

// `quadrix WORD` where WORD is no subcommand: the closest names, and where to look.
int UnknownSubcommand(CLI::App& app, const std::string& word) {
    std::string best;
    std::size_t bestDistance = 3;  // at most two edits away (or a prefix)
    for (const std::string& name : SubcommandNames(app)) {
        std::size_t d = name.rfind(word, 0) == 0 ? 1 : EditDistance(word, name);
        if (d < bestDistance) {
            bestDistance = d;
            best = name;
        }
    }
    std::string names;
    for (const std::string& name : SubcommandNames(app)) names += " " + name;
    std::fprintf(stderr, "quadrix: error: unknown subcommand '%s'", word.c_str());
    if (!best.empty()) std::fprintf(stderr, "; did you mean '%s'?", best.c_str());
    std::fprintf(stderr, "\nsubcommands:%s\n(run 'quadrix help' or 'quadrix help SUBCOMMAND')\n",
                 names.c_str());
    return 2;
}

// `quadrix help [SUBCOMMAND]`: the same text as --help.
int RunHelp(CLI::App& app, const std::string& topic) {
    if (topic.empty()) {
        // Not app.help(): after parsing it describes the selected subcommand (help itself).
        std::fputs(
            app.get_formatter()->make_help(&app, "quadrix", CLI::AppFormatMode::Normal).c_str(),
            stdout);
        return 0;
    }
    if (topic == "uq" || topic == "-i") {
        quadrix::cli::PrintUqUsage(stdout);
        return 0;
    }
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        if (sub->get_name() == topic) {
            std::fputs(sub->help().c_str(), stdout);
            return 0;
        }
    return UnknownSubcommand(app, topic);
}

int Run(int argc, char** argv) {
    CLI::App app{
        "Quadrix draws solids made of quadric surfaces and planes, and CSG combinations of them,\n"
        "exactly: no tessellation.\n\n"
        "Examples:\n"
        "  quadrix render examples/machined_part.uq -o part.png\n"
        "  quadrix render examples/stack_of_bundles.uq -o stack.png --size 800x600 --fast\n"
        "  quadrix render - -o out.ppm < scene.uq\n"
        "  quadrix render examples/machined_part.uq -o part.exr   (image + depth, normal, ids)\n"
        "  quadrix render examples/machined_part.uq --format ppm -o - | display\n"
        "  quadrix export --to pov examples/machined_part.uq -o part.pov\n"
        "  quadrix pipe examples/gallery/hilbert3.pipe -o hilbert3_tubes.uq\n"
        "  quadrix compare --engines scanline,raycast examples/machined_part.uq\n"
        "  quadrix draw examples/machined_part.uq -o part.svg --views front,top,right,iso\n",
        "quadrix"};
    app.set_version_flag("--version", std::string("quadrix ") + QUADRIX_VERSION);
    app.require_subcommand(1);
    app.fallthrough(false);

    // The subcommands, in the order `quadrix --help` lists them. A command line that names one
    // (other than help and man, which describe the others) builds only that one: CLI11's tables
    // of every subcommand's options were about 1 ms of each process (docs/performance.md).
    quadrix::cli::RenderArgs renderArgs;
    quadrix::cli::ExportArgs exportArgs;
    quadrix::cli::PipeArgs pipeArgs;
    quadrix::cli::CompareArgs compareArgs;
    bool enginesMarkdown = false;
    quadrix::cli::DrawArgs drawArgs;
    std::string helpTopic;
    quadrix::cli::ManArgs manArgs;
    quadrix::cli::BatchArgs batchArgs;
    quadrix::cli::ViewArgs viewArgs;
    const std::pair<const char*, std::function<void()>> subcommands[] = {
        {"render", [&] { quadrix::cli::AddRenderCommand(app, renderArgs); }},
        {"export", [&] { quadrix::cli::AddExportCommand(app, exportArgs); }},
        {"uq", [&] { quadrix::cli::AddUqCommand(app); }},
        {"pipe", [&] { quadrix::cli::AddPipeCommand(app, pipeArgs); }},
        {"compare", [&] { quadrix::cli::AddCompareCommand(app, compareArgs); }},
        {"engines", [&] { quadrix::cli::AddEnginesCommand(app, enginesMarkdown); }},
        {"draw", [&] { quadrix::cli::AddDrawCommand(app, drawArgs); }},
        {"help",
         [&] {
             app.add_subcommand("help", "Print this text, or the options of one subcommand")
                 ->add_option("subcommand", helpTopic, "The subcommand to describe");
         }},
        {"man", [&] { quadrix::cli::AddManCommand(app, manArgs); }},
        {"batch", [&] { quadrix::cli::AddBatchCommand(app, batchArgs); }},
        {"view", [&] { quadrix::cli::AddViewCommand(app, viewArgs); }},
    };
    const std::string_view named = argc >= 2 ? argv[1] : "";
    const bool justOne = named != "help" && named != "man" &&
                         std::any_of(std::begin(subcommands), std::end(subcommands),
                                     [&](const auto& s) { return named == s.first; });
    for (const auto& [name, add] : subcommands) {
        // The subcommands made after it inherit the footer (man, batch, view).
        if (std::string_view(name) == "man")
            app.footer(
                "Exit status: 0 success, 1 an error in the scene or input (or a failed output), 2 "
                "a usage error (unknown subcommand, option, engine or bad option value); see "
                "docs/cli.md.");
        if (!justOne || named == name) add();
    }
    // Every subcommand answers --version (docs/cli.md), and exit codes follow docs/cli.md.
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        sub->set_version_flag("--version", std::string("quadrix ") + QUADRIX_VERSION);

    if (int uqCode = 0; quadrix::cli::MaybeRunUq(argc, argv, uqCode)) return uqCode;
    if (argc >= 2 && argv[1][0] != '-') {
        const std::string first = argv[1];
        const std::vector<std::string> names = SubcommandNames(app);
        if (std::find(names.begin(), names.end(), first) == names.end())
            return UnknownSubcommand(app, first);
    }
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
    // The subcommand parsed (by name: got_subcommand would throw for one not built).
    const std::vector<CLI::App*> parsed = app.get_subcommands();
    const std::string got = parsed.empty() ? std::string() : parsed.front()->get_name();
    if (got == "render") {
        renderArgs.exitWhenDone = true;  // a one-shot process: no freeing pass (render_command)
        return quadrix::cli::RunRender(renderArgs);
    }
    if (got == "export") return quadrix::cli::RunExport(exportArgs);
    if (got == "pipe") return quadrix::cli::RunPipe(pipeArgs);
    if (got == "compare") return quadrix::cli::RunCompare(compareArgs);
    if (got == "engines") return quadrix::cli::RunEngines(enginesMarkdown);
    if (got == "draw") return quadrix::cli::RunDraw(drawArgs);
    if (got == "help") return RunHelp(app, helpTopic);
    if (got == "man") return quadrix::cli::RunMan(app, manArgs);
    if (got == "batch") return quadrix::cli::RunBatch(batchArgs);
    if (got == "view") return quadrix::cli::RunView(viewArgs);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    quadrix::MarkPhase("main");  // io/phase_times.h (QUADRIX_PHASE_TIMES)
    // The heap in transparent huge pages (util/heap_huge_pages.h): a 1280x720 render made
    // ~5,800 page faults, ~1,450 with it. QUADRIX_HEAP_PAGES=small leaves the heap as it was
    // (to measure the difference).
    if (const char* e = std::getenv("QUADRIX_HEAP_PAGES"); !e || std::string(e) != "small")
        quadrix::UseHugePagesForTheHeap(std::size_t{256} << 20);
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
    } catch (const quadrix::EngineLimitError& e) {
        // A complexity guard outside the render context's own catch: the shading budget
        // (shade/shade_budget.h). No picture is written; temporaries are removed on unwinding.
        std::fprintf(stderr, "quadrix: error: %s\n", e.what());
        return 1;
    } catch (const std::length_error& e) {
        std::fprintf(stderr, "quadrix: error: out of memory (%s)\n", e.what());
        return 1;
    }
}
