// Engine counters, declared once (issue 16 item 4; the idea of pbrt-v4's util/stats.h, our code).
//
// Each engine keeps one list of its counters, written as an X-macro of rows
//     X(id, "name", "what it counts")
// From that one list come the engine's enum of counter ids (QUADRIX_COUNTER_ID), the declaration
// table the registry row points to (QUADRIX_COUNTER_DECL; engines/registry.h: `quadrix engines`,
// docs/engines.md and the all-engines test read it) and the recording: the engine sets values by
// id in a CounterValues and appends them to RenderStats::counters in the list's order. A name that
// is not declared cannot be reported, and a declared counter has its meaning next to its name.
//
// Values that are not set are not reported (an engine reports some counters only in some modes,
// as pixelpowers does in its approximate mode).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace quadrix {

struct CounterDecl {
    const char* name;     // as in --stats and --stats --json
    const char* meaning;  // one line for docs/engines.md and `quadrix engines`
};

// X-macro helpers: QUADRIX_X_COUNTERS(QUADRIX_COUNTER_ID) makes enumerators, and
// QUADRIX_X_COUNTERS(QUADRIX_COUNTER_DECL) the rows of a CounterDecl array.
#define QUADRIX_COUNTER_ID(id, name, meaning) id,
#define QUADRIX_COUNTER_DECL(id, name, meaning) ::quadrix::CounterDecl{name, meaning},

// The values of one render for a declared list.
class CounterValues {
  public:
    explicit CounterValues(std::span<const CounterDecl> decls)
        : decls_(decls), values_(decls.size(), 0.0), set_(decls.size(), 0) {}

    template <class T>
    requires std::is_arithmetic_v<T>
    void Set(std::size_t id, T value) {
        values_[id] = static_cast<double>(value);
        set_[id] = 1;
    }

    // Appends (name, value) of every set counter, in the declared order.
    void AppendTo(std::vector<std::pair<std::string, double>>& out) const {
        for (std::size_t i = 0; i < decls_.size(); ++i)
            if (set_[i]) out.emplace_back(decls_[i].name, values_[i]);
    }

  private:
    std::span<const CounterDecl> decls_;
    std::vector<double> values_;
    std::vector<char> set_;
};

// Whether `name` is one of `decls` (the all-engines test checks every reported counter).
inline bool IsDeclared(std::span<const CounterDecl> decls, std::string_view name) {
    for (const CounterDecl& d : decls)
        if (name == d.name) return true;
    return false;
}

}  // namespace quadrix
