// The instruction set of the simulated Pixel-Powers logic-enhanced frame buffer (seed 004 §II–III,
// seed 003 §3; documented in docs/pixelpowers.md).
//
// Every pixel (x, y) = (i+½, j+½) in device space holds
//   ZTEMP, ZMIN  depth registers (device z, smaller = nearer; ZMIN starts at +inf),
//   F1, F2, F3   one-bit flags,
//   COLOR        the id of the patch last written (the host's patch table turns it into surface,
//                body, solid, and the normal at ZMIN at scan-out: deferred shading),
//   N0 N1 N2     with paper shading (kNLoad): the world-space approximate normal vector of the
//                patch last written, evaluated by the QEE (docs/pixelpowers.md "Shading").
// The host broadcasts instructions; a quadratic-expression evaluator (QEE) gives every pixel
//   Q(x, y) = A x² + B xy + C y² + D x + E y + F
// from the six broadcast coefficients (seed 004 §I). Instructions act only on the pixels of their
// screen rectangle ("an equation is evaluated only where it can matter", issue 4 item 5) and, for
// the per-pixel ones, only where their enable flag is set (the paper's ENABLE register).
//
// Two machines share the set:
//   - the paper's machine uses only QEE instructions (z of a quadric replaced by the envelope of
//     parabolic strips, seed 004 §III step 2);
//   - the "extended" machine of issue 4 item 4 adds kRoot and kInside: the pixel solves the
//     literal's quadratic along its ray (one square root), which makes depths exact and equal to
//     the raycast engine's bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "quadrix/eval/ray_literal.h"

namespace quadrix::pixelpowers {

enum class Opcode : std::uint8_t {
    kFlagSet,          // F[a] ← 1
    kFlagClear,        // F[a] ← 0
    kFlagCopy,         // F[a] ← F[b]
    kFlagAnd,          // F[a] ← F[a] ∧ F[b]
    kFlagAndNot,       // F[a] ← F[a] ∧ ¬F[b]
    kFlagOr,           // F[a] ← F[a] ∨ F[b]
    kQeeKeepPositive,  // QEE: F[a] ← F[a] ∧ (Q(x,y) > 0)        (seed 003 §3 "scan conversion")
    kQeeKeepNonPositive,  // QEE: F[a] ← F[a] ∧ (Q(x,y) <= 0)
    kZLoad,    // QEE: where F[a]: ZTEMP ← Q(x,y)           (seed 003 §3 "depth", case 1)
    kZMax,     // QEE: where F[a]: ZTEMP ← max(ZTEMP, Q)    (envelope of a front sheet)
    kZMin,     // QEE: where F[a]: ZTEMP ← min(ZTEMP, Q)    (envelope of a back sheet)
    kZKeepGE,  // QEE: where F[a]: F[a] ← (ZTEMP >= Q)      (seed 004 §III step 3 b)
    kZKeepLE,  // QEE: where F[a]: F[a] ← (ZTEMP <= Q)
    kZKeepGT,  // QEE: where F[a]: F[a] ← (ZTEMP > Q)   (one-sided inside tests, InsideMode)
    kZKeepLT,  // QEE: where F[a]: F[a] ← (ZTEMP < Q)
    kRoot,     // extended, every pixel of the rectangle: ZTEMP ← entry (b = 0) or exit
               // (b = 1) point of literal `arg` on the pixel's ray, F[a] ← it exists
    kInside,   // extended: where F[a]: F[a] ← ZTEMP inside literal `arg`, in the sense
               // b = InsideMode (closed set, interior, or one side of ZTEMP)
    kZTest,    // where F[a]: F[a] ← (ZTEMP < ZMIN), or with arg >= 0 also ZTEMP == ZMIN where
               // COLOR >= arg (a tie won against the patches from arg on); arg < 0: strict, ties
               // keep the earlier patch
    kZWrite,   // where F[a]: ZMIN ← ZTEMP, COLOR ← arg (a patch id)
    kNLoad,    // QEE: where F[a]: N[b] ← Q(x,y), b = world axis 0..2 — the paper's approximate
               // shading (seed 004 §III step 4): the numerator "L + sqrt Q" of the diffuse shade
               // with sqrt Q → s + tQ (one parabolic cylinder) over a constant denominator, kept
               // per world axis so that n·l is the paper's shade for every parallel light l
};

// kInside's b: which membership of ZTEMP in the literal's ray set S (a regular closed set, pieces
// [lo, hi]) is tested. The one-sided tests make coincident surfaces exact (docs/pixelpowers.md
// "Coincident surfaces"): a point at depth z is an entry of a regularised set iff the set holds on
// (z, z + ε) and not on (z − ε, z), for some ε > 0, and the sides of an intersection or a
// difference are those of its operands.
enum InsideMode : std::uint8_t {
    kInsideClosed = 0,  // z ∈ S:                 some lo <= z <= hi
    kInsideOpen = 1,    // z in S's interior:     some lo <  z <  hi
    kInsideAfter = 2,   // S holds on (z, z + ε): some lo <= z <  hi
    kInsideBefore = 3,  // S holds on (z − ε, z): some lo <  z <= hi
};

const char* OpcodeName(Opcode op);

// Pixel rectangle [x0, x1) × [y0, y1) (columns, rows).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool Empty() const { return x0 >= x1 || y0 >= y1; }
    PixelRect Intersected(const PixelRect& o) const;
};

struct Instruction {
    Opcode op = Opcode::kFlagSet;
    std::uint8_t a = 0, b = 0;         // flag numbers 0..2 (F1..F3); kRoot: b = 0 entry, 1 exit
    std::int32_t arg = -1;             // literal (kRoot, kInside) or patch id (kZWrite)
    double q[6] = {0, 0, 0, 0, 0, 0};  // QEE coefficients A B C D E F

    // Quadratic expressions broadcast by this instruction (Table 1 "Equations"): one per QEE
    // instruction; the extended root unit needs the linear L and the quadratic discriminant (2),
    // or one linear expression for a plane.
    int Equations(bool literalIsPlane) const;
};

// A patch program: the instructions that draw one patch (one literal's entry or exit sheet of one
// primitive, pared by the others of its product) over one screen rectangle.
struct Block {
    PixelRect rect;
    std::int32_t first = 0, count = 0;  // into Program::code
};

// A literal as the extended machine's root unit sees it.
struct MachineLiteral {
    eval::RayHalfSpace ray;
    bool complemented = false;
    bool isPlane = true;
};

// What a patch id written to COLOR means.
struct PatchInfo {
    std::int32_t halfSpace = -1, body = -1, solid = -1;
    // True when the block loaded N0–N2 (paper shading): scan-out takes the normal from them
    // instead of computing the exact one at ZMIN.
    bool machineNormal = false;
};

struct Program {
    std::vector<Instruction> code;
    std::vector<Block> blocks;
    std::vector<MachineLiteral> literals;
    std::vector<PatchInfo> patches;
    // Fixed-point depth words (option depth-bits): when depthStep > 0 every value the machine
    // stores in ZTEMP (and every QEE value compared with it) is rounded to depthOrigin + k·step,
    // k in [0, 2^bits − 1], as a register of `bits` bits would hold it (seed 004 §III: 20–30 bit
    // ZTEMP/ZMIN words).
    double depthOrigin = 0, depthStep = 0;
    int depthBits = 0;

    // Static counts (Table 1).
    std::uint64_t Opcodes() const { return code.size(); }
    std::uint64_t Equations() const;
    // "kRoot 3 entry" style listing, for tests and --engine-opt dump.
    std::string Disassemble(std::size_t maxInstructions = 200) const;
};

}  // namespace quadrix::pixelpowers
