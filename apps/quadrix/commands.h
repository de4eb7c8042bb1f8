// Subcommands of the quadrix tool.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace quadrix::cli {

struct RenderArgs {
    std::vector<std::string> scenes;
    std::string output;
    std::string size = "512x512";
    std::string view;
    std::string engine = "raycast";
    bool fast = false;
    bool stats = false;
    int threads = 0;
    std::string dumpFrame;
    std::vector<std::string> engineOptions;  // key=value
};
void AddRenderCommand(CLI::App& app, RenderArgs& args);
int RunRender(const RenderArgs& args);

struct ExportArgs {
    std::vector<std::string> scenes;
    std::string to = "pov";
    std::string output;
    std::string size = "512x512";
    std::string view;
    bool mask = false;
};
void AddExportCommand(CLI::App& app, ExportArgs& args);
int RunExport(const ExportArgs& args);

// "WxH" → width, height; returns an error message or empty.
std::string ParseSize(const std::string& text, int& width, int& height);

}  // namespace quadrix::cli
