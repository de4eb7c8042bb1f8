// The "file" device of seed 001 §2.2 ("a, ascii, file: Human-readable file uq.out"): a listing of
// the spans the device receives, one a line, so a picture can be inspected or diffed as text and
// read back (ParseListing) to the same spans. The format is in device.h.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <sstream>

#include "quadrix/device/device_internal.h"
#include "quadrix/io/writers.h"

namespace quadrix::device {

namespace internal {

namespace {

class AsciiDevice : public Device {
  public:
    explicit AsciiDevice(DeviceInfo info) { info_ = std::move(info); }

    std::string Open(bool color) override {
        color_ = color && info_.color;
        open_ = true;
        count_ = 0;
        text_ = fmt::format("quadrix-listing 1\nsize {} {}\nlevels {}\ncolor {}\n", info_.width,
                            info_.height, info_.levels, color_ ? 1 : 0);
        return {};
    }
    void Span(int row, int x0, int x1, Rgb c) override {
        if (!open_ || row < 0 || row >= info_.height) return;
        x0 = std::max(x0, 0);
        x1 = std::min(x1, info_.width);
        if (x0 >= x1) return;
        if (color_)
            text_ += fmt::format("span {} {} {} {} {} {}\n", row, x0, x1, Quantize(c.r),
                                 Quantize(c.g), Quantize(c.b));
        else
            text_ += fmt::format("span {} {} {} {}\n", row, x0, x1,
                                 Quantize(c.r == c.g && c.g == c.b ? c.r : Luminance(c)));
        ++count_;
    }
    std::string Close() override {
        if (!open_) return "device is not open";
        open_ = false;
        text_ += fmt::format("end {}\n", count_);
        std::string error = info_.path == "-" ? std::string() : WriteOutputFile(info_.path, text_);
        if (info_.path == "-") std::fwrite(text_.data(), 1, text_.size(), stdout);
        text_.clear();
        return error;
    }
    void Abort() override {
        open_ = false;
        text_.clear();
    }

  private:
    bool color_ = false, open_ = false;
    long long count_ = 0;
    std::string text_;
};

}  // namespace

std::unique_ptr<Device> MakeAsciiDevice(DeviceInfo info) {
    return std::make_unique<AsciiDevice>(std::move(info));
}

}  // namespace internal

namespace {

// Splits a line into integers; false when a word is not one.
bool Integers(std::string_view line, std::vector<long long>& out) {
    out.clear();
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && line[i] == ' ') ++i;
        if (i == line.size()) break;
        std::size_t j = line.find(' ', i);
        if (j == std::string_view::npos) j = line.size();
        long long v = 0;
        auto [end, ec] = std::from_chars(line.data() + i, line.data() + j, v);
        if (ec != std::errc() || end != line.data() + j) return false;
        out.push_back(v);
        i = j;
    }
    return true;
}

}  // namespace

std::string ParseListing(std::string_view text, Listing& listing) {
    listing = Listing{};
    int lineNo = 0;
    bool ended = false;
    std::vector<long long> v;
    std::size_t pos = 0;
    auto fail = [&](const std::string& what) { return fmt::format("line {}: {}", lineNo, what); };
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        if (nl == std::string_view::npos) nl = text.size();
        std::string_view line = text.substr(pos, nl - pos);
        pos = nl + 1;
        ++lineNo;
        if (ended) return fail("text after 'end'");
        std::string_view word = line.substr(0, line.find(' '));
        std::string_view rest = line.size() > word.size() ? line.substr(word.size() + 1) : "";
        if (lineNo == 1) {
            if (line != "quadrix-listing 1") return fail("not a quadrix listing");
            continue;
        }
        if (!Integers(rest, v)) return fail("expected integers");
        if (word == "size" && v.size() == 2 && v[0] > 0 && v[1] > 0) {
            listing.width = static_cast<int>(v[0]);
            listing.height = static_cast<int>(v[1]);
        } else if (word == "levels" && v.size() == 1) {
            listing.levels = static_cast<int>(v[0]);
        } else if (word == "color" && v.size() == 1 && (v[0] == 0 || v[0] == 1)) {
            listing.color = v[0] == 1;
        } else if (word == "span" && v.size() == (listing.color ? 6u : 4u)) {
            ListedSpan s;
            s.row = static_cast<int>(v[0]);
            s.x0 = static_cast<int>(v[1]);
            s.x1 = static_cast<int>(v[2]);
            for (std::size_t k = 3; k < v.size(); ++k)
                if (v[k] < 0 || v[k] > 255) return fail("intensity outside 0..255");
            if (s.row < 0 || s.row >= listing.height || s.x0 < 0 || s.x1 > listing.width ||
                s.x0 >= s.x1)
                return fail("span outside the picture");
            auto byte = [&](std::size_t k) { return static_cast<std::uint8_t>(v[k]); };
            s.color =
                listing.color ? Rgb{byte(3), byte(4), byte(5)} : Rgb{byte(3), byte(3), byte(3)};
            listing.spans.push_back(s);
        } else if (word == "end" && v.size() == 1) {
            if (v[0] != static_cast<long long>(listing.spans.size()))
                return fail("span count does not match 'end'");
            ended = true;
        } else {
            return fail(fmt::format("unexpected line '{}'", line));
        }
    }
    if (!ended) return "missing 'end' line (truncated listing)";
    return {};
}

}  // namespace quadrix::device
