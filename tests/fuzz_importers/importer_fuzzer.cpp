// libFuzzer targets for the importers and the whole pipeline (issue 23 item 5). One source, one
// executable per target, chosen by QUADRIX_FUZZ_TARGET at compile time (CMakeLists.txt here):
//
//   fuzz_v4        BRL-CAD ASCII v4 records        (import/brlcad/v4_reader.cpp)   then the
//   converter fuzz_v5        BRL-CAD ASCII v5 `put` script   (import/brlcad/v5_reader.cpp)   then
//   the converter fuzz_comgeom   COMGEOM deck                    (import/brlcad/comgeom_reader.cpp)
//   then the converter fuzz_openscad  OpenSCAD CSG subset             (import/openscad/)
//   fuzz_freeform  Newell / .bpt / Geomview .bez / OBJ (import/freeform/; the first byte picks one)
//   fuzz_pipeline  read → flatten → a 32×32 raycast render → shade, through the RenderContext; the
//                  first byte picks the format (.uq, .asc, .scad, .obj, .bpt) and the engine
//
// Properties (a violation aborts, so libFuzzer keeps the input; crashes, sanitizer reports,
// exceptions escaping and timeouts are findings by themselves):
//   - a reader returns false exactly when it added an error;
//   - every error message is non-empty and carries no NUL byte;
//   - a pipeline that reads and flattens without error renders a 32×32 Frame whose depths are
//     never NaN.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "quadrix/import/brlcad/brlcad_import.h"
#include "quadrix/import/brlcad/readers.h"
#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/import/openscad/openscad_import.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/scene/scene.h"

namespace {

using namespace quadrix;

[[noreturn]] void Fail(const std::string& what) {
    std::fprintf(stderr, "importer property violated: %s\n", what.c_str());
    std::abort();
}

void CheckDiagnostics(bool ok, const Diagnostics& diags, const char* who) {
    if (ok == diags.HasErrors())
        Fail(std::string(who) + (ok ? ": returned true with errors" : ": false without an error"));
    for (const Diagnostic& d : diags.Items()) {
        if (d.message.empty()) Fail(std::string(who) + ": empty message");
        if (d.message.find('\0') != std::string::npos) Fail(std::string(who) + ": NUL in message");
    }
}

[[maybe_unused]] void ImportBrlcadText(std::string_view text) {
    scene::Scene scene;
    Diagnostics diags;
    import::ImportOptions options;
    options.allowMissing = true;
    import::ImportReport report;
    bool ok = import::ImportBrlcad(text, "fuzz.asc", options, scene, diags, report);
    CheckDiagnostics(ok, diags, "ImportBrlcad");
}

#if QUADRIX_FUZZ_TARGET <= 3
[[maybe_unused]] void FuzzBrlcad(std::string_view text) {
    import::brlcad::Database db;
    Diagnostics diags;
    bool ok;
#if QUADRIX_FUZZ_TARGET == 1
    ok = import::brlcad::ParseV4(text, "fuzz.asc", db, diags);
#elif QUADRIX_FUZZ_TARGET == 2
    ok = import::brlcad::ParseV5(text, "fuzz.asc", db, diags);
#else
    ok = import::brlcad::ParseComgeom(text, "fuzz.cg", db, diags);
#endif
    CheckDiagnostics(ok, diags, "parser");
    ImportBrlcadText(text);  // detection, the same parser, then the converter
}
#endif

#if QUADRIX_FUZZ_TARGET == 4
[[maybe_unused]] void FuzzOpenScad(std::string_view text) {
    scene::Scene scene;
    Diagnostics diags;
    import::ImportOptions options;
    options.allowMissing = true;
    import::ImportReport report;
    bool ok = import::ImportOpenScad(text, "fuzz.scad", options, scene, diags, report);
    CheckDiagnostics(ok, diags, "ImportOpenScad");
}
#endif

#if QUADRIX_FUZZ_TARGET == 5
[[maybe_unused]] void FuzzFreeform(std::uint8_t selector, std::string_view text) {
    static const import::FreeformFormat kFormats[4] = {
        import::FreeformFormat::kNewell, import::FreeformFormat::kBpt,
        import::FreeformFormat::kGeomview, import::FreeformFormat::kObj};
    static const char* kNames[4] = {"fuzz.txt", "fuzz.bpt", "fuzz.bez", "fuzz.obj"};
    Diagnostics diags;
    auto model =
        import::ReadFreeformText(text, kNames[selector % 4], kFormats[selector % 4], diags);
    CheckDiagnostics(model.has_value(), diags, "ReadFreeformText");
}
#endif

#if QUADRIX_FUZZ_TARGET == 6
// The whole pipeline on a file of the chosen format, written in the working directory (run.sh
// runs the targets in a scratch directory).
[[maybe_unused]] void FuzzPipeline(std::uint8_t selector, std::string_view text) {
    static const char* kNames[5] = {"fuzz.uq", "fuzz.asc", "fuzz.scad", "fuzz.obj", "fuzz.bpt"};
    static const char* kEngines[4] = {"raycast", "scanline", "pixelpowers", "patch"};
    const std::string path = kNames[selector % 5];
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
    }
    RenderContext ctx(1);
    Diagnostics diags;
    InputRequest in;
    in.paths = {path};
    in.allowMissing = true;
    if (!ctx.Read(in, diags)) {
        if (!diags.HasErrors()) Fail("Read failed without an error");
        return;
    }
    ViewRequest view;
    view.width = view.height = 32;
    if (!ctx.Flatten(view, diags)) {
        if (!diags.HasErrors()) Fail("Flatten failed without an error");
        return;
    }
    EngineRequest er;
    er.engine = kEngines[(selector / 5) % 4];
    Frame frame;
    RenderReport report;
    if (!ctx.Render(er, frame, report, diags)) {
        if (!diags.HasErrors()) Fail("Render failed without an error");
        return;
    }
    if (frame.width != 32 || frame.height != 32) Fail("frame is not 32x32");
    for (double d : frame.depth)
        if (std::isnan(d)) Fail("NaN depth in the frame");
    (void)ctx.Shade(frame, ShadeOptions{});
}
#endif

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > 1 << 16) return 0;  // long inputs only slow the search
    std::string_view bytes(reinterpret_cast<const char*>(data), size);
    // Files that are read by name (devices, kernel files) gain the fuzzer nothing.
    for (const char* dir : {"/dev", "/proc", "/sys"})
        if (bytes.find(dir) != std::string_view::npos) return 0;
#if QUADRIX_FUZZ_TARGET <= 3
    FuzzBrlcad(bytes);
#elif QUADRIX_FUZZ_TARGET == 4
    FuzzOpenScad(bytes);
#else
    if (size == 0) return 0;
#if QUADRIX_FUZZ_TARGET == 5
    FuzzFreeform(data[0], bytes.substr(1));
#else
    FuzzPipeline(data[0], bytes.substr(1));
#endif
#endif
    return 0;
}
