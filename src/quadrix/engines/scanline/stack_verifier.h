// The VERIFIER of engine `scanline`'s face stacks (seed 001 §5.3–5.4, face_stack.h). It checks
// every event of pass three (crossings closer than 1e-4 px): the stack after it must be the
// stack before it ⊕ the event's faces (else stackRepairs), and every toggled face must be on it
// exactly when the FACE TEST at Q finds the face's point inside its body's other HSIs (else
// stackCorrections; the zero tests of §4.5.13 with the error estimates of coefficients.h); both
// are corrected, so the frame stays exact. Faces entering at the event are checked against the
// nearest faces of their own body above and below (stackOrderCorrections). All three are 0 on
// every example and gallery scene since the Resolver's wedge test removed the spurious
// show-edges at mitred joints (resolver.h). With verify=on it also checks each span's stack head
// against an exact evaluation of the stack bodies at the span's sample pixel (verifySpans,
// verifyMismatchSpans, verifyBodies, verifyBodyMismatches).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "quadrix/engines/scanline/edge_list.h"
#include "quadrix/engines/scanline/scan_context.h"
#include "quadrix/math/plane_or_quadric.h"

namespace quadrix::scanline {

class FaceOrder;
struct StackFace;

class StackVerifier {
  public:
    StackVerifier(ScanContext& ctx, FaceOrder& order);

    // The face test: is show-face f on its body's boundary at (x, y)? (stack_verifier.cpp.)
    bool PresentAt(int f, double x, double y) const;

    // After the event of AEL crossings [b, e) whose last stack edge is `last`: checks the stack
    // of ael[last] against `before` (the stack left of the event) and corrects it (above).
    // True when the stack was rebuilt (the next stack edge must then be derived again).
    bool VerifyEvent(const std::vector<int>& before, std::vector<ActiveEdge>& ael, std::size_t b,
                     std::size_t e, std::size_t last, double xq, double y);

    // verify=on: the stack head `shown` and each stack body's first face among the span's faces
    // against the nearest exact hit of the stack bodies active on the row at the sample pixel.
    void VerifySpan(const std::vector<int>& activeUnits, const std::vector<int>& shown,
                    const std::vector<StackFace>& spanFaces, int sample, double y);

  private:
    struct OrientedLiteral : PlaneOrQuadric {  // oriented: the complement applied
        int halfSpace = -1;
        bool zFree = false;  // contains the view direction (zero tests (1), (2))
    };

    // The depth of show-face f's sheet at (x, y); false when it has no point there.
    inline bool FaceZ(const ShowFace& sf, double x, double y, double& z) const;
    // The face's point (x, y, z) lies definitely inside every other HSI of its body.
    inline bool InsideOtherLiterals(const ShowFace& sf, double x, double y, double z) const;
    // The faces the event's stack edges toggle (odd number of crossings) into toggles_.
    inline void CollectToggles(const std::vector<ActiveEdge>& ael, std::size_t b, std::size_t e);
    inline bool Toggled(int f) const;
    // The structural check: t = before ⊕ toggles_.
    inline bool Structural(const std::vector<int>& before, const std::vector<int>& t) const;
    // The face test at Q for every toggled face (into present_); false when one disagrees.
    inline bool FaceTestsAgree(double xq, double y);
    // t rebuilt from `before` with the toggled faces the face test finds.
    inline void Rebuild(const std::vector<int>& before, std::vector<int>& t, double xe, double xq,
                        double y);
    // The entering faces of t against the nearest faces of their own body (order, §5.5.1).
    inline void FixOrder(std::vector<int>& t, double xe, double xq, double y);
    bool InP(int f) const { return markP_[static_cast<std::size_t>(f)] == gen_; }
    bool InT(int f) const { return markT_[static_cast<std::size_t>(f)] == gen_; }

    ScanContext& ctx_;
    FaceOrder& order_;
    std::vector<std::vector<OrientedLiteral>> bodyLiterals_;  // stack bodies: "<= 0 inside"
    std::vector<int> derived_;                                // scratch stack
    std::vector<std::pair<int, bool>> toggles_;  // an event's faces, odd number of crossings
    std::vector<char> present_;                  // the face test at Q for toggles_
    std::vector<std::uint32_t> markP_, markT_;   // per show-face: on the stack before / after
    std::uint32_t gen_ = 0;                      // stamp of markP_ / markT_
};

}  // namespace quadrix::scanline
