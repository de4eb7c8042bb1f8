#include "quadrix/engines/raycast/scene_tables.h"

#include "quadrix/util/parallel.h"

namespace quadrix::raycast {

SceneTables::SceneTables(const FlatScene& scene) {
    // Each half-space's entries depend on it alone: made in parallel (a 10,000-body model has
    // 30,000 half-spaces; this was serial, once for the frame and once for the samples).
    const std::size_t n = scene.halfSpaces.size();
    halfSpaces.resize(n);
    constantNormal.assign(n, 0);
    planeNormal.assign(n, Vec3{});
    packedPlaneNormal.assign(n, PackedNormal{});
    const Vec3 anchor = ReferenceAnchor(scene);
    ParallelFor(tbb::blocked_range<std::size_t>(0, n, 2048),
                [&](const tbb::blocked_range<std::size_t>& r) {
                    for (std::size_t h = r.begin(); h < r.end(); ++h) {
                        const FlatHalfSpace& hs = scene.halfSpaces[h];
                        halfSpaces[h] = RayHalfSpace::From(hs, ReferencePoint(hs, anchor));
                        if (hs.isPlane) {
                            constantNormal[h] = 1;
                            planeNormal[h] = scene.WorldNormal(static_cast<int>(h), Vec3{});
                            packedPlaneNormal[h] = PackedNormal(planeNormal[h]);
                        }
                    }
                });
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

Vec3 SceneTables::ReferenceAnchor(const FlatScene& scene) {
    return {std::round(0.5 * scene.width), std::round(0.5 * scene.height), 0};
}

Vec3 SceneTables::ReferencePoint(const FlatHalfSpace& hs, const Vec3& anchor) {
    return !hs.IsQuadric() ? anchor : RayHalfSpace::Centre(hs.quadric).value_or(anchor);
}

}  // namespace quadrix::raycast
