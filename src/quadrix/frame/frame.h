// The Frame: the contract between engines (DESIGN.md). Every engine fills the same W×H buffers;
// shading and output are applied to a Frame, never inside an engine.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "quadrix/math/vec.h"

namespace quadrix {

struct Frame {
    static constexpr std::int32_t kNone = -1;

    int width = 0, height = 0;
    std::vector<double> depth;        // device z; +inf = background
    std::vector<Vec3> normal;         // world-space unit normal facing the viewer; 0 = background
    std::vector<std::int32_t> surface;  // FlatScene half-space index, kNone = background
    std::vector<std::int32_t> body;     // FlatScene body index, kNone = background
    std::vector<std::int32_t> solid;    // FlatScene solid index, kNone = background

    Frame() = default;
    Frame(int w, int h) { Reset(w, h); }

    void Reset(int w, int h) {
        width = w;
        height = h;
        std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        depth.assign(n, HUGE_VAL);
        normal.assign(n, Vec3{});
        surface.assign(n, kNone);
        body.assign(n, kNone);
        solid.assign(n, kNone);
    }
    // For engines that write every pixel: keeps the buffers (and their contents) when the size
    // is unchanged, so a warm frame is not cleared twice; otherwise Reset.
    void ResizeForOverwrite(int w, int h) {
        const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        if (w == width && h == height && depth.size() == n && normal.size() == n &&
            surface.size() == n && body.size() == n && solid.size() == n)
            return;
        Reset(w, h);
    }
    void SetBackground(std::size_t i) {
        depth[i] = HUGE_VAL;
        normal[i] = Vec3{};
        surface[i] = kNone;
        body[i] = kNone;
        solid[i] = kNone;
    }
    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
               static_cast<std::size_t>(x);
    }
    bool Covered(int x, int y) const { return surface[Index(x, y)] != kNone; }
    std::size_t CoveredCount() const {
        std::size_t n = 0;
        for (auto s : surface) n += s != kNone;
        return n;
    }
    // Writes a sample when it is nearer than what is there (ties keep the earlier one): the
    // per-pixel minimum that composes Frames (DESIGN.md "unit of composition").
    void Offer(std::size_t i, double z, const Vec3& n, std::int32_t surf, std::int32_t bod,
               std::int32_t sol) {
        if (z < depth[i]) {
            depth[i] = z;
            normal[i] = n;
            surface[i] = surf;
            body[i] = bod;
            solid[i] = sol;
        }
    }
};

// Per-pixel minimum of two Frames of the same size (the union of their solids).
void ComposeMin(Frame& into, const Frame& other);

}  // namespace quadrix
