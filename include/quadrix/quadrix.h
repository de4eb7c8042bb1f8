// Quadrix's public C++ API: the one installed header (docs/api.md).
//
// Read a scene (any supported format) or build one in code, render it exactly (no tessellation)
// to a Frame — per-pixel depth, normal and ids as plain arrays — and an RGB image, compose
// renderings by depth, write PNG or PPM files:
//
//   quadrix::Scene scene = quadrix::Scene::FromFile("part.uq");
//   quadrix::Renderer renderer;
//   quadrix::Renderer::Options options;
//   options.width = 640;
//   options.height = 480;
//   quadrix::Rendering r = renderer.Render(scene, options);
//   r.image.Write("part.png");
//
// Error model: exceptions. Every function that can fail on user input (scene text, files, options)
// throws quadrix::Error, which carries every diagnostic with its file, line and column; nothing
// half-done is left behind (a Scene edit that fails leaves the scene as it was, a failed write
// leaves no file). Out-of-memory is std::bad_alloc. No other exception crosses this API.
//
// Stability: this header uses only the standard library and exposes no internal type; the
// implementation sits behind pointers (Scene::Impl, Renderer::Impl), so the internal headers of
// src/quadrix/ never reach a consumer. Everything here is in namespace quadrix and linked from
// libquadrix (CMake: find_package(Quadrix) → quadrix::quadrix; pkg-config: quadrix).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace quadrix {

// "0.1.0": the library's version (the same as `quadrix --version`).
const char* VersionString();

// One diagnostic about user input. line/column are 1-based; 0 = no position (an option).
struct Message {
    enum class Severity { kNote, kWarning, kError };
    Severity severity = Severity::kError;
    std::string file;  // the file (or text name) it is about; empty when none
    int line = 0, column = 0;
    std::string text;        // the message itself
    std::string sourceLine;  // the offending line of the input, empty when unknown
    // "file:line:column: error: text", with the source line and a caret when withSource.
    std::string Format(bool withSource = false) const;
};

// What every failing call throws. what() is every error formatted, one per line.
class Error : public std::runtime_error {
  public:
    explicit Error(std::vector<Message> messages);
    explicit Error(const std::string& text);  // one message without a position
    // Every diagnostic, errors and the warnings reported with them, in input order.
    const std::vector<Message>& Messages() const noexcept { return messages_; }
    // The position of the first error (file empty and line 0 when it has none).
    const std::string& File() const noexcept;
    int Line() const noexcept;
    int Column() const noexcept;

  private:
    std::vector<Message> messages_;
    std::size_t first_ = 0;
};

using Vector3 = std::array<double, 3>;

// Linear intensities in [0, 1].
struct Color {
    double r = 1, g = 1, b = 1;
};

// A view (docs/language.md §3.8): unset members take the language's defaults. dop points from
// the scene toward the viewer (parallel projection); cop is the eye (perspective); a view has at
// most one of them. halfHeight/halfWidth: the window on the view plane (unset: fitted to the
// scene).
struct View {
    std::string id;  // for AddView; empty = generated
    std::optional<Vector3> vrp, vpn, vup, dop, cop;
    std::optional<double> halfHeight, halfWidth;

    // A parallel view looking along -toward (toward = from the scene to the viewer), fitted.
    static View Parallel(const Vector3& toward);
    // A perspective view from `eye` at `target`.
    static View Perspective(const Vector3& eye, const Vector3& target);
};

// Options of Scene::FromFiles for imported formats (docs/import.md).
struct ReadOptions {
    std::vector<std::string> topObjects;  // BRL-CAD/OpenSCAD objects to draw (empty: all)
    bool strict = false;                  // primitives that cannot be drawn exactly: an error
    bool allowMissing = false;            // ... or left out with a warning
};

enum class CsgOperation { kUnion, kIntersection, kDifference };

// A scene: half-spaces, bodies, instances, CSG solids, solids by their dimensions, lights and
// views (docs/language.md). A value: copies are independent. Every Add* call is checked as the
// scene language checks the statement it stands for (unknown or duplicate ids, zero normals, bad
// dimensions) and throws Error without changing the scene.
class Scene {
  public:
    Scene();  // empty
    ~Scene();
    Scene(const Scene& other);
    Scene& operator=(const Scene& other);
    Scene(Scene&& other) noexcept;
    Scene& operator=(Scene&& other) noexcept;

    // Reads files of any supported format (.uq, BRL-CAD .g/.asc, OpenSCAD .csg/.scad, freeform
    // .obj/.bpt/...; docs/import.md), in order, into one scene. "-" = standard input.
    static Scene FromFiles(const std::vector<std::string>& paths, const ReadOptions& options = {});
    static Scene FromFile(const std::string& path, const ReadOptions& options = {});
    // Scene language text (docs/language.md); `name` appears in diagnostics.
    static Scene FromText(std::string_view text, const std::string& name = "<text>");

    // Adds scene-language statements (any of docs/language.md, definitions included) to this scene;
    // they may name what is already there. `name` appears in diagnostics.
    Scene& Append(std::string_view text, const std::string& name = "<text>");

    // Half-spaces: plane a·x + b·y + c·z + d <= 0 inside ((a, b, c) the outward normal);
    // quadric <A B C D E F G H J K> = Ax² + By² + Cz² + Dxy + Eyz + Fxz + Gx + Hy + Jz + K <= 0
    // inside (docs/language.md §2). Transparent half-spaces bound but are not drawn.
    Scene& AddPlane(const std::string& id, const std::array<double, 4>& abcd,
                    bool transparent = false);
    Scene& AddQuadric(const std::string& id, const std::array<double, 10>& coefficients,
                      bool transparent = false);
    // A body: the intersection of half-spaces, each named by id, "!id" for the complement.
    Scene& AddBody(const std::string& id, const std::vector<std::string>& literals,
                   std::optional<Color> color = {});
    // A CSG solid of two solids (bodies, instances, solids or other CSG solids) already defined.
    Scene& AddCsg(const std::string& id, CsgOperation operation, const std::string& left,
                  const std::string& right, std::optional<Color> color = {});
    // A CSG solid given as an expression: "a | b & c", "(a - b) - c" (docs/language.md §3.5).
    Scene& AddCsg(const std::string& id, const std::string& expression,
                  std::optional<Color> color = {});
    // Solids by their dimensions (docs/language.md §3.13): each makes its half-spaces and a body.
    Scene& AddSphere(const std::string& id, const Vector3& center, double radius,
                     std::optional<Color> color = {});
    Scene& AddBox(const std::string& id, const Vector3& corner0, const Vector3& corner1,
                  std::optional<Color> color = {});
    Scene& AddCylinder(const std::string& id, const Vector3& from, const Vector3& to, double radius,
                       std::optional<Color> color = {});
    Scene& AddCone(const std::string& id, const Vector3& from, const Vector3& to, double radius0,
                   double radius1, std::optional<Color> color = {});
    // Lights (docs/language.md §3.7), world space. A scene without any light is lit by the
    // default rig that follows the view.
    Scene& AddAmbientLight(const std::string& id, double intensity);
    Scene& AddParallelLight(const std::string& id, double intensity, const Vector3& towardLight,
                            std::optional<Color> color = {});
    Scene& AddPointLight(const std::string& id, double intensity, const Vector3& position,
                         std::optional<Color> color = {});
    // A named view; the last one added is the one rendered unless Options::view names another.
    Scene& AddView(const View& view);

    // What is in the top level of the scene.
    std::size_t HalfSpaceCount() const;
    std::size_t BodyCount() const;
    std::size_t CsgCount() const;
    std::size_t LightCount() const;
    std::vector<std::string> ViewNames() const;
    bool Empty() const;  // nothing would be drawn
    // Warnings of every read and Add* call so far (the ones that did not stop it).
    const std::vector<Message>& Warnings() const;

  private:
    friend class Renderer;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// An RGB image, 8 bits per channel, sRGB-encoded (what PNG and PPM files hold), rows top to
// bottom, channels interleaved; `linear` holds the same pixels in linear light as floats in
// [0, 1] before quantisation (for 16-bit output and further processing).
struct RgbImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // width·height·3
    std::vector<float> linear;      // width·height·3, or empty

    const std::uint8_t* At(int x, int y) const {
        return &rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)) *
                    3];
    }
    // Writes the image; the format follows the extension: .png (8 bits, or 16 with sixteenBit)
    // or .ppm. Written to a temporary file then renamed: a failure leaves no file. Throws Error.
    void Write(const std::string& path, bool sixteenBit = false) const;
};

// What one render produced: the Frame's buffers (one entry per pixel, rows top to bottom), the
// shaded image, the names the ids refer to, and how it was made.
struct Rendering {
    static constexpr std::int32_t kNone = -1;  // an id of a background pixel

    // Depth and normal as the renderer's Frame keeps them (16 bytes a pixel): depth is a float
    // value (within half a float ulp of the exact depth), the normal within about 4e-5 radians
    // of the exact one (exact along the axes).
    int width = 0, height = 0;
    std::vector<double> depth;  // device z (increases away from the viewer); +inf = background
    std::vector<double>
        normal;  // world-space unit normal toward the viewer, 3 per pixel; 0 = background
    std::vector<std::int32_t> surface;  // index into surfaceNames, kNone = background
    std::vector<std::int32_t> body;     // index into bodyNames
    std::vector<std::int32_t> solid;    // index into solidNames
    std::vector<std::string> surfaceNames, bodyNames, solidNames;  // e.g. "part/hole"
    RgbImage image;

    std::string engine;              // the engine asked for
    std::vector<std::string> notes;  // e.g. solids drawn by the reference engine instead
    double seconds = 0;              // render and shade

    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
               static_cast<std::size_t>(x);
    }
    bool Covered(int x, int y) const { return surface[Index(x, y)] != kNone; }
    std::size_t CoveredCount() const;
};

// The per-pixel nearer of two renderings of the same size (the picture of both scenes' solids
// together, when both were rendered with the same view and size): depth, normal, ids and image
// pixel all come from the rendering with the smaller depth (ties: `a`). Ids and names of `b` are
// renumbered after those of `a`. Throws Error when the sizes differ.
Rendering Compose(const Rendering& a, const Rendering& b);

// Renders scenes. Keeps its worker threads, engines and the last flattened scene, so rendering
// the same scene again (another engine, another shading) does not flatten again. Not for use by
// two threads at once; one Renderer per thread.
class Renderer {
  public:
    enum class Shading { kLambert, kFlat, kPhong, kBlinnPhong };

    struct Options {
        int width = 512, height = 512;
        std::string engine = "raycast";                    // Renderer::Engines()
        std::map<std::string, std::string> engineOptions;  // docs/engines.md
        // Refuse (Error) what the engine cannot draw instead of drawing it with raycast.
        bool strict = false;
        Shading shading = Shading::kLambert;
        bool shadows = false;  // shadow rays (parallel views)
        // Anti-aliasing (docs/shading.md): 0 = off, or 4, 16 or 64 exact samples on each edge
        // pixel (interior pixels are not resampled); edges = one-pixel silhouette/crease lines.
        int antialias = 0;
        bool edges = false;
        std::optional<Color> background;  // instead of the scene's
        std::string view;                 // a view of the scene by id (empty: the last one)
        std::optional<View> camera;       // a view given here instead
        bool image = true;                // false: the Frame only, no shading
    };

    // threads: worker threads, 0 = every hardware thread.
    explicit Renderer(int threads = 0);
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Throws Error: unknown engine or option, unknown view, bad size, or (strict) what the engine
    // cannot draw.
    Rendering Render(const Scene& scene, const Options& options);
    Rendering Render(const Scene& scene) { return Render(scene, Options{}); }

    // The engines' names (the first is the reference engine, raycast).
    static std::vector<std::string> Engines();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace quadrix
