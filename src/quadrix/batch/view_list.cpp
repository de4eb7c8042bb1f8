#include "quadrix/batch/view_list.h"

#include <fmt/format.h>

#include <cctype>
#include <memory>

#include "quadrix/io/bounded_read.h"
#include "quadrix/lang/reader.h"

namespace quadrix::batch {

namespace {

// One ';'-terminated command of an rt script: its first word and its span [begin, end).
struct RtCommand {
    std::string word;
    std::size_t begin = 0, end = 0;
};

std::vector<RtCommand> RtCommands(std::string_view text) {
    std::vector<RtCommand> out;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i >= text.size()) break;
        RtCommand c;
        c.begin = i;
        while (i < text.size() && text[i] != ';' &&
               !std::isspace(static_cast<unsigned char>(text[i])))
            c.word += text[i++];
        while (i < text.size() && text[i] != ';') ++i;
        if (i < text.size()) ++i;  // the ';'
        c.end = i;
        out.push_back(std::move(c));
    }
    return out;
}

bool IsRtWord(const std::string& w) {
    return w == "viewsize" || w == "eye_pt" || w == "viewrot" || w == "orientation" || w == "ae" ||
           w == "start";
}

// `text` with every byte outside [begin, end) blanked except newlines, so that the rt parser's
// line:column positions stay those of the file.
std::string Blanked(std::string_view text, std::size_t begin, std::size_t end,
                    const std::vector<std::pair<std::size_t, std::size_t>>& holes) {
    std::string out(text);
    for (std::size_t k = 0; k < out.size(); ++k) {
        bool keep = k >= begin && k < end;
        for (auto [b, e] : holes)
            if (k >= b && k < e) keep = false;
        if (!keep && out[k] != '\n') out[k] = ' ';
    }
    return out;
}

std::optional<std::vector<ListedView>> ParseRtList(std::string_view text, const std::string& file,
                                                   const std::vector<RtCommand>& commands,
                                                   Diagnostics& diags) {
    // Frames: the spans between `start` and `end`; none = the whole file is one view.
    std::vector<std::pair<std::size_t, std::size_t>> frames;
    std::vector<std::pair<std::size_t, std::size_t>> markers;  // the start/end commands
    bool isOpen = false;
    std::size_t open = 0;
    for (const RtCommand& c : commands) {
        if (c.word == "start") {
            if (isOpen) frames.emplace_back(open, c.begin);  // a missing `end`
            open = c.end;
            isOpen = true;
            markers.emplace_back(c.begin, c.end);
        } else if (c.word == "end") {
            if (isOpen) frames.emplace_back(open, c.begin);
            isOpen = false;
            markers.emplace_back(c.begin, c.end);
        }
    }
    if (isOpen) frames.emplace_back(open, text.size());
    if (frames.empty()) frames.emplace_back(0, text.size());
    std::vector<ListedView> views;
    bool ok = true;
    for (auto [b, e] : frames) {
        const std::string one = Blanked(text, b, e, markers);
        auto rt = import::ParseRtViewScript(one, file, diags);
        if (!rt) {
            ok = false;
            continue;
        }
        ListedView v;
        v.rtView = *rt;
        v.name = fmt::format("rt view {}", views.size());
        views.push_back(std::move(v));
    }
    if (!ok) return std::nullopt;
    return views;
}

}  // namespace

std::optional<std::vector<ListedView>> ParseViewList(std::string_view text, const std::string& file,
                                                     Diagnostics& diags) {
    const std::vector<RtCommand> commands = RtCommands(text);
    if (!commands.empty() && IsRtWord(commands.front().word))
        return ParseRtList(text, file, commands, diags);
    scene::Scene scene;
    lang::Reader reader(scene, diags);
    if (!reader.ReadText(text, file) || diags.HasErrors()) return std::nullopt;
    std::vector<ListedView> views;
    for (const scene::View& v : scene.views) {
        if (v.isDefault) continue;
        ListedView lv;
        lv.view = v;
        lv.name = v.id;
        views.push_back(std::move(lv));
    }
    if (views.empty()) {
        diags.Error(SourceLoc{std::make_shared<const std::string>(file), 1, 1},
                    "the view list has no view (expected `view` statements or an rt view script)",
                    {}, "input");
        return std::nullopt;
    }
    return views;
}

std::optional<std::vector<ListedView>> ReadViewList(const std::string& path, Diagnostics& diags) {
    std::string text;
    if (std::string why = ReadBoundedFile(path, text); !why.empty()) {
        diags.Error(SourceLoc{std::make_shared<const std::string>(path), 0, 0},
                    fmt::format("cannot read '{}': {}", path, why), {}, "input");
        return std::nullopt;
    }
    return ParseViewList(text, path, diags);
}

}  // namespace quadrix::batch
