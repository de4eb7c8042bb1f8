#include "quadrix/batch/sort_last.h"

#include <algorithm>
#include <cstdint>

#include "quadrix/batch/mpi_piece.h"
#include "quadrix/batch/run.h"

#ifdef QUADRIX_HAVE_MPI
#include <mpi.h>
#endif

namespace quadrix::batch {

#ifdef QUADRIX_HAVE_MPI
namespace {

void SendBytes(const void* data, std::size_t bytes, int to) {
    const char* p = static_cast<const char*>(data);
    for (std::size_t at = 0; at < bytes; at += kMpiPiece)
        MPI_Send(p + at, static_cast<int>(std::min(kMpiPiece, bytes - at)), MPI_BYTE, to, 7,
                 MPI_COMM_WORLD);
}

void ReceiveBytes(void* data, std::size_t bytes, int from) {
    char* p = static_cast<char*>(data);
    for (std::size_t at = 0; at < bytes; at += kMpiPiece)
        MPI_Recv(p + at, static_cast<int>(std::min(kMpiPiece, bytes - at)), MPI_BYTE, from, 7,
                 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

template <typename Array>
std::size_t Bytes(const Array& a) {
    return a.size() * sizeof(typename Array::value_type);
}

}  // namespace
#endif

bool RenderSortLast(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                    RenderReport& report, Diagnostics& diags) {
    const int ranks = MpiSize();
    if (ranks <= 1) return ctx.Render(engine, frame, report, diags);
#ifdef QUADRIX_HAVE_MPI
    const int rank = MpiRank();
    EngineRequest mine = engine;
    mine.share.emplace();
    for (int s = rank; s < static_cast<int>(ctx.Flat().solids.size()); s += ranks)
        mine.share->push_back(s);
    mine.shareFreeforms = rank == 0;
    int ok = ctx.Render(mine, frame, report, diags) ? 1 : 0;
    int all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all) return false;
    if (rank != 0) {
        SendBytes(frame.depth.data(), Bytes(frame.depth), 0);
        SendBytes(frame.normal.data(), Bytes(frame.normal), 0);
        SendBytes(frame.surface.data(), Bytes(frame.surface), 0);
        SendBytes(frame.body.data(), Bytes(frame.body), 0);
        SendBytes(frame.solid.data(), Bytes(frame.solid), 0);
        return true;
    }
    Frame other(frame.width, frame.height);
    for (int r = 1; r < ranks; ++r) {
        ReceiveBytes(other.depth.data(), Bytes(other.depth), r);
        ReceiveBytes(other.normal.data(), Bytes(other.normal), r);
        ReceiveBytes(other.surface.data(), Bytes(other.surface), r);
        ReceiveBytes(other.body.data(), Bytes(other.body), r);
        ReceiveBytes(other.solid.data(), Bytes(other.solid), r);
        ComposeMin(frame, other);
    }
    return true;
#else
    return ctx.Render(engine, frame, report, diags);
#endif
}

}  // namespace quadrix::batch
