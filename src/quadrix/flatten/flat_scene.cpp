#include "quadrix/flatten/flat_scene.h"

namespace quadrix {

Vec3 FlatScene::WorldNormal(int hs, const Vec3& p) const {
    const FlatHalfSpace& h = halfSpaces[hs];
    Vec4 g = h.HomogeneousGradient(p);
    // Face the viewer in device space: rays travel along +z, so a visible normal has g.z <= 0.
    if (g.z > 0) g = -g;
    const Mat4& m = projection.deviceFromWorld.Matrix();
    // n_world = Mᵀ g (covector pull-back), first three components.
    Vec3 n{m.m[0][0] * g.x + m.m[1][0] * g.y + m.m[2][0] * g.z + m.m[3][0] * g.w,
           m.m[0][1] * g.x + m.m[1][1] * g.y + m.m[2][1] * g.z + m.m[3][1] * g.w,
           m.m[0][2] * g.x + m.m[1][2] * g.y + m.m[2][2] * g.z + m.m[3][2] * g.w};
    // For perspective the homogeneous w of the device point can flip the sign of the pull-back;
    // it is positive in front of the eye, which the clipping planes guarantee.
    return Normalize(n);
}

scene::Color FlatScene::SurfaceColor(int surface, int body) const {
    if (body >= 0 && static_cast<std::size_t>(body) < bodies.size())
        return bodies[static_cast<std::size_t>(body)].color;
    const long long k = static_cast<long long>(surface) - static_cast<long long>(halfSpaces.size());
    if (k >= 0 && k < static_cast<long long>(freeforms.size()))
        return freeforms[static_cast<std::size_t>(k)].color;
    return {};
}

scene::Finish FlatScene::SurfaceFinish(int surface, int body) const {
    if (body >= 0 && static_cast<std::size_t>(body) < bodies.size())
        return bodies[static_cast<std::size_t>(body)].finish;
    const long long k = static_cast<long long>(surface) - static_cast<long long>(halfSpaces.size());
    if (k >= 0 && k < static_cast<long long>(freeforms.size()))
        return freeforms[static_cast<std::size_t>(k)].finish;
    return {};
}

}  // namespace quadrix
