#include "quadrix/engines/patch/integer_reference.h"

#include <cmath>

namespace quadrix::patch {
namespace {

__extension__ typedef __int128 Wide;
__extension__ typedef unsigned __int128 UWide;

// v mod 2^bits as a two's-complement value.
std::int64_t WrapWide(Wide v, int bits) {
    const UWide u = static_cast<UWide>(v);
    return Wrap(static_cast<std::int64_t>(static_cast<std::uint64_t>(u)), bits);
}

std::int64_t Linear(const Ep1Program& p, int i, int j, int bits) {
    return WrapWide(Wide{p.start} + Wide{i} * p.stepX + Wide{j} * p.stepY, bits);
}

std::int64_t Quadratic(const Ep2Program& p, int i, int j, int bits) {
    const Wide ii = i, jj = j;
    return WrapWide(Wide{p.q0} + jj * p.r0 + Wide{p.twoB} * (jj * (jj + 1) / 2) +
                        ii * (Wide{p.s0} + jj * p.c) + Wide{p.twoA} * (ii * (ii + 1) / 2),
                    bits);
}

// Signed difference of two d-bit words as the d-bit adder forms it.
std::int64_t Diff(std::int64_t a, std::int64_t b, int bits) { return WrapWide(Wide{a} - b, bits); }

}  // namespace

std::uint64_t IntegerSqrt(std::uint64_t v) {
    std::uint64_t r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(v)));
    // The double estimate is within a few units; correct it exactly.
    while (r > 0 && static_cast<UWide>(r) * r > v) --r;
    while (static_cast<UWide>(r + 1) * (r + 1) <= v) ++r;
    return r;
}

PixelSignals ReferencePixel(const FixedPatch& patch, const DatapathWidths& widths, int i, int j) {
    const int d = widths.depthBits, n = widths.normalBits, s = widths.NormalGuardBits();
    const int w2 = widths.Ep2Bits();
    PixelSignals px;
    px.f2 = Quadratic(patch.f2, i, j, w2);
    px.sgnF2 = px.f2 < 0;
    const std::uint64_t radicand =
        static_cast<std::uint64_t>(px.f2) & ((std::uint64_t{1} << w2) - 1);
    px.root = static_cast<std::int64_t>(IntegerSqrt(radicand));
    px.f1 = Linear(patch.f1, i, j, d);
    px.zf = Diff(px.f1, px.root, d);
    px.zb = WrapWide(Wide{px.f1} + px.root, d);

    // §1.3.2 written as published, with "x > 0" read as the sign bit of x being 0 (x >= 0).
    bool ef = true, eb = true;
    for (int k = 0; k < kMaxPlanes; ++k) {
        const PlaneUnitProgram& unit = patch.planes[static_cast<std::size_t>(k)];
        const std::int64_t zp = Linear(unit.zp, i, j, d);
        px.zp[static_cast<std::size_t>(k)] = zp;
        const std::int64_t dF = Diff(zp, px.zf, d), dB = Diff(zp, px.zb, d);
        if (unit.perpendicular) {
            if (zp < 0) ef = eb = false;
        } else if (unit.sgnCp) {  // front plane
            if (dB >= 0)
                ef = eb = false;
            else if (dF >= 0)
                ef = false;
        } else {  // back plane
            if (dF < 0)
                ef = eb = false;
            else if (dB < 0)
                eb = false;
        }
    }
    px.ef = ef;
    px.eb = eb;
    px.zPrime = ef ? px.zf : px.zb;
    px.zout = (!ef && !eb) || px.sgnF2 ? MaxWord(d) : px.zPrime;

    // Normals: floor(a·b / 2^n) as a plain product, then the sum and the back-sheet negation.
    const std::int64_t zHigh = Wrap(px.zPrime >> s, n);
    auto mul = [&](std::int64_t coef) {
        const Wide product = Wide{zHigh} * Wrap(coef, n);
        return WrapWide(product >> n, n);  // arithmetic shift: floor
    };
    auto base = [&](const Ep1Program& p) { return Linear(p, i, j, d) >> s; };
    px.nx = WrapWide(Wide{base(patch.nxBase)} + mul(patch.e), n);
    px.ny = WrapWide(Wide{base(patch.nyBase)} + mul(patch.f), n);
    px.nz = WrapWide(Wide{base(patch.nzBase)} + mul(patch.twoC), n);
    if (!ef && eb) {
        px.nx = WrapWide(-Wide{px.nx}, n);
        px.ny = WrapWide(-Wide{px.ny}, n);
        px.nz = WrapWide(-Wide{px.nz}, n);
    }
    return px;
}

}  // namespace quadrix::patch
