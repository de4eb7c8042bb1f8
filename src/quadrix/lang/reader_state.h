// What the reader remembers across statements and across the files of one Reader: the scope that
// statements add to (the top level or the open definition), the id tables of each scope, the
// global id tables (definitions, lights, views), generated ids and the stack of files being read.
//
// Id namespaces (seed 001 §2.1.3; docs/language.md "Ids"):
//   - per scope: half-spaces (planes and quadrics share one table, since bodies name both),
//     solids (bodies, instances, arrays and CSG solids share one table, since CSG operands name
//     all of them);
//   - global: definitions, lights, views.
// The same id may name one object of each namespace (the paper's `definition tube` holds a
// `body tube`).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "quadrix/lang/id_table.h"
#include "quadrix/lang/reader.h"

namespace quadrix::lang {

class Source;

// The id tables of one scope (id_table.h: the ids stay in the scope's objects). Solids are
// stored as index * 4 + kind.
struct ScopeIndex {
    IdTable halfSpaces;
    IdTable solids;
};

// One file (or text) being read; the stack of them detects cycles and limits nesting (§2.1.7).
struct IncludeFrame {
    std::string key;          // canonical path (cycle detection), "-" for standard input
    std::string displayName;  // as shown in diagnostics
};

class ReaderState {
  public:
    ReaderState(scene::Scene& scene, Diagnostics& diags, ReadOptions options);

    scene::Scene& scene;
    Diagnostics& diags;
    ReadOptions options;

    // --- scopes -----------------------------------------------------------------------------
    bool InDefinition() const { return openDefinition_.has_value(); }
    scene::Scope& CurrentScope();
    // The open definition's source (to require `enddef` in the file that opened it).
    const Source* DefinitionSource() const;
    void OpenDefinition(scene::Scope scope, const Source* source);
    // Moves the open definition into scene.definitions and returns its index.
    int CloseDefinition();

    int FindHalfSpace(const std::string& id) const;
    std::optional<scene::SolidRef> FindSolid(const std::string& id) const;
    SourceLoc SolidLoc(const scene::SolidRef& ref) const;
    // "body", "instance", "array" or "csg solid", for messages.
    std::string SolidKindName(const scene::SolidRef& ref) const;
    // Reports nothing; returns the message for a duplicate solid id, or empty when `id` is free.
    std::string DuplicateSolidMessage(const std::string& id) const;
    // Sets usedAsOperand on the solid `ref` of the current scope.
    void MarkOperand(const scene::SolidRef& ref);

    // Before a big input is parsed: makes room in the current scope for the statements the text
    // appears to hold (counted by the keyword after each ';', comments included, so it is an
    // estimate), so that its arrays are allocated once (big_arrays.h) instead of being moved
    // at each doubling. Nothing for a text under kReserveMinBytes.
    void ReserveForText(std::string_view text);
    static constexpr std::size_t kReserveMinBytes = 256 * 1024;

    int AddHalfSpace(scene::HalfSpace hs);
    int AddBody(scene::Body body);
    int AddInstance(scene::Instance instance);
    int AddCsg(scene::Csg csg);

    // --- global objects ---------------------------------------------------------------------
    int FindDefinition(const std::string& id) const;
    int FindLight(const std::string& id) const;
    int FindView(const std::string& id) const;
    int AddLight(scene::Light light);
    int AddView(scene::View view);

    // An id "<prefix>#<n>" for an object written without one, unused in its namespace: prefix "l"
    // gives l#1, l#2, ... (seed 001 §2.3 session: "warning: id l#1 created").
    enum class Namespace { kHalfSpace, kSolid, kDefinition, kLight, kView };
    std::string GenerateId(const std::string& prefix, Namespace ns);

    // --- reading ----------------------------------------------------------------------------
    std::vector<IncludeFrame> includeStack;
    // Set when reading must stop everywhere (too many errors).
    bool aborted = false;
    // Some number was written with `clock` (number_expression.cpp): the scene depends on it.
    bool usesClock = false;
    // ... outside view statements (the geometry, lights or background depend on it). View
    // parameters are read with viewDepth > 0: a scene whose `clock` is only in its views has
    // the same geometry at every clock (an animated camera), so an animation keeps its world
    // stage (flattener.h) from frame to frame.
    bool usesClockOutsideViews = false;
    int viewDepth = 0;
    // Every view and redef view statement read, as written (Reader::ViewStatements).
    std::vector<ViewStatement> viewStatements;
    // Statements read by this reader, over all its inputs. Beyond kMaxStatements reading stops
    // with a message: an endless generated input must not grow the scene until memory runs out.
    long long statementCount = 0;
    static constexpr long long kMaxStatements = 10'000'000;
    // The `read` fan-out budget (issue 23): files read by read statements, and their bytes, over
    // all inputs of this reader. Eight files that each read the next ten times would read 10⁸
    // files; past either limit reading stops with a message at the read statement.
    long long filesRead = 0, bytesRead = 0;
    static constexpr long long kMaxFilesRead = 10'000;
    static constexpr long long kMaxBytesRead = 1LL << 30;  // 1 GiB (each file: 256 MiB)

  private:
    ScopeIndex& CurrentIndex();
    const ScopeIndex& CurrentIndex() const;
    const scene::Scope& CurrentScopeConst() const;
    bool Taken(const std::string& id, Namespace ns) const;

    struct OpenDef {
        scene::Scope scope;
        ScopeIndex index;
        const Source* source = nullptr;
    };
    std::optional<OpenDef> openDefinition_;
    ScopeIndex topIndex_;
    std::unordered_map<std::string, int> definitions_, lights_, views_;
    std::map<std::string, int> idCounters_;
};

}  // namespace quadrix::lang
