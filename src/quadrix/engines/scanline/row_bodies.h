// The bodies of a row and of a span in engine `scanline` (seed 001 §5.1's per-scan-line work,
// made to follow the AEL): per-row and per-span work grows with the active edges, not with the
// bodies of the scene or the operands of a tree. Each row's bodies (RowBodies) are those with a
// crossing on it, plus the few whose bounds reach an image side, tested there (a body may cover
// a side's pixel without a crossing on the row), and refused bodies (their unit's bounds), each
// with its x range on the row, sorted on it; spans take the bodies whose range meets them from a
// sweep over that list (SweepTo). The units whose bounds hold the row are kept by a sweep over
// the units sorted on y0 (ActiveUnits).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "quadrix/engines/scanline/edge_list.h"
#include "quadrix/engines/scanline/scan_context.h"

namespace quadrix::scanline {

inline constexpr double kOnEdge = 1e-6;  // pixels: crossings this close to a centre → exact pixel

class RowBodies {
  public:
    explicit RowBodies(ScanContext& ctx);

    // The row's units, bodies and crossings (after passes one and two of row j).
    void BuildRow(int j, const std::vector<ActiveEdge>& ael);
    // Pass three's walk along the row: counts the crossings left of x − kOnEdge as passed (their
    // bodies' templates change there, csg_spans.h) and returns the next crossing (+inf: none).
    double PassCrossingsBefore(double x) {
        while (next_ < breaks_.size() && breaks_[next_] < x - kOnEdge)
            ++ownPassed_[static_cast<std::size_t>(breakBody_[next_++])];
        return next_ < breaks_.size() ? breaks_[next_] : HUGE_VAL;
    }
    // The sweep: SpanBodies() = the bodies whose x range meets the pixel centres i0 + ½ … i1 + ½
    // (spans come left to right, so each body enters once and leaves once per row).
    void SweepTo(int i0, int i1);

    const std::vector<int>& ActiveUnits() const { return activeUnits_; }
    const std::vector<int>& Bodies() const { return rowBodies_; }  // sorted on Lo
    const std::vector<int>& SpanBodies() const { return spanBodies_; }
    double Lo(int b) const { return lo_[static_cast<std::size_t>(b)]; }
    double Hi(int b) const { return hi_[static_cast<std::size_t>(b)]; }
    // The body's crossings left of the current pixel.
    int OwnPassed(int b) const { return ownPassed_[static_cast<std::size_t>(b)]; }

  private:
    // A body whose bounds reach an image side: its coverage of that side's pixel is evaluated per
    // row (it may have no crossing on the row and still cover it).
    struct SideBody {
        int body = -1;
        bool left = false, right = false;
        int y0 = 0, y1 = -1;
    };

    inline void UpdateActiveUnits(int j);
    // First touch of body b on row j: its x range starts empty and it joins rowBodies_.
    inline void TouchBody(int b, int j);
    // Refused bodies (their unit's bounds) and side bodies' coverage of the image sides.
    inline void AddUnitRanges(int j);
    inline void AddSideBody(const SideBody& sb, int j);
    // Whether the body's set on the ray has any finite endpoint or covers it (for the x range we
    // need where the body is, not where it is visible: a CSG operand matters where it is).
    inline bool SideCovered(int body, double x, double y);

    ScanContext& ctx_;
    std::vector<std::vector<int>> unitPixelBodies_;      // per unit: its refused bodies
    std::vector<std::vector<SideBody>> unitSideBodies_;  // per unit: its side bodies
    std::vector<int> unitsByY_;                          // units sorted on y0
    std::size_t unitPos_ = 0;                            // UpdateActiveUnits: next of unitsByY_
    std::vector<int> activeUnits_;
    std::vector<double> lo_, hi_;  // per body: x range on the current row
    std::vector<int> rangeRow_;    // the row lo_/hi_ were reset for
    std::vector<int> ownPassed_;   // per body: its crossings left of the current pixel
    std::vector<double> breaks_;   // the row's crossings, x order
    std::vector<int> breakBody_;   // per crossing in breaks_: its body
    std::size_t next_ = 0;         // PassCrossingsBefore: the next crossing
    std::vector<int> rowBodies_;   // bodies met on this row, sorted on lo_
    std::size_t sweepPos_ = 0;     // SweepTo: next of rowBodies_ to enter
    std::vector<int> spanBodies_;  // SweepTo: bodies whose range meets the current span
};

}  // namespace quadrix::scanline
