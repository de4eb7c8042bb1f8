#include "quadrix/batch/sort_last.h"

#include "quadrix/batch/mpi.h"
#include "quadrix/batch/run.h"

namespace quadrix::batch {

namespace {

template <typename Array>
MpiMessage ArrayMessage(bool send, Array& a, int peer) {
    return {send, reinterpret_cast<char*>(a.data()), a.size() * sizeof(typename Array::value_type),
            peer, 7};
}

// The Frame's four arrays to or from `peer` (its solids are its bodies', frame.h: every rank's
// scene has every body, so rank 0's table serves all).
void ExchangeFrame(bool send, Frame& f, int peer) {
    const MpiMessage m[4] = {ArrayMessage(send, f.depth, peer), ArrayMessage(send, f.normal, peer),
                             ArrayMessage(send, f.surface, peer), ArrayMessage(send, f.body, peer)};
    Mpi().exchange(m, 4);
}

}  // namespace

bool RenderSortLast(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                    RenderReport& report, Diagnostics& diags) {
    const int ranks = MpiSize();
    if (ranks <= 1) return ctx.Render(engine, frame, report, diags);
    const int rank = MpiRank();
    EngineRequest mine = engine;
    mine.share.emplace();
    for (int s = rank; s < static_cast<int>(ctx.Flat().solids.size()); s += ranks)
        mine.share->push_back(s);
    mine.shareFreeforms = rank == 0;
    const bool ok = ctx.Render(mine, frame, report, diags);
    if (Mpi().allMin(ok ? 1 : 0) == 0) return false;
    if (rank != 0) {
        ExchangeFrame(true, frame, 0);
        return true;
    }
    Frame other(frame.width, frame.height);
    for (int r = 1; r < ranks; ++r) {
        ExchangeFrame(false, other, r);
        ComposeMin(frame, other);
    }
    return true;
}

}  // namespace quadrix::batch
