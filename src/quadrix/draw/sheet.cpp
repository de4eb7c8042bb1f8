#include "quadrix/draw/sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>

namespace quadrix::draw {

namespace {

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

struct Bounds2 {
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    void Add(const Point2& p) {
        x0 = std::fmin(x0, p.x);
        y0 = std::fmin(y0, p.y);
        x1 = std::fmax(x1, p.x);
        y1 = std::fmax(y1, p.y);
    }
    bool Empty() const { return !(x0 <= x1 && y0 <= y1); }
};

Bounds2 BoundsOf(const Drawing& d) {
    Bounds2 b;
    for (const Stroke& s : d.strokes) {
        if (s.IsConicArc()) {
            for (int i = 0; i <= 64; ++i) b.Add(s.ArcPoint(s.a0 + (s.a1 - s.a0) * i / 64));
        } else {
            for (const Point2& p : s.points) b.Add(p);
        }
    }
    return b;
}

// Standard drawing scales, paper units per world unit, largest first.
constexpr std::array<double, 16> kScales = {10,  5,   4,    2,    1,    0.5,  0.4,   0.25,
                                            0.2, 0.1, 0.05, 0.04, 0.02, 0.01, 0.005, 0.001};

}  // namespace

std::string ScaleText(double s) {
    if (s >= 1) return fmt::format("{:g}:1", s);
    return fmt::format("1:{:g}", 1 / s);
}

std::string ParseScale(const std::string& text, double& out) {
    auto number = [](const std::string& t, double& v) {
        if (t.empty()) return false;
        std::size_t used = 0;
        try {
            v = std::stod(t, &used);
        } catch (...) {
            return false;
        }
        return used == t.size() && std::isfinite(v) && v > 0;
    };
    const std::size_t colon = text.find(':');
    double a = 0, b = 1;
    const bool ok = colon == std::string::npos
                        ? number(text, a)
                        : number(text.substr(0, colon), a) && number(text.substr(colon + 1), b);
    if (!ok)
        return "'" + text +
               "' is not a scale: give A:B (A mm of paper for B units of the model, e.g. 1:2 or "
               "2:1) or a positive number (A:1)";
    out = a / b;
    if (!(out >= 1e-6 && out <= 1e6)) return "scale '" + text + "' is out of range";
    return {};
}

bool SheetSizeByName(const std::string& name, SheetSize& out) {
    const std::string n = Lower(name);
    if (n == "a4")
        out = {"A4", 297, 210};
    else if (n == "a3")
        out = {"A3", 420, 297};
    else if (n == "letter")
        out = {"letter", 279.4, 215.9};
    else
        return false;
    return true;
}

bool StandardView(const std::string& name, scene::View& out) {
    out = scene::View{};
    out.id = Lower(name);
    const std::string n = out.id;
    if (n == "front") {
        out.dop = Vec3{0, 0, -1};
        out.vup = Vec3{0, 1, 0};
    } else if (n == "back") {
        out.dop = Vec3{0, 0, 1};
        out.vup = Vec3{0, 1, 0};
    } else if (n == "top") {
        out.dop = Vec3{0, 1, 0};
        out.vup = Vec3{0, 0, 1};
    } else if (n == "bottom") {
        out.dop = Vec3{0, -1, 0};
        out.vup = Vec3{0, 0, -1};
    } else if (n == "right") {
        out.dop = Vec3{1, 0, 0};
        out.vup = Vec3{0, 1, 0};
    } else if (n == "left") {
        out.dop = Vec3{-1, 0, 0};
        out.vup = Vec3{0, 1, 0};
    } else if (n == "iso") {
        out.dop = Vec3{1, 1, -1};
        out.vup = Vec3{0, 1, 0};
    } else
        return false;
    return true;
}

Page LayoutSheet(std::vector<SheetView> views, const SheetOptions& options, std::string* scaleText,
                 std::string* overflow) {
    Page page;
    page.unit = "mm";
    page.width = options.size.width;
    page.height = options.size.height;
    page.title = options.fileName;
    page.style = LineStyle{0.5, 0.35, 0.25, 2.0, 1.2, 0.5, 0.15};
    page.tolerance = options.tolerance;
    const double margin = 10, titleH = 24, titleW = 110;
    const double gx0 = margin, gy0 = margin, gx1 = page.width - margin;
    const double gy1 = page.height - margin - titleH;
    const double cw = (gx1 - gx0) / 2, ch = (gy1 - gy0) / 2;
    // Cells: (column, row) per layout slot front, top, right, iso.
    const int third[4][2] = {{0, 1}, {0, 0}, {1, 1}, {1, 0}};
    const int first[4][2] = {{1, 0}, {1, 1}, {0, 0}, {0, 1}};
    const auto& cells = options.firstAngle ? first : third;
    const char* slotName[4] = {"front", "top", "right", "iso"};
    std::vector<int> slotOf(views.size(), -1);
    bool used[4] = {false, false, false, false};
    for (std::size_t i = 0; i < views.size(); ++i)
        for (int s = 0; s < 4; ++s)
            if (!used[s] && Lower(views[i].name) == slotName[s]) {
                slotOf[i] = s;
                used[s] = true;
                break;
            }
    for (std::size_t i = 0; i < views.size(); ++i)
        for (int s = 0; s < 4 && slotOf[i] < 0; ++s)
            if (!used[s]) {
                slotOf[i] = s;
                used[s] = true;
            }
    // One scale for all views.
    double fit = HUGE_VAL;
    std::vector<Bounds2> world(views.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
        Bounds2 b = BoundsOf(views[i].drawing);
        if (b.Empty()) continue;
        const double k = 1 / views[i].pixelsPerUnit;
        world[i] = {b.x0 * k, b.y0 * k, b.x1 * k, b.y1 * k};
        const double w = world[i].x1 - world[i].x0, h = world[i].y1 - world[i].y0;
        if (w > 0) fit = std::fmin(fit, 0.85 * cw / w);
        if (h > 0) fit = std::fmin(fit, 0.85 * ch / h);
    }
    double fitting = kScales.back();
    for (double s : kScales)
        if (s <= fit) {
            fitting = s;
            break;
        }
    const double scale = options.scale > 0 ? options.scale : fitting;
    if (overflow) {
        overflow->clear();
        if (scale > fit / 0.85 * (1 + 1e-9))  // fit keeps 15 % of each cell free
            *overflow = fmt::format(
                "at scale {} the views do not fit their cells on {} (they overlap or leave the "
                "sheet); {} fits",
                ScaleText(scale), options.size.name, ScaleText(fitting));
    }
    for (std::size_t i = 0; i < views.size(); ++i) {
        if (slotOf[i] < 0 || world[i].Empty()) continue;
        const int col = cells[slotOf[i]][0], row = cells[slotOf[i]][1];
        const double cx = gx0 + cw * (col + 0.5), cy = gy0 + ch * (row + 0.5);
        const double s = scale / views[i].pixelsPerUnit;  // mm per device pixel
        const double bx = 0.5 * (world[i].x0 + world[i].x1) * scale;
        const double by = 0.5 * (world[i].y0 + world[i].y1) * scale;
        Drawing d = views[i].drawing;
        TransformDrawing(d, s, cx - bx, cy - by);
        page.strokes.insert(page.strokes.end(), d.strokes.begin(), d.strokes.end());
        page.texts.push_back({gx0 + cw * col + 3, gy0 + ch * row + 5, 3, views[i].name});
    }
    // Border and title block.
    auto rect = [&](double x0, double y0, double x1, double y1) {
        page.frameLines.push_back({{x0, y0}, {x1, y0}});
        page.frameLines.push_back({{x1, y0}, {x1, y1}});
        page.frameLines.push_back({{x1, y1}, {x0, y1}});
        page.frameLines.push_back({{x0, y1}, {x0, y0}});
    };
    rect(margin, margin, page.width - margin, page.height - margin);
    const double tx0 = page.width - margin - titleW, ty0 = page.height - margin - titleH;
    rect(tx0, ty0, page.width - margin, page.height - margin);
    page.frameLines.push_back({{tx0, ty0 + titleH / 2}, {page.width - margin, ty0 + titleH / 2}});
    const std::string st = ScaleText(scale);
    if (scaleText) *scaleText = st;
    page.texts.push_back({tx0 + 3, ty0 + 8, 4.5, options.fileName});
    page.texts.push_back({tx0 + 3, ty0 + titleH / 2 + 8, 3.2,
                          fmt::format("scale {}   {}-angle projection   {}   quadrix draw", st,
                                      options.firstAngle ? "first" : "third", options.size.name)});
    return page;
}

}  // namespace quadrix::draw
