#include "quadrix/io/pov_export.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

namespace quadrix {

namespace {

std::string Num(double v) { return fmt::format("{:.17g}", v); }

// Polynomials in (x, y, z) of degree <= 4, dense by exponents (for POV-Ray's `quartic`).
struct Poly3 {
    std::array<double, 125> c{};
    static std::size_t Index(int i, int j, int k) {
        return static_cast<std::size_t>(25 * i + 5 * j + k);
    }
    static Poly3 Linear(double a, double b, double cz, double d) {
        Poly3 p;
        p.c[Index(1, 0, 0)] = a;
        p.c[Index(0, 1, 0)] = b;
        p.c[Index(0, 0, 1)] = cz;
        p.c[Index(0, 0, 0)] = d;
        return p;
    }
    Poly3 operator*(const Poly3& o) const {
        Poly3 r;
        for (int i = 0; i < 5; ++i)
            for (int j = 0; i + j < 5; ++j)
                for (int k = 0; i + j + k < 5; ++k) {
                    const double a = c[Index(i, j, k)];
                    if (a == 0) continue;
                    for (int u = 0; i + u < 5; ++u)
                        for (int v = 0; j + v < 5 && i + u + j + v < 5; ++v)
                            for (int w = 0; i + j + k + u + v + w < 5; ++w)
                                r.c[Index(i + u, j + v, k + w)] += a * o.c[Index(u, v, w)];
                }
        return r;
    }
    Poly3 operator+(const Poly3& o) const {
        Poly3 r = *this;
        for (std::size_t i = 0; i < c.size(); ++i) r.c[i] += o.c[i];
        return r;
    }
    Poly3 operator*(double k) const {
        Poly3 r = *this;
        for (double& v : r.c) v *= k;
        return r;
    }
};

// F∘L as a polynomial in space coordinates relative to `centre` (x = centre + x'), where L is
// the quartic's localFromSpace: the local coordinates are linear in x'.
Poly3 QuarticInSpace(const QuarticSurface& q, const Vec3& centre) {
    const Mat4& m = q.localFromSpace.Matrix();
    Poly3 L[4];
    for (int r = 0; r < 4; ++r)
        L[r] =
            Poly3::Linear(m(r, 0), m(r, 1), m(r, 2),
                          m(r, 0) * centre.x + m(r, 1) * centre.y + m(r, 2) * centre.z + m(r, 3));
    const std::array<double, 6>& k = q.k;
    if (q.kind == QuarticSurface::Kind::kGeneralCone) {
        const Poly3 al = L[3] * k[0] + L[2] * k[1], be = L[3] * k[2] + L[2] * k[3];
        const Poly3 a2 = al * al, b2 = be * be;
        return L[0] * L[0] * b2 + L[1] * L[1] * a2 + a2 * b2 * -1.0;
    }
    const Poly3 r2 = L[0] * L[0] + L[1] * L[1];
    const Poly3 E = r2 * k[0] + L[2] * L[2] * k[2] + L[2] * L[3] * k[4] + L[3] * L[3] * k[5];
    const Poly3 O = L[2] * (2 * k[1]) + L[3] * k[3];
    return E * E + r2 * O * O * -1.0;
}

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
        if (h.IsQuartic()) {
            Quartic(*h.quartic);
        } else if (h.isPlane) {
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

    // A torus under an affine map: POV-Ray's `torus` (in its xz-plane, axis y) with the map as a
    // `matrix`. Otherwise (elliptical torus, general cone, projective device maps) a `quartic`
    // of 35 coefficients (x⁴, x³y, x³z, x³, x²y², …, z, 1: exponents of x, then y, then z in
    // descending order) about the centre of its box, solved with `sturm`, then translated. The
    // clip box of a general cone is left to its caps (which it must have).
    void Quartic(const QuarticSurface& q) {
        const Mat4& inv = q.localFromSpace.Inverse();  // spaceFromLocal
        const bool affine = inv(3, 0) == 0 && inv(3, 1) == 0 && inv(3, 2) == 0 && inv(3, 3) == 1 &&
                            q.localFromSpace.Matrix()(3, 0) == 0 &&
                            q.localFromSpace.Matrix()(3, 1) == 0 &&
                            q.localFromSpace.Matrix()(3, 2) == 0;
        if (q.kind == QuarticSurface::Kind::kTorus && affine) {
            // Local units: R + r = 1 (quartic_surface.cpp). POV's (x, y, z) → local (x, z, y).
            const double s = q.p[0] + q.p[1];
            const int col[3] = {0, 2, 1};
            std::string rows;
            for (int r = 0; r < 3; ++r)
                rows += fmt::format("{},{},{}, ", Num(inv(0, col[r])), Num(inv(1, col[r])),
                                    Num(inv(2, col[r])));
            out_ +=
                fmt::format("torus {{ {}, {} matrix <{}{},{},{}>", Num(q.p[0] / s), Num(q.p[1] / s),
                            rows, Num(inv(0, 3)), Num(inv(1, 3)), Num(inv(2, 3)));
            return;
        }
        const Box3 box = q.SpaceBounds();
        const Vec3 c = box.Finite() ? box.Center() : Vec3{};
        Poly3 p = QuarticInSpace(q, c);
        double mx = 0;
        for (double v : p.c) mx = std::fmax(mx, std::fabs(v));
        if (mx > 0) p = p * (1 / mx);
        std::string coeffs;
        for (int i = 4; i >= 0; --i)
            for (int j = 4 - i; j >= 0; --j)
                for (int k = 4 - i - j; k >= 0; --k)
                    coeffs += (coeffs.empty() ? "" : ",") + Num(p.c[Poly3::Index(i, j, k)]);
        out_ += fmt::format("quartic {{ <{}> sturm translate <{},{},{}>", coeffs, Num(c.x),
                            Num(c.y), Num(c.z));
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
        if (node.op == scene::CsgOp::kDifference && DistributesWell(node)) {
            // (∪ aᵢ) − S → ∪ (aᵢ − S): see pov_export.h.
            const FlatCsgNode& minuend = scene_.nodes[node.children[0]];
            Indent(depth);
            out_ += "union {\n";
            for (int a : minuend.children) {
                Indent(depth + 1);
                out_ += "difference {\n";
                Node(a, depth + 2);
                for (std::size_t k = 1; k < node.children.size(); ++k)
                    Node(node.children[k], depth + 2);
                Indent(depth + 1);
                out_ += "}\n";
            }
            Indent(depth);
            out_ += "}\n";
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

    // A difference whose minuend is a union of more than kDistributedUnion operands and whose
    // subtrahends are few (at most kDistributedSubtrahends bodies' worth of text per operand).
    bool DistributesWell(const FlatCsgNode& node) const {
        const FlatCsgNode& minuend = scene_.nodes[node.children[0]];
        return !minuend.isLeaf && minuend.op == scene::CsgOp::kUnion &&
               minuend.children.size() > kDistributedUnion &&
               node.children.size() - 1 <= kDistributedSubtrahends;
    }
    static constexpr std::size_t kDistributedUnion = 8, kDistributedSubtrahends = 4;

    const FlatScene& scene_;
    const PovExportOptions& options_;
    std::string out_;
};

}  // namespace

std::string ExportPov(const FlatScene& scene, const PovExportOptions& options) {
    return PovWriter(scene, options).Run();
}

}  // namespace quadrix
