// Helpers shared by the reader's unit tests (not part of the library).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "quadrix/lang/reader.h"

namespace quadrix::lang::testing {

// The result of reading one text.
struct Parsed {
    scene::Scene scene;
    Diagnostics diags;
    bool ok = false;

    std::vector<const Diagnostic*> Errors() const {
        std::vector<const Diagnostic*> v;
        for (const Diagnostic& d : diags.Items())
            if (d.severity == Diagnostic::Severity::kError) v.push_back(&d);
        return v;
    }
    std::vector<const Diagnostic*> Warnings() const {
        std::vector<const Diagnostic*> v;
        for (const Diagnostic& d : diags.Items())
            if (d.severity == Diagnostic::Severity::kWarning) v.push_back(&d);
        return v;
    }
    // Every diagnostic, formatted, for failure messages.
    std::string All() const {
        std::string s;
        for (const Diagnostic& d : diags.Items()) s += d.Format() + "\n";
        return s;
    }
};

inline Parsed Parse(const std::string& text, ReadOptions options = {},
                    const std::string& name = "test.uq") {
    Parsed r;
    Reader reader(r.scene, r.diags, options);
    r.ok = reader.ReadText(text, name);
    return r;
}

// A fresh temporary directory, removed at the end of the test.
class TempDir {
  public:
    TempDir() {
        auto base = std::filesystem::temp_directory_path();
        for (int i = 0;; ++i) {
            path_ = base /
                    ("quadrix_lang_test_" + std::to_string(::getpid()) + "_" + std::to_string(i));
            if (std::filesystem::create_directory(path_)) break;
        }
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& Path() const { return path_; }
    std::string Write(const std::string& name, const std::string& text) const {
        auto p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }

  private:
    std::filesystem::path path_;
};

}  // namespace quadrix::lang::testing
