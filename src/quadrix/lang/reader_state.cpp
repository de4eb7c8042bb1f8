#include "quadrix/lang/reader_state.h"

#include <cstring>

#include "quadrix/lang/big_arrays.h"
#include "quadrix/lang/keywords.h"

namespace quadrix::lang {

namespace {
using Kind = scene::SolidRef::Kind;

int EncodeSolid(const scene::SolidRef& ref) { return ref.index * 4 + static_cast<int>(ref.kind); }
scene::SolidRef DecodeSolid(int value) { return {static_cast<Kind>(value & 3), value >> 2}; }

// The idOf functions of the scope's id tables (id_table.h).
auto HalfSpaceIds(const scene::Scope& scope) {
    return [&scope](int v) -> const std::string& { return scope.halfSpaces[v].id; };
}
auto SolidIds(const scene::Scope& scope) {
    return [&scope](int v) -> const std::string& {
        scene::SolidRef ref = DecodeSolid(v);
        switch (ref.kind) {
            case Kind::kBody:
                return scope.bodies[ref.index].id;
            case Kind::kInstance:
                return scope.instances[ref.index].id;
            case Kind::kCsg:
                break;
        }
        return scope.csgs[ref.index].id;
    };
}

void IndexScope(const scene::Scope& scope, ScopeIndex& index) {
    for (int i = 0; i < static_cast<int>(scope.halfSpaces.size()); ++i)
        index.halfSpaces.Set(scope.halfSpaces[i].id, i, HalfSpaceIds(scope));
    for (int i = 0; i < static_cast<int>(scope.bodies.size()); ++i)
        index.solids.Set(scope.bodies[i].id, EncodeSolid({Kind::kBody, i}), SolidIds(scope));
    for (int i = 0; i < static_cast<int>(scope.instances.size()); ++i)
        index.solids.Set(scope.instances[i].id, EncodeSolid({Kind::kInstance, i}), SolidIds(scope));
    for (int i = 0; i < static_cast<int>(scope.csgs.size()); ++i)
        index.solids.Set(scope.csgs[i].id, EncodeSolid({Kind::kCsg, i}), SolidIds(scope));
}
template <class T>
void IndexGlobal(const std::vector<T>& items, std::unordered_map<std::string, int>& index) {
    for (int i = 0; i < static_cast<int>(items.size()); ++i) index[items[i].id] = i;
}
int Lookup(const std::unordered_map<std::string, int>& index, const std::string& id) {
    auto it = index.find(id);
    return it == index.end() ? -1 : it->second;
}
}  // namespace

ReaderState::ReaderState(scene::Scene& scene_, Diagnostics& diags_, ReadOptions options_)
    : scene(scene_), diags(diags_), options(options_) {
    // A Reader may add to a scene that already holds statements (several files, interactive
    // sessions): index what is there so that ids stay unique and can be referred to.
    IndexScope(scene.top, topIndex_);
    IndexGlobal(scene.definitions, definitions_);
    IndexGlobal(scene.lights, lights_);
    IndexGlobal(scene.views, views_);
}

scene::Scope& ReaderState::CurrentScope() {
    return openDefinition_ ? openDefinition_->scope : scene.top;
}
const scene::Scope& ReaderState::CurrentScopeConst() const {
    return openDefinition_ ? openDefinition_->scope : scene.top;
}
ScopeIndex& ReaderState::CurrentIndex() {
    return openDefinition_ ? openDefinition_->index : topIndex_;
}
const ScopeIndex& ReaderState::CurrentIndex() const {
    return openDefinition_ ? openDefinition_->index : topIndex_;
}

const Source* ReaderState::DefinitionSource() const {
    return openDefinition_ ? openDefinition_->source : nullptr;
}

void ReaderState::OpenDefinition(scene::Scope scope, const Source* source) {
    openDefinition_ = OpenDef{std::move(scope), {}, source};
}

int ReaderState::CloseDefinition() {
    int index = static_cast<int>(scene.definitions.size());
    definitions_[openDefinition_->scope.id] = index;
    scene.definitions.push_back(std::move(openDefinition_->scope));
    openDefinition_.reset();
    return index;
}

int ReaderState::FindHalfSpace(const std::string& id) const {
    return CurrentIndex().halfSpaces.Find(id, HalfSpaceIds(CurrentScopeConst()));
}

std::optional<scene::SolidRef> ReaderState::FindSolid(const std::string& id) const {
    int v = CurrentIndex().solids.Find(id, SolidIds(CurrentScopeConst()));
    if (v < 0) return std::nullopt;
    return DecodeSolid(v);
}

SourceLoc ReaderState::SolidLoc(const scene::SolidRef& ref) const {
    const scene::Scope& scope = openDefinition_ ? openDefinition_->scope : scene.top;
    switch (ref.kind) {
        case scene::SolidRef::Kind::kBody:
            return scope.bodies[ref.index].loc;
        case scene::SolidRef::Kind::kInstance:
            return scope.instances[ref.index].loc;
        case scene::SolidRef::Kind::kCsg:
            return scope.csgs[ref.index].loc;
    }
    return {};
}

std::string ReaderState::SolidKindName(const scene::SolidRef& ref) const {
    const scene::Scope& scope = openDefinition_ ? openDefinition_->scope : scene.top;
    switch (ref.kind) {
        case scene::SolidRef::Kind::kBody:
            return "body";
        case scene::SolidRef::Kind::kInstance:
            return scope.instances[ref.index].isArray ? "array" : "instance";
        case scene::SolidRef::Kind::kCsg:
            return "csg solid";
    }
    return "solid";
}

std::string ReaderState::DuplicateSolidMessage(const std::string& id) const {
    auto first = FindSolid(id);
    if (!first) return {};
    return "id '" + id + "' is already used by the " + SolidKindName(*first) + " at " +
           SolidLoc(*first).ToString();
}

void ReaderState::MarkOperand(const scene::SolidRef& ref) {
    scene::Scope& scope = CurrentScope();
    switch (ref.kind) {
        case scene::SolidRef::Kind::kBody:
            scope.bodies[ref.index].usedAsOperand = true;
            break;
        case scene::SolidRef::Kind::kInstance:
            scope.instances[ref.index].usedAsOperand = true;
            break;
        case scene::SolidRef::Kind::kCsg:
            scope.csgs[ref.index].usedAsOperand = true;
            break;
    }
}

void ReaderState::ReserveForText(std::string_view text) {
    if (text.size() < kReserveMinBytes) return;
    std::size_t halfSpaces = 0, bodies = 0, csgs = 0;
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')) ++p;
        const char* word = p;
        while (p < end && *p >= 'a' && *p <= 'z') ++p;
        switch (LookupKeyword(std::string_view(word, static_cast<std::size_t>(p - word)))) {
            case Keyword::kPlane:
            case Keyword::kQuadric:
                ++halfSpaces;
                break;
            case Keyword::kBody:
                ++bodies;
                break;
            case Keyword::kCsg:
                ++csgs;
                break;
            default:
                break;
        }
        const void* semicolon = std::memchr(p, ';', static_cast<std::size_t>(end - p));
        if (!semicolon) break;
        p = static_cast<const char*>(semicolon) + 1;
    }
    scene::Scope& scope = CurrentScope();
    ReserveAdvised(scope.halfSpaces, scope.halfSpaces.size() + halfSpaces);
    ReserveAdvised(scope.bodies, scope.bodies.size() + bodies);
    ReserveAdvised(scope.csgs, scope.csgs.size() + csgs);
    ScopeIndex& index = CurrentIndex();
    index.halfSpaces.Reserve(index.halfSpaces.Size() + halfSpaces);
    index.solids.Reserve(index.solids.Size() + bodies + csgs);
}

int ReaderState::AddHalfSpace(scene::HalfSpace hs) {
    scene::Scope& scope = CurrentScope();
    int index = static_cast<int>(scope.halfSpaces.size());
    PrepareAppend(scope.halfSpaces);
    scope.halfSpaces.push_back(std::move(hs));
    CurrentIndex().halfSpaces.Set(scope.halfSpaces.back().id, index, HalfSpaceIds(scope));
    return index;
}

int ReaderState::AddBody(scene::Body body) {
    scene::Scope& scope = CurrentScope();
    int index = static_cast<int>(scope.bodies.size());
    PrepareAppend(scope.bodies);
    scope.bodies.push_back(std::move(body));
    CurrentIndex().solids.Set(scope.bodies.back().id, EncodeSolid({Kind::kBody, index}),
                              SolidIds(scope));
    return index;
}

int ReaderState::AddInstance(scene::Instance instance) {
    scene::Scope& scope = CurrentScope();
    int index = static_cast<int>(scope.instances.size());
    PrepareAppend(scope.instances);
    scope.instances.push_back(std::move(instance));
    CurrentIndex().solids.Set(scope.instances.back().id, EncodeSolid({Kind::kInstance, index}),
                              SolidIds(scope));
    return index;
}

int ReaderState::AddCsg(scene::Csg csg) {
    scene::Scope& scope = CurrentScope();
    int index = static_cast<int>(scope.csgs.size());
    PrepareAppend(scope.csgs);
    scope.csgs.push_back(std::move(csg));
    CurrentIndex().solids.Set(scope.csgs.back().id, EncodeSolid({Kind::kCsg, index}),
                              SolidIds(scope));
    return index;
}

int ReaderState::FindDefinition(const std::string& id) const { return Lookup(definitions_, id); }
int ReaderState::FindLight(const std::string& id) const { return Lookup(lights_, id); }
int ReaderState::FindView(const std::string& id) const { return Lookup(views_, id); }

int ReaderState::AddLight(scene::Light light) {
    int index = static_cast<int>(scene.lights.size());
    lights_[light.id] = index;
    scene.lights.push_back(std::move(light));
    return index;
}

int ReaderState::AddView(scene::View view) {
    int index = static_cast<int>(scene.views.size());
    views_[view.id] = index;
    scene.views.push_back(std::move(view));
    return index;
}

bool ReaderState::Taken(const std::string& id, Namespace ns) const {
    switch (ns) {
        case Namespace::kHalfSpace:
            return FindHalfSpace(id) >= 0;
        case Namespace::kSolid:
            return FindSolid(id).has_value();
        case Namespace::kDefinition:
            return FindDefinition(id) >= 0 || (openDefinition_ && openDefinition_->scope.id == id);
        case Namespace::kLight:
            return FindLight(id) >= 0;
        case Namespace::kView:
            return FindView(id) >= 0;
    }
    return false;
}

std::string ReaderState::GenerateId(const std::string& prefix, Namespace ns) {
    int& counter = idCounters_[prefix];
    for (;;) {
        std::string id = prefix + "#" + std::to_string(++counter);
        if (!Taken(id, ns)) return id;
    }
}

}  // namespace quadrix::lang
