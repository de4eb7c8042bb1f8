#include "quadrix/engines/patch/patch_processor.h"

#include "quadrix/engines/patch/bounding_plane.h"

namespace quadrix::patch {

std::int64_t Zmax(const DatapathWidths& widths) { return MaxWord(widths.depthBits); }

void PatchProcessor::Load(const FixedPatch& patch) {
    patch_ = patch;
    const int d = widths_.depthBits;
    f2_.Load(patch.f2, widths_.Ep2Bits());
    f1_.Load(patch.f1, d);
    for (int k = 0; k < kMaxPlanes; ++k)
        zp_[static_cast<std::size_t>(k)].Load(patch.planes[static_cast<std::size_t>(k)].zp, d);
    nx_.Load(patch.nxBase, d);
    ny_.Load(patch.nyBase, d);
    nz_.Load(patch.nzBase, d);
    line_ = 0;
}

void PatchProcessor::StepLine() {
    f2_.StepLine();
    f1_.StepLine();
    for (Ep1& u : zp_) u.StepLine();
    nx_.StepLine();
    ny_.StepLine();
    nz_.StepLine();
    ++line_;
}

void PatchProcessor::SkipLines(int lines) {
    for (int k = 0; k < lines; ++k) StepLine();
}

void PatchProcessor::ScanLine(std::vector<PixelSignals>& out) {
    const int d = widths_.depthBits, n = widths_.normalBits, s = widths_.NormalGuardBits();
    const int width = patch_.window.Width();
    out.resize(static_cast<std::size_t>(width));
    for (int i = 0; i < width; ++i) {
        PixelSignals& px = out[static_cast<std::size_t>(i)];
        // Depths: EP2 → SRE; EP1 → F1; the two adder-registers.
        px.f2 = f2_.Value();
        px.sgnF2 = px.f2 < 0;
        const std::uint64_t radicand =
            static_cast<std::uint64_t>(px.f2) &
            ((std::uint64_t{1} << widths_.Ep2Bits()) - 1);  // the word's bits, unsigned
        px.root = static_cast<std::int64_t>(CellularSquareRoot(radicand, widths_.RootBits()).root);
        px.f1 = f1_.Value();
        px.zf = AddWrapped(px.f1, -px.root, d);
        px.zb = AddWrapped(px.f1, px.root, d);

        // Bounding planes: the 2 × 4 difference adders and the cutting-plane logics (Fig. 1.8).
        DepthFlags flags;
        for (int k = 0; k < kMaxPlanes; ++k) {
            const PlaneUnitProgram& unit = patch_.planes[static_cast<std::size_t>(k)];
            const std::int64_t zp = zp_[static_cast<std::size_t>(k)].Value();
            px.zp[static_cast<std::size_t>(k)] = zp;
            PlaneSignals sig;
            sig.perpendicular = unit.perpendicular;
            sig.sgnCp = unit.sgnCp;
            sig.sgnZp = zp < 0;
            sig.sgnZpMinusZf = AddWrapped(zp, -px.zf, d) < 0;
            sig.sgnZpMinusZb = AddWrapped(zp, -px.zb, d) < 0;
            const CutSignals cut = CuttingPlaneLogic(sig);
            flags.ef = flags.ef && !cut.cutF;  // the 4-input ANDs
            flags.eb = flags.eb && !cut.cutB;
        }
        px.ef = flags.ef;
        px.eb = flags.eb;
        px.zPrime = flags.ef ? px.zf : px.zb;
        px.zout = ZoutIsZmax(flags, px.sgnF2) ? Zmax(widths_) : px.zPrime;

        // Normals: the n most significant bits of Z' into the three multipliers.
        const std::int64_t zHigh = px.zPrime >> s;  // arithmetic shift (C++20)
        const std::int64_t mx = TruncatingMultiply(zHigh, patch_.e, n);
        const std::int64_t my = TruncatingMultiply(zHigh, patch_.f, n);
        const std::int64_t mz = TruncatingMultiply(zHigh, patch_.twoC, n);
        px.nx = AddWrapped(nx_.Value() >> s, mx, n);
        px.ny = AddWrapped(ny_.Value() >> s, my, n);
        px.nz = AddWrapped(nz_.Value() >> s, mz, n);
        if (!flags.ef && flags.eb) {  // back sheet: negate (§1.4.3)
            px.nx = Wrap(-px.nx, n);
            px.ny = Wrap(-px.ny, n);
            px.nz = Wrap(-px.nz, n);
        }

        f2_.StepPixel();
        f1_.StepPixel();
        for (Ep1& u : zp_) u.StepPixel();
        nx_.StepPixel();
        ny_.StepPixel();
        nz_.StepPixel();
    }
    StepLine();
}

}  // namespace quadrix::patch
