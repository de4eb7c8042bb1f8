// quadrix::Scene (include/quadrix/quadrix.h): a scene::Scene behind a pointer. Files are read
// through the render context's input stage (every format, pipeline/render_context.h); scenes
// built in code are built by the scene language itself: each Add* call writes the one statement
// it stands for (docs/language.md) and reads it into the scene, so the API checks exactly what
// the language checks, with the same messages, and cannot drift from it.
//
// An edit that fails leaves the scene as it was: the reader only appends to the scene's lists
// (and marks operands), so the lists are cut back to their old lengths and the operand marks
// restored (Snapshot), without copying the scene.
#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <utility>

#include "api_internal.h"
#include "quadrix/lang/reader.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix {

namespace {

std::uint64_t NextRevision() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

// What a failed read may have changed.
struct Snapshot {
    std::size_t halfSpaces, bodies, instances, csgs, freeforms, definitions, lights, views;
    std::optional<scene::Color> background, backgroundBottom;
    std::vector<bool> operands;  // usedAsOperand of bodies, instances, csgs in that order

    explicit Snapshot(const scene::Scene& s)
        : halfSpaces(s.top.halfSpaces.size()),
          bodies(s.top.bodies.size()),
          instances(s.top.instances.size()),
          csgs(s.top.csgs.size()),
          freeforms(s.top.freeforms.size()),
          definitions(s.definitions.size()),
          lights(s.lights.size()),
          views(s.views.size()),
          background(s.background),
          backgroundBottom(s.backgroundBottom) {
        for (const auto& b : s.top.bodies) operands.push_back(b.usedAsOperand);
        for (const auto& i : s.top.instances) operands.push_back(i.usedAsOperand);
        for (const auto& c : s.top.csgs) operands.push_back(c.usedAsOperand);
    }
    void Restore(scene::Scene& s) const {
        s.top.halfSpaces.resize(halfSpaces);
        s.top.bodies.resize(bodies);
        s.top.instances.resize(instances);
        s.top.csgs.resize(csgs);
        s.top.freeforms.resize(freeforms);
        s.definitions.resize(definitions);
        s.lights.resize(lights);
        s.views.resize(views);
        s.background = background;
        s.backgroundBottom = backgroundBottom;
        std::size_t k = 0;
        for (auto& b : s.top.bodies) b.usedAsOperand = operands[k++];
        for (auto& i : s.top.instances) i.usedAsOperand = operands[k++];
        for (auto& c : s.top.csgs) c.usedAsOperand = operands[k++];
    }
};

// Ids go into statement text: only what the language's lexer reads as one id (letters, digits,
// '#', '_', not starting with a digit) is accepted, so an id cannot smuggle in a statement.
void CheckId(const std::string& id, const char* what, bool optional = false) {
    if (id.empty()) {
        if (optional) return;
        throw Error(fmt::format("{}: the id is empty", what));
    }
    bool ok = !(id[0] >= '0' && id[0] <= '9');
    for (char c : id)
        ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '#');
    if (!ok)
        throw Error(
            fmt::format("{}: '{}' is not an id (letters, digits, '#' and '_', not "
                        "starting with a digit)",
                        what, id));
}

// Shortest text that reads back as the same double ({} of fmt round-trips).
std::string Num(double v, const char* what) {
    if (!std::isfinite(v)) throw Error(fmt::format("{}: a number is not finite ({})", what, v));
    return fmt::format("{}", v);
}
std::string Nums(const Vector3& v, const char* what) {
    return Num(v[0], what) + " " + Num(v[1], what) + " " + Num(v[2], what);
}
std::string ColorText(const std::optional<Color>& c, const char* what) {
    if (!c) return {};
    return " =c " + Num(c->r, what) + " " + Num(c->g, what) + " " + Num(c->b, what);
}

}  // namespace

void Scene::Impl::Touch() { revision = NextRevision(); }

Scene::Scene() : impl_(std::make_unique<Impl>()) { impl_->Touch(); }
Scene::~Scene() = default;
Scene::Scene(const Scene& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
Scene& Scene::operator=(const Scene& other) {
    if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
    return *this;
}
// A moved-from Scene is empty (and usable), not null.
Scene::Scene(Scene&& other) noexcept : impl_(std::move(other.impl_)) {
    other.impl_ = std::unique_ptr<Impl>(new (std::nothrow) Impl);
}
Scene& Scene::operator=(Scene&& other) noexcept {
    if (this != &other) {
        impl_ = std::move(other.impl_);
        other.impl_ = std::unique_ptr<Impl>(new (std::nothrow) Impl);
    }
    return *this;
}

Scene Scene::FromFiles(const std::vector<std::string>& paths, const ReadOptions& options) {
    if (paths.empty()) throw Error("Scene::FromFiles: no file given");
    InputRequest request;
    request.paths = paths;
    request.topObjects = options.topObjects;
    request.strict = options.strict;
    request.allowMissing = options.allowMissing;
    RenderContext context(1);
    Diagnostics diags;
    if (!context.Read(request, diags) || diags.HasErrors())
        api::ThrowDiagnostics(diags, "the scene could not be read");
    Scene s;
    s.impl_->scene = std::move(context.Scene());
    s.impl_->warnings = api::WarningsOf(diags);
    s.impl_->Touch();
    return s;
}

Scene Scene::FromFile(const std::string& path, const ReadOptions& options) {
    return FromFiles({path}, options);
}

Scene Scene::FromText(std::string_view text, const std::string& name) {
    Scene s;
    s.Append(text, name);
    return s;
}

Scene& Scene::Append(std::string_view text, const std::string& name) {
    Impl& impl = *impl_;
    const Snapshot before(impl.scene);
    Diagnostics diags;
    bool ok = false;
    {
        lang::Reader reader(impl.scene, diags);
        ok = reader.ReadText(text, name);
    }
    if (!ok || diags.HasErrors()) {
        before.Restore(impl.scene);
        api::ThrowDiagnostics(diags, "the scene text has errors");
    }
    for (Message& m : api::WarningsOf(diags)) impl.warnings.push_back(std::move(m));
    impl.Touch();
    return *this;
}

Scene& Scene::AddPlane(const std::string& id, const std::array<double, 4>& abcd, bool transparent) {
    CheckId(id, "AddPlane");
    std::string s = "plane " + id + " <";
    for (double v : abcd) s += " " + Num(v, "AddPlane");
    s += " >";
    if (transparent) s += " =t";
    return Append(s + ";", "<Scene::AddPlane>");
}

Scene& Scene::AddQuadric(const std::string& id, const std::array<double, 10>& coefficients,
                         bool transparent) {
    CheckId(id, "AddQuadric");
    std::string s = "quadric " + id + " <";
    for (double v : coefficients) s += " " + Num(v, "AddQuadric");
    s += " >";
    if (transparent) s += " =t";
    return Append(s + ";", "<Scene::AddQuadric>");
}

Scene& Scene::AddBody(const std::string& id, const std::vector<std::string>& literals,
                      std::optional<Color> color) {
    CheckId(id, "AddBody");
    std::string s = "body " + id + " <";
    for (const std::string& l : literals) {
        const bool complement = !l.empty() && l[0] == '!';
        const std::string name = complement ? l.substr(1) : l;
        CheckId(name, "AddBody");
        s += complement ? " !" + name : " " + name;
    }
    s += " >" + ColorText(color, "AddBody");
    return Append(s + ";", "<Scene::AddBody>");
}

Scene& Scene::AddCsg(const std::string& id, CsgOperation operation, const std::string& left,
                     const std::string& right, std::optional<Color> color) {
    CheckId(left, "AddCsg");
    CheckId(right, "AddCsg");
    const char* op = operation == CsgOperation::kUnion          ? " | "
                     : operation == CsgOperation::kIntersection ? " & "
                                                                : " - ";
    return AddCsg(id, left + op + right, color);
}

Scene& Scene::AddCsg(const std::string& id, const std::string& expression,
                     std::optional<Color> color) {
    CheckId(id, "AddCsg");
    // The expression is the language's own (ids, | & - and parentheses): anything else, a ';'
    // in particular, is refused here rather than read as another statement.
    for (char c : expression)
        if (c == ';' || c == '{' || c == '}' || c == '"' || c == '=')
            throw Error(fmt::format("AddCsg: '{}' is not allowed in a CSG expression", c));
    return Append("csg " + id + " (" + expression + ")" + ColorText(color, "AddCsg") + ";",
                  "<Scene::AddCsg>");
}

Scene& Scene::AddSphere(const std::string& id, const Vector3& center, double radius,
                        std::optional<Color> color) {
    CheckId(id, "AddSphere");
    return Append("solid sphere " + id + " =r " + Num(radius, "AddSphere") + " =at " +
                      Nums(center, "AddSphere") + ColorText(color, "AddSphere") + ";",
                  "<Scene::AddSphere>");
}

Scene& Scene::AddBox(const std::string& id, const Vector3& corner0, const Vector3& corner1,
                     std::optional<Color> color) {
    CheckId(id, "AddBox");
    return Append("solid box " + id + " =from " + Nums(corner0, "AddBox") + " =to " +
                      Nums(corner1, "AddBox") + ColorText(color, "AddBox") + ";",
                  "<Scene::AddBox>");
}

Scene& Scene::AddCylinder(const std::string& id, const Vector3& from, const Vector3& to,
                          double radius, std::optional<Color> color) {
    CheckId(id, "AddCylinder");
    return Append("solid cylinder " + id + " =from " + Nums(from, "AddCylinder") + " =to " +
                      Nums(to, "AddCylinder") + " =r " + Num(radius, "AddCylinder") +
                      ColorText(color, "AddCylinder") + ";",
                  "<Scene::AddCylinder>");
}

Scene& Scene::AddCone(const std::string& id, const Vector3& from, const Vector3& to, double radius0,
                      double radius1, std::optional<Color> color) {
    CheckId(id, "AddCone");
    return Append("solid cone " + id + " =from " + Nums(from, "AddCone") + " =to " +
                      Nums(to, "AddCone") + " =r0 " + Num(radius0, "AddCone") + " =r1 " +
                      Num(radius1, "AddCone") + ColorText(color, "AddCone") + ";",
                  "<Scene::AddCone>");
}

Scene& Scene::AddAmbientLight(const std::string& id, double intensity) {
    CheckId(id, "AddAmbientLight", true);
    return Append("light " + id + " " + Num(intensity, "AddAmbientLight") + ";",
                  "<Scene::AddAmbientLight>");
}

Scene& Scene::AddParallelLight(const std::string& id, double intensity, const Vector3& towardLight,
                               std::optional<Color> color) {
    CheckId(id, "AddParallelLight", true);
    return Append("light " + id + " " + Num(intensity, "AddParallelLight") + " " +
                      Nums(towardLight, "AddParallelLight") + ColorText(color, "AddParallelLight") +
                      ";",
                  "<Scene::AddParallelLight>");
}

Scene& Scene::AddPointLight(const std::string& id, double intensity, const Vector3& position,
                            std::optional<Color> color) {
    CheckId(id, "AddPointLight", true);
    return Append("light " + id + " " + Num(intensity, "AddPointLight") + " =at " +
                      Nums(position, "AddPointLight") + ColorText(color, "AddPointLight") + ";",
                  "<Scene::AddPointLight>");
}

Scene& Scene::AddView(const View& view) {
    CheckId(view.id, "AddView", true);
    std::string s = "view " + view.id;
    auto vec = [&](const char* key, const std::optional<Vector3>& v) {
        if (v) s += fmt::format(" {} {}", key, Nums(*v, "AddView"));
    };
    vec("vrp", view.vrp);
    vec("vpn", view.vpn);
    vec("vup", view.vup);
    vec("dop", view.dop);
    vec("cop", view.cop);
    if (view.halfHeight) s += " whh " + Num(*view.halfHeight, "AddView");
    if (view.halfWidth) s += " whw " + Num(*view.halfWidth, "AddView");
    return Append(s + ";", "<Scene::AddView>");
}

std::size_t Scene::HalfSpaceCount() const { return impl_->scene.top.halfSpaces.size(); }
std::size_t Scene::BodyCount() const { return impl_->scene.top.bodies.size(); }
std::size_t Scene::CsgCount() const { return impl_->scene.top.csgs.size(); }
std::size_t Scene::LightCount() const { return impl_->scene.lights.size(); }
std::vector<std::string> Scene::ViewNames() const {
    std::vector<std::string> names;
    for (const scene::View& v : impl_->scene.views) names.push_back(v.id);
    return names;
}
bool Scene::Empty() const { return impl_->scene.Empty(); }
const std::vector<Message>& Scene::Warnings() const { return impl_->warnings; }

View View::Parallel(const Vector3& toward) {
    View v;
    v.dop = toward;
    return v;
}

View View::Perspective(const Vector3& eye, const Vector3& target) {
    View v;
    v.cop = eye;
    v.vrp = target;
    return v;
}

namespace api {

scene::View ToSceneView(const View& view, const std::string& id) {
    auto vec = [](const std::optional<Vector3>& v) -> std::optional<Vec3> {
        if (!v) return std::nullopt;
        for (double c : *v)
            if (!std::isfinite(c)) throw Error("Options::camera: a number is not finite");
        return Vec3{(*v)[0], (*v)[1], (*v)[2]};
    };
    scene::View out;
    out.id = id;
    out.vrp = vec(view.vrp);
    out.vpn = vec(view.vpn);
    out.vup = vec(view.vup);
    out.dop = vec(view.dop);
    out.cop = vec(view.cop);
    out.whh = view.halfHeight;
    out.whw = view.halfWidth;
    return out;
}

}  // namespace api
}  // namespace quadrix
