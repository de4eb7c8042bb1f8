// OpenSCAD CSG subset → Scene; see openscad_import.h.
//
// Grammar read (what `openscad -o x.csg` writes, plus the same statements in .scad):
//   statement := [modifier] name '(' [arg {',' arg}] ')' (';' | statement | '{' {statement} '}')
//              | '{' {statement} '}' | ';' | '$'name '=' value ';'
//   arg       := [name '='] value        value := number | true | false | undef | "string"
//                                                | '[' [value {',' value}] ']'
// Modifiers: '*' (disabled) and '%' (background) drop the subtree, '#' and '!' are ignored.
// Geometry (OpenSCAD manual, "Primitive Solids" and "Transformations"):
//   cube(size = 1 | [x, y, z], center = false), sphere(r = 1 | d), cylinder(h = 1, r = 1 | r1, r2
//   | d, d1, d2, center = false) with positional (h, r1, r2, center); multmatrix(m) (3 or 4 rows,
//   applied to column vectors), translate(v), rotate([ax, ay, az]) = Rz·Ry·Rx, rotate(a, v) about
//   the axis v (right-hand rule), rotate(a) about z, scale(v | s), mirror(n) = I - 2nnᵀ/|n|².
//   difference: the first child minus the others; intersection: all children; group, union and
//   render: the union. color(c [, alpha]) colours its subtree; the innermost colour wins.
#include "quadrix/import/openscad/openscad_import.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>

#include "quadrix/import/model_space.h"
#include "quadrix/import/openscad/polygon_solids.h"
#include "quadrix/import/shapes/ellipsoid.h"
#include "quadrix/import/shapes/hexahedron.h"
#include "quadrix/import/shapes/mesh_solid.h"
#include "quadrix/import/shapes/torus.h"
#include "quadrix/import/shapes/truncated_cone.h"
#include "quadrix/import/text_map.h"
#include "quadrix/math/srgb.h"
#include "quadrix/scene/css_colors.h"

namespace quadrix::import {

namespace {

// A color() of the scene: linear-light color and optional opacity (OpenSCAD's alpha).
struct Paint {
    scene::Color color;
    std::optional<double> alpha;
};

struct Value {
    enum class Kind { kUndef, kNumber, kBool, kString, kVector };
    Kind kind = Kind::kUndef;
    double number = 0;
    bool boolean = false;
    std::string text;
    std::vector<Value> items;
};

struct Arg {
    std::string name;  // empty = positional
    Value value;
    std::size_t offset = 0;
};

struct Node {
    std::string name;  // "" for an anonymous { } block
    std::vector<Arg> args;
    std::vector<Node> children;
    std::size_t offset = 0;
    bool dropped = false;  // '*' or '%'
};

class Parser {
  public:
    Parser(const TextMap& map, Diagnostics& diags) : map_(map), t_(map.text()), diags_(diags) {}

    bool Run(std::vector<Node>& out) {
        // A UTF-8 byte order mark (editors on Windows write one) is not text; OpenSCAD skips it.
        if (t_.substr(0, 3) == "\xEF\xBB\xBF") i_ = 3;
        while (Skip(), i_ < t_.size()) {
            Node n;
            if (!Statement(n, 0)) return false;
            if (!n.name.empty() || !n.children.empty()) out.push_back(std::move(n));
        }
        return true;
    }

  private:
    bool Fail(std::size_t at, std::string message) {
        diags_.Error(map_.At(at), std::move(message), map_.LineText(at), "syntax");
        return false;
    }

    void Skip() {
        while (i_ < t_.size()) {
            if (std::isspace(static_cast<unsigned char>(t_[i_]))) {
                ++i_;
            } else if (t_.compare(i_, 2, "//") == 0) {
                while (i_ < t_.size() && t_[i_] != '\n') ++i_;
            } else if (t_.compare(i_, 2, "/*") == 0) {
                std::size_t e = t_.find("*/", i_ + 2);
                i_ = e == std::string_view::npos ? t_.size() : e + 2;
            } else {
                break;
            }
        }
    }

    bool Peek(char c) {
        Skip();
        return i_ < t_.size() && t_[i_] == c;
    }

    bool Expect(char c, const char* context) {
        if (Peek(c)) {
            ++i_;
            return true;
        }
        return Fail(i_, i_ >= t_.size()
                            ? fmt::format("unexpected end of file: expected '{}' {}", c, context)
                            : fmt::format("expected '{}' {}, found '{}'", c, context, t_[i_]));
    }

    std::string Ident() {
        Skip();
        std::size_t s = i_;
        while (i_ < t_.size() &&
               (std::isalnum(static_cast<unsigned char>(t_[i_])) || t_[i_] == '_' || t_[i_] == '$'))
            ++i_;
        return std::string(t_.substr(s, i_ - s));
    }

    bool ParseValue(Value& v, int depth) {
        Skip();
        if (depth > 64) return Fail(i_, "vector nested too deeply");
        if (i_ >= t_.size()) return Fail(i_, "unexpected end of file: expected a value");
        char c = t_[i_];
        if (c == '[') {
            ++i_;
            v.kind = Value::Kind::kVector;
            if (Peek(']')) {
                ++i_;
                return true;
            }
            while (true) {
                Value item;
                if (!ParseValue(item, depth + 1)) return false;
                v.items.push_back(std::move(item));
                if (Peek(',')) {
                    ++i_;
                    continue;
                }
                return Expect(']', "to close the vector");
            }
        }
        if (c == '"') {
            std::size_t s = ++i_;
            while (i_ < t_.size() && t_[i_] != '"') i_ += t_[i_] == '\\' ? 2 : 1;
            if (i_ >= t_.size()) return Fail(s - 1, "unterminated string");
            v.kind = Value::Kind::kString;
            v.text = std::string(t_.substr(s, i_ - s));
            ++i_;
            return true;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
            std::string s;
            std::size_t start = i_;
            while (i_ < t_.size() && (std::isalnum(static_cast<unsigned char>(t_[i_])) ||
                                      t_[i_] == '.' || t_[i_] == '-' || t_[i_] == '+'))
                s += t_[i_++];
            char* end = nullptr;
            v.number = std::strtod(s.c_str(), &end);
            if (!s.empty() && *end == 0 && !std::isfinite(v.number))
                return Fail(start, fmt::format("'{}' is not a finite number", s));
            if (s.empty() || *end != 0)
                return Fail(start, fmt::format("'{}' is not a number (only literal values are "
                                               "supported, no expressions)",
                                               s));
            v.kind = Value::Kind::kNumber;
            return true;
        }
        std::size_t start = i_;
        std::string word = Ident();
        if (word == "true" || word == "false") {
            v.kind = Value::Kind::kBool;
            v.boolean = word == "true";
            return true;
        }
        if (word == "undef") return true;
        return Fail(start, word.empty() ? fmt::format("unexpected '{}': expected a value", c)
                                        : fmt::format("'{}': variables and expressions are not "
                                                      "supported, only literal values",
                                                      word));
    }

    bool Statement(Node& n, int depth) {
        Skip();
        if (depth > 500) return Fail(i_, "statements nested too deeply");
        if (i_ >= t_.size()) return Fail(i_, "unexpected end of file: expected a statement");
        n.offset = i_;
        char c = t_[i_];
        if (c == ';') {
            ++i_;
            return true;
        }
        if (c == '*' || c == '%' || c == '#' || c == '!') {
            ++i_;
            bool ok = Statement(n, depth + 1);
            if (c == '*' || c == '%') n.dropped = true;
            return ok;
        }
        if (c == '{') {
            ++i_;
            return Block(n, depth);
        }
        std::string name = Ident();
        if (name.empty()) return Fail(i_, fmt::format("unexpected '{}': expected a statement", c));
        if (name == "module" || name == "function" || name == "include" || name == "use" ||
            name == "for" || name == "if" || name == "let")
            return Fail(n.offset, fmt::format("'{}' is not supported: this reader takes the CSG "
                                              "subset written by 'openscad -o model.csg'",
                                              name));
        if (Peek('=')) {  // a special-variable assignment such as $fn = 6; for its scope
            ++i_;
            Value v;
            if (!ParseValue(v, 0)) return false;
            if (name[0] != '$')
                return Fail(n.offset, fmt::format("variable '{}': variables are not supported, "
                                                  "only $fn/$fa/$fs-style settings",
                                                  name));
            n.name = "=";
            n.args.push_back({name, std::move(v), n.offset});
            return Expect(';', "after the assignment");
        }
        n.name = name;
        if (!Expect('(', fmt::format("after '{}'", name).c_str())) return false;
        if (!Peek(')')) {
            while (true) {
                Arg a;
                Skip();
                a.offset = i_;
                std::size_t save = i_;
                std::string id = Ident();
                if (!id.empty() && Peek('=') && !(t_.compare(i_, 2, "==") == 0)) {
                    ++i_;
                    a.name = id;
                } else {
                    i_ = save;
                }
                if (!ParseValue(a.value, 0)) return false;
                n.args.push_back(std::move(a));
                if (Peek(',')) {
                    ++i_;
                    continue;
                }
                break;
            }
        }
        if (!Expect(')', fmt::format("to close the arguments of '{}'", name).c_str())) return false;
        Skip();
        if (Peek(';')) {
            ++i_;
            return true;
        }
        if (Peek('{')) {
            Node block;
            block.offset = i_++;
            if (!Block(block, depth)) return false;
            n.children = std::move(block.children);
            return true;
        }
        Node child;
        if (!Statement(child, depth + 1)) return false;
        n.children.push_back(std::move(child));
        return true;
    }

    bool Block(Node& n, int depth) {
        while (!Peek('}')) {
            if (i_ >= t_.size()) return Fail(n.offset, "unbalanced '{': the block is never closed");
            Node c;
            if (!Statement(c, depth + 1)) return false;
            if (!c.name.empty() || !c.children.empty()) n.children.push_back(std::move(c));
        }
        ++i_;
        return true;
    }

    const TextMap& map_;
    std::string_view t_;
    Diagnostics& diags_;
    std::size_t i_ = 0;
};

Mat4 Translate(const Vec3& v) {
    Mat4 m = Mat4::Identity();
    m.m[0][3] = v.x, m.m[1][3] = v.y, m.m[2][3] = v.z;
    return m;
}

// Rotation by `deg` about the unit axis a (Rodrigues), exact for multiples of 90°.
Mat4 AxisRotation(const Vec3& axis, double deg) {
    Vec3 a = Normalize(axis);
    double s = 0, c = 1;
    SinCosDegrees(deg, s, c);
    double t = 1 - c;
    Mat4 m = Mat4::Identity();
    m.m[0][0] = c + a.x * a.x * t;
    m.m[0][1] = a.x * a.y * t - a.z * s;
    m.m[0][2] = a.x * a.z * t + a.y * s;
    m.m[1][0] = a.y * a.x * t + a.z * s;
    m.m[1][1] = c + a.y * a.y * t;
    m.m[1][2] = a.y * a.z * t - a.x * s;
    m.m[2][0] = a.z * a.x * t - a.y * s;
    m.m[2][1] = a.z * a.y * t + a.x * s;
    m.m[2][2] = c + a.z * a.z * t;
    return m;
}

class Builder {
  public:
    Builder(const TextMap& map, const ImportOptions& options, scene::Scene& scene,
            Diagnostics& diags, ImportReport& report)
        : map_(map), options_(options), scene_(scene), diags_(diags), report_(report) {}

    void Top(const std::vector<Node>& nodes, const Mat4& m, std::optional<Paint> color) {
        SpecialsScope scope(*this, nodes);
        for (const Node& n : nodes) {
            if (n.dropped || n.name == "=") continue;
            // Unions at the top level are split so that each part is its own named solid.
            if (n.name.empty() || n.name == "group" || n.name == "union") {
                Top(n.children, m, color);
                continue;
            }
            if (n.name == "color") {
                auto c = ColorOf(n);
                Top(n.children, m, c ? c : color);
                continue;
            }
            scene::Csg csg;
            csg.id = fmt::format("{}@{}", n.name, map_.At(n.offset).line);
            csg.loc = map_.At(n.offset);
            Box3 box;
            csg.root = Emit(csg, n, m, color, box);
            if (csg.root < 0) continue;
            if (box.Finite()) report_.bounds.Extend(box);
            scene_.top.csgs.push_back(std::move(csg));
            ++report_.solids;
        }
    }

    bool failed() const { return failed_; }

  private:
    void Warn(const Node& n, const std::string& message) {
        if (options_.strict)
            diags_.Error(map_.At(n.offset), message + " (--strict)", map_.LineText(n.offset));
        else
            diags_.Warning(map_.At(n.offset), message, map_.LineText(n.offset));
    }
    // A statement that is not drawn: an error unless --allow-missing (import_report.h).
    void Missing(const Node& n, const std::string& message) {
        if (options_.MissingIsError())
            diags_.Error(map_.At(n.offset),
                         message + " (--allow-missing draws the model without it)",
                         map_.LineText(n.offset));
        else
            diags_.Warning(map_.At(n.offset), message + " (--allow-missing)",
                           map_.LineText(n.offset));
    }
    void Error(std::size_t at, const std::string& message) {
        diags_.Error(map_.At(at), message, map_.LineText(at));
        failed_ = true;
    }

    const Value* Find(const Node& n, const char* name, int position) const {
        int pos = 0;
        for (const Arg& a : n.args) {
            if (a.name == name) return &a.value;
            if (a.name.empty() && pos++ == position) return &a.value;
        }
        return nullptr;
    }
    std::optional<double> Num(const Node& n, const char* name, int position = -1) {
        const Value* v = Find(n, name, position);
        if (!v || v->kind == Value::Kind::kUndef) return std::nullopt;
        if (v->kind != Value::Kind::kNumber) {
            Error(n.offset, fmt::format("{}: '{}' must be a number", n.name, name));
            return std::nullopt;
        }
        return v->number;
    }
    // Sizes must be positive: OpenSCAD draws nothing for a zero or negative size (and warns
    // with --check-parameter-ranges), where the quadric of a negative radius is the same as
    // the positive one's; both are errors here rather than a silently different picture.
    bool Positive(const Node& n, const char* name, double v) {
        if (v > 0) return true;
        Error(n.offset, fmt::format("{}: {} = {} must be positive (OpenSCAD draws nothing)", n.name,
                                    name, v));
        return false;
    }
    bool Flag(const Node& n, const char* name, int position) {
        const Value* v = Find(n, name, position);
        return v && v->kind == Value::Kind::kBool && v->boolean;
    }
    std::optional<Vec3> Vec(const Node& n, const char* name, int position, bool allowScalar) {
        const Value* v = Find(n, name, position);
        if (!v || v->kind == Value::Kind::kUndef) return std::nullopt;
        if (allowScalar && v->kind == Value::Kind::kNumber)
            return Vec3{v->number, v->number, v->number};
        Vec3 out;
        if (v->kind == Value::Kind::kVector && v->items.size() >= 2 && v->items.size() <= 3) {
            for (std::size_t k = 0; k < v->items.size(); ++k) {
                if (v->items[k].kind != Value::Kind::kNumber) break;
                out[k] = v->items[k].number;
                if (k + 1 == v->items.size()) return out;
            }
        }
        Error(n.offset, fmt::format("{}: '{}' must be a vector of 2 or 3 numbers", n.name, name));
        return std::nullopt;
    }

    // color(c, alpha) (OpenSCAD manual, "Transformations: color"): c is [r, g, b] or [r, g, b, a]
    // with components in [0, 1], a CSS/SVG color name or "#rgb", "#rgba", "#rrggbb",
    // "#rrggbbaa"; alpha (default 1) is overridden by an alpha inside c. OpenSCAD's values are
    // sRGB (display) values: they are decoded to linear light (math/srgb.h), so the PNG shows the
    // color OpenSCAD shows.
    std::optional<Paint> ColorOf(const Node& n) {
        const Value* v = Find(n, "c", 0);
        if (!v) return std::nullopt;
        auto clamp = [](double x) { return std::fmin(1.0, std::fmax(0.0, x)); };
        Paint paint;
        if (const Value* a = Find(n, "alpha", 1); a && a->kind == Value::Kind::kNumber)
            paint.alpha = clamp(a->number);
        if (v->kind == Value::Kind::kVector && v->items.size() >= 3) {
            paint.color = {LinearFromSrgb(clamp(v->items[0].number)),
                           LinearFromSrgb(clamp(v->items[1].number)),
                           LinearFromSrgb(clamp(v->items[2].number))};
            if (v->items.size() >= 4 && v->items[3].kind == Value::Kind::kNumber)
                paint.alpha = clamp(v->items[3].number);
            return paint;
        }
        if (v->kind == Value::Kind::kString) {
            if (auto hex = HexColor(v->text)) {
                paint.color = hex->color;
                if (hex->alpha) paint.alpha = hex->alpha;
                return paint;
            }
            if (auto c = scene::CssColor(v->text)) {
                paint.color = *c;
                return paint;
            }
            Warn(n, fmt::format("colour name '{}' is not a CSS/SVG colour name; the colour is "
                                "ignored",
                                v->text));
        }
        return std::nullopt;
    }

    static std::optional<Paint> HexColor(const std::string& text) {
        if (text.empty() || text[0] != '#') return std::nullopt;
        const std::string h = text.substr(1);
        if (h.size() != 3 && h.size() != 4 && h.size() != 6 && h.size() != 8) return std::nullopt;
        for (char c : h)
            if (!std::isxdigit(static_cast<unsigned char>(c))) return std::nullopt;
        const bool shortForm = h.size() <= 4;
        const std::size_t count = shortForm ? h.size() : h.size() / 2;
        double v[4] = {0, 0, 0, 1};
        for (std::size_t k = 0; k < count; ++k) {
            const std::string digits = shortForm ? std::string(2, h[k]) : h.substr(2 * k, 2);
            v[k] = std::strtol(digits.c_str(), nullptr, 16) / 255.0;
        }
        Paint p;
        p.color = {LinearFromSrgb(v[0]), LinearFromSrgb(v[1]), LinearFromSrgb(v[2])};
        if (count == 4) p.alpha = v[3];
        return p;
    }

    int Add(scene::Csg& csg, scene::CsgNode node) {
        csg.nodes.push_back(node);
        return static_cast<int>(csg.nodes.size()) - 1;
    }
    int Op(scene::Csg& csg, scene::CsgOp op, int l, int r) {
        scene::CsgNode n;
        n.isLeaf = false;
        n.op = op;
        n.left = l;
        n.right = r;
        return Add(csg, n);
    }

    std::optional<Mat4> TransformOf(const Node& n) {
        const std::string& k = n.name;
        if (k == "translate") {
            auto v = Vec(n, "v", 0, false);
            return v ? std::optional<Mat4>(Translate(*v)) : std::nullopt;
        }
        if (k == "scale") {
            auto v = Vec(n, "v", 0, true);
            if (!v) return std::nullopt;
            const Value* raw = Find(n, "v", 0);
            if (raw->kind == Value::Kind::kVector && raw->items.size() == 2) v->z = 1;
            Mat4 m = Mat4::Identity();
            m.m[0][0] = v->x, m.m[1][1] = v->y, m.m[2][2] = v->z;
            return m;
        }
        if (k == "rotate") {
            const Value* a = Find(n, "a", 0);
            if (a && a->kind == Value::Kind::kVector) {
                auto v = Vec(n, "a", 0, false);
                if (!v) return std::nullopt;
                return AxisRotation({0, 0, 1}, v->z) * AxisRotation({0, 1, 0}, v->y) *
                       AxisRotation({1, 0, 0}, v->x);
            }
            auto deg = Num(n, "a", 0);
            if (!deg) return Mat4::Identity();
            auto axis = Vec(n, "v", 1, false);
            Vec3 ax = axis.value_or(Vec3{0, 0, 1});
            if (Length(ax) == 0) return Mat4::Identity();
            return AxisRotation(ax, *deg);
        }
        if (k == "mirror") {
            auto v = Vec(n, "v", 0, false);
            if (!v) return std::nullopt;
            double l2 = Dot(*v, *v);
            Mat4 m = Mat4::Identity();
            if (l2 == 0) return m;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) m.m[r][c] -= 2 * (*v)[r] * (*v)[c] / l2;
            return m;
        }
        if (k == "multmatrix") {
            const Value* v = Find(n, "m", 0);
            Mat4 m = Mat4::Identity();
            bool ok = v && v->kind == Value::Kind::kVector && v->items.size() >= 3 &&
                      v->items.size() <= 4;
            for (std::size_t r = 0; ok && r < v->items.size(); ++r) {
                const Value& row = v->items[r];
                ok = row.kind == Value::Kind::kVector && row.items.size() == 4;
                for (std::size_t c = 0; ok && c < 4; ++c) {
                    ok = row.items[c].kind == Value::Kind::kNumber;
                    if (ok) m.m[r][c] = row.items[c].number;
                }
            }
            if (!ok) {
                Error(n.offset, "multmatrix: 'm' must be 3 or 4 rows of 4 numbers");
                return std::nullopt;
            }
            return m;
        }
        return std::nullopt;
    }

    // A leaf built by a shape builder (import/shapes/); a refused one (zero sizes) draws nothing.
    int Leaf(scene::Csg& csg, const Node& n, const ShapeResult& s, const Mat4& m,
             const std::optional<Paint>& color, Box3& box) {
        if (!s.ok) return -1;
        return LeafShape(csg, n, s.shape, m, color, box);
    }

    int LeafShape(scene::Csg& csg, const Node& n, const Shape& shape, const Mat4& m,
                  const std::optional<Paint>& color, Box3& box) {
        struct {
            const Shape& shape;
        } cr{shape};
        Mat4 total = QuadrixFromZUp() * m;
        auto t = Transform::FromMatrix(total);
        if (!t) {
            Error(n.offset,
                  fmt::format("{}: the transformation cannot be inverted: singular (a zero "
                              "scale?), not finite, or scales more than 1e14 apart",
                              n.name));
            return -1;
        }
        int root = -1;
        // A shape of one body keeps its placed extent (and its box is that extent's).
        std::vector<ExtentPiece> extent = BodyExtent(cr.shape, total);
        box = ShapeBox(cr.shape, total, extent);
        for (const ShapeBody& sb : cr.shape.bodies) {
            scene::Body body;
            body.id = csg.id;
            body.loc = map_.At(n.offset);
            body.usedAsOperand = true;
            body.extent = std::move(extent);  // empty unless the shape is this one body
            if (color) {
                body.color = color->color;
                body.finish.opacity = color->alpha;
            }
            for (const ShapeHalfSpace& h : sb) {
                scene::HalfSpace hs;
                hs.id = fmt::format("{}.{}", n.name, scene_.top.halfSpaces.size());
                hs.loc = body.loc;
                hs.transparent = h.transparent;
                SetSceneSurface(Placed(h, *t), hs);
                body.literals.push_back(
                    {static_cast<int>(scene_.top.halfSpaces.size()), h.complement});
                scene_.top.halfSpaces.push_back(std::move(hs));
            }
            scene::CsgNode leaf;
            leaf.ref = {scene::SolidRef::Kind::kBody, static_cast<int>(scene_.top.bodies.size())};
            leaf.loc = body.loc;
            scene_.top.bodies.push_back(std::move(body));
            int li = Add(csg, leaf);
            root = root < 0 ? li : Op(csg, scene::CsgOp::kUnion, root, li);
        }
        return root;
    }

    int Emit(scene::Csg& csg, const Node& n, const Mat4& m, std::optional<Paint> color, Box3& box) {
        box = Box3{};
        if (n.dropped || failed_) return -1;
        const std::string& k = n.name;
        if (k == "sphere") {
            ++report_.census[k];
            double r = Num(n, "r", 0).value_or(1);
            if (auto d = Num(n, "d", -1)) r = *d / 2;
            if (!Positive(n, "r", r)) return -1;
            if (auto sides = scad::PolygonSides(r, SpecialsOf(n)); sides && r > 0)
                if (auto shape = scad::PolygonalSphere(r, *sides))
                    return LeafShape(csg, n, *shape, m, color, box);
            return Leaf(csg, n, SphereShape({0, 0, 0}, r), m, color, box);
        }
        if (k == "cube") {
            ++report_.census[k];
            Vec3 s = Vec(n, "size", 0, true).value_or(Vec3{1, 1, 1});
            if (!Positive(n, "size[0]", s.x) || !Positive(n, "size[1]", s.y) ||
                !Positive(n, "size[2]", s.z))
                return -1;
            Vec3 lo = Flag(n, "center", 1) ? s * -0.5 : Vec3{};
            Vec3 hi = lo + s;
            return Leaf(csg, n, BoxShape(lo, hi), m, color, box);
        }
        if (k == "cylinder") {
            ++report_.census[k];
            double h = Num(n, "h", 0).value_or(1);
            double r = Num(n, "r", -1).value_or(1);
            if (auto d = Num(n, "d", -1)) r = *d / 2;
            double r1 = Num(n, "r1", 1).value_or(r), r2 = Num(n, "r2", 2).value_or(r);
            if (auto d = Num(n, "d1", -1)) r1 = *d / 2;
            if (auto d = Num(n, "d2", -1)) r2 = *d / 2;
            if (!Positive(n, "h", h)) return -1;
            // One radius may be 0 (a cone), not both; none may be negative.
            if (r1 < 0 || r2 < 0 || (r1 == 0 && r2 == 0)) {
                Error(n.offset, fmt::format("cylinder: radii r1 = {} and r2 = {} must not be "
                                            "negative nor both zero (OpenSCAD draws nothing)",
                                            r1, r2));
                return -1;
            }
            double z0 = Flag(n, "center", 3) ? -h / 2 : 0;
            if (auto sides = scad::PolygonSides(std::fmax(r1, r2), SpecialsOf(n));
                sides && h > 0 && std::fmax(r1, r2) > 0)
                return LeafShape(csg, n, scad::PolygonalCylinder(r1, r2, z0, h, *sides), m, color,
                                 box);
            const ConeShape cone = TruncatedConeShape({0, 0, z0}, {0, 0, h}, {r1, 0, 0}, {0, r1, 0},
                                                      {r2, 0, 0}, {0, r2, 0});
            return Leaf(csg, n, cone, m, color, box);
        }
        if (k == "polyhedron") return Polyhedron(csg, n, m, color, box);
        if (k == "linear_extrude" || k == "rotate_extrude") return Extrude(csg, n, m, color, box);
        if (k == "square" || k == "circle" || k == "polygon")
            return Refuse(n, fmt::format("'{}' is a 2D shape outside linear_extrude or "
                                         "rotate_extrude; it is left out",
                                         k));
        if (k == "color") {
            auto c = ColorOf(n);
            return Children(csg, n, m, c ? c : color, scene::CsgOp::kUnion, box);
        }
        if (k.empty() || k == "group" || k == "union" || k == "render" || k == "children")
            return Children(csg, n, m, color, scene::CsgOp::kUnion, box);
        if (k == "difference") return Children(csg, n, m, color, scene::CsgOp::kDifference, box);
        if (k == "intersection")
            return Children(csg, n, m, color, scene::CsgOp::kIntersection, box);
        if (auto t = TransformOf(n))
            return Children(csg, n, m * *t, color, scene::CsgOp::kUnion, box);
        if (failed_) return -1;
        ++report_.skipped[k];
        Missing(n, fmt::format("'{}' cannot be drawn exactly with quadrics and planes; it is left "
                               "out",
                               k));
        return -1;
    }

    int Children(scene::Csg& csg, const Node& n, const Mat4& m, const std::optional<Paint>& color,
                 scene::CsgOp op, Box3& box) {
        int acc = -1;
        bool first = true;
        SpecialsScope scope(*this, n.children, &n);
        for (const Node& c : n.children) {
            if (c.dropped || c.name == "=") continue;
            Box3 cb;
            int e = extrusion_ ? Emit2D(csg, c, m, color, cb) : Emit(csg, c, m, color, cb);
            if (op == scene::CsgOp::kUnion) {
                if (e >= 0) {
                    acc = acc < 0 ? e : Op(csg, op, acc, e);
                    box.Extend(cb);
                }
            } else if (op == scene::CsgOp::kDifference) {
                if (first) {
                    acc = e;
                    box = cb;
                } else if (acc >= 0 && e >= 0) {
                    acc = Op(csg, op, acc, e);
                }
            } else {
                if (first) {
                    acc = e;
                    box = cb;
                } else if (acc >= 0) {
                    acc = e < 0 ? -1 : Op(csg, op, acc, e);
                    box = box.Intersected(cb);
                }
            }
            first = false;
        }
        return acc;
    }

    // --- $fn/$fa/$fs, polyhedron and extrusions (polygon_solids.h, shapes/mesh_solid.h) ---

    // The specials of a scope: the enclosing ones overridden by the scope's assignments (the last
    // assignment of a name holds for the whole scope, as in OpenSCAD).
    class SpecialsScope {
      public:
        // parent: the statement whose children these are; its own $fn/$fa/$fs arguments hold
        // for its children (OpenSCAD's special variables are passed down the call).
        SpecialsScope(Builder& b, const std::vector<Node>& nodes, const Node* parent = nullptr)
            : b_(b) {
            scad::Specials s = b.specials_.back();
            if (parent)
                for (const Arg& a : parent->args) SetSpecial(s, a);
            for (const Node& n : nodes)
                if (n.name == "=" && !n.args.empty()) SetSpecial(s, n.args[0]);
            b.specials_.push_back(s);
        }
        ~SpecialsScope() { b_.specials_.pop_back(); }
        SpecialsScope(const SpecialsScope&) = delete;
        SpecialsScope& operator=(const SpecialsScope&) = delete;

      private:
        Builder& b_;
    };
    static void SetSpecial(scad::Specials& s, const Arg& a) {
        if (a.value.kind != Value::Kind::kNumber) return;
        if (a.name == "$fn") s.fn = a.value.number;
        if (a.name == "$fa") s.fa = a.value.number;
        if (a.name == "$fs") s.fs = a.value.number;
    }
    scad::Specials SpecialsOf(const Node& n) const {
        scad::Specials s = specials_.back();
        for (const Arg& a : n.args) SetSpecial(s, a);
        return s;
    }

    int Refuse(const Node& n, const std::string& message) {
        ++report_.skipped[n.name];
        Missing(n, message);
        return -1;
    }

    // polyhedron(points, faces | triangles): the solid the closed mesh bounds.
    int Polyhedron(scene::Csg& csg, const Node& n, const Mat4& m, const std::optional<Paint>& color,
                   Box3& box) {
        ++report_.census[n.name];
        const Value* pts = Find(n, "points", 0);
        const Value* faces = Find(n, "faces", 1);
        if (!faces) faces = Find(n, "triangles", -1);
        std::vector<Vec3> v;
        std::vector<std::vector<int>> f;
        bool ok = pts && faces && pts->kind == Value::Kind::kVector &&
                  faces->kind == Value::Kind::kVector;
        for (std::size_t i = 0; ok && i < pts->items.size(); ++i) {
            const Value& p = pts->items[i];
            ok = p.kind == Value::Kind::kVector && p.items.size() == 3;
            Vec3 x;
            for (std::size_t k = 0; ok && k < 3; ++k) {
                ok = p.items[k].kind == Value::Kind::kNumber;
                if (ok) x[k] = p.items[k].number;
            }
            v.push_back(x);
        }
        for (std::size_t i = 0; ok && i < faces->items.size(); ++i) {
            const Value& fc = faces->items[i];
            ok = fc.kind == Value::Kind::kVector;
            std::vector<int> idx;
            for (std::size_t k = 0; ok && k < fc.items.size(); ++k) {
                ok = fc.items[k].kind == Value::Kind::kNumber &&
                     fc.items[k].number == std::floor(fc.items[k].number);
                if (ok) idx.push_back(static_cast<int>(fc.items[k].number));
            }
            f.push_back(std::move(idx));
        }
        if (!ok) {
            Error(n.offset,
                  "polyhedron: 'points' must be [[x, y, z], ...] and 'faces' a list of "
                  "vertex-index lists");
            return -1;
        }
        MeshSolid ms = MeshToSolid(v, f);
        if (!ms.ok) return Refuse(n, fmt::format("polyhedron: {}; it is left out", ms.problem));
        return LeafShape(csg, n, ms.shape, m, color, box);
    }

    // linear_extrude / rotate_extrude: the 2D children (square, circle, polygon, their
    // transforms and booleans) become 3D leaves combined by the same booleans, which commute
    // with both extrusions.
    int Extrude(scene::Csg& csg, const Node& n, const Mat4& m, const std::optional<Paint>& color,
                Box3& box) {
        ++report_.census[n.name];
        if (extrusion_) return Refuse(n, fmt::format("'{}' inside another extrusion", n.name));
        Extrusion e;
        e.node = &n;
        e.outer = m;
        if (n.name == "linear_extrude") {
            const double h = Num(n, "height", 0).value_or(100);
            const double twist = Num(n, "twist", -1).value_or(0);
            const Value* sc = Find(n, "scale", -1);
            if (sc && sc->kind == Value::Kind::kNumber) {
                e.scale = sc->number;
            } else if (sc && sc->kind == Value::Kind::kVector && sc->items.size() == 2 &&
                       sc->items[0].kind == Value::Kind::kNumber &&
                       sc->items[1].kind == Value::Kind::kNumber) {
                if (sc->items[0].number != sc->items[1].number)
                    return Refuse(n,
                                  "linear_extrude with a non-uniform scale sweeps twisted "
                                  "(ruled) sides, which are not planes; it is left out");
                e.scale = sc->items[0].number;
            }
            if (twist != 0)
                return Refuse(n,
                              "linear_extrude with twist ≠ 0 sweeps twisted (ruled) sides, "
                              "which are not quadrics or planes; it is left out");
            if (!(e.scale >= 0))
                return Refuse(n, "linear_extrude: a negative scale; it is left out");
            if (!(h > 0)) return -1;  // nothing to extrude
            e.h = h;
            e.z0 = Flag(n, "center", -1) ? -h / 2 : 0;
        } else {
            const double angle = Num(n, "angle", -1).value_or(360);
            if (std::fabs(angle) != 360)
                return Refuse(n,
                              "rotate_extrude with an angle other than 360° is not supported; "
                              "it is left out");
            e.rotate = true;
            e.specials = SpecialsOf(n);
        }
        extrusion_ = e;
        int root = Children(csg, n, Mat4::Identity(), color, scene::CsgOp::kUnion, box);
        extrusion_.reset();
        return root;
    }

    // A node of the 2D profile under an extrusion; m2 places it in the extrusion's plane.
    int Emit2D(scene::Csg& csg, const Node& n, const Mat4& m2, const std::optional<Paint>& color,
               Box3& box) {
        box = Box3{};
        if (n.dropped || failed_) return -1;
        const std::string& k = n.name;
        if (k == "square" || k == "circle" || k == "polygon")
            return Profile(csg, n, m2, color, box);
        if (k == "color") {
            auto c = ColorOf(n);
            return Children(csg, n, m2, c ? c : color, scene::CsgOp::kUnion, box);
        }
        if (k.empty() || k == "group" || k == "union" || k == "render" || k == "children")
            return Children(csg, n, m2, color, scene::CsgOp::kUnion, box);
        if (k == "difference") return Children(csg, n, m2, color, scene::CsgOp::kDifference, box);
        if (k == "intersection")
            return Children(csg, n, m2, color, scene::CsgOp::kIntersection, box);
        if (auto t = TransformOf(n))
            return Children(csg, n, m2 * *t, color, scene::CsgOp::kUnion, box);
        if (failed_) return -1;
        return Refuse(n, fmt::format("'{}' in the profile of {} cannot be drawn exactly; it is "
                                     "left out",
                                     k, extrusion_->node->name));
    }

    // rotate_extrude of an exact circle (x = radius, y = height in the profile plane): a torus
    // about the z axis, or an elliptical torus (shapes/torus.h) when the profile's transforms make
    // the circle an ellipse; its principal semi-axes u ⊥ v come from the images a, b of the radii
    // (a cos t + b sin t is extreme at tan 2t = 2a·b / (|a|² − |b|²)). A circle that reaches the
    // axis is refused (OpenSCAD refuses it too).
    int RevolvedCircle(scene::Csg& csg, const Node& n, const Mat4& m2, double r,
                       const std::optional<Paint>& color, Box3& box) {
        const Vec3 c = m2.MapPoint({0, 0, 0});
        const Vec3 a = m2.MapPoint({r, 0, 0}) - c, b = m2.MapPoint({0, r, 0}) - c;
        const double t0 = 0.5 * std::atan2(2 * (a.x * b.x + a.y * b.y),
                                           a.x * a.x + a.y * a.y - b.x * b.x - b.y * b.y);
        const Vec3 u = a * std::cos(t0) + b * std::sin(t0), v = b * std::cos(t0) - a * std::sin(t0);
        const double lu = std::hypot(u.x, u.y), lv = std::hypot(v.x, v.y);
        const double reach = std::sqrt(u.x * u.x + v.x * v.x);  // the ellipse's radial half extent
        if (!(std::fabs(c.x) > reach))
            return Refuse(n,
                          "rotate_extrude: the circle reaches the rotation axis (OpenSCAD "
                          "refuses it too); it is left out");
        ShapeResult s;
        if (std::fabs(lu - lv) <= 1e-12 * std::fmax(lu, lv)) {
            s = TorusShape({0, 0, c.y}, {0, 0, 1}, std::fabs(c.x), lu);
        } else {
            // The semi-axis vector C in the meridian plane through +x (radius x, axis z); a
            // circle at negative x is the same solid mirrored: flip its radial component.
            const double sx = c.x < 0 ? -1 : 1;
            s = EllipticalTorusShape({0, 0, c.y}, {0, 0, 1}, std::fabs(c.x), {sx * u.x, 0, u.y},
                                     lv);
        }
        if (!s.ok) return Refuse(n, fmt::format("rotate_extrude: {}; it is left out", s.problem));
        return LeafShape(csg, n, s.shape, extrusion_->outer, color, box);
    }

    // square, circle, polygon → rings in the extrusion plane → the extruded or revolved shape.
    int Profile(scene::Csg& csg, const Node& n, const Mat4& m2, const std::optional<Paint>& color,
                Box3& box) {
        ++report_.census[n.name];
        const Extrusion& e = *extrusion_;
        const std::string& k = n.name;
        auto at = [&](double x, double y) {
            const Vec3 p = m2.MapPoint({x, y, 0});
            return scad::Pt2{p.x, p.y};
        };
        std::vector<scad::Ring> rings;
        if (k == "square") {
            const Vec3 s = Vec(n, "size", 0, true).value_or(Vec3{1, 1, 1});
            const bool centre = Flag(n, "center", 1);
            const double x0 = centre ? -s.x / 2 : 0, y0 = centre ? -s.y / 2 : 0;
            rings.push_back(
                {at(x0, y0), at(x0 + s.x, y0), at(x0 + s.x, y0 + s.y), at(x0, y0 + s.y)});
        } else if (k == "circle") {
            double r = Num(n, "r", 0).value_or(1);
            if (auto d = Num(n, "d", -1)) r = *d / 2;
            if (!(r > 0)) return -1;
            auto sides = scad::PolygonSides(r, SpecialsOf(n));
            if (!sides) {
                if (e.rotate) return RevolvedCircle(csg, n, m2, r, color, box);
                // The exact circle: an elliptic cylinder (or cone, with scale) in the extrusion.
                const Vec3 c = m2.MapPoint({0, 0, 0});
                Vec3 a = m2.MapPoint({r, 0, 0}) - c, b = m2.MapPoint({0, r, 0}) - c;
                a.z = b.z = 0;
                const ConeShape cone = TruncatedConeShape(
                    {c.x, c.y, e.z0}, {c.x * (e.scale - 1), c.y * (e.scale - 1), e.h}, a, b,
                    a * e.scale, b * e.scale);
                return Leaf(csg, n, cone, e.outer, color, box);
            }
            scad::Ring ring;
            for (const scad::Pt2& q : scad::RegularPolygon(r, *sides)) ring.push_back(at(q.x, q.y));
            rings.push_back(std::move(ring));
        } else {
            const Value* pts = Find(n, "points", 0);
            const Value* paths = Find(n, "paths", 1);
            std::vector<scad::Pt2> all;
            bool ok = pts && pts->kind == Value::Kind::kVector;
            for (std::size_t i = 0; ok && i < pts->items.size(); ++i) {
                const Value& q = pts->items[i];
                ok = q.kind == Value::Kind::kVector && q.items.size() >= 2 &&
                     q.items[0].kind == Value::Kind::kNumber &&
                     q.items[1].kind == Value::Kind::kNumber;
                if (ok) all.push_back(at(q.items[0].number, q.items[1].number));
            }
            if (ok && paths && paths->kind == Value::Kind::kVector) {
                for (const Value& path : paths->items) {
                    scad::Ring ring;
                    ok = ok && path.kind == Value::Kind::kVector;
                    for (std::size_t i = 0; ok && i < path.items.size(); ++i) {
                        const double x = path.items[i].number;
                        ok = path.items[i].kind == Value::Kind::kNumber && x >= 0 &&
                             x < static_cast<double>(all.size()) && x == std::floor(x);
                        if (ok) ring.push_back(all[static_cast<std::size_t>(x)]);
                    }
                    rings.push_back(std::move(ring));
                }
            } else if (ok) {
                rings.push_back(all);
            }
            if (!ok) {
                Error(n.offset,
                      "polygon: 'points' must be [[x, y], ...] and 'paths' lists of "
                      "point indices");
                return -1;
            }
        }
        if (e.rotate) {
            std::string problem;
            auto shape = scad::RotateExtrude(rings, e.specials, &problem);
            if (!shape)
                return Refuse(n, fmt::format("rotate_extrude: {}; it is left out", problem));
            return LeafShape(csg, n, *shape, e.outer, color, box);
        }
        return LeafShape(csg, n, scad::LinearExtrude(rings, e.z0, e.h, e.scale), e.outer, color,
                         box);
    }

    const TextMap& map_;
    const ImportOptions& options_;
    scene::Scene& scene_;
    Diagnostics& diags_;
    ImportReport& report_;
    bool failed_ = false;
    std::vector<scad::Specials> specials_{scad::Specials{}};
    // Inside linear_extrude/rotate_extrude: the extrusion and the matrix that places its frame.
    struct Extrusion {
        bool rotate = false;
        scad::Specials specials;  // rotate_extrude's: its fragments (polygon_solids.h)
        double z0 = 0, h = 1, scale = 1;
        const Node* node = nullptr;
        Mat4 outer = Mat4::Identity();
    };
    std::optional<Extrusion> extrusion_;
};

}  // namespace

bool ImportOpenScad(std::string_view text, const std::string& file, const ImportOptions& options,
                    scene::Scene& scene, Diagnostics& diags, ImportReport& report) {
    report.format = "OpenSCAD CSG";
    TextMap map(text, file);
    std::vector<Node> nodes;
    int errorsBefore = diags.ErrorCount();
    if (!Parser(map, diags).Run(nodes)) return false;
    Builder builder(map, options, scene, diags, report);
    builder.Top(nodes, Mat4::Identity(), std::nullopt);
    if (!options.topObjects.empty()) {
        // OpenSCAD files have no named objects: --top applies to BRL-CAD files only.
        for (const std::string& t : options.topObjects) report.missingTops.push_back(t);
    }
    return diags.ErrorCount() == errorsBefore && !builder.failed();
}

bool ParsesAsOpenScadSubset(std::string_view text, const std::string& file, Diagnostics& diags) {
    TextMap map(text, file);
    std::vector<Node> nodes;
    return Parser(map, diags).Run(nodes);
}

}  // namespace quadrix::import
