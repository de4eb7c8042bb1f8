// The Frame: the contract between engines (DESIGN.md). Every engine fills the same W×H buffers;
// shading and output are applied to a Frame, never inside an engine.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "quadrix/frame/packed_normal.h"
#include "quadrix/math/vec.h"

namespace quadrix {

// The allocator of the Frame's arrays: like std::allocator, except that an element constructed
// without arguments (vector::resize) is left as the memory holds it. The elements (float,
// int32, PackedNormal) are implicit-lifetime types, so this is well defined, and it lets an engine
// that writes every pixel (Frame::ResizeForOverwrite) size a fresh Frame without first writing 40
// MB from one thread: the pages are first touched by the engine's own parallel writes.
//
// Arrays of 2 MiB and more are mapped on their own, aligned to 2 MiB, with
// madvise(MADV_HUGEPAGE): where transparent huge pages are enabled for madvise (Debian's
// default), a fresh 1280×720 Frame is faulted in 20 pages of 2 MiB instead of about 10,000 of
// 4 KiB (issue 24: writing a fresh Frame costs 12 ms in small pages, 4 ms in huge ones).
//
// Freed mappings of up to 32 MiB are kept (96 MiB in all) for the next allocation: one of the
// same length, else the start of the shortest longer one (its rest unmapped), so that memory the
// process has already faulted in serves again (frame.cpp). ReleaseKeptFrameBytes unmaps them.
void* AllocateFrameBytes(std::size_t bytes);
void FreeFrameBytes(void* p, std::size_t bytes);
void ReleaseKeptFrameBytes();
constexpr std::size_t kFrameHugeBytes = std::size_t{2} << 20;

template <class T>
struct FrameAllocator : std::allocator<T> {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = FrameAllocator<U>;
    };
    FrameAllocator() = default;
    template <class U>
    FrameAllocator(const FrameAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        if (n * sizeof(T) < kFrameHugeBytes) return std::allocator<T>::allocate(n);
        return static_cast<T*>(AllocateFrameBytes(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < kFrameHugeBytes)
            std::allocator<T>::deallocate(p, n);
        else
            FreeFrameBytes(p, n * sizeof(T));
    }
    template <class U>
    void construct(U*) noexcept {}
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
template <class T, class U>
bool operator==(const FrameAllocator<T>&, const FrameAllocator<U>&) noexcept {
    return true;
}

template <class T>
using FrameArray = std::vector<T, FrameAllocator<T>>;

// A pixel costs 16 bytes (issue 24 item 3; it was 44): depth as a float, the normal packed in
// 32 bits, the surface and body as 32-bit ids. The solid is not stored per pixel: it is the
// body's solid (FlatBody::solid), looked up in a table of one entry per body.
//
// Depth. Engines compute depth in double and keep it so in their own tiles and z-buffers where
// they compare or compose (raycast's tiles, Pixel-Powers' registers, the scanline's spans); the
// Frame holds it rounded to the nearest float. Device z is in pixel units (|z| is a few hundred
// for a 720p picture, a few thousand at most), so the rounding moves a point by at most half a
// float ulp: 1.5e-5 pixel at |z| = 256, 1.2e-4 at 2048. The shaders read depth for the world
// point of point lights and for the start of shadow rays (shade/shadows.h starts them beyond
// the rounding), the viewer for picking and edges; none needs more.
//
// Normal. PackedNormal (octahedral, 2 × 16 bits): at most PackedNormal::kMaxError (7e-5)
// radians from the engine's double normal, exact along the axes.
//
// Composition keeps the nearer sample by the stored (float) depth, ties keeping the earlier
// one, so Frames compose the same however their engines rounded.
struct Frame {
    static constexpr std::int32_t kNone = -1;
    static constexpr std::size_t kBytesPerPixel =
        sizeof(float) + sizeof(PackedNormal) + 2 * sizeof(std::int32_t);
    static_assert(kBytesPerPixel == 16);

    int width = 0, height = 0;
    FrameArray<float> depth;           // device z, rounded to float; +inf = background
    FrameArray<PackedNormal> normal;   // world-space unit normal facing the viewer; 0 = background
    FrameArray<std::int32_t> surface;  // FlatScene half-space index, kNone = background
    FrameArray<std::int32_t> body;     // FlatScene body index, kNone = background
    // Per body (not per pixel): the FlatScene solid it belongs to. Engine::Render sets it from
    // the scene; a Frame read from a dump (io/writers.h) from the dump's own (body, solid) pairs.
    std::vector<std::int32_t> bodySolid;

    Frame() = default;
    Frame(int w, int h) { Reset(w, h); }

    void Reset(int w, int h) {
        width = w;
        height = h;
        std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        depth.assign(n, HUGE_VALF);
        normal.assign(n, PackedNormal{});
        surface.assign(n, kNone);
        body.assign(n, kNone);
    }
    // For engines that write every pixel: keeps the buffers (and their contents) when the size
    // is unchanged, so a warm frame is not cleared twice; otherwise new buffers whose contents
    // are unspecified until the engine writes them (no clearing pass, see FrameAllocator).
    void ResizeForOverwrite(int w, int h) {
        const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        if (w == width && h == height && depth.size() == n && normal.size() == n &&
            surface.size() == n && body.size() == n)
            return;
        width = w;
        height = h;
        depth = {};
        normal = {};
        surface = {};
        body = {};
        depth.resize(n);
        normal.resize(n);
        surface.resize(n);
        body.resize(n);
    }
    void SetBackground(std::size_t i) { SetBackground(i, 1); }
    // Background on the n pixels from `from` (array by array: wide contiguous stores).
    void SetBackground(std::size_t from, std::size_t n) {
        std::fill_n(depth.data() + from, n, HUGE_VALF);
        std::fill_n(normal.data() + from, n, PackedNormal{});
        std::fill_n(surface.data() + from, n, kNone);
        std::fill_n(body.data() + from, n, kNone);
    }
    // The solid seen at pixel i: kNone for the background, for a sample of no body (a freeform
    // surface) and for a body the table does not know.
    std::int32_t Solid(std::size_t i) const {
        const std::int32_t b = body[i];
        return b >= 0 && static_cast<std::size_t>(b) < bodySolid.size()
                   ? bodySolid[static_cast<std::size_t>(b)]
                   : kNone;
    }
    // The normal at pixel i, unpacked.
    Vec3 Normal(std::size_t i) const { return normal[i]; }
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
    // per-pixel minimum that composes Frames (DESIGN.md "unit of composition"). Nearer is
    // decided on the depth as stored, rounded to float.
    void Offer(std::size_t i, double z, PackedNormal n, std::int32_t surf, std::int32_t bod) {
        const float zf = static_cast<float>(z);
        if (zf < depth[i]) {
            depth[i] = zf;
            normal[i] = n;
            surface[i] = surf;
            body[i] = bod;
        }
    }
    // Whether a sample at depth z would be kept by Offer (for z-buffers that skip the work of a
    // sample's normal when it is hidden).
    bool Nearer(std::size_t i, double z) const { return static_cast<float>(z) < depth[i]; }
};

// The most that storing depth z in the Frame (rounding to float) changes it: half a float ulp.
// For comparisons of a Frame with exact values: |frame.depth[i] − z| ≤ DepthRounding(z) + the
// engine's own error.
// 0 for a depth beyond the floats (the background's +inf).
inline double DepthRounding(double z) {
    if (!(std::fabs(z) <= static_cast<double>(std::numeric_limits<float>::max()))) return 0;
    // The float's ulp from its exponent bits (no libm call: shadow rays ask once each): 2^(e−23)
    // for a normal float, 2^−149 below.
    const auto bits = std::bit_cast<std::uint32_t>(std::fabs(static_cast<float>(z)));
    if (bits < 0x00800000u)
        return 0.5 * static_cast<double>(std::numeric_limits<float>::denorm_min());
    return 0.5 * static_cast<double>(std::bit_cast<float>(bits & 0x7f800000u)) * 0x1p-23;
}

// Per-pixel minimum of two Frames of the same size (the union of their solids).
void ComposeMin(Frame& into, const Frame& other);

// Asks for small (4 KiB) pages on the Frame's mapped arrays (those of kFrameHugeBytes and more)
// where their memory is not yet touched: for a Frame of which one process writes only some rows
// (sort-first, batch/sort_first.h), whose 2 MiB pages would each hold rows of every rank and so
// be faulted in whole by each. Advice only: the memory is the same.
void AdviseSmallPages(Frame& frame);

}  // namespace quadrix
