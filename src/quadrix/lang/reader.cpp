// The public face of the reader (reader.h): a ReaderState shared by every input given to one
// Reader, so that later files see the ids of earlier ones.
#include "quadrix/lang/reader.h"

#include "quadrix/lang/input_files.h"
#include "quadrix/lang/reader_state.h"

namespace quadrix::lang {

struct Reader::Impl {
    ReaderState state;
};

Reader::Reader(scene::Scene& scene, Diagnostics& diags, ReadOptions options)
    : impl_(new Impl{ReaderState(scene, diags, options)}) {}

Reader::~Reader() = default;

bool Reader::ReadFile(const std::string& path) {
    int before = impl_->state.diags.ErrorCount();
    ReadTopLevelFile(impl_->state, path);
    return impl_->state.diags.ErrorCount() == before;
}

bool Reader::ReadText(std::string_view text, const std::string& name) {
    int before = impl_->state.diags.ErrorCount();
    ReadTopLevelText(impl_->state, text, name);
    return impl_->state.diags.ErrorCount() == before;
}

bool Reader::UsesClock() const { return impl_->state.usesClock; }
bool Reader::UsesClockOutsideViews() const { return impl_->state.usesClockOutsideViews; }
const std::vector<ViewStatement>& Reader::ViewStatements() const {
    return impl_->state.viewStatements;
}

void Reader::Resume() { impl_->state.aborted = false; }

ReaderState& Reader::State() { return impl_->state; }

bool ReadSceneFiles(const std::vector<std::string>& paths, scene::Scene& scene, Diagnostics& diags,
                    ReadOptions options) {
    Reader reader(scene, diags, options);
    bool ok = true;
    // With no file, standard input is read (seed 001 §2.2).
    if (paths.empty()) return reader.ReadFile("-");
    for (const std::string& p : paths) ok &= reader.ReadFile(p);
    return ok;
}

}  // namespace quadrix::lang
