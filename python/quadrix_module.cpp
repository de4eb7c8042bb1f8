// The Python module `quadrix` (issue 21 item 3, docs/python.md): the render context
// (pipeline/render_context.h) bound with pybind11. Nothing here reads, flattens, renders or shades
// by itself: every stage is a RenderContext call, made with the GIL released.
//
// Interface (Python):
//   read(path | [paths], *, text=, name=, top=, strict=, allow_missing=, threads=) -> Scene
//   render(path | Scene | None, *, text=, size=(w, h), engine=, view=, camera=, shading=,
//          threads=, engine_options=, strict=, shadows=, background=, aa=, edges=) -> Frame
//   Scene: add(text), add_solid(kind, id, **params), add_light(...), add_view(...), solids(),
//          lights(), views(), render(...)
//   Frame: image, linear, depth, normals, surface, body, solid (NumPy arrays sharing the Frame's
//          memory, their base the Frame object), stats, solid_names, ..., save(path)
//   SceneError(Exception): file, line, column, message, diagnostics
//   write_png(path, array): an 8-bit gray or RGB array written as it is (data maps).
//
// Arrays without copying: each array points into the C++ Frame (or the shaded Image) owned by
// the Python Frame object, which is the array's base, so the memory lives as long as any array
// does. Without NumPy in the interpreter the same memory is exposed as quadrix.ArrayView objects
// (buffer protocol, shape, dtype, strides): memoryview(v) and numpy.asarray(v) do not copy either.
//
// Threads: the GIL is released around every RenderContext call (Read, the reader of added
// statements, Flatten, Render, Shade, the writers). A Scene has a mutex, taken after the GIL is
// released (never the other way round, so no lock-order deadlock), so two Python threads may use
// one Scene; different Scenes render in parallel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/engines/registry.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/io/writers.h"
#include "quadrix/lang/reader.h"
#include "quadrix/pipeline/output.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"
#include "quadrix/shade/shader.h"

namespace py = pybind11;

namespace quadrix::python {
namespace {

PyObject* gSceneError = nullptr;

// ---- errors --------------------------------------------------------------------------------

// Raises quadrix.SceneError from the errors of `diags` (the GIL must be held). The attributes
// file/line/column/message are those of the first error; `diagnostics` lists every one as
// (severity, file, line, column, message); str(e) is every error formatted with its source line.
[[noreturn]] void RaiseSceneError(const Diagnostics& diags, const std::string& fallback = {}) {
    const Diagnostic* first = nullptr;
    std::string text;
    py::list all;
    for (const Diagnostic& d : diags.Items()) {
        const char* severity = d.severity == Diagnostic::Severity::kError     ? "error"
                               : d.severity == Diagnostic::Severity::kWarning ? "warning"
                                                                              : "note";
        all.append(py::make_tuple(severity, d.loc.file ? py::cast(*d.loc.file) : py::none(),
                                  d.loc.line, d.loc.column, d.message));
        if (d.severity != Diagnostic::Severity::kError) continue;
        if (!first) first = &d;
        if (!text.empty()) text += "\n";
        text += d.Format(true);
    }
    if (text.empty()) text = fallback.empty() ? "error" : fallback;
    py::object error = py::reinterpret_borrow<py::object>(gSceneError)(text);
    error.attr("file") = first && first->loc.file ? py::cast(*first->loc.file) : py::none();
    error.attr("line") = first && first->loc.line > 0 ? py::cast(first->loc.line) : py::none();
    error.attr("column") =
        first && first->loc.column > 0 ? py::cast(first->loc.column) : py::none();
    error.attr("message") = first ? first->message : text;
    error.attr("diagnostics") = all;
    PyErr_SetObject(gSceneError, error.ptr());
    throw py::error_already_set();
}

std::vector<std::string> Warnings(const Diagnostics& diags) {
    std::vector<std::string> out;
    for (const Diagnostic& d : diags.Items())
        if (d.severity == Diagnostic::Severity::kWarning) out.push_back(d.Format(false));
    return out;
}

// ---- values from Python ----------------------------------------------------------------------

Vec3 ToVec3(const py::handle& value, const char* what) {
    auto seq = py::cast<std::vector<double>>(value);
    if (seq.size() != 3) throw py::value_error(std::string(what) + ": expected 3 numbers");
    return {seq[0], seq[1], seq[2]};
}

// A number as the language reads it back exactly.
std::string Number(double v) {
    if (!std::isfinite(v)) throw py::value_error("parameters must be finite numbers");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// A statement parameter's value: a number, a sequence of numbers, or a word (a color name).
std::string Values(const py::handle& value) {
    if (py::isinstance<py::str>(value)) return py::cast<std::string>(value);
    if (py::isinstance<py::bool_>(value))
        throw py::type_error("a flag parameter is given as True only");
    if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
        return Number(py::cast<double>(value));
    std::string out;
    for (const py::handle& item : py::reinterpret_borrow<py::iterable>(value)) {
        if (!out.empty()) out += ' ';
        out += Number(py::cast<double>(item));
    }
    return out;
}

// Appends pieces to a statement (one append each: GCC 12's false -Wrestrict positive on
// `"literal" + std::string&&`, GCC bug 105329, is not triggered).
void Append(std::string& out, std::initializer_list<std::string_view> pieces) {
    for (std::string_view p : pieces) out.append(p);
}

// A Python keyword to a language option: trailing '_' dropped (`from_` is `=from`).
std::string OptionName(std::string key) {
    while (!key.empty() && key.back() == '_') key.pop_back();
    return key;
}

// The view parameters of a camera dict or add_view's keywords, as statement text and as a
// scene::View (both are accepted by the same names: vrp vpn vup dop cop whh whw fbp).
struct ViewParams {
    std::string text;
    scene::View view;
};
ViewParams ParseView(const py::dict& params) {
    ViewParams out;
    for (const auto& [k, v] : params) {
        const std::string key = py::cast<std::string>(k);
        if (v.is_none()) continue;
        if (key == "id") {
            out.view.id = py::cast<std::string>(v);
            continue;
        }
        if (key == "vrp" || key == "vpn" || key == "vup" || key == "dop" || key == "cop") {
            const Vec3 p = ToVec3(v, key.c_str());
            std::optional<Vec3>& field = key == "vrp"   ? out.view.vrp
                                         : key == "vpn" ? out.view.vpn
                                         : key == "vup" ? out.view.vup
                                         : key == "dop" ? out.view.dop
                                                        : out.view.cop;
            field = p;
        } else if (key == "whh") {
            out.view.whh = py::cast<double>(v);
        } else if (key == "whw") {
            out.view.whw = py::cast<double>(v);
        } else if (key == "fbp") {
            auto f = py::cast<std::vector<double>>(v);
            if (f.size() != 2) throw py::value_error("fbp: expected 2 numbers (front, back)");
            out.view.front = f[0];
            out.view.back = f[1];
        } else {
            throw py::type_error("unknown view parameter '" + key +
                                 "' (vrp, vpn, vup, dop, cop, whh, whw, fbp)");
        }
        Append(out.text, {" ", key, " ", Values(v)});
    }
    return out;
}

ShadingModel ParseShading(const std::string& name) {
    if (name == "lambert") return ShadingModel::kLambert;
    if (name == "fast") return ShadingModel::kFast;
    if (name == "phong") return ShadingModel::kPhong;
    if (name == "blinn-phong" || name == "blinn_phong") return ShadingModel::kBlinnPhong;
    throw py::value_error("unknown shading model '" + name +
                          "' (lambert, fast, phong, blinn-phong)");
}

// ---- the products of one render ------------------------------------------------------------

struct Rendered {
    Frame frame;
    // The Frame keeps normals packed and solids per body (frame.h): their arrays for Python are
    // unpacked once, on first use.
    std::vector<double> normals;
    std::vector<std::int32_t> solids;
    Image image;                     // RGB, linear light (io/image.h)
    std::vector<std::uint8_t> srgb;  // image.pixels sRGB-encoded: the bytes a PNG file holds
    RenderReport report;
    std::vector<std::string> warnings;
    std::vector<std::string> surfaceNames, bodyNames, solidNames;
    std::string viewName;
    double readSeconds = 0, flattenSeconds = 0, shadeSeconds = 0;
    bool flattenReused = false;
};

// The Python face of one array of a Rendered: a NumPy array whose base is `owner` (the Frame
// object), or an ArrayView without NumPy.
struct ArrayView {
    py::object owner;
    void* data = nullptr;
    py::ssize_t itemsize = 0;
    std::string format, dtype;
    std::vector<py::ssize_t> shape, strides;
};

bool HaveNumpy() {
    static const bool have = [] {
        try {
            py::module_::import("numpy");
            return true;
        } catch (const py::error_already_set&) {
            return false;
        }
    }();
    return have;
}

template <class T>
py::object MakeArray(const py::object& owner, const T* data, std::vector<py::ssize_t> shape,
                     const char* dtype) {
    std::vector<py::ssize_t> strides(shape.size());
    py::ssize_t stride = sizeof(T);
    for (std::size_t k = shape.size(); k-- > 0;) {
        strides[k] = stride;
        stride *= shape[k];
    }
    if (HaveNumpy())
        return py::array_t<T>(shape, strides, data, owner);  // no copy: `owner` is the base
    ArrayView v{
        owner,  const_cast<T*>(data), sizeof(T), py::format_descriptor<T>::format(), dtype, shape,
        strides};
    return py::cast(std::move(v));
}

py::dict Stats(const Rendered& r) {
    py::dict s;
    s["engine"] = r.report.engine;
    s["view"] = r.viewName;
    s["width"] = r.frame.width;
    s["height"] = r.frame.height;
    s["covered_pixels"] = r.frame.CoveredCount();
    s["read_seconds"] = r.readSeconds;
    s["flatten_seconds"] = r.flattenSeconds;
    s["flatten_reused"] = r.flattenReused;
    s["render_seconds"] = r.report.seconds;
    s["engine_seconds"] = r.report.stats.seconds;
    s["shade_seconds"] = r.shadeSeconds;
    py::dict counters;
    for (const auto& [name, value] : r.report.Counters()) counters[py::str(name)] = value;
    s["counters"] = counters;
    py::list byReference;
    for (const UndrawnSolid& u : r.report.byReference)
        byReference.append(py::make_tuple(
            u.solid >= 0 && u.solid < static_cast<int>(r.solidNames.size()) ? r.solidNames[u.solid]
                                                                            : std::string(),
            u.reason));
    s["by_reference"] = byReference;
    s["notes"] = r.report.notes;
    std::vector<std::string> warnings = r.warnings;
    for (const std::string& w : r.report.stats.warnings) warnings.push_back(w);
    s["warnings"] = warnings;
    s["report"] = r.report.stats.report;
    return s;
}

// ---- the scene -----------------------------------------------------------------------------

struct RenderArgs {
    int width = 512, height = 512;
    std::string engine = "raycast";
    std::string viewName;
    std::optional<scene::View> camera;
    ShadeOptions shade;
    std::optional<int> threads;
    std::map<std::string, std::string> engineOptions;
    bool strict = false;
};

EngineRequest EngineOf(const RenderArgs& args) {
    EngineRequest e;
    e.engine = args.engine;
    e.options = args.engineOptions;
    e.strict = args.strict;
    return e;
}

class Scene {
  public:
    explicit Scene(int threads = 0)
        : threads_(threads), ctx_(std::make_unique<RenderContext>(threads)) {}

    // Stage 1: replaces the scene (every input format, pipeline/inputs.h).
    void Read(const InputRequest& request) {
        Diagnostics diags;
        bool ok;
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mutex_);
            ok = ctx_->Read(request, diags);
            readSeconds_ = ctx_->readSeconds;
        }
        if (!ok || diags.HasErrors()) RaiseSceneError(diags, "the scene could not be read");
        warnings_ = Warnings(diags);
    }

    // Statements of the UniQuadrix language added to the scene, all or nothing: they are read
    // into a copy, which replaces the scene only when it has no error. Ids of the scene are known
    // to the statements (the reader indexes what is there, lang/reader_state.h).
    void Add(const std::string& text, const std::string& name) {
        Diagnostics diags;
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mutex_);
            scene::Scene copy = ctx_->Scene();
            {
                lang::Reader reader(copy, diags);
                reader.ReadText(text, name);
            }
            if (!diags.HasErrors()) {
                ctx_->Scene() = std::move(copy);
                ctx_->SceneChanged();
            }
        }
        if (diags.HasErrors()) RaiseSceneError(diags);
        for (std::string& w : Warnings(diags)) warnings_.push_back(std::move(w));
    }

    py::list Solids() {
        auto lock = LockWithoutGil();
        const scene::Scope& top = ctx_->Scene().top;
        py::list out;
        auto row = [&](const std::string& id, const char* kind, bool operand, const SourceLoc& at) {
            py::dict d;
            d["id"] = id;
            d["kind"] = kind;
            d["drawn"] = !operand;  // operands of a csg solid are drawn only as part of it
            d["file"] = at.file ? py::cast(*at.file) : py::none();
            d["line"] = at.line;
            out.append(d);
        };
        for (const scene::Body& b : top.bodies) row(b.id, "body", b.usedAsOperand, b.loc);
        for (const scene::Instance& i : top.instances)
            row(i.id, i.isArray ? "array" : "instance", i.usedAsOperand, i.loc);
        for (const scene::Csg& c : top.csgs) row(c.id, "csg", c.usedAsOperand, c.loc);
        for (const scene::FreeformSurface& f : top.freeforms) row(f.id, "freeform", false, f.loc);
        return out;
    }
    std::vector<std::string> Views() {
        auto lock = LockWithoutGil();
        std::vector<std::string> out;
        for (const scene::View& v : ctx_->Scene().views) out.push_back(v.id);
        return out;
    }
    py::list Lights() {
        auto lock = LockWithoutGil();
        py::list out;
        for (const scene::Light& l : ctx_->Scene().lights) {
            using K = scene::Light::Kind;
            py::dict d;
            d["id"] = l.id;
            d["kind"] = l.kind == K::kAmbient    ? "ambient"
                        : l.kind == K::kParallel ? "parallel"
                        : l.kind == K::kPoint    ? "point"
                                                 : "spot";
            d["intensity"] = l.intensity;
            out.append(d);
        }
        return out;
    }
    std::vector<std::string> WarningsSoFar() {
        auto lock = LockWithoutGil();
        return warnings_;
    }

    // Stages 2-4 and the products copied out of nothing: the Frame is rendered in place.
    std::shared_ptr<Rendered> Render(const RenderArgs& args) {
        if (auto e = RenderContext::CheckEngine(EngineOf(args)); !e.empty())
            throw py::value_error(e);
        auto out = std::make_shared<Rendered>();
        Diagnostics diags;
        bool ok;
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mutex_);
            if (args.threads && *args.threads != threads_) {
                // The thread limit belongs to the context's arena: a new context, the same scene.
                auto fresh = std::make_unique<RenderContext>(*args.threads);
                fresh->Scene() = ctx_->Scene();
                ctx_ = std::move(fresh);
                threads_ = *args.threads;
            }
            ViewRequest view;
            view.width = args.width;
            view.height = args.height;
            view.viewName = args.viewName;
            view.view = args.camera;
            const EngineRequest engine = EngineOf(args);
            ok = ctx_->Flatten(view, diags) && ctx_->Render(engine, out->frame, out->report, diags);
            if (ok && !diags.HasErrors()) {
                const auto t0 = std::chrono::steady_clock::now();
                ShadeOptions shade = args.shade;
                shade.forceColor = true;  // always H×W×3
                out->image = ctx_->Shade(out->frame, shade);
                out->srgb = EncodeSrgb8(out->image);
                out->shadeSeconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                const FlatScene& flat = ctx_->Flat();
                for (const FlatHalfSpace& h : flat.halfSpaces) out->surfaceNames.push_back(h.name);
                for (const FlatFreeform& f : flat.freeforms) out->surfaceNames.push_back(f.name);
                for (const FlatBody& b : flat.bodies) out->bodyNames.push_back(b.name);
                for (const FlatSolid& s : flat.solids) out->solidNames.push_back(s.name);
                out->viewName = flat.viewName;
                out->readSeconds = readSeconds_;
                out->flattenSeconds = ctx_->flattenSeconds;
                out->flattenReused = ctx_->LastFlattenReused();
            }
        }
        if (!ok || diags.HasErrors()) RaiseSceneError(diags, "the scene could not be rendered");
        out->warnings = warnings_;
        for (std::string& w : Warnings(diags)) out->warnings.push_back(std::move(w));
        return out;
    }

  private:
    // The scene's lock for a caller holding the GIL: waited for with the GIL released, so that a
    // render of this scene in another thread (which holds the lock, not the GIL) never waits
    // for this thread, and other Python threads run meanwhile.
    std::unique_lock<std::mutex> LockWithoutGil() {
        std::unique_lock lock(mutex_, std::defer_lock);
        py::gil_scoped_release release;
        lock.lock();
        return lock;
    }

    std::mutex mutex_;
    int threads_ = 0;
    std::unique_ptr<RenderContext> ctx_;
    double readSeconds_ = 0;
    std::vector<std::string> warnings_;
};

RenderArgs ParseRenderArgs(const py::object& size, const std::string& engine,
                           const py::object& view, const py::object& camera,
                           const std::string& shading, const py::object& threads,
                           const py::object& engineOptions, bool strict, bool shadows,
                           const py::object& background, int aa, bool edges) {
    RenderArgs a;
    auto wh = py::cast<std::vector<long long>>(size);
    if (wh.size() != 2 || wh[0] < 1 || wh[1] < 1 || wh[0] > 1 << 20 || wh[1] > 1 << 20)
        throw py::value_error("size: expected (width, height), positive");
    a.width = static_cast<int>(wh[0]);
    a.height = static_cast<int>(wh[1]);
    a.engine = engine;
    if (!view.is_none()) a.viewName = py::cast<std::string>(view);
    if (!camera.is_none()) {
        if (!a.viewName.empty()) throw py::value_error("give view or camera, not both");
        ViewParams p = ParseView(py::cast<py::dict>(camera));
        if (p.view.id.empty()) p.view.id = "camera";
        a.camera = p.view;
    }
    a.shade.model = ParseShading(shading);
    a.shade.shadows = shadows;
    if (aa != 0 && aa != 4 && aa != 16 && aa != 64)
        throw py::value_error("aa: 0 (off), 4, 16 or 64 samples on edge pixels");
    a.shade.aaSamples = aa;
    a.shade.edges = edges;
    if (!background.is_none()) {
        const Vec3 c = ToVec3(background, "background");
        a.shade.background = scene::Color{c.x, c.y, c.z};
    }
    if (!threads.is_none()) {
        const int t = py::cast<int>(threads);
        if (t < 0) throw py::value_error("threads: 0 (all) or a positive number");
        a.threads = t;
    }
    if (!engineOptions.is_none())
        for (const auto& [k, v] : py::cast<py::dict>(engineOptions))
            a.engineOptions[py::cast<std::string>(k)] = py::cast<std::string>(py::str(v));
    a.strict = strict;
    return a;
}

InputRequest ParseInput(const py::object& path, const py::object& text, const std::string& name,
                        const py::object& top, bool strict, bool allowMissing) {
    InputRequest r;
    if (!path.is_none() && !text.is_none()) throw py::value_error("give a path or text, not both");
    if (!path.is_none()) {
        py::object fspath = py::module_::import("os").attr("fspath");
        if (py::isinstance<py::str>(path) || py::hasattr(path, "__fspath__"))
            r.paths.push_back(py::cast<std::string>(fspath(path)));
        else
            for (const py::handle& p : py::reinterpret_borrow<py::iterable>(path))
                r.paths.push_back(py::cast<std::string>(fspath(p)));
        if (r.paths.empty()) throw py::value_error("no path given");
    } else if (!text.is_none()) {
        r.text = py::cast<std::string>(text);
        r.textName = name;
    } else {
        throw py::value_error("give a path or text=");
    }
    if (!top.is_none()) r.topObjects = py::cast<std::vector<std::string>>(top);
    r.strict = strict;
    r.allowMissing = allowMissing;
    return r;
}

}  // namespace
}  // namespace quadrix::python

PYBIND11_MODULE(quadrix, m) {
    using namespace quadrix;
    using namespace quadrix::python;
    m.doc() = "Quadrix: exact rendering of quadric/plane CSG solids (docs/python.md).";
    m.attr("__version__") = QUADRIX_VERSION;

    gSceneError = PyErr_NewExceptionWithDoc(
        "quadrix.SceneError",
        "An error in a scene (reading, flattening or rendering it). Attributes of the first "
        "error: file, line, column (None when unknown) and message; diagnostics lists every "
        "diagnostic as (severity, file, line, column, message).",
        PyExc_Exception, nullptr);
    m.attr("SceneError") = py::handle(gSceneError);

    py::class_<ArrayView>(m, "ArrayView", py::buffer_protocol(),
                          "The Frame's memory when NumPy is not installed: memoryview(v) and "
                          "numpy.asarray(v) share it.")
        .def_buffer([](ArrayView& v) {
            return py::buffer_info(v.data, v.itemsize, v.format,
                                   static_cast<py::ssize_t>(v.shape.size()), v.shape, v.strides);
        })
        .def_property_readonly("shape",
                               [](const ArrayView& v) { return py::tuple(py::cast(v.shape)); })
        .def_property_readonly("strides",
                               [](const ArrayView& v) { return py::tuple(py::cast(v.strides)); })
        .def_property_readonly("ndim", [](const ArrayView& v) { return v.shape.size(); })
        .def_property_readonly("dtype", [](const ArrayView& v) { return v.dtype; })
        .def("__repr__", [](const ArrayView& v) {
            return "<quadrix.ArrayView dtype=" + v.dtype +
                   " shape=" + py::cast<std::string>(py::str(py::tuple(py::cast(v.shape)))) + ">";
        });

    auto frame = py::class_<Rendered, std::shared_ptr<Rendered>>(
        m, "Frame", "One rendered picture: the Frame's buffers and the shaded image as arrays.");
    auto hw = [](const Rendered& r) {
        return std::vector<py::ssize_t>{r.frame.height, r.frame.width};
    };
    auto hw3 = [](const Rendered& r) {
        return std::vector<py::ssize_t>{r.frame.height, r.frame.width, 3};
    };
    frame.def_property_readonly("width", [](const Rendered& r) { return r.frame.width; })
        .def_property_readonly("height", [](const Rendered& r) { return r.frame.height; })
        .def_property_readonly(
            "image",
            [hw3](py::object self) {
                auto& r = self.cast<Rendered&>();
                return MakeArray(self, r.srgb.data(), hw3(r), "uint8");
            },
            "H×W×3 uint8, sRGB-encoded (the bytes of the PNG)")
        .def_property_readonly(
            "linear",
            [hw3](py::object self) -> py::object {
                auto& r = self.cast<Rendered&>();
                if (r.image.linear.empty()) return py::none();
                return MakeArray(self, r.image.linear.data(), hw3(r), "float32");
            },
            "H×W×3 float32, linear light in [0, 1]")
        .def_property_readonly(
            "depth",
            [hw](py::object self) {
                auto& r = self.cast<Rendered&>();
                return MakeArray(self, r.frame.depth.data(), hw(r), "float32");
            },
            "H×W float32 device z (pixels; +inf where nothing is drawn)")
        .def_property_readonly(
            "normals",
            [hw3](py::object self) {
                auto& r = self.cast<Rendered&>();
                if (r.normals.size() != 3 * r.frame.normal.size()) {
                    r.normals.resize(3 * r.frame.normal.size());
                    for (std::size_t i = 0; i < r.frame.normal.size(); ++i) {
                        const Vec3 n = r.frame.normal[i];
                        r.normals[3 * i] = n.x;
                        r.normals[3 * i + 1] = n.y;
                        r.normals[3 * i + 2] = n.z;
                    }
                }
                return MakeArray(self, r.normals.data(), hw3(r), "float64");
            },
            "H×W×3 float64 world-space unit normals facing the viewer (0 where empty)")
        .def_property_readonly("surface",
                               [hw](py::object self) {
                                   auto& r = self.cast<Rendered&>();
                                   return MakeArray(self, r.frame.surface.data(), hw(r), "int32");
                               })
        .def_property_readonly("body",
                               [hw](py::object self) {
                                   auto& r = self.cast<Rendered&>();
                                   return MakeArray(self, r.frame.body.data(), hw(r), "int32");
                               })
        .def_property_readonly("solid",
                               [hw](py::object self) {
                                   auto& r = self.cast<Rendered&>();
                                   if (r.solids.size() != r.frame.body.size()) {
                                       r.solids.resize(r.frame.body.size());
                                       for (std::size_t i = 0; i < r.solids.size(); ++i)
                                           r.solids[i] = r.frame.Solid(i);
                                   }
                                   return MakeArray(self, r.solids.data(), hw(r), "int32");
                               })
        .def_readonly("surface_names", &Rendered::surfaceNames)
        .def_readonly("body_names", &Rendered::bodyNames)
        .def_readonly("solid_names", &Rendered::solidNames)
        .def_property_readonly("stats", [](const Rendered& r) { return Stats(r); })
        .def(
            "save",
            [](const Rendered& r, const std::string& path) {
                OutputRequest request;
                request.image = path;
                if (auto e = CheckOutputs(request); !e.empty()) throw py::value_error(e);
                std::string error;
                {
                    py::gil_scoped_release release;
                    error = WriteOutputs(request, r.frame, &r.image);
                }
                if (!error.empty()) throw std::runtime_error(error);
            },
            py::arg("path"),
            "Writes the picture (.png, .ppm/.pgm) or the Frame (.qxf), atomically.")
        .def("__repr__", [](const Rendered& r) {
            return "<quadrix.Frame " + std::to_string(r.frame.width) + "x" +
                   std::to_string(r.frame.height) + " engine=" + r.report.engine + ">";
        });

    auto renderDoc =
        "Renders through the render context: size=(width, height), engine (quadrix.engines()), "
        "view (a view id of the scene) or camera (a dict of view parameters: vrp vpn vup dop "
        "cop whh whw fbp), shading (lambert, fast, phong, blinn-phong), threads (0 = all), "
        "engine_options (dict), strict, shadows, background=(r, g, b), aa (0 = off, 4, 16, 64 "
        "samples on edge pixels), edges (silhouette lines). Returns a Frame.";

    py::class_<Scene>(m, "Scene", "A scene: read from files or text, edited, rendered.")
        .def(py::init<int>(), py::arg("threads") = 0, "An empty scene.")
        .def(
            "add",
            [](Scene& s, const std::string& text, const std::string& name) -> Scene& {
                s.Add(text, name);
                return s;
            },
            py::arg("text"), py::arg("name") = "<python>", py::return_value_policy::reference,
            "Adds statements of the UniQuadrix language; all or nothing (SceneError).")
        .def(
            "add_solid",
            [](Scene& s, const std::string& kind, const std::string& id,
               const py::kwargs& kw) -> Scene& {
                std::string text;
                Append(text, {"solid ", kind, " ", id});
                for (const auto& [k, v] : kw) {
                    Append(text, {" =", OptionName(py::cast<std::string>(k))});
                    if (!(py::isinstance<py::bool_>(v) && py::cast<bool>(v)))
                        Append(text, {" ", Values(v)});
                }
                s.Add(text + ";", "<add_solid>");
                return s;
            },
            py::arg("kind"), py::arg("id"), py::return_value_policy::reference,
            "solid KIND ID =param value...; e.g. add_solid('sphere', 'ball', at=(0, 0, 0), r=1, "
            "c='gold'); from_=... is =from; open=True is the flag =open.")
        .def(
            "add_light",
            [](Scene& s, double intensity, const py::object& direction, const py::object& at,
               const py::object& aim, const py::object& cone, const py::object& color,
               const std::string& id) -> Scene& {
                std::string text;
                Append(text, {"light ", id, " ", Number(intensity)});
                if (!direction.is_none()) Append(text, {" ", Values(direction)});
                if (!at.is_none()) Append(text, {" =at ", Values(at)});
                if (!aim.is_none()) Append(text, {" =aim ", Values(aim)});
                if (!cone.is_none()) Append(text, {" =cone ", Values(cone)});
                if (!color.is_none()) Append(text, {" =c ", Values(color)});
                s.Add(text + ";", "<add_light>");
                return s;
            },
            py::arg("intensity"), py::arg("direction") = py::none(), py::arg("at") = py::none(),
            py::arg("aim") = py::none(), py::arg("cone") = py::none(),
            py::arg("color") = py::none(), py::arg("id") = "", py::return_value_policy::reference,
            "An ambient light (intensity only), parallel (direction toward the light), point "
            "(at) or spot (at, aim, cone).")
        .def(
            "add_view",
            [](Scene& s, const std::string& id, const py::kwargs& kw) -> Scene& {
                ViewParams p = ParseView(py::dict(kw));
                std::string text;
                Append(text, {"view ", id, p.text, ";"});
                s.Add(text, "<add_view>");
                return s;
            },
            py::arg("id") = "", py::return_value_policy::reference,
            "view ID vrp=.. vpn=.. vup=.. dop=.. cop=.. whh=.. whw=.. fbp=(d1, d2)")
        .def("solids", &Scene::Solids,
             "The solids of the top level: dicts with id, kind, drawn, file, line.")
        .def("views", &Scene::Views)
        .def("lights", &Scene::Lights)
        .def_property_readonly("warnings", &Scene::WarningsSoFar)
        .def(
            "render",
            [](Scene& s, const py::object& size, const std::string& engine, const py::object& view,
               const py::object& camera, const std::string& shading, const py::object& threads,
               const py::object& engineOptions, bool strict, bool shadows,
               const py::object& background, int aa, bool edges) {
                return s.Render(ParseRenderArgs(size, engine, view, camera, shading, threads,
                                                engineOptions, strict, shadows, background, aa,
                                                edges));
            },
            py::kw_only(), py::arg("size") = py::make_tuple(512, 512),
            py::arg("engine") = "raycast", py::arg("view") = py::none(),
            py::arg("camera") = py::none(), py::arg("shading") = "lambert",
            py::arg("threads") = py::none(), py::arg("engine_options") = py::none(),
            py::arg("strict") = false, py::arg("shadows") = false,
            py::arg("background") = py::none(), py::arg("aa") = 0, py::arg("edges") = false,
            renderDoc);

    m.def(
        "read",
        [](const py::object& path, const py::object& text, const std::string& name,
           const py::object& top, bool strict, bool allowMissing, int threads) {
            InputRequest request = ParseInput(path, text, name, top, strict, allowMissing);
            auto scene = std::make_unique<Scene>(threads);
            scene->Read(request);
            return scene;
        },
        py::arg("path") = py::none(), py::kw_only(), py::arg("text") = py::none(),
        py::arg("name") = "<text>", py::arg("top") = py::none(), py::arg("strict") = false,
        py::arg("allow_missing") = false, py::arg("threads") = 0,
        "Reads a scene (a path, a list of paths, or text=) in any supported format; errors "
        "raise SceneError with file, line and column.");

    m.def(
        "render",
        [](const py::object& source, const py::object& text, const py::object& size,
           const std::string& engine, const py::object& view, const py::object& camera,
           const std::string& shading, const py::object& threads, const py::object& engineOptions,
           bool strict, bool shadows, const py::object& background, int aa, bool edges) {
            RenderArgs args =
                ParseRenderArgs(size, engine, view, camera, shading, threads, engineOptions, strict,
                                shadows, background, aa, edges);
            if (!source.is_none() && py::isinstance<Scene>(source))
                return source.cast<Scene&>().Render(args);
            Scene scene(args.threads.value_or(0));
            scene.Read(ParseInput(source, text, "<text>", py::none(), strict, false));
            return scene.Render(args);
        },
        py::arg("source") = py::none(), py::kw_only(), py::arg("text") = py::none(),
        py::arg("size") = py::make_tuple(512, 512), py::arg("engine") = "raycast",
        py::arg("view") = py::none(), py::arg("camera") = py::none(),
        py::arg("shading") = "lambert", py::arg("threads") = py::none(),
        py::arg("engine_options") = py::none(), py::arg("strict") = false,
        py::arg("shadows") = false, py::arg("background") = py::none(), py::arg("aa") = 0,
        py::arg("edges") = false,
        "render(path | Scene, ...) — reads (when given a path or text=) and renders. "
        "See Scene.render.");

    m.def(
        "engines",
        [] {
            std::vector<std::string> names;
            for (const EngineInfo& e : Engines())
                if (!e.hidden) names.push_back(e.name);
            return names;
        },
        "The names of the engines.");

    m.def(
        "write_png",
        [](const std::string& path,
           const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a) {
            if (a.ndim() != 2 && !(a.ndim() == 3 && a.shape(2) == 3))
                throw py::value_error("write_png: expected an H×W or H×W×3 uint8 array");
            Image image(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)),
                        a.ndim() == 2 ? 1 : 3);
            std::copy(a.data(), a.data() + a.size(), image.pixels.begin());
            std::string error;
            {
                py::gil_scoped_release release;
                error = WritePng(path, image, PngOptions{8, false});
            }
            if (!error.empty()) throw std::runtime_error(error);
        },
        py::arg("path"), py::arg("array"),
        "Writes an 8-bit gray (H×W) or RGB (H×W×3) array as a PNG, the values as they are (no "
        "sRGB encoding: for depth and normal maps), atomically.");
}
