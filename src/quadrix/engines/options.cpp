#include "quadrix/engines/options.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "quadrix/util/check.h"

namespace quadrix {

namespace {

const char* TypeName(OptionSpec::Type t) {
    switch (t) {
        case OptionSpec::Type::kBool:
            return "on|off";
        case OptionSpec::Type::kInt:
            return "integer";
        case OptionSpec::Type::kNumber:
            return "number";
        case OptionSpec::Type::kChoice:
            return "choice";
    }
    return "?";
}

std::string Join(const std::vector<std::string>& items, std::string_view sep) {
    std::string s;
    for (const auto& i : items) s += (s.empty() ? "" : std::string(sep)) + i;
    return s;
}

std::string Names(const OptionSchema& schema) {
    std::vector<std::string> n;
    for (const OptionSpec& s : schema) n.push_back(s.name);
    return Join(n, ", ");
}

// What a value of `spec` may be, for messages and help: "on or off", "an integer in 1..4096".
std::string Accepted(const OptionSpec& spec) {
    auto num = [&](double v) {
        return spec.type == OptionSpec::Type::kInt ? fmt::format("{}", static_cast<long long>(v))
                                                   : fmt::format("{:g}", v);
    };
    switch (spec.type) {
        case OptionSpec::Type::kBool:
            return "on or off";
        case OptionSpec::Type::kChoice: {
            if (spec.choices.size() < 2) return Join(spec.choices, "");
            std::vector<std::string> head(spec.choices.begin(), spec.choices.end() - 1);
            return Join(head, ", ") + " or " + spec.choices.back();
        }
        case OptionSpec::Type::kInt:
        case OptionSpec::Type::kNumber: {
            const char* what = spec.allowsAuto                       ? "auto or an integer"
                               : spec.type == OptionSpec::Type::kInt ? "an integer"
                                                                     : "a number";
            const bool lo = std::isfinite(spec.min), hi = std::isfinite(spec.max);
            if (lo && hi && !spec.minExclusive)
                return fmt::format("{} in {}..{}", what, num(spec.min), num(spec.max));
            if (lo && hi) return fmt::format("{} in ({}, {}]", what, num(spec.min), num(spec.max));
            if (lo)
                return fmt::format("{} {} {}", what, spec.minExclusive ? ">" : ">=", num(spec.min));
            if (hi) return fmt::format("{} <= {}", what, num(spec.max));
            return what;
        }
    }
    return {};
}

// Checks one value; fills `v` (text canonical, number); returns false when it does not parse.
bool ParseValue(const OptionSpec& spec, const std::string& text, std::string& canonical,
                double& number) {
    switch (spec.type) {
        case OptionSpec::Type::kBool: {
            bool ok = false;
            bool b = ParseBoolWord(text, &ok);
            if (!ok) return false;
            canonical = b ? "on" : "off";
            number = b ? 1 : 0;
            return true;
        }
        case OptionSpec::Type::kChoice:
            for (const std::string& c : spec.choices)
                if (c == text) {
                    canonical = text;
                    return true;
                }
            return false;
        case OptionSpec::Type::kInt:
        case OptionSpec::Type::kNumber: {
            if (spec.allowsAuto && text == "auto") {
                canonical = text;
                number = 0;
                return true;
            }
            if (text.empty() || text.size() > 64) return false;
            char* end = nullptr;
            errno = 0;
            double d = 0;
            if (spec.type == OptionSpec::Type::kInt) {
                long long n = std::strtoll(text.c_str(), &end, 10);
                if (errno == ERANGE) return false;
                d = static_cast<double>(n);
            } else {
                d = std::strtod(text.c_str(), &end);
                if (!std::isfinite(d)) return false;
            }
            if (*end != '\0') return false;
            if (d < spec.min || d > spec.max || (spec.minExclusive && d <= spec.min)) return false;
            canonical = text;
            number = d;
            return true;
        }
    }
    return false;
}

}  // namespace

OptionSpec OptionSpec::Bool(std::string name, std::string defaultValue, std::string help) {
    OptionSpec o;
    o.name = std::move(name);
    o.type = Type::kBool;
    o.defaultValue = std::move(defaultValue);
    o.help = std::move(help);
    return o;
}

OptionSpec OptionSpec::Int(std::string name, std::string defaultValue, double min, double max,
                           std::string help) {
    OptionSpec o = Bool(std::move(name), std::move(defaultValue), std::move(help));
    o.type = Type::kInt;
    o.min = min;
    o.max = max;
    return o;
}

OptionSpec OptionSpec::Number(std::string name, std::string defaultValue, double min, double max,
                              bool minExclusive, std::string help) {
    OptionSpec o = Int(std::move(name), std::move(defaultValue), min, max, std::move(help));
    o.type = Type::kNumber;
    o.minExclusive = minExclusive;
    return o;
}

OptionSpec OptionSpec::Choice(std::string name, std::string defaultValue,
                              std::vector<std::string> choices, std::string help) {
    OptionSpec o = Bool(std::move(name), std::move(defaultValue), std::move(help));
    o.type = Type::kChoice;
    o.choices = std::move(choices);
    return o;
}

bool ParseBoolWord(std::string_view text, bool* ok) {
    if (ok) *ok = true;
    if (text == "on" || text == "true" || text == "yes" || text == "1") return true;
    if (text == "off" || text == "false" || text == "no" || text == "0") return false;
    if (ok) *ok = false;
    return false;
}

std::string ParseEngineOptions(std::string_view engine, const OptionSchema& schema,
                               const std::map<std::string, std::string>& raw, EngineOptions& out) {
    out.values_.clear();
    for (const OptionSpec& spec : schema) {
        EngineOptions::Value v;
        v.spec = &spec;
        if (!spec.defaultValue.empty()) {
            const bool ok = ParseValue(spec, spec.defaultValue, v.text, v.number);
            QUADRIX_CHECK(ok, "engine '{}': default '{}' of option '{}' does not fit its schema",
                          engine, spec.defaultValue, spec.name);
        }
        out.values_.push_back(std::move(v));
    }
    for (const auto& [key, text] : raw) {
        EngineOptions::Value* v = nullptr;
        for (auto& candidate : out.values_)
            if (candidate.spec->name == key) v = &candidate;
        if (!v) {
            if (schema.empty())
                return fmt::format("engine '{}' has no options (given '{}')", engine, key);
            return fmt::format("engine '{}' has no option '{}' (options: {})", engine, key,
                               Names(schema));
        }
        if (!ParseValue(*v->spec, text, v->text, v->number))
            return fmt::format("engine '{}': option '{}' must be {}, not '{}'", engine, key,
                               Accepted(*v->spec), text);
        v->given = true;
    }
    return {};
}

const EngineOptions::Value& EngineOptions::Find(std::string_view name,
                                                OptionSpec::Type type) const {
    for (const Value& v : values_)
        if (v.spec->name == name) {
            QUADRIX_CHECK(v.spec->type == type, "option '{}' read as {} but declared {}", name,
                          TypeName(type), TypeName(v.spec->type));
            return v;
        }
    QUADRIX_CHECK(false, "option '{}' is not in the engine's schema (or options were not parsed)",
                  name);
    std::abort();
}

bool EngineOptions::Bool(std::string_view name) const {
    return Find(name, OptionSpec::Type::kBool).number != 0;
}
int EngineOptions::Int(std::string_view name) const {
    return static_cast<int>(Find(name, OptionSpec::Type::kInt).number);
}
double EngineOptions::Number(std::string_view name) const {
    return Find(name, OptionSpec::Type::kNumber).number;
}
const std::string& EngineOptions::Choice(std::string_view name) const {
    return Find(name, OptionSpec::Type::kChoice).text;
}
bool EngineOptions::Given(std::string_view name) const {
    for (const Value& v : values_)
        if (v.spec->name == name) return v.given;
    return false;
}

std::string EngineOptions::Summary() const {
    std::string s;
    for (const Value& v : values_)
        s += fmt::format("{}{}={}", s.empty() ? "" : " ", v.spec->name,
                         v.text.empty() ? "(auto)" : v.text);
    return s;
}

std::string FormatOptionsHelp(const OptionSchema& schema, std::string_view indent) {
    std::string s;
    for (const OptionSpec& o : schema)
        s += fmt::format("{}{}={} (default {}): {}\n", indent, o.name, Accepted(o),
                         o.defaultValue.empty() ? "auto" : o.defaultValue, o.help);
    return s;
}

std::string FormatOptionsMarkdown(const OptionSchema& schema) {
    std::string s = "| option | values | default | what it does |\n|---|---|---|---|\n";
    for (const OptionSpec& o : schema)
        s += fmt::format("| `{}` | {} | {} | {} |\n", o.name, Accepted(o),
                         o.defaultValue.empty() ? "auto" : "`" + o.defaultValue + "`", o.help);
    return s;
}

}  // namespace quadrix
