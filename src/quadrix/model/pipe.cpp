#include "quadrix/model/pipe.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <set>

#include "quadrix/model/solids.h"

namespace quadrix::model {

// --- the text format ------------------------------------------------------------------------

namespace {

struct Word {
    std::string_view text;
    int column = 0;  // 1-based
};

std::vector<Word> SplitLine(std::string_view line) {
    std::vector<Word> words;
    std::size_t i = 0;
    while (i < line.size()) {
        if (line[i] == '#') break;
        if (std::isspace(static_cast<unsigned char>(line[i]))) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j])) &&
               line[j] != '#')
            ++j;
        words.push_back({line.substr(i, j - i), static_cast<int>(i) + 1});
        i = j;
    }
    return words;
}

std::optional<double> ToNumber(std::string_view s) {
    double v = 0;
    const char* first = s.data();
    if (!s.empty() && s[0] == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

class PipeTextReader {
  public:
    PipeTextReader(const std::string& name, PipeSpec& spec, Diagnostics& diags)
        : file_(std::make_shared<const std::string>(name)), spec_(spec), diags_(diags) {}

    void Line(std::string_view line, int lineNo) {
        line_ = line;
        lineNo_ = lineNo;
        std::vector<Word> w = SplitLine(line);
        if (w.empty()) return;
        std::string_view key = w[0].text;
        if (ToNumber(key)) return Point(w);
        if (key == "path" || key == "loop") return Start(w, key == "loop");
        if (key == "end") {
            if (Count(w, 0)) Finish();
            return;
        }
        if (key == "radius") {
            if (auto v = PositiveArg(w, "radius")) radius_ = *v;
            return;
        }
        if (key == "ball") {
            if (w.size() == 2 && w[1].text == "off") {
                ball_ = 0;
                return;
            }
            if (auto v = PositiveArg(w, "ball")) {
                ball_ = *v;
                ballLoc_ = Loc(w[1]);
            }
            return;
        }
        if (key == "caps") {
            if (w.size() == 2 && (w[1].text == "on" || w[1].text == "off"))
                caps_ = w[1].text == "on";
            else
                Error(w[0], "'caps' takes one word: on or off");
            return;
        }
        if (key == "color") return Color(w);
        Error(w[0], fmt::format("unknown directive '{}' (expected radius, ball, caps, color, path, "
                                "loop, end or a point x y z)",
                                key));
    }

    void Finish() {
        if (!open_) return;
        open_ = false;
        spec_.paths.push_back(std::move(current_));
        current_ = {};
    }

  private:
    SourceLoc Loc(const Word& w) const { return SourceLoc{file_, lineNo_, w.column}; }
    void Error(const Word& w, std::string message) {
        diags_.Error(Loc(w), std::move(message), std::string(line_), "input");
    }
    bool Count(const std::vector<Word>& w, std::size_t n) {
        if (w.size() == n + 1) return true;
        Error(w[0], fmt::format("'{}' takes {} value{}, found {}", w[0].text, n, n == 1 ? "" : "s",
                                w.size() - 1));
        return false;
    }
    std::optional<double> PositiveArg(const std::vector<Word>& w, std::string_view what) {
        if (!Count(w, 1)) return std::nullopt;
        auto v = ToNumber(w[1].text);
        if (!v || !(*v > 0)) {
            Error(w[1], fmt::format("'{}' needs a number > 0, found '{}'", what, w[1].text));
            return std::nullopt;
        }
        return v;
    }
    void Color(const std::vector<Word>& w) {
        if (w.size() == 2 && w[1].text == "off") {
            color_.reset();
            return;
        }
        if (!Count(w, 3)) return;
        std::array<double, 3> c{};
        for (int i = 0; i < 3; ++i) {
            auto v = ToNumber(w[i + 1].text);
            if (!v || *v < 0 || *v > 1) {
                Error(w[i + 1], fmt::format("color components are numbers in [0, 1], found '{}'",
                                            w[i + 1].text));
                return;
            }
            c[i] = *v;
        }
        color_ = c;
    }
    void Start(const std::vector<Word>& w, bool closed) {
        Finish();
        if (!Count(w, 0)) return;
        open_ = true;
        current_.closed = closed;
        current_.radius = radius_;
        current_.ball = ball_;
        current_.caps = caps_;
        current_.color = color_;
        current_.loc = Loc(w[0]);
        if (ball_ > 0 && ball_ < radius_)
            diags_.Error(ballLoc_,
                         fmt::format("the ball radius {} is smaller than the tube radius {}: the "
                                     "joints would show gaps",
                                     ball_, radius_),
                         {}, "input");
    }
    void Point(const std::vector<Word>& w) {
        if (w.size() != 3) {
            Error(w[0], fmt::format("a point has 3 coordinates x y z, found {}", w.size()));
            return;
        }
        Vec3 p;
        for (int i = 0; i < 3; ++i) {
            auto v = ToNumber(w[i].text);
            if (!v) {
                Error(w[i], fmt::format("expected a number, found '{}'", w[i].text));
                return;
            }
            p[i] = *v;
        }
        if (!open_) {
            Error(w[0], "a point outside a path: start one with 'path' or 'loop'");
            return;
        }
        current_.points.push_back(p);
    }

    std::shared_ptr<const std::string> file_;
    PipeSpec& spec_;
    Diagnostics& diags_;
    std::string_view line_;
    int lineNo_ = 0;
    double radius_ = 1, ball_ = 0;
    SourceLoc ballLoc_;
    bool caps_ = true;
    std::optional<std::array<double, 3>> color_;
    bool open_ = false;
    PipePath current_;
};

}  // namespace

bool ReadPipeText(std::string_view text, const std::string& name, PipeSpec& spec,
                  Diagnostics& diags) {
    int before = diags.ErrorCount();
    PipeTextReader reader(name, spec, diags);
    int lineNo = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string_view::npos) eol = text.size();
        std::string_view line = text.substr(pos, eol - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        reader.Line(line, ++lineNo);
        if (diags.ErrorCount() >= Diagnostics::kMaxStored) break;
        pos = eol + 1;
    }
    reader.Finish();
    return diags.ErrorCount() == before;
}

// --- building the tubes ---------------------------------------------------------------------

namespace {

Plane PlaneThrough(const Vec3& point, const Vec3& normal) {
    return Plane{normal.x, normal.y, normal.z, -Dot(normal, point)};
}

std::string PointText(const Vec3& p) { return fmt::format("({} {} {})", p.x, p.y, p.z); }

}  // namespace

bool BuildPipes(const PipeSpec& spec, PipeModel& model, Diagnostics& diags) {
    const int before = diags.ErrorCount();
    model = {};
    // Weld tolerance: relative to the extent of all points, so that generated coordinates that
    // should coincide (midpoints computed along different routes) do.
    double extent = 1;
    for (const PipePath& path : spec.paths)
        for (const Vec3& p : path.points)
            extent = std::max({extent, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    const double weld = 1e-9 * extent;
    auto jointOf = [&](const Vec3& p) {
        for (std::size_t j = 0; j < model.joints.size(); ++j)
            if (Length(model.joints[j].point - p) <= weld) return static_cast<int>(j);
        model.joints.push_back({p, {}, 0});
        return static_cast<int>(model.joints.size()) - 1;
    };

    std::set<std::pair<int, int>> seen;
    for (std::size_t pi = 0; pi < spec.paths.size(); ++pi) {
        const PipePath& path = spec.paths[pi];
        std::vector<int> ids;
        for (const Vec3& p : path.points) {
            int j = jointOf(p);
            if (!ids.empty() && ids.back() == j) {
                diags.Warning(path.loc, fmt::format("point {} repeats the one before it; dropped",
                                                    PointText(p)));
                continue;
            }
            ids.push_back(j);
        }
        if (path.closed && ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
        const std::size_t need = path.closed ? 3 : 2;
        if (ids.size() < need) {
            diags.Error(path.loc, fmt::format("a {} needs at least {} distinct points, found {}",
                                              path.closed ? "loop" : "path", need, ids.size()));
            continue;
        }
        const std::size_t count = path.closed ? ids.size() : ids.size() - 1;
        for (std::size_t i = 0; i < count; ++i) {
            int a = ids[i], b = ids[(i + 1) % ids.size()];
            if (!seen.insert({std::min(a, b), std::max(a, b)}).second) {
                diags.Warning(path.loc, fmt::format("the element {} -> {} is given twice; the "
                                                    "second is dropped",
                                                    PointText(model.joints[a].point),
                                                    PointText(model.joints[b].point)));
                continue;
            }
            PipeElement e;
            e.path = static_cast<int>(pi);
            e.joint0 = a;
            e.joint1 = b;
            e.p0 = model.joints[a].point;
            e.p1 = model.joints[b].point;
            e.radius = path.radius;
            e.color = path.color;
            int index = static_cast<int>(model.elements.size());
            model.joints[a].elements.push_back(index);
            model.joints[b].elements.push_back(index);
            model.elements.push_back(std::move(e));
        }
    }

    for (PipeJoint& joint : model.joints) {
        for (int ei : joint.elements) {
            const PipeElement& e = model.elements[ei];
            joint.ball = std::max(joint.ball, spec.paths[e.path].ball);
        }
        if (joint.elements.size() == 1)
            ++model.freeEnds;
        else if (joint.ball > 0)
            ++model.balls;
        else if (joint.elements.size() > 1)
            ++model.mitered;
    }

    for (std::size_t ei = 0; ei < model.elements.size(); ++ei) {
        PipeElement& e = model.elements[ei];
        auto frame = MakeAxisFrame(e.p0, e.p1);
        e.side = MakeCylinder(*frame, {e.radius, e.radius}).surfaces[0].quadric;
        for (int end = 0; end < 2; ++end) {
            const int ji = end == 0 ? e.joint0 : e.joint1;
            const PipeJoint& joint = model.joints[ji];
            const Vec3 along = end == 0 ? frame->w : -frame->w;  // away from the joint
            if (joint.elements.size() == 1 || joint.ball > 0) {
                // A square end: a cap at a free end (transparent when open), or the cut hidden in
                // the joint's ball (ball >= tube radius covers the cut disc).
                e.ends.push_back(PlaneThrough(joint.point, -along));
                e.endTransparent.push_back(joint.elements.size() == 1 && !spec.paths[e.path].caps);
                continue;
            }
            for (int fi : joint.elements) {
                if (fi == static_cast<int>(ei)) continue;
                const PipeElement& f = model.elements[fi];
                const Vec3 other = f.joint0 == ji ? f.p1 - f.p0 : f.p0 - f.p1;
                Vec3 bisector = Normalize(other) - along;  // outward normal of e's side
                if (Length(bisector) < 1e-9) {
                    diags.Error(spec.paths[e.path].loc,
                                fmt::format("two elements leave the joint {} in the same "
                                            "direction: they overlap",
                                            PointText(joint.point)));
                    continue;
                }
                if (f.radius != e.radius && fi > static_cast<int>(ei))
                    diags.Warning(spec.paths[e.path].loc,
                                  fmt::format("tubes of radii {} and {} are mitered at {}: the "
                                              "miter is exact only for equal radii (use 'ball')",
                                              e.radius, f.radius, PointText(joint.point)));
                e.ends.push_back(PlaneThrough(joint.point, Normalize(bisector)));
                e.endTransparent.push_back(false);
            }
        }
    }
    return diags.ErrorCount() == before;
}

// --- writing --------------------------------------------------------------------------------

namespace {

// Shortest round-trip text; values below 1e-14 of the largest coefficient are rounding noise
// of the frame products and are written as 0 for readability.
std::string Numbers(const double* v, int n) {
    double scale = 0;
    for (int i = 0; i < n; ++i) scale = std::max(scale, std::fabs(v[i]));
    std::string s;
    for (int i = 0; i < n; ++i) {
        double x = std::fabs(v[i]) < 1e-14 * scale ? 0.0 : v[i];
        if (x == 0) x = 0;  // no "-0"
        s += (i ? " " : "") + fmt::format("{}", x);
    }
    return s;
}

std::string ColorText(const std::optional<std::array<double, 3>>& c) {
    return c ? fmt::format(" =c {} {} {}", (*c)[0], (*c)[1], (*c)[2]) : std::string();
}

}  // namespace

std::string WriteUniQuadrix(const PipeModel& model, const PipeWriteOptions& options) {
    std::string out = fmt::format(
        "{{ Pipes written by 'quadrix pipe'{}{} (seed 001 §7.2: mkworm / ugpipe).\n"
        "  {} elements, {} joints: {} mitered, {} with balls, {} free ends. }}\n",
        options.source.empty() ? "" : " from ", options.source, model.elements.size(),
        model.joints.size(), model.mitered, model.balls, model.freeEnds);
    if (!options.definition.empty()) out += fmt::format("definition {};\n", options.definition);
    const std::string& pre = options.prefix;
    for (std::size_t i = 0; i < model.elements.size(); ++i) {
        const PipeElement& e = model.elements[i];
        const std::string id = fmt::format("{}{}", pre, i + 1);
        out += fmt::format("{{ {}: {} -> {}, radius {} }}\n", id, PointText(e.p0), PointText(e.p1),
                           e.radius);
        out += fmt::format("quadric {} <{}>;\n", id, Numbers(e.side.k.data(), 10));
        std::string literals = id;
        for (std::size_t k = 0; k < e.ends.size(); ++k) {
            const Vec4 p = e.ends[k].AsVec4();
            const double c[4] = {p.x, p.y, p.z, p.w};
            out += fmt::format("plane {}#{} <{}>{};\n", id, k + 1, Numbers(c, 4),
                               e.endTransparent[k] ? " =t" : "");
            literals += fmt::format(" {}#{}", id, k + 1);
        }
        out += fmt::format("body {} ({}){};\n", id, literals, ColorText(e.color));
    }
    int ball = 0;
    for (const PipeJoint& j : model.joints) {
        if (j.ball <= 0 || j.elements.size() < 2) continue;
        const std::string id = fmt::format("j{}", ++ball);
        const Quadric s = MakeSphere(j.point, j.ball).surfaces[0].quadric;
        // The ball takes the color of the first element that meets here.
        const auto& color = model.elements[j.elements[0]].color;
        out += fmt::format("quadric {} <{}>;\nbody {} ({}){};\n", id, Numbers(s.k.data(), 10), id,
                           id, ColorText(color));
    }
    if (!options.definition.empty()) out += fmt::format("enddef {};\n", options.definition);
    return out;
}

// --- generators -----------------------------------------------------------------------------

std::vector<Vec3> HilbertCurve(int order) {
    const int n = 1 << order;
    std::vector<Vec3> points;
    points.reserve(static_cast<std::size_t>(n) * n);
    for (int d = 0; d < n * n; ++d) {
        // The classic index → (x, y) conversion: at each scale s, pick the quadrant and rotate
        // or reflect the sub-curve so that the pieces join end to end.
        int x = 0, y = 0, t = d;
        for (int s = 1; s < n; s *= 2) {
            int rx = 1 & (t / 2), ry = 1 & (t ^ rx);
            if (ry == 0) {
                if (rx == 1) {
                    x = s - 1 - x;
                    y = s - 1 - y;
                }
                std::swap(x, y);
            }
            x += s * rx;
            y += s * ry;
            t /= 4;
        }
        points.push_back({static_cast<double>(x), static_cast<double>(y), 0});
    }
    return points;
}

std::vector<Vec3> TrefoilKnot(int samples) {
    std::vector<Vec3> points;
    for (int k = 0; k < samples; ++k) {
        double t = 2 * M_PI * k / samples;
        points.push_back({std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t),
                          -std::sin(3 * t)});
    }
    return points;
}

namespace {
void Sierpinski(const std::array<Vec3, 3>& t, int order, std::vector<std::array<Vec3, 3>>& out) {
    if (order == 0) {
        out.push_back(t);
        return;
    }
    // Each midpoint is computed once and handed to both triangles that share it, so shared
    // corners are bit-identical.
    Vec3 ab = (t[0] + t[1]) * 0.5, bc = (t[1] + t[2]) * 0.5, ca = (t[2] + t[0]) * 0.5;
    Sierpinski({t[0], ab, ca}, order - 1, out);
    Sierpinski({ab, t[1], bc}, order - 1, out);
    Sierpinski({ca, bc, t[2]}, order - 1, out);
}
}  // namespace

std::vector<std::array<Vec3, 3>> SierpinskiTriangles(int order) {
    const double side = std::ldexp(1.0, order);
    std::vector<std::array<Vec3, 3>> out;
    Sierpinski({Vec3{0, 0, 0}, Vec3{side, 0, 0}, Vec3{side / 2, side * std::sqrt(3.0) / 2, 0}},
               order, out);
    return out;
}

namespace {
// A stroke font on a 2 × 3 cell (x to the right, y up). Junctions are vertices of every stroke
// that meets there, so the pipe builder sees them as joints of three or four elements.
using Stroke = std::vector<std::array<double, 2>>;
const std::vector<Stroke>* Glyph(char c) {
    static const std::vector<std::pair<char, std::vector<Stroke>>> kFont = {
        {'A', {{{0, 0}, {1.0 / 3, 1}, {1, 3}, {5.0 / 3, 1}, {2, 0}}, {{1.0 / 3, 1}, {5.0 / 3, 1}}}},
        {'D', {{{0, 0}, {1.3, 0}, {2, 0.8}, {2, 2.2}, {1.3, 3}, {0, 3}, {0, 0}}}},
        {'E', {{{2, 3}, {0, 3}, {0, 1.5}, {0, 0}, {2, 0}}, {{0, 1.5}, {1.4, 1.5}}}},
        {'H', {{{0, 0}, {0, 1.5}, {0, 3}}, {{2, 0}, {2, 1.5}, {2, 3}}, {{0, 1.5}, {2, 1.5}}}},
        {'I', {{{0, 0}, {1, 0}, {2, 0}}, {{0, 3}, {1, 3}, {2, 3}}, {{1, 0}, {1, 3}}}},
        {'L', {{{0, 3}, {0, 0}, {2, 0}}}},
        {'N', {{{0, 0}, {0, 3}, {2, 0}, {2, 3}}}},
        {'O',
         {{{0.6, 0},
           {1.4, 0},
           {2, 0.6},
           {2, 2.4},
           {1.4, 3},
           {0.6, 3},
           {0, 2.4},
           {0, 0.6},
           {0.6, 0}}}},
        {'Q',
         {{{0.6, 0},
           {1.4, 0},
           {2, 0.6},
           {2, 2.4},
           {1.4, 3},
           {0.6, 3},
           {0, 2.4},
           {0, 0.6},
           {0.6, 0}},
          {{1.1, 0.9}, {2.3, -0.4}}}},
        {'R',
         {{{0, 0}, {0, 1.5}, {0, 3}, {1.5, 3}, {2, 2.5}, {2, 2}, {1.5, 1.5}, {1, 1.5}, {0, 1.5}},
          {{1, 1.5}, {2, 0}}}},
        {'T', {{{0, 3}, {1, 3}, {2, 3}}, {{1, 3}, {1, 0}}}},
        {'U', {{{0, 3}, {0, 0.6}, {0.6, 0}, {1.4, 0}, {2, 0.6}, {2, 3}}}},
        {'X', {{{0, 0}, {1, 1.5}, {2, 3}}, {{0, 3}, {1, 1.5}, {2, 0}}}},
    };
    for (const auto& [ch, strokes] : kFont)
        if (ch == c) return &strokes;
    return nullptr;
}
}  // namespace

std::vector<std::vector<Vec3>> StrokeText(std::string_view text, std::string* unsupported) {
    std::vector<std::vector<Vec3>> out;
    double x0 = 0;
    for (char c : text) {
        char up = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (up != ' ') {
            const std::vector<Stroke>* glyph = Glyph(up);
            if (!glyph) {
                if (unsupported) unsupported->push_back(c);
            } else {
                for (const Stroke& s : *glyph) {
                    std::vector<Vec3> line;
                    for (const auto& p : s) line.push_back({x0 + p[0], p[1], 0});
                    out.push_back(std::move(line));
                }
            }
        }
        x0 += 3;
    }
    return out;
}

}  // namespace quadrix::model
