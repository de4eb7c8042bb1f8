#include "quadrix/batch/sort_first.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include "quadrix/batch/run.h"

#ifdef QUADRIX_HAVE_MPI
#include <mpi.h>
#endif

namespace quadrix::batch {

PixelRegion SortFirstRegion(int width, int height, int rank, int ranks) {
    return InterleavedBands(width, height, rank, ranks, kSortFirstBandRows);
}

#ifdef QUADRIX_HAVE_MPI
namespace {

constexpr std::size_t kPiece = std::size_t{256} << 20;
constexpr std::size_t kPixelBytes = sizeof(double) + sizeof(Vec3) + 3 * sizeof(std::int32_t);  // 60

// The region's row runs inside the frame: (first pixel index, count), in order.
std::vector<std::pair<std::size_t, std::size_t>> Runs(const Frame& f, const PixelRegion& region) {
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (const PixelRect& r : region.rects) {
        const int x0 = std::max(r.x0, 0), x1 = std::min(r.x1, f.width);
        if (x0 >= x1) continue;
        for (int y = std::max(r.y0, 0); y < std::min(r.y1, f.height); ++y)
            runs.emplace_back(f.Index(x0, y), static_cast<std::size_t>(x1 - x0));
    }
    return runs;
}

// The region's pixels, array by array (depth, normal, surface, body, solid), packed or unpacked.
template <bool kPack>
void Transfer(std::conditional_t<kPack, const Frame, Frame>& f,
              const std::vector<std::pair<std::size_t, std::size_t>>& runs, char* buffer) {
    auto move = [&](auto& array) {
        using T = typename std::remove_reference_t<decltype(array)>::value_type;
        for (const auto& [at, n] : runs) {
            if constexpr (kPack)
                std::memcpy(buffer, array.data() + at, n * sizeof(T));
            else
                std::memcpy(array.data() + at, buffer, n * sizeof(T));
            buffer += n * sizeof(T);
        }
    };
    move(f.depth);
    move(f.normal);
    move(f.surface);
    move(f.body);
    move(f.solid);
}

std::size_t PixelCount(const std::vector<std::pair<std::size_t, std::size_t>>& runs) {
    std::size_t n = 0;
    for (const auto& r : runs) n += r.second;
    return n;
}

}  // namespace
#endif

bool RenderSortFirst(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                     RenderReport& report, Diagnostics& diags) {
    const int ranks = MpiSize();
    if (ranks <= 1) return ctx.Render(engine, frame, report, diags);
#ifdef QUADRIX_HAVE_MPI
    const int rank = MpiRank();
    const int width = ctx.Flat().width, height = ctx.Flat().height;
    EngineRequest mine = engine;
    mine.region = SortFirstRegion(width, height, rank, ranks);
    int ok = ctx.Render(mine, frame, report, diags) ? 1 : 0;
    int all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all) return false;
    if (rank != 0) {
        const auto runs = Runs(frame, *mine.region);
        std::vector<char> buffer(PixelCount(runs) * kPixelBytes);
        Transfer<true>(frame, runs, buffer.data());
        for (std::size_t at = 0; at < buffer.size(); at += kPiece)
            MPI_Send(buffer.data() + at, static_cast<int>(std::min(kPiece, buffer.size() - at)),
                     MPI_BYTE, 0, 8, MPI_COMM_WORLD);
        return true;
    }
    for (int r = 1; r < ranks; ++r) {
        const auto runs = Runs(frame, SortFirstRegion(width, height, r, ranks));
        std::vector<char> buffer(PixelCount(runs) * kPixelBytes);
        for (std::size_t at = 0; at < buffer.size(); at += kPiece)
            MPI_Recv(buffer.data() + at, static_cast<int>(std::min(kPiece, buffer.size() - at)),
                     MPI_BYTE, r, 8, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        Transfer<false>(frame, runs, buffer.data());
    }
    return true;
#else
    return ctx.Render(engine, frame, report, diags);
#endif
}

}  // namespace quadrix::batch
