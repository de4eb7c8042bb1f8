// The input dispatcher; see inputs.h.
#include "quadrix/pipeline/inputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include "quadrix/import/brlcad/readers.h"
#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/import/model_space.h"
#include "quadrix/import/openscad/openscad_import.h"
#include "quadrix/import/openscad/scad_source.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/lang/reader.h"

namespace quadrix {

namespace {

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

SourceLoc FileLoc(const std::string& path) {
    SourceLoc loc;
    loc.file = std::make_shared<const std::string>(path);
    return loc;
}

}  // namespace

InputFormat DetectInputFormat(const std::string& path, std::string_view text) {
    std::string p = Lower(path);
    if (EndsWith(p, ".uq")) return InputFormat::kUniQuadrix;
    for (const char* ext : {".asc", ".g-ascii", ".comgeom", ".cg", ".g"})
        if (EndsWith(p, ext)) return InputFormat::kBrlcad;
    for (const char* ext : {".csg", ".scad"})
        if (EndsWith(p, ext)) return InputFormat::kOpenScad;
    for (const char* ext : {".obj", ".bpt", ".bez", ".bbp", ".teaset"})
        if (EndsWith(p, ext)) return InputFormat::kFreeform;
    if (import::brlcad::DetectFormat(text) == import::brlcad::TextFormat::kV4 ||
        import::brlcad::IsV5Binary(text))
        return InputFormat::kBrlcad;
    return InputFormat::kUniQuadrix;
}

bool ReadSceneInputs(const std::vector<std::string>& paths, const InputOptions& options,
                     scene::Scene& scene, Diagnostics& diags, InputReport& report) {
    std::unique_ptr<lang::Reader> uq;  // one reader for every .uq file, as before importers
    auto uqReader = [&]() -> lang::Reader& {
        if (!uq) {
            lang::ReadOptions ro;
            ro.clock = options.clock;
            uq = std::make_unique<lang::Reader>(scene, diags, ro);
        }
        return *uq;
    };
    for (const std::string& path : paths) {
        if (path == "-") {
            uqReader().ReadFile(path);
            continue;
        }
        // Every format through the bounded reader (io/bounded_read.h), read once: a FIFO or
        // process substitution cannot be read twice.
        std::string text;
        if (std::string why = ReadBoundedFile(path, text); !why.empty()) {
            diags.Error(FileLoc(path), fmt::format("cannot read '{}': {}", path, why), {}, "input");
            continue;
        }
        switch (DetectInputFormat(path, text)) {
            case InputFormat::kUniQuadrix:
                uqReader().ReadText(text, path);
                break;
            case InputFormat::kBrlcad: {
                ImportReport r;
                import::ImportBrlcad(text, path, options.import, scene, diags, r);
                report.importedBounds.Extend(r.bounds);
                report.imports.emplace_back(path, std::move(r));
                break;
            }
            case InputFormat::kOpenScad: {
                ImportReport r;
                // .scad: read directly, or evaluated by OpenSCAD when it is beyond the literal
                // subset (import/openscad/scad_source.h); .csg is OpenSCAD's own output.
                if (EndsWith(Lower(path), ".scad"))
                    import::ImportScadSource(text, path, options.import, scene, diags, r);
                else
                    import::ImportOpenScad(text, path, options.import, scene, diags, r);
                report.importedBounds.Extend(r.bounds);
                report.imports.emplace_back(path, std::move(r));
                break;
            }
            case InputFormat::kFreeform: {
                // Freeform models (docs/isocurve.md): every surface of the file, drawn by
                // adaptive isocurves. OBJ is Y-up like Quadrix; the tea-set formats (BPT,
                // Geomview BEZ/BBP, Newell) are Z-up like BRL-CAD and get the same axis swap.
                auto model =
                    import::ReadFreeformText(text, path, import::FreeformFormat::kAuto, diags);
                if (!model) break;
                const bool zUp = model->format != import::FreeformFormat::kObj;
                const std::string stem = std::filesystem::path(path).stem().string();
                for (std::size_t k = 0; k < model->surfaces.size(); ++k) {
                    scene::FreeformSurface f;
                    f.id = fmt::format("{}[{}]", stem, k);
                    f.surface = zUp ? model->surfaces[k].Transformed(import::QuadrixFromZUp())
                                    : model->surfaces[k];
                    f.surface.SetName(f.id);
                    f.loc = FileLoc(path);
                    scene.top.freeforms.push_back(std::move(f));
                }
                if (model->surfaces.empty())
                    diags.Warning(FileLoc(path),
                                  fmt::format("'{}' holds no freeform surface", path), {}, "input");
                break;
            }
        }
    }
    // A --top name must be defined by at least one imported file.
    const auto& tops = options.import.topObjects;
    if (!tops.empty() && report.imports.empty()) {
        diags.Warning({}, "--top has no effect: no BRL-CAD or OpenSCAD file was given", {},
                      "command line");
    }
    for (const std::string& name : tops) {
        if (report.imports.empty() || name == "all") continue;
        bool found = std::any_of(report.imports.begin(), report.imports.end(), [&](auto& r) {
            const auto& m = r.second.missingTops;
            return std::find(m.begin(), m.end(), name) == m.end();
        });
        if (!found)
            diags.Error({},
                        fmt::format("--top {}: no object of that name in {}", name,
                                    report.imports.size() == 1 ? "'" + report.imports[0].first + "'"
                                                               : std::string("the imported files")),
                        {}, "command line");
    }
    report.usesClock = uq && uq->UsesClock();
    report.clockOutsideViews = uq && uq->UsesClockOutsideViews();
    if (report.usesClock && !report.clockOutsideViews) report.viewStatements = uq->ViewStatements();
    return !diags.HasErrors();
}

}  // namespace quadrix
