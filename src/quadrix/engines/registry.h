// The engine registry: one row per engine. Adding an engine is one folder under engines/ and one
// row here (or, for a test, one RegisterEngine call): the CLI's --engine, `quadrix render --help`,
// docs/engines.md, the viewer's engine switch and the all-engines test all read this table.
//
// Row: name, one line of help, the factory, the option schema (engines/options.h), the
// capabilities (engines/engine.h) and the declared counters (engines/counters.h). The built-in rows
// are in registry.cpp, in the order they are listed to users; raycast, the exact reference, is
// first.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/engines/counters.h"
#include "quadrix/engines/engine.h"

namespace quadrix {

struct EngineInfo {
    std::string name;
    std::string help;  // one line
    std::function<std::unique_ptr<Engine>()> make;
    EngineCapabilities capabilities;
    // Every counter the engine reports in RenderStats::counters, declared once in the engine's
    // counters.h (engines/counters.h); `quadrix engines` and docs/engines.md list them.
    std::span<const CounterDecl> counters;
    // True for engines that exist for tests and must not be offered to users (dummy engines).
    bool hidden = false;
};

// Every registered engine, built-ins first, then those registered at run time.
const std::vector<EngineInfo>& Engines();
// nullptr when no engine has that name.
const EngineInfo* FindEngine(std::string_view name);
// Adds a row (a test's dummy engine); returns true so that it can initialise a static.
bool RegisterEngine(EngineInfo info);

// "raycast, scanline, ..." of the engines offered to users, for messages.
std::string EngineList();
// The name of the reference engine (raycast): draws what another engine leaves out.
inline constexpr std::string_view kReferenceEngine = "raycast";

// `quadrix render --help`'s engine section and docs/engines.md's option tables, from the rows.
std::string EnginesHelp();
std::string EnginesMarkdown();
// The whole of docs/engines.md: a short introduction, then EnginesMarkdown().
std::string EnginesMarkdownPage();

}  // namespace quadrix
