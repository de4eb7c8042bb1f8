#include "quadrix/io/pov_export.h"

#include <fmt/format.h>

#include <cmath>

namespace quadrix {

namespace {

std::string Num(double v) { return fmt::format("{:.17g}", v); }

class PovWriter {
  public:
    PovWriter(const FlatScene& scene, const PovExportOptions& options)
        : scene_(scene), options_(options) {}

    std::string Run() {
        Header();
        out_ += "union {\n";
        for (std::size_t s = 0; s < scene_.solids.size(); ++s) Node(scene_.solids[s].root, 1);
        // Quadrix renders without shadows unless asked to, so the export's solids cast none then
        // (`no_shadow` on the objects, not `shadowless` lights: POV-Ray's shadowless lights give no
        // highlights).
        out_ += options_.shadows ? "  scale <1,-1,1>\n}\n" : "  scale <1,-1,1>\n  no_shadow\n}\n";
        return out_;
    }

  private:
    void Header() {
        const double w = scene_.width, h = scene_.height;
        double zmin = HUGE_VAL;
        for (const FlatSolid& s : scene_.solids)
            if (std::isfinite(s.bounds.lo.z)) zmin = std::fmin(zmin, s.bounds.lo.z);
        double camZ = std::isfinite(zmin) ? zmin - 1.0 - std::fabs(zmin) * 1e-3 : -1e7;
        out_ += "// Written by quadrix export --to pov (device space; see docs/pov-export.md)\n";
        out_ += "#version 3.7;\n";
        out_ += fmt::format(
            "camera {{ orthographic location <{0},{1},{2}> right <{3},0,0> up <0,{4},0> "
            "direction <0,0,1> }}\n",
            Num(w / 2), Num(-h / 2), Num(camZ), Num(w), Num(h));
        if (options_.mask) out_ += "background { color rgb <0,0,0> }\n";
        scene::Color ambient{0, 0, 0};
        for (const scene::Light& l : scene_.lights)
            if (l.kind == scene::Light::Kind::kAmbient) {
                ambient.r += l.intensity * l.color.r;
                ambient.g += l.intensity * l.color.g;
                ambient.b += l.intensity * l.color.b;
            }
        if (options_.mask) {
            out_ += "global_settings { assumed_gamma 1.0 ambient_light rgb <1,1,1> }\n";
            out_ +=
                "#default { finish { ambient 1 diffuse 0 specular 0 phong 0 } pigment { color rgb "
                "<1,1,1> } }\n";
            return;
        }
        // Linear light in, as Quadrix shades (assumed_gamma 1.0); the output encoding is the
        // renderer's File_Gamma (docs/pov-export.md: File_Gamma=sRGB matches Quadrix's PNGs).
        out_ +=
            fmt::format("global_settings {{ assumed_gamma 1.0 ambient_light {} }}\n", Rgb(ambient));
        out_ += "#default { finish { ambient 1 diffuse 1 brilliance 1 specular 0 phong 0 } }\n";
        Background(w, h);
        const Mat4& m = scene_.projection.deviceFromWorld.Matrix();
        for (const scene::Light& l : scene_.lights) {
            const scene::Color c{l.intensity * l.color.r, l.intensity * l.color.g,
                                 l.intensity * l.color.b};
            switch (l.kind) {
                case scene::Light::Kind::kAmbient:
                    break;
                case scene::Light::Kind::kParallel: {
                    // Direction toward the light in device space, then into POV space (y flipped).
                    Vec3 d = Normalize(m.MapVector(l.direction));
                    Vec3 p = d * 1e7;
                    out_ +=
                        fmt::format("light_source {{ {} color {} parallel point_at <0,0,0> }}\n",
                                    Pov(p), Rgb(c));
                    break;
                }
                case scene::Light::Kind::kPoint:
                    out_ += fmt::format("light_source {{ {} color {} }}\n",
                                        Pov(m.MapPoint(l.position)), Rgb(c));
                    break;
                case scene::Light::Kind::kSpot:
                    // POV-Ray's spot attenuation is the same cubic spline in cos θ (lighting.h).
                    out_ += fmt::format(
                        "light_source {{ {} color {} spotlight point_at {} radius {} falloff {} "
                        "tightness 0 }}\n",
                        Pov(m.MapPoint(l.position)), Rgb(c), Pov(m.MapPoint(l.aim)),
                        Num(l.coneDegrees), Num(l.falloffDegrees));
                    break;
            }
        }
    }

    static std::string Rgb(const scene::Color& c) {
        return fmt::format("rgb <{},{},{}>", Num(c.r), Num(c.g), Num(c.b));
    }
    // A device-space point in POV-Ray's space (y flipped; the lights are outside the scaled union).
    static std::string Pov(const Vec3& p) {
        return fmt::format("<{},{},{}>", Num(p.x), Num(-p.y), Num(p.z));
    }

    // A plain background, or the vertical gradient as an emitting plane behind every solid
    // (POV-Ray's background and sky_sphere are uniform under an orthographic camera).
    void Background(double w, double h) {
        const scene::Color& top = scene_.background;
        const scene::Color& bottom = scene_.backgroundBottom;
        out_ += fmt::format("background {{ color {} }}\n", Rgb(top));
        if (top == bottom) return;
        double zmax = -HUGE_VAL;
        for (const FlatSolid& s : scene_.solids)
            if (std::isfinite(s.bounds.hi.z)) zmax = std::fmax(zmax, s.bounds.hi.z);
        const double z = std::isfinite(zmax) ? zmax + 1 + std::fabs(zmax) * 1e-3 : 1e7;
        // POV y runs from -h (bottom row) to 0 (top row): gradient y scaled to h, shifted down.
        out_ += fmt::format(
            "plane {{ <0,0,-1>, {} pigment {{ gradient y color_map {{ [0 color {}] [1 color {}] }} "
            "scale <1,{},1> translate <0,{},0> }} finish {{ emission 1 ambient 0 diffuse 0 }} "
            "no_shadow }}\n",
            Num(-z), Rgb(bottom), Rgb(top), Num(h), Num(-h));
        (void)w;
    }

    void Indent(int depth) { out_.append(static_cast<std::size_t>(depth) * 2, ' '); }

    void HalfSpace(const FlatLiteral& lit, int depth) {
        const FlatHalfSpace& h = scene_.halfSpaces[lit.halfSpace];
        Indent(depth);
        if (h.isPlane) {
            double len = Length(h.plane.Normal());
            out_ += fmt::format("plane {{ <{},{},{}>, {}", Num(h.plane.a), Num(h.plane.b),
                                Num(h.plane.c), Num(len > 0 ? -h.plane.d / len : 0));
        } else {
            const Quadric& q = h.quadric;
            out_ +=
                fmt::format("quadric {{ <{},{},{}>, <{},{},{}>, <{},{},{}>, {}", Num(q.A()),
                            Num(q.B()), Num(q.C()), Num(2 * q.D()), Num(2 * q.F()), Num(2 * q.E()),
                            Num(2 * q.G()), Num(2 * q.H()), Num(2 * q.J()), Num(q.K()));
        }
        out_ += lit.complemented ? " inverse }\n" : " }\n";
    }

    void Body(int b, int depth) {
        const FlatBody& body = scene_.bodies[b];
        std::vector<FlatLiteral> opaque, bounding;
        for (const FlatLiteral& l : body.literals)
            (scene_.halfSpaces[l.halfSpace].transparent ? bounding : opaque).push_back(l);
        // One opaque literal is written as a plain object: POV-Ray decides intersection membership
        // of surface points by evaluating the other members, so repeating a member to satisfy the
        // "two members" rule would make on-surface points flicker between inside and outside.
        Indent(depth);
        out_ += opaque.size() == 1 ? "object {\n" : "intersection {\n";
        if (opaque.empty()) {
            // Nothing is drawn, but the body must stay a valid (empty) solid.
            Indent(depth + 1);
            out_ += "sphere { <0,0,0>, 1 inverse } sphere { <0,0,0>, 1 }\n";
        }
        for (const FlatLiteral& l : opaque) HalfSpace(l, depth + 1);
        if (!bounding.empty()) {
            // clipped_by with several objects keeps what is inside all of them.
            Indent(depth + 1);
            out_ += "clipped_by {\n";
            for (const FlatLiteral& l : bounding) HalfSpace(l, depth + 2);
            Indent(depth + 1);
            out_ += "}\n";
        }
        if (!options_.mask) {
            const scene::Color& c = body.color;
            const scene::Finish& f = body.finish;
            Indent(depth + 1);
            if (f.opacity && *f.opacity < 1)
                out_ += fmt::format("pigment {{ color rgbt <{},{},{},{}> }}\n", Num(c.r), Num(c.g),
                                    Num(c.b), Num(1 - *f.opacity));
            else
                out_ += fmt::format("pigment {{ color rgb <{},{},{}> }}\n", Num(c.r), Num(c.g),
                                    Num(c.b));
            if (f.diffuse || f.specular) {
                // The Lambert model's finish (shade/shader.h): a Blinn–Phong highlight, which is
                // POV-Ray's `specular` with roughness 1/shininess.
                Indent(depth + 1);
                out_ += fmt::format("finish {{ ambient 1 diffuse {} specular {} roughness {} }}\n",
                                    Num(f.diffuse.value_or(1)), Num(f.specular.value_or(0)),
                                    Num(1 / f.shininess.value_or(24)));
            }
        }
        Indent(depth);
        out_ += "}\n";
    }

    void Node(int n, int depth) {
        const FlatCsgNode& node = scene_.nodes[n];
        if (node.isLeaf) {
            Body(node.body, depth);
            return;
        }
        if (node.children.size() == 1) {
            Node(node.children[0], depth);
            return;
        }
        const char* op = node.op == scene::CsgOp::kUnion          ? "union"
                         : node.op == scene::CsgOp::kIntersection ? "intersection"
                                                                  : "difference";
        Indent(depth);
        out_ += fmt::format("{} {{\n", op);
        for (int c : node.children) Node(c, depth + 1);
        Indent(depth);
        out_ += "}\n";
    }

    const FlatScene& scene_;
    const PovExportOptions& options_;
    std::string out_;
};

}  // namespace

std::string ExportPov(const FlatScene& scene, const PovExportOptions& options) {
    return PovWriter(scene, options).Run();
}

}  // namespace quadrix
