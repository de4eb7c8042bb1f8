#include "quadrix/engines/raycast/scene_tables.h"

namespace quadrix::raycast {

SceneTables::SceneTables(const FlatScene& scene) {
    std::vector<Vec3> reference = ReferencePoints(scene);
    halfSpaces.reserve(scene.halfSpaces.size());
    constantNormal.assign(scene.halfSpaces.size(), 0);
    planeNormal.assign(scene.halfSpaces.size(), Vec3{});
    packedPlaneNormal.assign(scene.halfSpaces.size(), PackedNormal{});
    for (std::size_t h = 0; h < scene.halfSpaces.size(); ++h) {
        halfSpaces.push_back(RayHalfSpace::From(scene.halfSpaces[h], reference[h]));
        if (scene.halfSpaces[h].isPlane) {
            constantNormal[h] = 1;
            planeNormal[h] = scene.WorldNormal(static_cast<int>(h), Vec3{});
            packedPlaneNormal[h] = PackedNormal(planeNormal[h]);
        }
    }
    bodyFirstTag.reserve(scene.bodies.size() + 1);
    bodyValid.assign(scene.bodies.size(), 1);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        bodyFirstTag.push_back(static_cast<std::int32_t>(tags.size()));
        for (const FlatLiteral& lit : scene.bodies[b].literals) {
            if (lit.halfSpace < 0 ||
                static_cast<std::size_t>(lit.halfSpace) >= scene.halfSpaces.size()) {
                bodyValid[b] = 0;
                continue;
            }
            const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
            tags.push_back({lit.halfSpace, static_cast<std::int32_t>(b), lit.complemented,
                            !hs.transparent && !hs.isClip});
        }
    }
    bodyFirstTag.push_back(static_cast<std::int32_t>(tags.size()));
    tagSequence.resize(tags.size());
    for (std::size_t i = 0; i < tagSequence.size(); ++i)
        tagSequence[i] = static_cast<std::int32_t>(i);
}

std::vector<Vec3> SceneTables::ReferencePoints(const FlatScene& scene) {
    Vec3 anchor{std::round(0.5 * scene.width), std::round(0.5 * scene.height), 0};
    std::vector<Vec3> ref;
    ref.reserve(scene.halfSpaces.size());
    for (const FlatHalfSpace& hs : scene.halfSpaces)
        ref.push_back(!hs.IsQuadric() ? anchor : RayHalfSpace::Centre(hs.quadric).value_or(anchor));
    return ref;
}

}  // namespace quadrix::raycast
