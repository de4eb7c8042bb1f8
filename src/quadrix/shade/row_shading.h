// Shading part of a picture: the rows one process shades in sort-first rendering (issue 22,
// batch/sort_first.h), each pixel getting the same bits as in a shading of the whole Frame.
//
// A pixel's shading (shader.h) reads only its own Frame entry, but the anti-aliasing and the edge
// lines (antialias.h) compare 4-neighbours and the pixels beyond them: the edge bits of a row
// depend on the Frame up to kShadeHaloRows = 2 rows away and, with shadows (the shadow-boundary
// test, FindEdgesAndShadingJumps), on the base shading of those rows. So ShadeRows needs the Frame
// to hold the picture's pixels on the rows and on the two rows around each span (the halo); it
// base-shades the halo rows when the shadow-boundary test reads them, and finds edges, resamples
// and draws edge lines on the rows only. The image's other rows are left unset. The fast model is
// not local (its normal per surface is the mean over the whole Frame): for it the caller shades the
// whole Frame.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/shade/antialias.h"
#include "quadrix/shade/shader.h"

namespace quadrix {

// Image rows [y0, y1).
struct RowSpan {
    int y0 = 0, y1 = 0;
};

// How far around a pixel its shading looks (antialias.h: a pair and the pixel beyond each side).
constexpr int kShadeHaloRows = 2;

// Per image row: kRowShaded for the rows of `spans`, kRowHalo for the kShadeHaloRows rows around
// them that are not themselves shaded, 0 for the rest. Empty `spans`: every row is shaded (the
// result is then empty too, which every *Rows function below reads as "every row").
constexpr std::uint8_t kRowShaded = 2, kRowHalo = 1;
std::vector<std::uint8_t> RowKinds(const std::vector<RowSpan>& spans, int height);

// Whether row y of `rows` (from RowKinds; empty: every row) is shaded.
inline bool RowShaded(const std::vector<std::uint8_t>& rows, int y) {
    return rows.empty() || rows[static_cast<std::size_t>(y)] == kRowShaded;
}
// Whether row y is read at all (shaded, or in the halo around shaded rows).
inline bool RowRead(const std::vector<std::uint8_t>& rows, int y) {
    return rows.empty() || rows[static_cast<std::size_t>(y)] != 0;
}

// What RenderContext::Shade does (Shade, then Antialias when options.aaSamples > 1, then
// HatchSection when options.hatch, then DrawEdgeLines when options.edges), on the rows of `spans`
// only. options must not ask for the fast model.
Image ShadeRows(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                const std::vector<RowSpan>& spans);

// The row-limited forms of Shade, Antialias and DrawEdgeLines that the whole-picture ones call
// with empty `rows` (from RowKinds).
// `wide`: the flat scene's wide-node trees (PixelShader), or null.
Image ShadeRowKinds(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                    const std::vector<std::uint8_t>& rows,
                    std::shared_ptr<const WideNodeTrees> wide = nullptr);
AntialiasStats AntialiasRowKinds(const Frame& frame, const FlatScene& scene,
                                 const ShadeOptions& options, Image& image,
                                 const std::vector<std::uint8_t>& rows,
                                 std::shared_ptr<const WideNodeTrees> wide = nullptr);
std::size_t DrawEdgeLinesRowKinds(const Frame& frame, const ShadeOptions& options, Image& image,
                                  const std::vector<std::uint8_t>& rows);

}  // namespace quadrix
