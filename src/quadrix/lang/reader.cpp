// STUB — to be replaced by the language implementation.
#include "quadrix/lang/reader.h"

namespace quadrix::lang {
struct Reader::Impl {
    scene::Scene& scene;
    Diagnostics& diags;
    ReadOptions options;
};
Reader::Reader(scene::Scene& scene, Diagnostics& diags, ReadOptions options)
    : impl_(new Impl{scene, diags, options}) {}
Reader::~Reader() = default;
bool Reader::ReadFile(const std::string&) { return false; }
bool Reader::ReadText(std::string_view, const std::string&) { return false; }
bool ReadSceneFiles(const std::vector<std::string>& paths, scene::Scene& scene, Diagnostics& diags,
                    ReadOptions options) {
    Reader r(scene, diags, options);
    bool ok = true;
    for (const auto& p : paths) ok &= r.ReadFile(p);
    return ok;
}
}  // namespace quadrix::lang
