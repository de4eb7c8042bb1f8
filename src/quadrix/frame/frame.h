// The Frame: the contract between engines (DESIGN.md). Every engine fills the same W×H buffers;
// shading and output are applied to a Frame, never inside an engine.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "quadrix/math/vec.h"

namespace quadrix {

// The allocator of the Frame's arrays: like std::allocator, except that an element constructed
// without arguments (vector::resize) is left as the memory holds it. The elements (double,
// int32, Vec3) are implicit-lifetime types, so this is well defined, and it lets an engine that
// writes every pixel (Frame::ResizeForOverwrite) size a fresh Frame without first writing 40 MB
// from one thread: the pages are first touched by the engine's own parallel writes.
//
// Arrays of 2 MiB and more are mapped on their own, aligned to 2 MiB, with
// madvise(MADV_HUGEPAGE): where transparent huge pages are enabled for madvise (Debian's
// default), a fresh 1280×720 Frame is faulted in 20 pages of 2 MiB instead of about 10,000 of
// 4 KiB (issue 24: writing a fresh Frame costs 12 ms in small pages, 4 ms in huge ones).
void* AllocateFrameBytes(std::size_t bytes);
void FreeFrameBytes(void* p, std::size_t bytes);
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

struct Frame {
    static constexpr std::int32_t kNone = -1;

    int width = 0, height = 0;
    FrameArray<double> depth;          // device z; +inf = background
    FrameArray<Vec3> normal;           // world-space unit normal facing the viewer; 0 = background
    FrameArray<std::int32_t> surface;  // FlatScene half-space index, kNone = background
    FrameArray<std::int32_t> body;     // FlatScene body index, kNone = background
    FrameArray<std::int32_t> solid;    // FlatScene solid index, kNone = background

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
    // is unchanged, so a warm frame is not cleared twice; otherwise new buffers whose contents
    // are unspecified until the engine writes them (no clearing pass, see FrameAllocator).
    void ResizeForOverwrite(int w, int h) {
        const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        if (w == width && h == height && depth.size() == n && normal.size() == n &&
            surface.size() == n && body.size() == n && solid.size() == n)
            return;
        width = w;
        height = h;
        depth = {};
        normal = {};
        surface = {};
        body = {};
        solid = {};
        depth.resize(n);
        normal.resize(n);
        surface.resize(n);
        body.resize(n);
        solid.resize(n);
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

// Asks for small (4 KiB) pages on the Frame's mapped arrays (those of kFrameHugeBytes and more)
// where their memory is not yet touched: for a Frame of which one process writes only some rows
// (sort-first, batch/sort_first.h), whose 2 MiB pages would each hold rows of every rank and so
// be faulted in whole by each. Advice only: the memory is the same.
void AdviseSmallPages(Frame& frame);

}  // namespace quadrix
