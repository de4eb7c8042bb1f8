// The Frame's normals of the visible points on quadrics of one sub-tile, made together (issue 24
// item 4: one normal at a time, the gradient, its pull-back to world space, the normalisation
// and the octahedral packing were 13 % of the machined part's frame).
//
// A lane's code is bit for bit PackedNormal(scene.WorldNormal(hs, p)) (flat_scene.cpp,
// packed_normal.h): the same IEEE operations in the same order, their branches written as
// selects of values computed in every lane, in three passes built for AVX2 and the baseline
// (util/cpu_features.h): the gradients and pull-backs, which the compiler vectorises; the square
// roots, by intrinsics (-fmath-errno keeps the compiler from vectorising std::sqrt); the
// divisions and the packing, which GCC leaves scalar ("control flow in loop": its selects are
// not if-converted under -ftrapping-math). A lane whose normal falls outside Normalize's safe range
// (math/vec.h: a squared length below 1e-280 or above 1e280, or not finite) has no code here:
// NeedsScalar says so, and the caller packs it one at a time as before.
#pragma once

#include <cstdint>

#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"

namespace quadrix::raycast {

class QuadricNormals {
  public:
    static constexpr int kCapacity = 64;  // a sub-tile's pixels (tiling.h kLanePixels)

    void Clear() { n_ = 0; }
    int Size() const { return n_; }
    // Adds the device point (x, y, z) on the device-space quadric q; returns its lane. At most
    // kCapacity lanes between Clears.
    int Add(const Quadric& q, double x, double y, double z) {
        const int i = n_++;
        for (int c = 0; c < 10; ++c) coef_[c][i] = q.k[static_cast<std::size_t>(c)];
        x_[i] = x;
        y_[i] = y;
        z_[i] = z;
        return i;
    }
    // Every lane's code, for the scene whose FlatScene::projection.deviceFromWorld is `m`.
    void Pack(const Mat4& m);
    std::uint32_t Code(int lane) const { return code_[lane]; }
    bool NeedsScalar(int lane) const { return scalar_[lane] != 0; }
    // The lane's point, as added.
    double X(int lane) const { return x_[lane]; }
    double Y(int lane) const { return y_[lane]; }
    double Z(int lane) const { return z_[lane]; }

  private:
    int n_ = 0;
    alignas(64) double coef_[10][kCapacity];  // <A B C D E F G H J K> per lane
    alignas(64) double x_[kCapacity], y_[kCapacity], z_[kCapacity];
    alignas(64) std::uint32_t code_[kCapacity];
    alignas(64) std::uint8_t scalar_[kCapacity];
};

}  // namespace quadrix::raycast
