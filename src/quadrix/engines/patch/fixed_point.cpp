#include "quadrix/engines/patch/fixed_point.h"

namespace quadrix::patch {

std::string DatapathWidths::Validate() const {
    if (depthBits < kMinDepthBits || depthBits > kMaxDepthBits)
        return "depth-bits must be in [" + std::to_string(kMinDepthBits) + ", " +
               std::to_string(kMaxDepthBits) + "], not " + std::to_string(depthBits);
    if (normalBits < kMinNormalBits || normalBits > depthBits)
        return "normal-bits must be in [" + std::to_string(kMinNormalBits) +
               ", depth-bits = " + std::to_string(depthBits) + "], not " +
               std::to_string(normalBits);
    return {};
}

std::int64_t Wrap(std::int64_t v, int bits) {
    if (bits >= 64) return v;
    const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
    std::uint64_t u = static_cast<std::uint64_t>(v) & mask;
    if ((u >> (bits - 1)) & 1) u |= ~mask;  // sign extension
    return static_cast<std::int64_t>(u);    // modular conversion (C++20)
}

std::int64_t AddWrapped(std::int64_t a, std::int64_t b, int bits) {
    return Wrap(
        static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b)),
        bits);
}

std::int64_t MaxWord(int bits) { return (std::int64_t{1} << (bits - 1)) - 1; }
std::int64_t MinWord(int bits) { return -(std::int64_t{1} << (bits - 1)); }

// ---------------------------------------------------------------------------------------------
// EP1

void Ep1::Load(const Ep1Program& program, int bits) {
    program_ = program;
    bits_ = bits;
    line_ = Wrap(program.start, bits);
    pixel_ = line_;
}

void Ep1::StepLine() {
    line_ = AddWrapped(line_, program_.stepY, bits_);
    pixel_ = line_;
}

// ---------------------------------------------------------------------------------------------
// EP2

std::int64_t Ep2::PipelinedAdd(std::int64_t a, std::int64_t b, int wordBits) {
    const int half = wordBits / 2;
    const std::uint64_t mask = (std::uint64_t{1} << half) - 1;
    const std::uint64_t ua = static_cast<std::uint64_t>(a), ub = static_cast<std::uint64_t>(b);
    // Cycle 1: the low halves; their carry out is latched.
    const std::uint64_t lowSum = (ua & mask) + (ub & mask);
    const std::uint64_t carry = lowSum >> half;
    // Cycle 2: the high halves plus the latched carry; the carry out of the top is dropped.
    const std::uint64_t highSum = ((ua >> half) & mask) + ((ub >> half) & mask) + carry;
    const std::uint64_t word = ((highSum & mask) << half) | (lowSum & mask);
    return Wrap(static_cast<std::int64_t>(word), wordBits);
}

void Ep2::Load(const Ep2Program& program, int wordBits) {
    bits_ = wordBits;
    program_ = {Wrap(program.q0, wordBits),   Wrap(program.r0, wordBits),
                Wrap(program.s0, wordBits),   Wrap(program.twoA, wordBits),
                Wrap(program.twoB, wordBits), Wrap(program.c, wordBits)};
    q_ = program_.q0;
    r_ = program_.r0;
    sLine_ = program_.s0;
    v_ = q_;
    s_ = sLine_;
}

void Ep2::StepPixel() {
    // Cell 1 forms the next increment, cell 2 adds it (Q(y+1) = Q(y) + R(y+1), §1.5.1).
    s_ = PipelinedAdd(s_, program_.twoA, bits_);
    v_ = PipelinedAdd(v_, s_, bits_);
}

void Ep2::StepLine() {
    r_ = PipelinedAdd(r_, program_.twoB, bits_);
    q_ = PipelinedAdd(q_, r_, bits_);
    sLine_ = PipelinedAdd(sLine_, program_.c, bits_);
    v_ = q_;
    s_ = sLine_;
}

// ---------------------------------------------------------------------------------------------
// Square-root extractor

SquareRootResult CellularSquareRoot(std::uint64_t radicand, int rootBits) {
    const int n = rootBits;
    std::uint64_t remainder = 0;  // output of the previous line (< 2^(k+1) after line k)
    std::uint64_t root = 0;
    for (int k = 1; k <= n; ++k) {
        // Inputs of line k: the previous remainder shifted in front of the next two radicand
        // bits, and the trial divisor 4·root + 1.
        const std::uint64_t pair = (radicand >> (2 * (n - k))) & 3;
        const std::uint64_t t = (remainder << 2) | pair;
        const std::uint64_t d = (root << 2) | 1;
        const int cells = 2 * k;
        std::uint64_t diff = 0;
        unsigned borrow = 0;
        for (int c = 0; c < cells; ++c) {  // the borrow ripples from the least significant cell
            const unsigned a = static_cast<unsigned>((t >> c) & 1);
            const unsigned b = static_cast<unsigned>((d >> c) & 1);
            const unsigned dbit = a ^ b ^ borrow;
            borrow = ((~a & b) | (~(a ^ b) & borrow)) & 1;
            diff |= static_cast<std::uint64_t>(dbit) << c;
        }
        const unsigned bit = borrow ^ 1;  // no borrow out of the line: T >= D
        // Each cell selects the difference or its previous rest.
        std::uint64_t next = 0;
        for (int c = 0; c < cells; ++c) {
            const std::uint64_t keep = bit ? (diff >> c) & 1 : (t >> c) & 1;
            next |= keep << c;
        }
        remainder = next;
        root = (root << 1) | bit;
    }
    return {root, remainder};
}

// ---------------------------------------------------------------------------------------------
// Multiplier

std::int64_t TruncatingMultiply(std::int64_t a, std::int64_t b, int bits) {
    const int n = bits;
    const int accBits = n + 1;  // holds P + a for every row (see fixed_point.h)
    const std::uint64_t ua = static_cast<std::uint64_t>(Wrap(a, n));  // sign-extended
    const std::uint64_t ub = static_cast<std::uint64_t>(Wrap(b, n));
    std::uint64_t acc = 0;  // accBits-wide two's complement, as bits
    for (int row = 0; row < n; ++row) {
        const bool bk = (ub >> row) & 1;
        const bool signRow = row == n - 1;
        // Partial product: a, or -a = ~a + 1 for the sign bit of b, or 0.
        std::uint64_t addend = 0;
        unsigned carry = 0;
        if (bk) {
            addend = signRow ? ~ua : ua;
            carry = signRow ? 1 : 0;
        }
        std::uint64_t sum = 0;
        for (int c = 0; c < accBits; ++c) {  // one full-adder cell per bit
            const unsigned x = static_cast<unsigned>((acc >> c) & 1);
            const unsigned y = static_cast<unsigned>((addend >> c) & 1);
            sum |= static_cast<std::uint64_t>(x ^ y ^ carry) << c;
            carry = (x & y) | (x & carry) | (y & carry);
        }
        // Shift right by one, dropping the low bit and repeating the sign bit.
        const std::uint64_t sign = (sum >> (accBits - 1)) & 1;
        acc = (sum >> 1) | (sign << (accBits - 1));
    }
    return Wrap(static_cast<std::int64_t>(acc), n);
}

}  // namespace quadrix::patch
