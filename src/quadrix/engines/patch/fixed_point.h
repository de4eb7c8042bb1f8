// The arithmetic units of the quadric patch processor (seed 000 §1.5), emulated bit for bit.
//
// Words are two's-complement integers of a given width held in std::int64_t; every adder wraps
// modulo 2^width exactly as a hardware adder that drops its carry out. Widths are parameters
// (DatapathWidths); the paper's are 24-bit depths, 48-bit F2, a 24-bit square root and 16-bit
// normals.
//
//  - EP1 (§1.5.1, Fig. 1.5): forward differencing of a linear expression L(i, j) = L0 + A i + B j
//    over the pixels (i, j) of a window. The RAM holds three words (A, B and the value at the start
//    of the current line); per pixel the register adds A, per line the RAM word adds B.
//  - EP2 (§1.5.1, Fig. 1.6): forward differencing of a quadratic. With F(i, j) the value at pixel
//    i of line j, the paper's recurrences Q(y+1) = Q(y) + R(y+1), R(y+1) = R(y) + 2B are used in
//    both directions: per line R += 2B, Q += R, S_line += C; per pixel S += 2A, V += S. Its six
//    RAM words are Q, R, S_line, 2A, 2B, C (hence "six word RAMs"); the two calculation cells are
//    the adders of S and V. Each 2w-bit addition is done by two pipelined w-bit adders: the low
//    halves first, their carry into the high halves on the next cycle (§1.5.1, "we cannot
//    compute a 48-bit addition in one cycle").
//  - SRE (§1.5.2, Fig. 1.7): the restoring cellular array of Majithia. Line k (1-based) of n has
//    2k cells; it subtracts the trial divisor 4·Q + 1 (Q = root bits found so far) from the
//    partial remainder aligned with the 2k top bits of the radicand, and each cell selects the
//    difference or the previous remainder by the line's final borrow: root bit k = no borrow.
//    The result is floor(sqrt(N)) for an unsigned 2n-bit N.
//  - Multiplier (§1.5.3, Table 1.5): an n × n array keeping only the n most significant bits of
//    the 2n-bit product. Row k adds the partial product (b_k · a; for the sign bit of b it
//    subtracts a, two's complement) to an (n+1)-bit accumulator and shifts it right by one,
//    dropping the bit that falls out. Nested floors compose (floor((floor(x/2) + y)/2) =
//    floor((x + 2y)/4) for integers), so the result is exactly floor(a·b / 2^n).
#pragma once

#include <cstdint>
#include <string>

namespace quadrix::patch {

// Word widths of the datapath. The EP2 and the square-root extractor's input are 2·depthBits
// wide and its result depthBits (F2 is in squared depth units, so sqrt(F2) is a depth); the
// multipliers are normalBits × normalBits and take the normalBits most significant bits of Z'.
struct DatapathWidths {
    int depthBits = 24;
    int normalBits = 16;

    static constexpr int kMinDepthBits = 12;
    static constexpr int kMaxDepthBits = 30;  // the EP2 words (2·depthBits) stay within 60 bits
    static constexpr int kMinNormalBits = 8;

    int Ep2Bits() const { return 2 * depthBits; }
    int RootBits() const { return depthBits; }
    int MultiplierBits() const { return normalBits; }
    // Guard bits of the normal EP1s: NXBASE is held with depthBits - normalBits fraction bits.
    int NormalGuardBits() const { return depthBits - normalBits; }
    // Empty when usable, else why not.
    std::string Validate() const;
    bool operator==(const DatapathWidths&) const = default;
};

// The low `bits` bits of v as a two's-complement number (the value a `bits`-wide register holds).
std::int64_t Wrap(std::int64_t v, int bits);
// A `bits`-wide adder: (a + b) mod 2^bits, two's complement.
std::int64_t AddWrapped(std::int64_t a, std::int64_t b, int bits);
// Largest and smallest values of a `bits`-wide word.
std::int64_t MaxWord(int bits);
std::int64_t MinWord(int bits);

// RAM contents of an EP1: the value at the window's first pixel and the steps per pixel (x) and
// per line (y). Words are depthBits wide.
struct Ep1Program {
    std::int64_t start = 0, stepX = 0, stepY = 0;
    bool operator==(const Ep1Program&) const = default;
};

class Ep1 {
  public:
    void Load(const Ep1Program& program, int bits);
    std::int64_t Value() const { return pixel_; }
    void StepPixel() { pixel_ = AddWrapped(pixel_, program_.stepX, bits_); }
    // Next line: the RAM's line word adds stepY and is copied into the pixel register.
    void StepLine();

  private:
    Ep1Program program_;
    int bits_ = 24;
    std::int64_t line_ = 0, pixel_ = 0;
};

// RAM contents of an EP2 (six words, 2·depthBits wide) for F(i, j) = value at pixel i of line j:
//   q0 = F(0, 0),  r0 = F(0, 0) - F(0, -1),  s0 = F(0, 0) - F(-1, 0),
//   twoA = F(i+1, j) - 2 F(i, j) + F(i-1, j),  twoB = the same along j,  c = the mixed difference
//   F(i+1, j+1) - F(i+1, j) - F(i, j+1) + F(i, j).
// Then F(i, j) = q0 + j r0 + twoB j(j+1)/2 + i (s0 + j c) + twoA i(i+1)/2 (the reference's form).
struct Ep2Program {
    std::int64_t q0 = 0, r0 = 0, s0 = 0, twoA = 0, twoB = 0, c = 0;
    bool operator==(const Ep2Program&) const = default;
};

class Ep2 {
  public:
    void Load(const Ep2Program& program, int wordBits);
    std::int64_t Value() const { return v_; }
    void StepPixel();
    void StepLine();
    // The 2w-bit addition as two pipelined w-bit adders (low half, then high half plus carry).
    static std::int64_t PipelinedAdd(std::int64_t a, std::int64_t b, int wordBits);

  private:
    Ep2Program program_;
    int bits_ = 48;
    // Line state (RAM words) and pixel state (the two calculation cells).
    std::int64_t q_ = 0, r_ = 0, sLine_ = 0;
    std::int64_t v_ = 0, s_ = 0;
};

struct SquareRootResult {
    std::uint64_t root = 0;       // rootBits wide
    std::uint64_t remainder = 0;  // radicand - root², at most 2·root
};

// The cellular array of Fig. 1.7, cell by cell: floor(sqrt(radicand)) for the unsigned
// 2·rootBits-bit radicand (higher bits are ignored). Cost: rootBits·(rootBits + 1) cells.
SquareRootResult CellularSquareRoot(std::uint64_t radicand, int rootBits);

// The array multiplier of §1.5.3, cell by cell: floor(a·b / 2^bits) for bits-wide signed a, b
// (inputs are wrapped to `bits` first). The result always fits in `bits` bits.
std::int64_t TruncatingMultiply(std::int64_t a, std::int64_t b, int bits);

}  // namespace quadrix::patch
