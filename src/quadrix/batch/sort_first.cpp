#include "quadrix/batch/sort_first.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include "quadrix/batch/mpi.h"
#include "quadrix/batch/run.h"

namespace quadrix::batch {

PixelRegion SortFirstRegion(int width, int height, int rank, int ranks) {
    return InterleavedBands(width, height, rank, ranks, kSortFirstBandRows);
}

std::vector<RowSpan> SortFirstRows(int width, int height, int rank, int ranks) {
    std::vector<RowSpan> rows;
    for (const PixelRect& r : SortFirstRegion(width, height, rank, ranks).rects)
        if (!r.Empty()) rows.push_back({r.y0, r.y1});
    return rows;
}

namespace {

constexpr std::size_t kPixelBytes = Frame::kBytesPerPixel;
constexpr int kFrameTag = 8, kHaloTag = 9, kImageTag = 10;

using Runs = std::vector<std::pair<std::size_t, std::size_t>>;  // (first pixel index, count)

// The region's row runs inside the frame, in order.
Runs RunsOf(const Frame& f, const PixelRegion& region) {
    Runs runs;
    for (const PixelRect& r : region.rects) {
        const int x0 = std::max(r.x0, 0), x1 = std::min(r.x1, f.width);
        if (x0 >= x1) continue;
        for (int y = std::max(r.y0, 0); y < std::min(r.y1, f.height); ++y)
            runs.emplace_back(f.Index(x0, y), static_cast<std::size_t>(x1 - x0));
    }
    return runs;
}

// Whole rows `rows` (ascending) of a picture `width` wide as runs.
Runs RowRuns(const std::vector<int>& rows, int width) {
    Runs runs;
    for (int y : rows)
        runs.emplace_back(static_cast<std::size_t>(y) * static_cast<std::size_t>(width),
                          static_cast<std::size_t>(width));
    return runs;
}

std::size_t PixelCount(const Runs& runs) {
    std::size_t n = 0;
    for (const auto& r : runs) n += r.second;
    return n;
}

// The runs' pixels, array by array (depth, normal, surface, body), packed or unpacked.
template <bool kPack>
void Transfer(std::conditional_t<kPack, const Frame, Frame>& f, const Runs& runs, char* buffer) {
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
}

// The runs' image pixels: the 8-bit values, then Image::linear when the image has it.
std::size_t ImageBytes(const Image& image, const Runs& runs) {
    const std::size_t values = PixelCount(runs) * static_cast<std::size_t>(image.channels);
    const bool linear = image.linear.size() == image.pixels.size();
    return values * (1 + (linear ? sizeof(float) : 0));
}
template <bool kPack>
void TransferImage(std::conditional_t<kPack, const Image, Image>& image, const Runs& runs,
                   char* buffer) {
    const std::size_t ch = static_cast<std::size_t>(image.channels);
    auto move = [&](auto& array) {
        using T = typename std::remove_reference_t<decltype(array)>::value_type;
        for (const auto& [at, n] : runs) {
            if constexpr (kPack)
                std::memcpy(buffer, array.data() + at * ch, n * ch * sizeof(T));
            else
                std::memcpy(array.data() + at * ch, buffer, n * ch * sizeof(T));
            buffer += n * ch * sizeof(T);
        }
    };
    move(image.pixels);
    if (image.linear.size() == image.pixels.size()) move(image.linear);
}

// One whole message of `buffer` to or from `peer`, waited for.
void Exchange(bool send, std::vector<char>& buffer, int peer, int tag) {
    const MpiMessage m{send, buffer.data(), buffer.size(), peer, tag};
    Mpi().exchange(&m, 1);
}

// The rows of `from`'s bands that `to` reads around its own (its kRowHalo rows), ascending.
std::vector<int> HaloRows(int width, int height, int from, int to, int ranks) {
    const std::vector<std::uint8_t> kinds =
        RowKinds(SortFirstRows(width, height, to, ranks), height);
    std::vector<int> rows;
    for (int y = 0; y < height; ++y)
        if (kinds[static_cast<std::size_t>(y)] == kRowHalo &&
            (y / kSortFirstBandRows) % ranks == from)
            rows.push_back(y);
    return rows;
}

// Fills the Frame rows around this rank's bands (kShadeHaloRows each side) from the ranks that
// drew them, and sends them the rows of this rank's bands that they read: peer to peer, all
// messages posted at once.
void ExchangeHalo(Frame& frame, int rank, int ranks) {
    std::vector<std::vector<char>> out(static_cast<std::size_t>(ranks)),
        in(static_cast<std::size_t>(ranks));
    std::vector<Runs> inRuns(static_cast<std::size_t>(ranks));
    std::vector<MpiMessage> messages;
    for (int peer = 0; peer < ranks; ++peer) {
        if (peer == rank) continue;
        const auto p = static_cast<std::size_t>(peer);
        const Runs send =
            RowRuns(HaloRows(frame.width, frame.height, rank, peer, ranks), frame.width);
        out[p].resize(PixelCount(send) * kPixelBytes);
        Transfer<true>(frame, send, out[p].data());
        messages.push_back({true, out[p].data(), out[p].size(), peer, kHaloTag});
        inRuns[p] = RowRuns(HaloRows(frame.width, frame.height, peer, rank, ranks), frame.width);
        in[p].resize(PixelCount(inRuns[p]) * kPixelBytes);
        messages.push_back({false, in[p].data(), in[p].size(), peer, kHaloTag});
    }
    Mpi().exchange(messages.data(), messages.size());
    for (int peer = 0; peer < ranks; ++peer)
        if (peer != rank)
            Transfer<false>(frame, inRuns[static_cast<std::size_t>(peer)],
                            in[static_cast<std::size_t>(peer)].data());
}

// Every rank's bands of the Frame into rank 0's.
void GatherFrame(Frame& frame, int rank, int ranks) {
    const int width = frame.width, height = frame.height;
    if (rank != 0) {
        const Runs runs = RunsOf(frame, SortFirstRegion(width, height, rank, ranks));
        std::vector<char> buffer(PixelCount(runs) * kPixelBytes);
        Transfer<true>(frame, runs, buffer.data());
        Exchange(true, buffer, 0, kFrameTag);
        return;
    }
    for (int r = 1; r < ranks; ++r) {
        const Runs runs = RunsOf(frame, SortFirstRegion(width, height, r, ranks));
        std::vector<char> buffer(PixelCount(runs) * kPixelBytes);
        Exchange(false, buffer, r, kFrameTag);
        Transfer<false>(frame, runs, buffer.data());
    }
}

// Every rank's shaded rows into rank 0's image.
void GatherImage(Image& image, int rank, int ranks) {
    const int width = image.width, height = image.height;
    auto runsOf = [&](int r) {
        Runs runs;
        for (const RowSpan& s : SortFirstRows(width, height, r, ranks))
            for (int y = s.y0; y < s.y1; ++y)
                runs.emplace_back(static_cast<std::size_t>(y) * static_cast<std::size_t>(width),
                                  static_cast<std::size_t>(width));
        return runs;
    };
    if (rank != 0) {
        const Runs runs = runsOf(rank);
        std::vector<char> buffer(ImageBytes(image, runs));
        TransferImage<true>(image, runs, buffer.data());
        Exchange(true, buffer, 0, kImageTag);
        return;
    }
    for (int r = 1; r < ranks; ++r) {
        const Runs runs = runsOf(r);
        std::vector<char> buffer(ImageBytes(image, runs));
        Exchange(false, buffer, r, kImageTag);
        TransferImage<false>(image, runs, buffer.data());
    }
}

// Every rank draws its bands; false on every rank when one failed.
bool DrawBands(RenderContext& ctx, const EngineRequest& engine, Frame& frame, RenderReport& report,
               Diagnostics& diags, int rank, int ranks) {
    EngineRequest mine = engine;
    const int width = std::max(ctx.Flat().width, 0), height = std::max(ctx.Flat().height, 0);
    mine.region = SortFirstRegion(width, height, rank, ranks);
    // A Frame of the picture's size of which this rank writes only its bands (and the halo and,
    // on rank 0, the gathered bands): the engine leaves the rest unwritten (regionOnly), and
    // small pages keep its memory untouched there (frame.h AdviseSmallPages), so a rank faults
    // in about 1/N of the Frame, not all of it.
    mine.regionOnly = true;
    if (frame.width != width || frame.height != height) {
        frame.ResizeForOverwrite(width, height);
        AdviseSmallPages(frame);
    }
    const bool ok = ctx.Render(mine, frame, report, diags);
    return Mpi().allMin(ok ? 1 : 0) != 0;
}

}  // namespace

bool RenderSortFirst(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                     RenderReport& report, Diagnostics& diags) {
    const int ranks = MpiSize();
    if (ranks <= 1) return ctx.Render(engine, frame, report, diags);
    const int rank = MpiRank();
    if (!DrawBands(ctx, engine, frame, report, diags, rank, ranks)) return false;
    GatherFrame(frame, rank, ranks);
    return true;
}

bool RenderShadeSortFirst(RenderContext& ctx, const EngineRequest& engine,
                          const ShadeOptions& shade, bool needFrame, Frame& frame, Image& image,
                          RenderReport& report, Diagnostics& diags) {
    const int ranks = MpiSize();
    const bool fast = shade.fast || shade.model == ShadingModel::kFast;
    if (ranks <= 1 || fast) {
        // The fast model's mean normals are the whole picture's: rank 0 shades the gathered Frame.
        if (!RenderSortFirst(ctx, engine, frame, report, diags)) return false;
        if (MpiRank() == 0) image = ctx.Shade(frame, shade);
        return true;
    }
    const int rank = MpiRank();
    if (!DrawBands(ctx, engine, frame, report, diags, rank, ranks)) return false;
    ExchangeHalo(frame, rank, ranks);
    // The shading of RenderContext::Shade, on this rank's rows (shade/row_shading.h).
    ctx.InArena([&] {
        image = ShadeRows(frame, ctx.Flat(), shade,
                          SortFirstRows(frame.width, frame.height, rank, ranks));
    });
    if (needFrame) GatherFrame(frame, rank, ranks);
    GatherImage(image, rank, ranks);
    return true;
}

}  // namespace quadrix::batch
