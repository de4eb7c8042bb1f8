// quadrix::Renderer, Rendering, RgbImage and Compose (include/quadrix/quadrix.h), on THE render
// path: a RenderContext (pipeline/render_context.h) kept by the Renderer — Flatten, Render with
// composition, Shade — and the writers of io/writers.h for files (temporary file + rename).
//
// The Frame's buffers are copied out into plain arrays (the public type holds no internal one);
// the image is shaded in RGB (ShadeOptions::forceColor), so a gray scene gives r = g = b.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <utility>

#include "api_internal.h"
#include "quadrix/engines/registry.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix {

struct Renderer::Impl {
    explicit Impl(int threads) : context(threads) {}
    RenderContext context;
    std::uint64_t revision = 0;  // of the scene last handed to the context; 0 = none
};

Renderer::Renderer(int threads) {
    if (threads < 0) throw Error("Renderer: threads must be 0 (all) or more");
    impl_ = std::make_unique<Impl>(threads);
}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

std::vector<std::string> Renderer::Engines() {
    std::vector<std::string> names;
    for (const EngineInfo& e : ::quadrix::Engines())
        if (!e.hidden) names.push_back(e.name);
    return names;
}

namespace {

ShadingModel ToModel(Renderer::Shading s) {
    switch (s) {
        case Renderer::Shading::kFlat:
            return ShadingModel::kFast;
        case Renderer::Shading::kPhong:
            return ShadingModel::kPhong;
        case Renderer::Shading::kBlinnPhong:
            return ShadingModel::kBlinnPhong;
        case Renderer::Shading::kLambert:
            break;
    }
    return ShadingModel::kLambert;
}

void CheckCamera(const View& v) {
    auto nonZero = [](const std::optional<Vector3>& d, const char* what) {
        if (d && (*d)[0] == 0 && (*d)[1] == 0 && (*d)[2] == 0)
            throw Error(fmt::format("Options::camera: {} is the zero vector", what));
    };
    nonZero(v.vpn, "vpn");
    nonZero(v.vup, "vup");
    nonZero(v.dop, "dop");
    if (v.dop && v.cop) throw Error("Options::camera: a view has dop or cop, not both");
    if ((v.halfHeight && !(*v.halfHeight > 0)) || (v.halfWidth && !(*v.halfWidth > 0)))
        throw Error("Options::camera: the window half-sizes must be positive");
}

RgbImage ToRgbImage(const Image& image) {
    RgbImage out;
    out.width = image.width;
    out.height = image.height;
    const std::vector<std::uint8_t> encoded = EncodeSrgb8(image);
    const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
    out.rgb.resize(n * 3);
    const bool hasLinear = image.linear.size() == image.pixels.size();
    if (hasLinear) out.linear.resize(n * 3);
    for (std::size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c) {
            const std::size_t from = p * image.channels + (image.channels == 3 ? c : 0);
            out.rgb[p * 3 + c] = encoded[from];
            if (hasLinear) out.linear[p * 3 + c] = image.linear[from];
        }
    return out;
}

}  // namespace

Rendering Renderer::Render(const Scene& scene, const Options& options) {
    const auto t0 = std::chrono::steady_clock::now();
    if (auto e = CheckImageSize(options.width, options.height); !e.empty())
        throw Error("Options: " + e);
    if (options.antialias != 0 && options.antialias != 4 && options.antialias != 16 &&
        options.antialias != 64)
        throw Error(
            fmt::format("Options: antialias {}: expected 0 (off), 4, 16 or 64", options.antialias));
    EngineRequest engine;
    engine.engine = options.engine;
    engine.options = options.engineOptions;
    engine.strict = options.strict;
    if (auto e = RenderContext::CheckEngine(engine); !e.empty()) throw Error("Options: " + e);

    RenderContext& ctx = impl_->context;
    if (impl_->revision != scene.impl_->revision) {
        ctx.Scene() = scene.impl_->scene;
        ctx.SceneChanged();
        impl_->revision = scene.impl_->revision;
    }
    ViewRequest view;
    view.width = options.width;
    view.height = options.height;
    view.viewName = options.view;
    if (options.camera) {
        CheckCamera(*options.camera);
        view.view = api::ToSceneView(*options.camera,
                                     options.camera->id.empty() ? "camera" : options.camera->id);
    }
    Diagnostics diags;
    Frame frame;
    RenderReport report;
    if (!ctx.Flatten(view, diags) || diags.HasErrors()) {
        impl_->revision = 0;  // nothing kept that a retry could trust
        api::ThrowDiagnostics(diags, "the scene could not be set up for this view");
    }
    if (!ctx.Render(engine, frame, report, diags) || diags.HasErrors())
        api::ThrowDiagnostics(diags, "the scene could not be rendered");

    Rendering r;
    r.width = frame.width;
    r.height = frame.height;
    r.depth.assign(frame.depth.begin(), frame.depth.end());
    r.normal.resize(frame.normal.size() * 3);
    for (std::size_t i = 0; i < frame.normal.size(); ++i) {
        const Vec3 n = frame.normal[i];
        r.normal[3 * i] = n.x;
        r.normal[3 * i + 1] = n.y;
        r.normal[3 * i + 2] = n.z;
    }
    r.surface.assign(frame.surface.begin(), frame.surface.end());
    r.body.assign(frame.body.begin(), frame.body.end());
    r.solid.resize(frame.body.size());
    for (std::size_t i = 0; i < frame.body.size(); ++i) r.solid[i] = frame.Solid(i);
    const FlatScene& flat = ctx.Flat();
    for (const auto& h : flat.halfSpaces) r.surfaceNames.push_back(h.name);
    for (const auto& f : flat.freeforms) r.surfaceNames.push_back(f.name);
    for (const auto& b : flat.bodies) r.bodyNames.push_back(b.name);
    for (const auto& s : flat.solids) r.solidNames.push_back(s.name);
    r.engine = options.engine;
    r.notes = report.notes;
    for (const std::string& w : report.stats.warnings) r.notes.push_back("warning: " + w);
    if (options.image) {
        ShadeOptions so;
        so.model = ToModel(options.shading);
        so.shadows = options.shadows;
        so.aaSamples = options.antialias;
        so.edges = options.edges;
        so.forceColor = true;
        if (options.background)
            so.background =
                scene::Color{options.background->r, options.background->g, options.background->b};
        r.image = ToRgbImage(ctx.Shade(frame, so));
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

std::size_t Rendering::CoveredCount() const {
    return static_cast<std::size_t>(
        std::count_if(surface.begin(), surface.end(), [](std::int32_t s) { return s != kNone; }));
}

void RgbImage::Write(const std::string& path, bool sixteenBit) const {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (width <= 0 || height <= 0 || rgb.size() != n * 3)
        throw Error(
            fmt::format("RgbImage::Write: '{}': the image is empty or its size is wrong", path));
    ImageFormat format;
    if (!ImageFormatFromPath(path, format) || format == ImageFormat::kFrameDump ||
        (path.size() >= 4 && path.compare(path.size() - 4, 4, ".pgm") == 0))
        throw Error(fmt::format("RgbImage::Write: '{}': expected a .png or .ppm file name", path));
    // The writers encode sRGB from linear 8-bit pixels; the sRGB bytes held here go back through
    // the inverse table, which is exact for bytes that came from the encoder (a monotonic map of
    // 256 levels) and the nearest linear level for bytes set by hand.
    Image image(width, height, 3);
    std::array<std::uint8_t, 256> linearOf{};
    {
        Image probe(256, 1, 1);
        for (int v = 0; v < 256; ++v) probe.pixels[v] = static_cast<std::uint8_t>(v);
        const std::vector<std::uint8_t> enc = EncodeSrgb8(probe);
        for (int s = 0, v = 0; s < 256; ++s) {
            while (v < 255 && enc[v] < s) ++v;  // first linear level whose encoding reaches s
            linearOf[s] = static_cast<std::uint8_t>(v);
        }
    }
    for (std::size_t k = 0; k < rgb.size(); ++k) image.pixels[k] = linearOf[rgb[k]];
    if (linear.size() == rgb.size()) image.linear = linear;
    std::string error;
    if (format == ImageFormat::kPng) {
        PngOptions png;
        png.bitDepth = sixteenBit ? 16 : 8;
        error = WritePng(path, image, png);
    } else {
        if (sixteenBit) throw Error("RgbImage::Write: 16 bits are for PNG output only");
        error = WritePnm(path, image);
    }
    if (!error.empty()) throw Error("RgbImage::Write: " + error);
}

Rendering Compose(const Rendering& a, const Rendering& b) {
    if (a.width != b.width || a.height != b.height)
        throw Error(fmt::format("Compose: sizes differ ({}x{} and {}x{})", a.width, a.height,
                                b.width, b.height));
    const bool images = a.image.rgb.size() == b.image.rgb.size() && !a.image.rgb.empty();
    const bool linear = images && a.image.linear.size() == a.image.rgb.size() &&
                        b.image.linear.size() == b.image.rgb.size();
    Rendering r = a;
    if (!images) r.image = {};
    if (!linear) r.image.linear.clear();
    auto shift = [](std::int32_t id, std::size_t by) {
        return id == Rendering::kNone ? id : static_cast<std::int32_t>(id + by);
    };
    const std::size_t ds = a.surfaceNames.size(), db = a.bodyNames.size(), dl = a.solidNames.size();
    r.surfaceNames.insert(r.surfaceNames.end(), b.surfaceNames.begin(), b.surfaceNames.end());
    r.bodyNames.insert(r.bodyNames.end(), b.bodyNames.begin(), b.bodyNames.end());
    r.solidNames.insert(r.solidNames.end(), b.solidNames.begin(), b.solidNames.end());
    for (std::size_t i = 0; i < r.depth.size(); ++i) {
        if (!(b.depth[i] < a.depth[i])) continue;  // ties keep a (Frame::Offer's rule)
        r.depth[i] = b.depth[i];
        for (int c = 0; c < 3; ++c) r.normal[3 * i + c] = b.normal[3 * i + c];
        r.surface[i] = shift(b.surface[i], ds);
        r.body[i] = shift(b.body[i], db);
        r.solid[i] = shift(b.solid[i], dl);
        if (images)
            for (int c = 0; c < 3; ++c) {
                r.image.rgb[3 * i + c] = b.image.rgb[3 * i + c];
                if (linear) r.image.linear[3 * i + c] = b.image.linear[3 * i + c];
            }
    }
    r.notes.insert(r.notes.end(), b.notes.begin(), b.notes.end());
    r.seconds = a.seconds + b.seconds;
    if (a.engine != b.engine) r.engine = a.engine + "+" + b.engine;
    return r;
}

}  // namespace quadrix
