// QuadricNormals against the definition it replaces, PackedNormal(FlatScene::WorldNormal), one
// point at a time: the same 32 bits in every lane, on random quadrics, points and device maps
// (parallel and perspective), including normals on the octahedron's folded half and along the
// axes; and lanes out of Normalize's safe range flagged for the scalar path.
#include "quadrix/engines/raycast/quadric_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/packed_normal.h"

namespace quadrix::raycast {
namespace {

FlatScene SceneWithMap(const Mat4& deviceFromWorld) {
    FlatScene scene;
    scene.projection.deviceFromWorld = Transform::FromMatrix(deviceFromWorld).value();
    return scene;
}

// Fills `normals` with n random points on random quadrics (appended to scene.halfSpaces, lane i
// on half-space i) and checks every lane's code against the scalar definition.
void CheckLanes(FlatScene& scene, std::mt19937_64& rng, int n, double coefScale) {
    std::uniform_real_distribution<double> u(-1, 1);
    scene.halfSpaces.clear();
    QuadricNormals normals;
    normals.Clear();
    for (int i = 0; i < n; ++i) {
        FlatHalfSpace h;
        h.isPlane = false;
        for (double& c : h.quadric.k) c = u(rng) * coefScale;
        // Now and then an axis-aligned one (normals along the axes, exact codes) or a sphere.
        if (i % 7 == 3)
            for (int c = 3; c < 6; ++c) h.quadric.k[static_cast<std::size_t>(c)] = 0;
        scene.halfSpaces.push_back(h);
        EXPECT_EQ(normals.Add(h.quadric, 640 * (u(rng) + 1), 360 * (u(rng) + 1), 100 * u(rng)), i);
    }
    ASSERT_EQ(normals.Size(), n);
    normals.Pack(scene.projection.deviceFromWorld.Matrix());
    for (int i = 0; i < n; ++i) {
        const Vec3 p{normals.X(i), normals.Y(i), normals.Z(i)};
        const std::uint32_t want = PackedNormal(scene.WorldNormal(i, p)).bits;
        // These normals are far inside Normalize's safe range: no lane is left to the scalar path.
        ASSERT_FALSE(normals.NeedsScalar(i)) << "lane " << i;
        EXPECT_EQ(normals.Code(i), want) << "lane " << i << " of " << n;
    }
}

TEST(QuadricNormals, EveryLaneIsTheScalarPackingBitForBit) {
    std::mt19937_64 rng(20261207);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int round = 0; round < 200; ++round) {
        // A random invertible device map: affine (parallel views) or projective (perspective).
        Mat4 m = Mat4::Identity();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) m.m[r][c] = u(rng) * 50 + (r == c ? 100 : 0);
        if (round % 2) {
            m.m[3][2] = 0.01 * u(rng);
            m.m[3][3] = 1 + 0.1 * u(rng);
        }
        FlatScene scene = SceneWithMap(m);
        // Every lane count from 1 to the capacity (the vector loops' remainders).
        const int n = 1 + round % QuadricNormals::kCapacity;
        CheckLanes(scene, rng, n, round % 3 == 0 ? 1e-3 : 1.0);
    }
}

TEST(QuadricNormals, LanesOutOfTheSafeRangeAreLeftToTheScalarPath) {
    FlatScene scene = SceneWithMap(Mat4::Identity());
    QuadricNormals normals;
    normals.Clear();
    Quadric tiny, huge, sphere;
    tiny.k = {1e-300, 1e-300, 1e-300, 0, 0, 0, 0, 0, 0, -1e-300};
    huge.k = {1e300, 1e300, 1e300, 0, 0, 0, 0, 0, 0, -1e300};
    sphere.k = {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};
    for (const Quadric* q : {&tiny, &huge, &sphere}) {
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = *q;
        scene.halfSpaces.push_back(h);
    }
    normals.Add(tiny, 0.6, 0.8, 0);
    normals.Add(huge, 0.6, 0.8, 0);
    // Its gradient there faces away from the viewer (z > 0): turned, (−0.6, 0, −0.8), on the
    // octahedron's folded half, u = −1 exactly.
    normals.Add(sphere, 0.6, 0, 0.8);
    normals.Pack(Mat4::Identity());
    EXPECT_TRUE(normals.NeedsScalar(0));
    EXPECT_TRUE(normals.NeedsScalar(1));
    ASSERT_FALSE(normals.NeedsScalar(2));
    EXPECT_EQ(normals.Code(2), PackedNormal(scene.WorldNormal(2, {0.6, 0, 0.8})).bits);
    EXPECT_EQ(normals.Code(2) >> 16, 0x8001u);
}

}  // namespace
}  // namespace quadrix::raycast
