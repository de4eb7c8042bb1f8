// The bounding-plane algorithm of seed 000 §1.3.2 (and its logic form, §1.5.5 / Fig. 1.8).
//
// At a pixel the quadric has the depths ZF <= ZB. Flags EF and EB say whether each is still
// "able". Every plane i has a depth ZPi on the pixel's ray and the z component CPi of its
// outward normal (Quadrix planes keep A x + B y + C z + D <= 0, so CP = C):
//   CP < 0  front plane: keeps z >= ZP     ZP > ZB → EF = EB = 0;   else ZP > ZF → EF = 0
//   CP > 0  back plane:  keeps z <= ZP     ZP < ZF → EF = EB = 0;   else ZP < ZB → EB = 0
//   CP = 0  perpendicular plane: ZP holds -(A x + B y + D), the kept side being ZP >= 0;
//                                ZP < 0 → EF = EB = 0
// Then Z' = ZF if EF else ZB, and ZOUT = ZMAX (nothing) if neither is able or F2 < 0
// (no root), else Z'. The back sheet is shown when EF = 0 and EB = 1 (§1.4.3: its normal is
// negated).
//
// The published logic equations of §1.5.5 list "sgn(CP) = 0 and sgn(ZP - ZB) = 1" twice (for both
// flags and for ZB only); the both-flags case of a back plane must read sgn(ZP - ZF) = 1, or a
// back plane in front of the whole patch would never disable EF. CuttingPlaneLogic uses the
// corrected equation; a test checks it against the algorithm on every sign combination.
//
// Ties. §1.3.2 compares strictly (a root lying on the plane is kept: the half-spaces are
// closed). The hardware only has sign bits, sgn(x) = 1 iff x < 0, so a zero difference counts as
// positive: a front plane through ZF disables it. The float engine follows §1.3.2; the fixed-point
// emulator and its integer reference follow the sign bits.
#pragma once

#include <cstdint>

namespace quadrix::patch {

enum class PlaneKind : std::uint8_t {
    kFront,          // CP < 0
    kBack,           // CP > 0
    kPerpendicular,  // CP = 0
};

inline PlaneKind KindOfPlane(double cp) {
    return cp < 0 ? PlaneKind::kFront : (cp > 0 ? PlaneKind::kBack : PlaneKind::kPerpendicular);
}

struct DepthFlags {
    bool ef = true;  // ZF able
    bool eb = true;  // ZB able
};

// One step of §1.3.2 with its strict comparisons.
inline void CutByPlane(PlaneKind kind, double zp, double zf, double zb, DepthFlags& flags) {
    switch (kind) {
        case PlaneKind::kPerpendicular:
            if (zp < 0) flags.ef = flags.eb = false;
            break;
        case PlaneKind::kFront:
            if (zp > zb)
                flags.ef = flags.eb = false;
            else if (zp > zf)
                flags.ef = false;
            break;
        case PlaneKind::kBack:
            if (zp < zf)
                flags.ef = flags.eb = false;
            else if (zp < zb)
                flags.eb = false;
            break;
    }
}

// Which depth ZOUT is (§1.3.2 "selection of the right depth").
enum class Sheet : std::uint8_t {
    kNone,   // ZOUT = ZMAX
    kFront,  // ZOUT = Z' = ZF
    kBack,   // ZOUT = Z' = ZB, normal negated
};

inline Sheet SelectSheet(DepthFlags flags, bool f2Negative) {
    if (f2Negative || (!flags.ef && !flags.eb)) return Sheet::kNone;
    return flags.ef ? Sheet::kFront : Sheet::kBack;
}

// The five criteria of one plane unit (§1.5.4), as sign bits (true = negative).
struct PlaneSignals {
    bool perpendicular = false;  // the host's flag (CP = 0?)
    bool sgnCp = false;
    bool sgnZp = false;
    bool sgnZpMinusZf = false;
    bool sgnZpMinusZb = false;
};

// Active-high disables produced by one cutting-plane logic (Fig. 1.8); EF is the AND of the
// negated cutF of all plane units, EB likewise.
struct CutSignals {
    bool cutF = false;
    bool cutB = false;
};

inline CutSignals CuttingPlaneLogic(const PlaneSignals& s) {
    const bool slanted = !s.perpendicular;
    const bool front = slanted && s.sgnCp;
    const bool back = slanted && !s.sgnCp;
    // Both depths: perpendicular plane with ZP < 0; front plane with ZP - ZB >= 0; back plane
    // with ZP - ZF < 0 (corrected, see the file comment).
    const bool both =
        (s.perpendicular && s.sgnZp) || (front && !s.sgnZpMinusZb) || (back && s.sgnZpMinusZf);
    return {both || (front && !s.sgnZpMinusZf), both || (back && s.sgnZpMinusZb)};
}

// Control bit of the ZOUT multiplexer (§1.5.5): EF'·EB' + sgn(F2).
inline bool ZoutIsZmax(DepthFlags flags, bool sgnF2) { return (!flags.ef && !flags.eb) || sgnF2; }

}  // namespace quadrix::patch
