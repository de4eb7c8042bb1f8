// The Newell tea-set format and BPT (freeform_reader.h describes both).
#include <algorithm>
#include <array>

#include "quadrix/freeform/bezier_surface.h"
#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/import/freeform/readers_internal.h"

namespace quadrix::import::detail {

namespace {

// Counts come from the file: never reserve more than this up front.
constexpr std::size_t kMaxReserve = 1 << 16;

std::optional<long long> ReadCount(TextScanner& s, std::string_view what) {
    ScanToken t;
    if (!s.Next(t)) {
        s.ErrorAtEnd("unexpected end of file, expected " + std::string(what));
        return std::nullopt;
    }
    std::optional<long long> n = s.Integer(t, what);
    if (n && *n < 0) {
        s.Error(t, std::string(what) + " must not be negative");
        return std::nullopt;
    }
    return n;
}

std::optional<Vec3> ReadPoint(TextScanner& s) {
    std::optional<double> x = s.NextNumber("x coordinate");
    if (!x) return std::nullopt;
    std::optional<double> y = s.NextNumber("y coordinate");
    if (!y) return std::nullopt;
    std::optional<double> z = s.NextNumber("z coordinate");
    if (!z) return std::nullopt;
    return Vec3{*x, *y, *z};
}

void WarnTrailing(TextScanner& s, std::string_view after) {
    ScanToken t;
    if (s.Next(t)) s.Warning(t, "text after the last " + std::string(after) + " is ignored");
}

}  // namespace

std::vector<freeform::Surface> ReadNewell(TextScanner& s, const std::string& baseName) {
    std::vector<freeform::Surface> out;
    std::optional<long long> patches = ReadCount(s, "number of patches");
    if (!patches) return out;
    // 16 indices per patch, kept with their tokens to report a bad index where it is written.
    std::vector<std::array<ScanToken, 16>> indexTokens;
    std::vector<std::array<long long, 16>> indices;
    indices.reserve(std::min<std::size_t>(static_cast<std::size_t>(*patches), kMaxReserve));
    for (long long p = 0; p < *patches; ++p) {
        std::array<ScanToken, 16> tokens;
        std::array<long long, 16> idx{};
        for (int k = 0; k < 16; ++k) {
            if (!s.Next(tokens[static_cast<std::size_t>(k)])) {
                s.ErrorAtEnd("unexpected end of file in patch " + std::to_string(p + 1) +
                             ": expected 16 vertex indices");
                return out;
            }
            std::optional<long long> i =
                s.Integer(tokens[static_cast<std::size_t>(k)], "vertex index");
            if (!i) return out;
            idx[static_cast<std::size_t>(k)] = *i;
        }
        indexTokens.push_back(tokens);
        indices.push_back(idx);
    }
    std::optional<long long> vertices = ReadCount(s, "number of vertices");
    if (!vertices) return out;
    std::vector<Vec3> points;
    points.reserve(std::min<std::size_t>(static_cast<std::size_t>(*vertices), kMaxReserve));
    for (long long v = 0; v < *vertices; ++v) {
        std::optional<Vec3> p = ReadPoint(s);
        if (!p) return out;
        points.push_back(*p);
    }
    WarnTrailing(s, "vertex");
    bool ok = true;
    for (std::size_t p = 0; p < indices.size(); ++p) {
        std::vector<Vec3> cp;
        for (std::size_t k = 0; k < 16; ++k) {
            long long i = indices[p][k];
            if (i < 1 || i > static_cast<long long>(points.size())) {
                s.Error(indexTokens[p][k], "vertex index " + std::to_string(i) +
                                               " is out of range 1.." +
                                               std::to_string(points.size()));
                ok = false;
                break;
            }
            cp.push_back(points[static_cast<std::size_t>(i - 1)]);
        }
        if (ok)
            out.push_back(freeform::Surface::FromBezier(
                freeform::BezierSurface::FromPoints(3, 3, cp), SurfaceName(baseName, p)));
    }
    return out;
}

std::vector<freeform::Surface> ReadBpt(TextScanner& s, const std::string& baseName) {
    std::vector<freeform::Surface> out;
    std::optional<long long> patches = ReadCount(s, "number of patches");
    if (!patches) return out;
    for (long long p = 0; p < *patches; ++p) {
        ScanToken at;
        if (!s.Peek(at)) {
            s.ErrorAtEnd("unexpected end of file: expected patch " + std::to_string(p + 1) +
                         " of " + std::to_string(*patches));
            return out;
        }
        int degree[2];
        for (int d = 0; d < 2; ++d) {
            ScanToken t;
            if (!s.Next(t)) {
                s.ErrorAtEnd("unexpected end of file, expected a degree");
                return out;
            }
            std::optional<long long> n = s.Integer(t, d == 0 ? "degree in u" : "degree in v");
            if (!n) return out;
            if (*n < 1 || *n > kMaxFreeformDegree) {
                s.Error(t, "degree " + std::to_string(*n) + " is outside 1.." +
                               std::to_string(kMaxFreeformDegree));
                return out;
            }
            degree[d] = static_cast<int>(*n);
        }
        std::vector<Vec3> cp;
        for (int k = 0; k < (degree[0] + 1) * (degree[1] + 1); ++k) {
            std::optional<Vec3> q = ReadPoint(s);
            if (!q) return out;
            cp.push_back(*q);
        }
        out.push_back(freeform::Surface::FromBezier(
            freeform::BezierSurface::FromPoints(degree[0], degree[1], cp),
            SurfaceName(baseName, out.size())));
    }
    WarnTrailing(s, "patch");
    return out;
}

}  // namespace quadrix::import::detail
