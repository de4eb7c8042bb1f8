#include "quadrix/scene/scene.h"

#include <fmt/format.h>

namespace quadrix {

std::string SourceLoc::ToString() const {
    if (line <= 0) return FileName();
    if (column <= 0) return fmt::format("{}:{}", FileName(), line);  // a line without a column
    return fmt::format("{}:{}:{}", FileName(), line, column);
}

}  // namespace quadrix

namespace quadrix::scene {

namespace {
template <class T>
int FindById(const std::vector<T>& v, const std::string& id) {
    for (int i = static_cast<int>(v.size()) - 1; i >= 0; --i)
        if (v[i].id == id) return i;
    return -1;
}
}  // namespace

int Scene::FindDefinition(const std::string& id) const { return FindById(definitions, id); }
int Scene::FindView(const std::string& id) const { return FindById(views, id); }
int Scene::FindLight(const std::string& id) const { return FindById(lights, id); }

View DefaultView() {
    View v;
    v.id = "default";
    v.dop = Vec3{0.3, 0.3, -1};
    v.isDefault = true;
    return v;
}

Light DefaultLight() {
    Light l;
    l.id = "default";
    l.kind = Light::Kind::kParallel;
    l.intensity = 1;
    l.direction = {0, 0, -1};
    l.isDefault = true;
    return l;
}

std::optional<View> Scene::ViewToUse(const std::string& name) const {
    if (!name.empty()) {
        int i = FindView(name);
        if (i >= 0) return views[i];
        if (name == "default") return DefaultView();
        return std::nullopt;
    }
    if (!views.empty()) return views.back();
    return DefaultView();
}

std::vector<Light> Scene::LightsToUse() const {
    if (lights.empty()) return {};  // the default rig (built by the Flattener from the view)
    return WithDefaultLight(lights);
}

std::vector<Light> Scene::WithDefaultLight(std::vector<Light> result) {
    bool anyDirected = false;
    for (const Light& l : result) anyDirected |= l.kind != Light::Kind::kAmbient;
    if (!anyDirected) result.push_back(DefaultLight());
    return result;
}

bool Scene::Empty() const {
    if (!top.freeforms.empty()) return false;
    for (const Body& b : top.bodies)
        if (!b.usedAsOperand) return false;
    for (const Instance& i : top.instances)
        if (!i.usedAsOperand && i.count > 0) return false;
    for (const Csg& c : top.csgs)
        if (!c.usedAsOperand) return false;
    return true;
}

}  // namespace quadrix::scene
