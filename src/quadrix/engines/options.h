// Engine options: one typed schema per engine and one parser for all of them.
//
// Each engine declares its options once, as a list of OptionSpec rows (name, type, default,
// range or choices, one line of help). The user's request (`--engine-opt KEY=VALUE`, repeatable;
// the `engineOptions` map of RenderOptions) is checked against the schema by ParseEngineOptions
// before any work: an unknown key, a value of the wrong type or out of range is an error naming
// the engine, the key and what is accepted. Engines then read typed values (EngineOptions::Bool,
// Int, Number, Choice), never the raw text, so no engine parses on its own.
//
// One boolean vocabulary for every engine: on/off, true/false, yes/no, 1/0 (case-sensitive,
// lower case). The same rows print `quadrix render --help`'s engine section and the table of
// docs/engines.md (FormatOptionsHelp, FormatOptionsMarkdown), so help and docs cannot drift.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace quadrix {

struct OptionSpec {
    enum class Type { kBool, kInt, kNumber, kChoice };
    std::string name;
    Type type = Type::kBool;
    // The default as text ("on", "24", "0.5", "exact"). Empty: "depends", explained in help
    // (the engine reads Given() and picks its own default).
    std::string defaultValue;
    std::string help;
    std::vector<std::string> choices;  // kChoice
    // Inclusive range for kInt/kNumber; kNumber also requires a finite value. minExclusive makes
    // the lower bound strict (a positive number: min 0, minExclusive).
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minExclusive = false;
    // kInt: the word "auto" is accepted too and reads as 0 (e.g. isocurve's base=auto|N).
    bool allowsAuto = false;

    // The rows of a schema, one call each.
    static OptionSpec Bool(std::string name, std::string defaultValue, std::string help);
    static OptionSpec Int(std::string name, std::string defaultValue, double min, double max,
                          std::string help);
    // A finite number in [min, max], or in (min, max] with minExclusive.
    static OptionSpec Number(std::string name, std::string defaultValue, double min, double max,
                             bool minExclusive, std::string help);
    static OptionSpec Choice(std::string name, std::string defaultValue,
                             std::vector<std::string> choices, std::string help);
    OptionSpec&& AllowingAuto() && {
        allowsAuto = true;
        return std::move(*this);
    }
};

using OptionSchema = std::vector<OptionSpec>;

// Typed values of one engine's options: every schema option has a value (the user's or the
// default). Reading a name that is not in the schema is a programming error (a CHECK).
class EngineOptions {
  public:
    bool Bool(std::string_view name) const;
    int Int(std::string_view name) const;
    double Number(std::string_view name) const;
    const std::string& Choice(std::string_view name) const;
    // True when the user set the option (not the default).
    bool Given(std::string_view name) const;
    // Canonical text of every value, in schema order ("batch=on kernel=off"): for --stats.
    std::string Summary() const;

  private:
    friend std::string ParseEngineOptions(std::string_view, const OptionSchema&,
                                          const std::map<std::string, std::string>&,
                                          EngineOptions&);
    struct Value {
        const OptionSpec* spec = nullptr;
        std::string text;  // canonical: "on"/"off" for booleans
        double number = 0;
        bool given = false;
    };
    const Value& Find(std::string_view name, OptionSpec::Type type) const;
    std::vector<Value> values_;
};

// Parses `raw` against `schema`; returns an error message (naming `engine`) or empty.
std::string ParseEngineOptions(std::string_view engine, const OptionSchema& schema,
                               const std::map<std::string, std::string>& raw, EngineOptions& out);

// "on", "true", "yes", "1" → true; "off", "false", "no", "0" → false; false for anything else
// (with *ok = false).
bool ParseBoolWord(std::string_view text, bool* ok);

// The schema as indented help lines (for --help) and as a Markdown table (for docs/).
std::string FormatOptionsHelp(const OptionSchema& schema, std::string_view indent);
std::string FormatOptionsMarkdown(const OptionSchema& schema);

}  // namespace quadrix
