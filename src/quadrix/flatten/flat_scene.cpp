#include "quadrix/flatten/flat_scene.h"

#include <string>

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

std::string FlatScene::Validate() const {
    auto bad = [](const std::string& what) { return "FlatScene: " + what; };
    if (width < 0 || height < 0) return bad("negative size");
    const int nh = static_cast<int>(halfSpaces.size()), nb = static_cast<int>(bodies.size()),
              nn = static_cast<int>(nodes.size()), ns = static_cast<int>(solids.size());
    if (sectionHalfSpace < -1 || sectionHalfSpace >= nh ||
        (sectionHalfSpace >= 0 &&
         (!section || !halfSpaces[static_cast<std::size_t>(sectionHalfSpace)].isPlane)))
        return bad("section half-space " + std::to_string(sectionHalfSpace));
    for (int b = 0; b < nb; ++b) {
        const FlatBody& body = bodies[static_cast<std::size_t>(b)];
        for (const FlatLiteral& l : body.literals)
            if (l.halfSpace < 0 || l.halfSpace >= nh)
                return bad("body " + std::to_string(b) + " names half-space " +
                           std::to_string(l.halfSpace));
        if (body.solid < -1 || body.solid >= ns)
            return bad("body " + std::to_string(b) + " names solid " + std::to_string(body.solid));
    }
    for (int n = 0; n < nn; ++n) {
        const FlatCsgNode& node = nodes[static_cast<std::size_t>(n)];
        if (node.isLeaf) {
            if (node.body < 0 || node.body >= nb)
                return bad("leaf " + std::to_string(n) + " names body " +
                           std::to_string(node.body));
        } else {
            for (int c : node.children)
                if (c < 0 || c >= n)
                    return bad("node " + std::to_string(n) + " has child " + std::to_string(c) +
                               " (children come before their parents)");
        }
    }
    for (int s = 0; s < ns; ++s) {
        const int root = solids[static_cast<std::size_t>(s)].root;
        if (root < 0 || root >= nn)
            return bad("solid " + std::to_string(s) + " has root " + std::to_string(root));
    }
    return {};
}

}  // namespace quadrix
