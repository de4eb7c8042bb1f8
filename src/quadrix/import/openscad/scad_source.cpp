// .scad sources, read directly or evaluated by OpenSCAD; see scad_source.h.
#include "quadrix/import/openscad/scad_source.h"

#include <fmt/format.h>

#include <cctype>
#include <map>
#include <memory>
#include <vector>

#include "quadrix/import/openscad/openscad_import.h"
#include "quadrix/import/openscad/openscad_program.h"
#include "quadrix/import/text_map.h"

namespace quadrix::import {

namespace {

bool IdentChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$';
}

// Offsets of the calls `name (` in OpenSCAD source, by name (comments and strings skipped).
std::map<std::string, std::vector<std::size_t>> CallSites(std::string_view t) {
    std::map<std::string, std::vector<std::size_t>> out;
    std::size_t i = 0;
    while (i < t.size()) {
        if (t.compare(i, 2, "//") == 0) {
            while (i < t.size() && t[i] != '\n') ++i;
        } else if (t.compare(i, 2, "/*") == 0) {
            const std::size_t e = t.find("*/", i + 2);
            i = e == std::string_view::npos ? t.size() : e + 2;
        } else if (t[i] == '"') {
            for (++i; i < t.size() && t[i] != '"'; ++i)
                if (t[i] == '\\') ++i;
            ++i;
        } else if (IdentChar(t[i]) && !std::isdigit(static_cast<unsigned char>(t[i]))) {
            const std::size_t s = i;
            while (i < t.size() && IdentChar(t[i])) ++i;
            std::size_t j = i;
            while (j < t.size() && std::isspace(static_cast<unsigned char>(t[j]))) ++j;
            if (j < t.size() && t[j] == '(') out[std::string(t.substr(s, i - s))].push_back(s);
        } else if (std::isdigit(static_cast<unsigned char>(t[i]))) {
            while (i < t.size() && (IdentChar(t[i]) || t[i] == '.')) ++i;
        } else {
            ++i;
        }
    }
    return out;
}

// Maps positions in OpenSCAD's CSG output back to the .scad source (scad_source.h).
class PositionMap {
  public:
    PositionMap(std::string_view scad, const std::string& path, std::string_view csg,
                const std::string& csgLabel)
        : scadMap_(scad, path), csg_(csg), csgLabel_(csgLabel), calls_(CallSites(scad)) {
        path_ = std::make_shared<const std::string>(path);
        lineStarts_.push_back(0);
        for (std::size_t k = 0; k < csg.size(); ++k)
            if (csg[k] == '\n') lineStarts_.push_back(k + 1);
    }

    bool FromCsg(const SourceLoc& loc) const { return loc.file && *loc.file == csgLabel_; }

    struct Mapped {
        SourceLoc loc;
        std::string sourceLine;
        std::string name;  // the statement's name at the CSG position
        std::string note;  // empty when mapped to one call
    };

    Mapped Map(const SourceLoc& loc) const {
        Mapped m;
        m.loc.file = path_;
        if (loc.line < 1 || loc.line > static_cast<int>(lineStarts_.size())) {
            m.note = "(evaluated by OpenSCAD)";
            return m;
        }
        const std::size_t ls = lineStarts_[static_cast<std::size_t>(loc.line) - 1];
        std::size_t le = csg_.find('\n', ls);
        if (le == std::string_view::npos) le = csg_.size();
        // OpenSCAD writes one statement per line, its name first (after indentation and a
        // modifier): the name of the statement, whichever column the diagnostic points at.
        std::size_t p = ls;
        while (p < le && !IdentChar(csg_[p])) ++p;
        std::size_t q = p;
        while (q < le && IdentChar(csg_[q])) ++q;
        m.name = std::string(csg_.substr(p, q - p));
        std::string_view text = csg_.substr(ls, le - ls);
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
            text.remove_prefix(1);
        auto it = calls_.find(m.name);
        if (it != calls_.end() && it->second.size() == 1) {
            m.loc = scadMap_.At(it->second[0]);
            m.sourceLine = scadMap_.LineText(it->second[0]);
            return m;
        }
        std::string csgText(text.substr(0, 60));
        if (text.size() > 60) csgText += "...";
        std::string where;
        if (it == calls_.end() || m.name.empty()) {
            where = fmt::format("'{}' is not called in the file itself", m.name);
        } else {
            std::string lines;
            for (std::size_t k = 0; k < it->second.size() && k < 8; ++k)
                lines += (k ? ", " : "") + std::to_string(scadMap_.At(it->second[k]).line);
            if (it->second.size() > 8) lines += ", ...";
            where = fmt::format("'{}' is called at lines {}", m.name, lines);
        }
        m.note =
            fmt::format("(evaluated by OpenSCAD: CSG line {} '{}'; {})", loc.line, csgText, where);
        return m;
    }

    // A scene element's location and "name@line" id.
    void Relocate(SourceLoc& loc, std::string* id) const {
        if (!FromCsg(loc)) return;
        const Mapped m = Map(loc);
        if (id) {
            const std::size_t at = id->rfind('@');
            if (at != std::string::npos)
                *id = id->substr(0, at + 1) + (m.note.empty() ? std::to_string(m.loc.line)
                                                              : "csg" + std::to_string(loc.line));
        }
        loc = m.loc;
    }

  private:
    TextMap scadMap_;
    std::string_view csg_;
    std::string csgLabel_;
    std::map<std::string, std::vector<std::size_t>> calls_;
    std::shared_ptr<const std::string> path_;
    std::vector<std::size_t> lineStarts_;
};

}  // namespace

bool ImportScadSource(std::string_view text, const std::string& path, const ImportOptions& options,
                      scene::Scene& scene, Diagnostics& diags, ImportReport& report) {
    Diagnostics parse;
    if (ParsesAsOpenScadSubset(text, path, parse))
        return ImportOpenScad(text, path, options, scene, diags, report);

    const std::string program = scad::FindOpenScad();
    if (program.empty()) {
        for (const Diagnostic& d : parse.Items()) diags.Add(d);
        diags.Error(
            [&] {
                SourceLoc l;
                l.file = std::make_shared<const std::string>(path);
                return l;
            }(),
            fmt::format("'{}' uses the OpenSCAD language beyond the literal CSG subset Quadrix "
                        "reads itself; install OpenSCAD (apt-get install openscad) and Quadrix "
                        "evaluates it with 'openscad -o model.csg' (docs/import.md)",
                        path),
            {}, "input");
        return false;
    }
    std::string csg;
    if (!scad::EvaluateWithOpenScad(program, path, text, csg, diags)) return false;

    const std::string label = path + " (as evaluated by OpenSCAD)";
    const PositionMap map(text, path, csg, label);
    const std::size_t hs0 = scene.top.halfSpaces.size(), b0 = scene.top.bodies.size(),
                      c0 = scene.top.csgs.size();
    Diagnostics inner;
    const bool ok = ImportOpenScad(csg, label, options, scene, inner, report);
    report.format = "OpenSCAD (evaluated by openscad)";
    for (Diagnostic d : inner.Items()) {
        if (map.FromCsg(d.loc)) {
            PositionMap::Mapped m = map.Map(d.loc);
            d.loc = m.loc;
            d.sourceLine = m.sourceLine;
            if (!m.note.empty()) d.message += " " + m.note;
        }
        diags.Add(std::move(d));
    }
    for (std::size_t k = hs0; k < scene.top.halfSpaces.size(); ++k)
        map.Relocate(scene.top.halfSpaces[k].loc, nullptr);
    std::map<std::string, std::string> ids;  // a solid's bodies carry the solid's id
    for (std::size_t k = c0; k < scene.top.csgs.size(); ++k) {
        scene::Csg& c = scene.top.csgs[k];
        const std::string old = c.id;
        map.Relocate(c.loc, &c.id);
        ids[old] = c.id;
        for (scene::CsgNode& n : c.nodes) map.Relocate(n.loc, nullptr);
    }
    for (std::size_t k = b0; k < scene.top.bodies.size(); ++k) {
        scene::Body& b = scene.top.bodies[k];
        if (auto it = ids.find(b.id); it != ids.end()) b.id = it->second;
        map.Relocate(b.loc, nullptr);
    }
    return ok && !inner.HasErrors();
}

}  // namespace quadrix::import
