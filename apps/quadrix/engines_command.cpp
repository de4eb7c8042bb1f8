// `quadrix engines [--markdown]`: the engine registry (engines/registry.h) — every engine, what
// it draws and its options, from the same rows as `quadrix render --help`. --markdown prints
// docs/engines.md (a test checks that the checked-in page is this output).
#include <cstdio>

#include "commands.h"
#include "quadrix/engines/registry.h"

namespace quadrix::cli {

void AddEnginesCommand(CLI::App& app, bool& markdown) {
    CLI::App* cmd = app.add_subcommand("engines", "List the engines and their options");
    cmd->add_flag("--markdown", markdown, "Print docs/engines.md");
}

int RunEngines(bool markdown) {
    std::fputs((markdown ? EnginesMarkdownPage() : EnginesHelp()).c_str(), stdout);
    return 0;
}

}  // namespace quadrix::cli
