// The per-pixel expressions of seed 000 as polynomials in the device coordinates (x, y): what the
// host loads into the EP1s and the EP2 (§1.2.1, §1.4.2-1.4.3). Paper letters in terms of the
// UniQuadrix coefficients are listed in patch.h (a = A, d = 2D, e = 2F, f = 2E, g = 2G, h = 2H,
// i = 2J, j = K). Re-derived: along the ray of (x, y) the quadric is c z² + β z + α = 0 with
// β = e x + f y + i and α = a x² + b y² + d xy + g x + h y + j, so z = F1 ± sqrt(F2) with
//   F1 = -β / 2c                              = -e/2c x - f/2c y - i/2c
//   F2 = (β² - 4cα) / 4c²
//      = (e² - 4ac)/4c² x² + (f² - 4bc)/4c² y² + (ef - 2cd)/2c² xy
//        + (ei - 2cg)/2c² x + (fi - 2ch)/2c² y + (i² - 4cj)/4c²          (eq. 1.3, as printed)
//   ZPk = -(A x + B y + D) / C for a plane <A B C D> with C != 0, -(A x + B y + D) when C = 0
//   NXBASE = 2a x + d y + g,  NYBASE = 2b y + d x + h,  NZBASE = e x + f y + i     (§1.4.3)
//   NX = NXBASE + e Z',  NY = NYBASE + f Z',  NZ = NZBASE + 2c Z'                 (eq. 1.4)
// A test checks each against the direct evaluation of the quadric at random points.
#pragma once

#include <array>

#include "quadrix/engines/patch/bounding_plane.h"
#include "quadrix/engines/patch/patch.h"

namespace quadrix::patch {

// a x + b y + c
struct Linear2 {
    double a = 0, b = 0, c = 0;
    double operator()(double x, double y) const { return a * x + b * y + c; }
};

// xx x² + yy y² + xy x y + x x + y y + c
struct Quadratic2 {
    double xx = 0, yy = 0, xy = 0, x = 0, y = 0, c = 0;
    double operator()(double px, double py) const {
        return xx * px * px + yy * py * py + xy * px * py + x * px + y * py + c;
    }
};

struct PatchPolynomials {
    Linear2 f1;
    Quadratic2 f2;
    int planeCount = 0;
    std::array<Linear2, kMaxPlanes> zp{};
    std::array<PlaneKind, kMaxPlanes> kind{};
    Linear2 nxBase, nyBase, nzBase;
    double e = 0, f = 0, twoC = 0;  // the multipliers' coefficients
};

// Requires patch.quadric.C() != 0 (ConvertBody guarantees it).
PatchPolynomials PolynomialsOf(const QuadricPatch& patch);

// Extremes of q over the closed rectangle [x0, x1] × [y0, y1] (corners, edge and interior
// critical points).
struct Range {
    double lo = 0, hi = 0;
};
Range RangeOnRectangle(const Quadratic2& q, double x0, double x1, double y0, double y1);
Range RangeOnRectangle(const Linear2& l, double x0, double x1, double y0, double y1);

}  // namespace quadrix::patch
