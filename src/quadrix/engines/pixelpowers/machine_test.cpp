// The simulated frame buffer on hand-assembled programs: the semantics of each opcode of isa.h,
// independent of the compiler.
#include "quadrix/engines/pixelpowers/machine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace quadrix::pixelpowers {
namespace {

constexpr std::uint8_t kF1 = 0, kF2 = 1, kF3 = 2;

struct Assembler {
    Program program;
    Block block;

    void Begin(PixelRect r) {
        block = {};
        block.rect = r;
        block.first = static_cast<std::int32_t>(program.code.size());
    }
    void End() {
        block.count = static_cast<std::int32_t>(program.code.size()) - block.first;
        program.blocks.push_back(block);
    }
    void Op(Opcode op, std::uint8_t a, std::uint8_t b = 0, std::int32_t arg = -1,
            std::array<double, 6> q = {}) {
        Instruction in;
        in.op = op;
        in.a = a;
        in.b = b;
        in.arg = arg;
        for (int i = 0; i < 6; ++i) in.q[i] = q[static_cast<std::size_t>(i)];
        program.code.push_back(in);
    }
    std::int32_t Patch(int halfSpace) {
        program.patches.push_back({halfSpace, 0, 0});
        return static_cast<std::int32_t>(program.patches.size() - 1);
    }
};

FlatScene PlaneScene(int w, int h) {
    // One plane so that scan-out can compute normals for patch 0 (z = 0 plane, normal −z).
    FlatScene s;
    s.width = w;
    s.height = h;
    FlatHalfSpace p;
    p.isPlane = true;
    p.plane = {0, 0, -1, 0};
    s.halfSpaces.push_back(p);
    return s;
}

// Seed 003 §3 scan conversion and the z-buffer: a disk of radius 5 (QNPOS on its circle) at depth
// z = x, then the same disk at depth 20 − x; ZMIN keeps min(x, 20 − x), COLOR names the winner.
TEST(PixelPowersMachine, ScanConversionAndZBuffer) {
    Assembler as;
    std::int32_t p0 = as.Patch(0), p1 = as.Patch(0);
    // (x − 10)² + (y − 8)² − 25 <= 0  →  A=1 C=1 D=−20 E=−16 F=100+64−25
    std::array<double, 6> disk{1, 0, 1, -20, -16, 139};
    for (int k = 0; k < 2; ++k) {
        as.Begin({0, 0, 20, 16});
        as.Op(Opcode::kFlagSet, kF1);
        as.Op(Opcode::kQeeKeepNonPositive, kF1, 0, -1, disk);
        as.Op(Opcode::kZLoad, kF1, 0, -1,
              k == 0 ? std::array<double, 6>{0, 0, 0, 1, 0, 0}
                     : std::array<double, 6>{0, 0, 0, -1, 0, 20});
        as.Op(Opcode::kZTest, kF1);
        as.Op(Opcode::kZWrite, kF1, 0, k == 0 ? p0 : p1);
        as.End();
    }
    FlatScene scene = PlaneScene(20, 16);
    Frame f;
    MachineCounters c = Execute(as.program, scene, f);
    int covered = 0;
    for (int j = 0; j < 16; ++j) {
        for (int i = 0; i < 20; ++i) {
            double x = i + 0.5, y = j + 0.5;
            bool in = (x - 10) * (x - 10) + (y - 8) * (y - 8) <= 25;
            std::size_t k = f.Index(i, j);
            ASSERT_EQ(f.surface[k] != Frame::kNone, in) << i << "," << j;
            if (!in) continue;
            ++covered;
            EXPECT_EQ(f.depth[k], std::min(x, 20 - x));
        }
    }
    EXPECT_EQ(static_cast<std::uint64_t>(covered), f.CoveredCount());
    EXPECT_GT(c.writes, static_cast<std::uint64_t>(covered));  // the second disk overwrote half
}

// Envelopes and flag logic: ZMAX over two lines gives |x − 10| + 5 style roofs; ZGE/ZLE pare
// against a third line; FCOPY/FANDN combine as in seed 004 §II.b step 3.
TEST(PixelPowersMachine, EnvelopesAndFlagLogic) {
    Assembler as;
    std::int32_t p = as.Patch(0);
    as.Begin({0, 0, 20, 1});
    as.Op(Opcode::kFlagSet, kF1);
    as.Op(Opcode::kZLoad, kF1, 0, -1, {0, 0, 0, 1, 0, -10});  // z = x − 10
    as.Op(Opcode::kZMax, kF1, 0, -1, {0, 0, 0, -1, 0, 10});   // z = max(x − 10, 10 − x)
    as.Op(Opcode::kFlagCopy, kF2, kF1);
    as.Op(Opcode::kZKeepLE, kF2, 0, -1, {0, 0, 0, 0, 0, 3});  // F2: |x − 10| <= 3
    as.Op(Opcode::kFlagCopy, kF3, kF1);
    as.Op(Opcode::kZKeepGE, kF3, 0, -1, {0, 0, 0, 0, 0, 8});  // F3: |x − 10| >= 8
    as.Op(Opcode::kFlagOr, kF2, kF3);                         // F2: near the centre or the ends
    as.Op(Opcode::kFlagAndNot, kF1, kF2);                     // F1: the rest
    as.Op(Opcode::kZTest, kF1);
    as.Op(Opcode::kZWrite, kF1, 0, p);
    as.End();
    FlatScene scene = PlaneScene(20, 1);
    Frame f;
    Execute(as.program, scene, f);
    for (int i = 0; i < 20; ++i) {
        double d = std::fabs(i + 0.5 - 10);
        bool drawn = !(d <= 3 || d >= 8);
        EXPECT_EQ(f.surface[static_cast<std::size_t>(i)] != Frame::kNone, drawn) << i;
        if (drawn) {
            EXPECT_EQ(f.depth[static_cast<std::size_t>(i)], d);
        }
    }
}

// Instructions act only inside their block's rectangle, and tiles (64 × 64) do not change the
// result: a 150 × 70 disk program split across six tiles covers exactly the disk's pixels.
TEST(PixelPowersMachine, RectanglesAndTiles) {
    Assembler as;
    std::int32_t p = as.Patch(0);
    as.Begin({10, 5, 140, 66});
    as.Op(Opcode::kFlagSet, kF1);
    as.Op(Opcode::kQeeKeepNonPositive, kF1, 0, -1,
          {1, 0, 4, -150, -280, 75 * 75 + 4 * 35 * 35 - 3600});
    as.Op(Opcode::kZLoad, kF1, 0, -1, {0, 0, 0, 0, 0, 1});
    as.Op(Opcode::kZWrite, kF1, 0, p);
    as.End();
    FlatScene scene = PlaneScene(150, 70);
    Frame f;
    MachineCounters c = Execute(as.program, scene, f);
    EXPECT_EQ(c.tiles, 6u);
    for (int j = 0; j < 70; ++j) {
        for (int i = 0; i < 150; ++i) {
            double x = i + 0.5, y = j + 0.5;
            // (x − 75)² + 4 (y − 35)² <= 3600, clipped to the block rectangle.
            bool in = (x - 75) * (x - 75) + 4 * (y - 35) * (y - 35) <= 3600 && i >= 10 && i < 140 &&
                      j >= 5 && j < 66;
            ASSERT_EQ(f.surface[f.Index(i, j)] != Frame::kNone, in) << i << "," << j;
        }
    }
}

// Paper shading registers: NLOAD puts Q(x, y) into N0–N2 on enabled pixels only, and scan-out of
// a patch marked machineNormal turns them into a unit normal with the key light's term kept
// (ShadingUnitNormal). Key light k = (0, 0, −1): n·k = a·k, so n_z = a_z.
TEST(PixelPowersMachine, NormalRegistersAndScanOut) {
    Assembler as;
    as.program.patches.push_back({0, 0, 0, true});
    as.Begin({0, 0, 10, 1});
    as.Op(Opcode::kFlagSet, kF1);
    as.Op(Opcode::kQeeKeepNonPositive, kF1, 0, -1, {0, 0, 0, 1, 0, -5});  // x <= 5
    as.Op(Opcode::kZLoad, kF1, 0, -1, {0, 0, 0, 0, 0, 3});
    as.Op(Opcode::kNLoad, kF1, 0, -1, {0, 0, 0, 0.1, 0, 0});  // a_x = 0.1 x
    as.Op(Opcode::kNLoad, kF1, 1, -1, {0, 0, 0, 0, 0, 0});
    as.Op(Opcode::kNLoad, kF1, 2, -1, {0, 0, 0, 0.05, 0, -0.9});  // a_z = 0.05 x − 0.9
    as.Op(Opcode::kZTest, kF1);
    as.Op(Opcode::kZWrite, kF1, 0, 0);
    as.End();
    FlatScene scene = PlaneScene(10, 1);
    scene::Light l;
    l.kind = scene::Light::Kind::kParallel;
    l.intensity = 1;
    l.direction = {0, 0, -2};
    scene.lights = {l};
    Frame f;
    MachineCounters c = Execute(as.program, scene, f);
    EXPECT_EQ(as.program.Equations(), 5u);  // QNPOS, ZLOAD and three NLOADs
    for (int i = 0; i < 10; ++i) {
        double x = i + 0.5;
        const Vec3 n = f.Normal(static_cast<std::size_t>(i));
        if (x > 5) {
            EXPECT_EQ(f.surface[static_cast<std::size_t>(i)], Frame::kNone);
            continue;
        }
        EXPECT_NEAR(Length(n), 1, 1e-12);
        // The key light's term, as computed, then packed in the Frame (frame/packed_normal.h).
        EXPECT_NEAR(n.z, 0.05 * x - 0.9, PackedNormal::kMaxError) << i;
        EXPECT_NEAR(n.y, 0, PackedNormal::kMaxError);
        EXPECT_GT(n.x, 0);  // the rest of a's direction
    }
    EXPECT_GT(c.pixelOps, 0u);
}

// The sides of INSIDE (isa.h InsideMode) and the strict ZGT/ZLT, on ZTEMP = z = i − 10 at pixel i
// of a row: against the plane literal z <= 0 (set (−∞, 0]), its complement ([0, ∞)) and the
// quadric literal z² − 25 <= 0 (set [−5, 5]), every endpoint landing exactly on a pixel.
TEST(PixelPowersMachine, InsideModesAndStrictDepthTests) {
    FlatHalfSpace plane;
    plane.isPlane = true;
    plane.plane = {0, 0, 1, 0};
    FlatHalfSpace slab;
    slab.isPlane = false;
    slab.quadric = Quadric::FromCoefficients({0, 0, 1, 0, 0, 0, 0, 0, 0, -25});
    // Runs ZLOAD z = x − 10.5, then `op`, and returns which of the 20 pixels were written.
    auto run = [](const Program& base, Opcode op, std::uint8_t b, std::int32_t arg) {
        Assembler as;
        as.program.literals = base.literals;
        std::int32_t p = as.Patch(0);
        as.Begin({0, 0, 20, 1});
        as.Op(Opcode::kFlagSet, kF1);
        as.Op(Opcode::kZLoad, kF1, 0, -1, {0, 0, 0, 1, 0, -10.5});
        as.Op(op, kF1, b, arg);
        as.Op(Opcode::kZTest, kF1);
        as.Op(Opcode::kZWrite, kF1, 0, p);
        as.End();
        FlatScene scene = PlaneScene(20, 1);
        Frame f;
        Execute(as.program, scene, f);
        std::vector<int> drawn;
        for (int i = 0; i < 20; ++i)
            if (f.surface[static_cast<std::size_t>(i)] != Frame::kNone) drawn.push_back(i);
        return drawn;
    };
    auto range = [](int lo, int hi) {
        std::vector<int> v;
        for (int i = lo; i <= hi; ++i) v.push_back(i);
        return v;
    };
    Program lits;
    lits.literals.push_back({eval::RayHalfSpace::From(plane), false, true});
    lits.literals.push_back({eval::RayHalfSpace::From(plane), true, true});
    lits.literals.push_back({eval::RayHalfSpace::From(slab), false, false});
    // z <= 0: the endpoint 0 (pixel 10) belongs to the closed set and to the side before it.
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideClosed, 0), range(0, 10));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideOpen, 0), range(0, 9));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideAfter, 0), range(0, 9));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideBefore, 0), range(0, 10));
    // z >= 0 (the closure of the complement): the endpoint holds after, not before.
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideClosed, 1), range(10, 19));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideOpen, 1), range(11, 19));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideAfter, 1), range(10, 19));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideBefore, 1), range(11, 19));
    // [−5, 5]: pixels 5 and 15 are its endpoints.
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideClosed, 2), range(5, 15));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideOpen, 2), range(6, 14));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideAfter, 2), range(5, 14));
    EXPECT_EQ(run(lits, Opcode::kInside, kInsideBefore, 2), range(6, 15));
    // ZGT / ZLT against the constant 0 (q = 0): strict, unlike ZGE / ZLE.
    EXPECT_EQ(run(lits, Opcode::kZKeepGT, 0, -1), range(11, 19));
    EXPECT_EQ(run(lits, Opcode::kZKeepLT, 0, -1), range(0, 9));
    EXPECT_EQ(run(lits, Opcode::kZKeepGE, 0, -1), range(10, 19));
    EXPECT_EQ(run(lits, Opcode::kZKeepLE, 0, -1), range(0, 10));
}

// ZTEST's tie threshold: three patches at one depth on pixels 0..9. Patch 1's ZTEST (from 0)
// wins the tie against patch 0; patch 2's (from 2) loses it to patch 1, and so does a strict one.
TEST(PixelPowersMachine, ZTestTieThreshold) {
    Assembler as;
    auto block = [&](std::int32_t from) {
        std::int32_t p = as.Patch(0);
        as.Begin({0, 0, 10, 1});
        as.Op(Opcode::kFlagSet, kF1);
        as.Op(Opcode::kZLoad, kF1, 0, -1, {0, 0, 0, 0, 0, 4});
        as.Op(Opcode::kZTest, kF1, 0, from);
        as.Op(Opcode::kZWrite, kF1, 0, p);
        as.End();
    };
    FlatScene scene = PlaneScene(10, 1);
    scene.halfSpaces.push_back(scene.halfSpaces[0]);  // a second plane names patch 1
    block(-1);
    block(0);
    block(2);
    block(-1);
    as.program.patches[1].halfSpace = 1;
    Frame f;
    Execute(as.program, scene, f);
    for (int i = 0; i < 10; ++i) {
        EXPECT_EQ(f.surface[static_cast<std::size_t>(i)], 1) << i;
        EXPECT_EQ(f.depth[static_cast<std::size_t>(i)], 4);
    }
}

}  // namespace
}  // namespace quadrix::pixelpowers
