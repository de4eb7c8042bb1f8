#include "quadrix/engines/pixelpowers/machine.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "quadrix/util/parallel.h"

namespace quadrix::pixelpowers {
namespace {

constexpr int kTile = 64;
constexpr std::size_t kTilePixels = static_cast<std::size_t>(kTile) * kTile;

// The registers of one tile's pixels (structure of arrays).
struct TileRegisters {
    std::array<double, kTilePixels> ztemp;
    std::array<double, kTilePixels> zmin;
    std::array<std::int32_t, kTilePixels> color;
    std::array<std::array<std::uint8_t, kTilePixels>, 3> flag;
    std::array<std::array<double, kTilePixels>, 3> normal;  // N0–N2 (kNLoad)

    void Reset() {
        zmin.fill(HUGE_VAL);
        color.fill(-1);
        ztemp.fill(HUGE_VAL);
        for (auto& f : flag) f.fill(0);
        for (auto& n : normal) n.fill(0);
    }
};

double Qee(const double* q, double x, double y) {
    return (q[0] * x + q[1] * y + q[3]) * x + (q[2] * y + q[4]) * y + q[5];
}

// Plane literals inline, with exactly the arithmetic of eval::LiteralOnRay (ray_literal.cpp:
// e = A x + B y + D, r = −e/C, the set (−∞, r] for C > 0, [r, ∞) for C < 0, all or nothing for
// C = 0, empty both ways for non-finite values, closure of the complement when complemented), so
// results stay bit-identical to the oracle; this only skips the call and the interval bookkeeping.
// `word` rounds the finite root as ZTEMP's words do (depth-bits; the identity otherwise), so that
// coincident surfaces compare equal in the rounded domain too.
template <class Word>
bool PlaneInside(const eval::RayHalfSpace& h, bool complemented, double x, double y, double z,
                 std::uint8_t mode, const Word& word) {
    double e = h.px * x + h.py * y + h.pd;
    if (!std::isfinite(e) || !std::isfinite(h.c)) return false;
    if (h.c == 0) return (e <= 0) != complemented;  // all of the ray or nothing: every mode
    double r = -e / h.c;
    if (std::isfinite(r)) r = word(r);
    bool below = (h.c > 0) != complemented;  // the set is (−∞, r] (else [r, ∞))
    // A piece with lo == hi is dropped (regularised), which only happens for r = ±∞.
    // The mode (InsideMode) decides whether the endpoint r itself counts.
    if (below) {
        bool closedEnd = mode == kInsideClosed || mode == kInsideBefore;
        return r > -HUGE_VAL && (closedEnd ? z <= r : z < r);
    }
    bool closedEnd = mode == kInsideClosed || mode == kInsideAfter;
    return r < HUGE_VAL && (closedEnd ? z >= r : z > r);
}

// z in the piece v in the sense of `mode` (InsideMode).
bool InPiece(const Interval& v, double z, std::uint8_t mode) {
    switch (mode) {
        case kInsideOpen:
            return v.lo < z && z < v.hi;
        case kInsideAfter:
            return v.lo <= z && z < v.hi;
        case kInsideBefore:
            return v.lo < z && z <= v.hi;
        default:
            return v.lo <= z && z <= v.hi;
    }
}

// The plane's finite entry (exit) point, if any.
bool PlaneRoot(const eval::RayHalfSpace& h, bool complemented, bool exit, double x, double y,
               double& t) {
    double e = h.px * x + h.py * y + h.pd;
    if (!std::isfinite(e) || !std::isfinite(h.c) || h.c == 0) return false;
    double r = -e / h.c;
    if (!std::isfinite(r)) return false;
    bool below = (h.c > 0) != complemented;  // (−∞, r]: r is an exit; [r, ∞): an entry
    if (below != exit) return false;
    t = r;
    return true;
}

bool ClearsF1(const Instruction& in) {
    if (in.a != 0) return false;
    switch (in.op) {
        case Opcode::kRoot:
        case Opcode::kInside:
        case Opcode::kQeeKeepPositive:
        case Opcode::kQeeKeepNonPositive:
        case Opcode::kZKeepGE:
        case Opcode::kZKeepLE:
        case Opcode::kZKeepGT:
        case Opcode::kZKeepLT:
        case Opcode::kFlagAnd:
        case Opcode::kFlagAndNot:
        case Opcode::kFlagClear:
        case Opcode::kZTest:
            return true;
        default:
            return false;
    }
}

class TileRunner {
  public:
    TileRunner(const Program& program, TileRegisters& regs, MachineCounters& counters)
        : program_(program), r_(regs), counters_(counters) {
        if (program.depthStep > 0 && program.depthBits > 0) {
            step_ = program.depthStep;
            origin_ = program.depthOrigin;
            maxWord_ = std::ldexp(1.0, program.depthBits) - 1;
        }
    }

    void Run(int tx0, int ty0, int tx1, int ty1) {
        tx0_ = tx0;
        ty0_ = ty0;
        PixelRect tile{tx0, ty0, tx1, ty1};
        for (const Block& b : program_.blocks) {
            PixelRect rect = b.rect.Intersected(tile);
            if (rect.Empty()) continue;
            ++counters_.blockRuns;
            for (std::int32_t k = b.first; k < b.first + b.count; ++k) {
                const Instruction& in = program_.code[static_cast<std::size_t>(k)];
                ++counters_.instructions;
                Execute(in, rect);
                if (ClearsF1(in) && !AnyF1(rect)) {
                    ++counters_.blocksAbandoned;
                    break;
                }
            }
        }
    }

  private:
    // A depth as a fixed-point register word holds it (Program::depthStep; identity when off).
    double Word(double z) const {
        if (step_ == 0) return z;
        double k = std::nearbyint((z - origin_) / step_);
        return origin_ + step_ * std::clamp(k, 0.0, maxWord_);
    }

    template <class Fn>
    void ForEach(const PixelRect& rect, Fn&& fn) {
        for (int j = rect.y0; j < rect.y1; ++j) {
            double y = j + 0.5;
            std::size_t row = static_cast<std::size_t>(j - ty0_) * kTile;
            for (int i = rect.x0; i < rect.x1; ++i)
                fn(row + static_cast<std::size_t>(i - tx0_), i + 0.5, y);
        }
    }

    bool AnyF1(const PixelRect& rect) {
        for (int j = rect.y0; j < rect.y1; ++j) {
            std::size_t row = static_cast<std::size_t>(j - ty0_) * kTile;
            const std::uint8_t* f =
                r_.flag[0].data() + row + static_cast<std::size_t>(rect.x0 - tx0_);
            for (int i = 0; i < rect.x1 - rect.x0; ++i)
                if (f[i]) return true;
        }
        return false;
    }

    const MachineLiteral& Literal(std::int32_t i) const {
        return program_.literals[static_cast<std::size_t>(i)];
    }

    void Execute(const Instruction& in, const PixelRect& rect) {
        auto& fa = r_.flag[in.a];
        auto& fb = r_.flag[in.b < 3 ? in.b : 0];
        std::uint64_t ops = 0;
        switch (in.op) {
            case Opcode::kFlagSet:
                ForEach(rect, [&](std::size_t k, double, double) { fa[k] = 1; });
                break;
            case Opcode::kFlagClear:
                ForEach(rect, [&](std::size_t k, double, double) { fa[k] = 0; });
                break;
            case Opcode::kFlagCopy:
                ForEach(rect, [&](std::size_t k, double, double) { fa[k] = fb[k]; });
                break;
            case Opcode::kFlagAnd:
                ForEach(rect, [&](std::size_t k, double, double) { fa[k] &= fb[k]; });
                break;
            case Opcode::kFlagAndNot:
                ForEach(rect, [&](std::size_t k, double, double) { fa[k] &= !fb[k]; });
                break;
            case Opcode::kFlagOr:
                ForEach(rect, [&](std::size_t k, double, double) { fa[k] |= fb[k]; });
                break;
            case Opcode::kQeeKeepPositive:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) fa[k] = Qee(in.q, x, y) > 0, ++ops;
                });
                break;
            case Opcode::kQeeKeepNonPositive:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) fa[k] = Qee(in.q, x, y) <= 0, ++ops;
                });
                break;
            case Opcode::kZLoad:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) r_.ztemp[k] = Word(Qee(in.q, x, y)), ++ops;
                });
                break;
            case Opcode::kZMax:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) r_.ztemp[k] = std::max(r_.ztemp[k], Word(Qee(in.q, x, y))), ++ops;
                });
                break;
            case Opcode::kZMin:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) r_.ztemp[k] = std::min(r_.ztemp[k], Word(Qee(in.q, x, y))), ++ops;
                });
                break;
            case Opcode::kZKeepGE:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) fa[k] = r_.ztemp[k] >= Word(Qee(in.q, x, y)), ++ops;
                });
                break;
            case Opcode::kZKeepLE:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) fa[k] = r_.ztemp[k] <= Word(Qee(in.q, x, y)), ++ops;
                });
                break;
            case Opcode::kZKeepGT:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) fa[k] = r_.ztemp[k] > Word(Qee(in.q, x, y)), ++ops;
                });
                break;
            case Opcode::kZKeepLT:
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) fa[k] = r_.ztemp[k] < Word(Qee(in.q, x, y)), ++ops;
                });
                break;
            case Opcode::kNLoad: {
                auto& n = r_.normal[in.b < 3 ? in.b : 0];
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (fa[k]) n[k] = Qee(in.q, x, y), ++ops;
                });
                break;
            }
            case Opcode::kRoot: {
                const MachineLiteral& lit = Literal(in.arg);
                bool exit = in.b != 0;
                if (lit.isPlane) {
                    ForEach(rect, [&](std::size_t k, double x, double y) {
                        double t = 0;
                        fa[k] = PlaneRoot(lit.ray, lit.complemented, exit, x, y, t);
                        if (fa[k]) r_.ztemp[k] = Word(t);
                        ++ops;
                    });
                    break;
                }
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    eval::RaySet s =
                        eval::LiteralOnRay(lit.ray, lit.complemented, x, y, 0, literalCounters_);
                    ++ops;
                    // A literal has at most one finite entry and one finite exit on a ray
                    // (ray_literal.h: at most two pieces, infinite at the outer ends).
                    bool found = false;
                    for (int p = 0; p < s.count && !found; ++p) {
                        double t = exit ? s.piece[p].hi : s.piece[p].lo;
                        if (std::isfinite(t)) {
                            r_.ztemp[k] = Word(t);
                            found = true;
                        }
                    }
                    fa[k] = found;
                });
                counters_.rootSolves += ops;
                break;
            }
            case Opcode::kInside: {
                const MachineLiteral& lit = Literal(in.arg);
                const std::uint8_t mode = in.b;
                if (lit.isPlane) {
                    ForEach(rect, [&](std::size_t k, double x, double y) {
                        if (!fa[k]) return;
                        fa[k] = PlaneInside(lit.ray, lit.complemented, x, y, r_.ztemp[k], mode,
                                            [this](double t) { return Word(t); });
                        ++ops;
                    });
                    break;
                }
                ForEach(rect, [&](std::size_t k, double x, double y) {
                    if (!fa[k]) return;
                    eval::RaySet s =
                        eval::LiteralOnRay(lit.ray, lit.complemented, x, y, 0, literalCounters_);
                    ++ops;
                    double z = r_.ztemp[k];
                    bool in = false;
                    for (int p = 0; p < s.count; ++p) {
                        Interval v = s.piece[p];
                        // Roots as depth words, like ZTEMP's (identity without depth-bits).
                        if (step_ != 0) {
                            if (std::isfinite(v.lo)) v.lo = Word(v.lo);
                            if (std::isfinite(v.hi)) v.hi = Word(v.hi);
                        }
                        in = in || InPiece(v, z, mode);
                    }
                    fa[k] = in;
                });
                counters_.rootSolves += ops;
                break;
            }
            case Opcode::kZTest:
                if (in.arg < 0) {
                    ForEach(rect, [&](std::size_t k, double, double) {
                        if (fa[k]) fa[k] = r_.ztemp[k] < r_.zmin[k], ++ops;
                    });
                    break;
                }
                ForEach(rect, [&](std::size_t k, double, double) {
                    if (fa[k])
                        fa[k] = r_.ztemp[k] < r_.zmin[k] ||
                                (r_.ztemp[k] == r_.zmin[k] && r_.color[k] >= in.arg),
                        ++ops;
                });
                break;
            case Opcode::kZWrite:
                ForEach(rect, [&](std::size_t k, double, double) {
                    if (!fa[k]) return;
                    r_.zmin[k] = r_.ztemp[k];
                    r_.color[k] = in.arg;
                    ++ops;
                });
                counters_.writes += ops;
                break;
        }
        counters_.pixelOps += ops;
    }

    const Program& program_;
    TileRegisters& r_;
    MachineCounters& counters_;
    eval::LiteralCounters literalCounters_;
    int tx0_ = 0, ty0_ = 0;
    double step_ = 0, origin_ = 0, maxWord_ = 0;
};

struct Worker {
    TileRegisters regs;
    MachineCounters counters;
};

}  // namespace

Vec3 KeyLight(const FlatScene& scene) {
    Vec3 key{};
    double best = 0;
    for (const scene::Light& l : scene.lights) {
        if (l.kind == scene::Light::Kind::kAmbient) continue;
        Vec3 d = Normalize(l.direction);
        if (l.intensity > best && std::isfinite(Dot(d, d))) {
            best = l.intensity;
            key = d;
        }
    }
    return key;
}

Vec3 ShadingUnitNormal(const Vec3& approx, const Vec3& key) {
    const double kk = Dot(key, key);
    if (!(kk > 0)) {
        double len = Length(approx);
        return len > 0 && std::isfinite(len) ? approx / len : Vec3{0, 0, 1};
    }
    if (!std::isfinite(Dot(approx, approx))) return key;
    double along = Dot(approx, key);
    double c = std::clamp(along, -1.0, 1.0);
    Vec3 perp = approx - key * along;
    double pl = Length(perp);
    if (!(pl > 1e-12 * (std::fabs(along) + 1e-300))) {
        // Parallel to the light: any perpendicular direction gives the same n·l.
        perp = Cross(key, std::fabs(key.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
        pl = Length(perp);
    }
    return key * c + perp * (std::sqrt(std::max(0.0, 1 - c * c)) / pl);
}

MachineCounters Execute(const Program& program, const FlatScene& scene, Frame& frame) {
    int width = std::max(scene.width, 0), height = std::max(scene.height, 0);
    frame.Reset(width, height);
    int tilesX = (width + kTile - 1) / kTile, tilesY = (height + kTile - 1) / kTile;
    PerThread<Worker> workers;
    const Vec3 key = KeyLight(scene);
    auto runTile = [&](int t) {
        Worker& w = workers.Local();
        int x0 = (t % tilesX) * kTile, y0 = (t / tilesX) * kTile;
        int x1 = std::min(x0 + kTile, width), y1 = std::min(y0 + kTile, height);
        ++w.counters.tiles;
        w.regs.Reset();
        TileRunner(program, w.regs, w.counters).Run(x0, y0, x1, y1);
        // Scan-out: COLOR names the patch; normals are computed at ZMIN (deferred shading).
        for (int j = y0; j < y1; ++j) {
            for (int i = x0; i < x1; ++i) {
                std::size_t k =
                    static_cast<std::size_t>(j - y0) * kTile + static_cast<std::size_t>(i - x0);
                std::int32_t c = w.regs.color[k];
                if (c < 0) continue;
                const PatchInfo& p = program.patches[static_cast<std::size_t>(c)];
                std::size_t f = frame.Index(i, j);
                double z = w.regs.zmin[k];
                frame.depth[f] = z;
                frame.normal[f] =
                    p.machineNormal
                        ? ShadingUnitNormal(
                              {w.regs.normal[0][k], w.regs.normal[1][k], w.regs.normal[2][k]}, key)
                        : scene.WorldNormal(p.halfSpace, {i + 0.5, j + 0.5, z});
                frame.surface[f] = p.halfSpace;
                frame.body[f] = p.body;
            }
        }
    };
    auto run = [&] {
        ParallelFor(tbb::blocked_range<int>(0, tilesX * tilesY, 1),
                    [&](const tbb::blocked_range<int>& range) {
                        for (int t = range.begin(); t < range.end(); ++t) runTile(t);
                    });
    };
    run();
    MachineCounters total;
    workers.ForEach([&](const Worker& w) { total.Add(w.counters); });
    return total;
}

}  // namespace quadrix::pixelpowers
