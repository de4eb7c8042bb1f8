// The property every input of the language reader must have, shared by the libFuzzer target
// (reader_fuzzer.cpp) and the corpus replay in the ordinary suite (tests/fuzz_reader_test.cpp):
//
//   - reading returns (no crash, no hang, no exception escapes);
//   - Reader::ReadText reports failure exactly when an error was added;
//   - every error has a position (file, line, column) and formats;
//   - whatever was read is a consistent Scene: every index points into its vector.
//
// The check returns a description of the first violation, or an empty string.
#pragma once

#include <string>
#include <string_view>

#include "quadrix/lang/reader.h"

namespace quadrix::fuzz {

// Stops reading at every seventh interactive command, so `quit` and friends are exercised both
// ways.
class FuzzCommandHandler : public lang::CommandHandler {
  public:
    bool OnCommand(const lang::Command&, scene::Scene&, Diagnostics&) override {
        return ++count_ % 7 != 0;
    }

  private:
    int count_ = 0;
};

inline std::string CheckScope(const scene::Scene& scene, const scene::Scope& sc) {
    const int halfSpaces = static_cast<int>(sc.halfSpaces.size());
    for (const scene::Body& b : sc.bodies) {
        if (b.literals.empty()) return "body '" + b.id + "' has no literal";
        for (const scene::Literal& l : b.literals)
            if (l.halfSpace < 0 || l.halfSpace >= halfSpaces)
                return "body '" + b.id + "' names half-space index out of range";
    }
    for (const scene::Instance& i : sc.instances)
        if (i.definition < 0 || i.definition >= static_cast<int>(scene.definitions.size()))
            return "instance '" + i.id + "' names a definition index out of range";
    for (const scene::Csg& c : sc.csgs) {
        const int n = static_cast<int>(c.nodes.size());
        if (c.root < 0 || c.root >= n) return "csg '" + c.id + "' root out of range";
        for (const scene::CsgNode& node : c.nodes) {
            if (!node.isLeaf) {
                if (node.left < 0 || node.left >= n || node.right < 0 || node.right >= n)
                    return "csg '" + c.id + "' child out of range";
                continue;
            }
            int size = node.ref.kind == scene::SolidRef::Kind::kBody
                           ? static_cast<int>(sc.bodies.size())
                       : node.ref.kind == scene::SolidRef::Kind::kInstance
                           ? static_cast<int>(sc.instances.size())
                           : static_cast<int>(sc.csgs.size());
            if (node.ref.index < 0 || node.ref.index >= size)
                return "csg '" + c.id + "' operand out of range";
        }
    }
    return {};
}

inline std::string CheckReaderInput(std::string_view text, const std::string& name,
                                    bool withHandler) {
    scene::Scene scene;
    Diagnostics diags;
    FuzzCommandHandler handler;
    lang::ReadOptions options;
    if (withHandler) options.commands = &handler;
    lang::Reader reader(scene, diags, options);
    bool ok = reader.ReadText(text, name);
    if (ok == diags.HasErrors()) return "ReadText's result disagrees with the diagnostics";
    for (const Diagnostic& d : diags.Items()) {
        if (d.severity != Diagnostic::Severity::kError) continue;
        if (!d.loc.file || d.loc.line <= 0 || d.loc.column <= 0)
            return "error without a position: " + d.message;
        if (d.Format().empty()) return "error formats to nothing";
    }
    if (auto e = CheckScope(scene, scene.top); !e.empty()) return e;
    for (const scene::Scope& d : scene.definitions)
        if (auto e = CheckScope(scene, d); !e.empty()) return "definition " + d.id + ": " + e;
    return {};
}

}  // namespace quadrix::fuzz
