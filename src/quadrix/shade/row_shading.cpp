#include "quadrix/shade/row_shading.h"

#include <algorithm>

#include "quadrix/shade/section_hatch.h"
#include "quadrix/util/check.h"

namespace quadrix {

std::vector<std::uint8_t> RowKinds(const std::vector<RowSpan>& spans, int height) {
    if (spans.empty()) return {};
    std::vector<std::uint8_t> kinds(static_cast<std::size_t>(std::max(height, 0)), 0);
    for (const RowSpan& s : spans)
        for (int y = std::max(s.y0 - kShadeHaloRows, 0);
             y < std::min(s.y1 + kShadeHaloRows, height); ++y)
            kinds[static_cast<std::size_t>(y)] = kRowHalo;
    for (const RowSpan& s : spans)
        for (int y = std::max(s.y0, 0); y < std::min(s.y1, height); ++y)
            kinds[static_cast<std::size_t>(y)] = kRowShaded;
    return kinds;
}

Image ShadeRows(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                const std::vector<RowSpan>& spans) {
    QUADRIX_CHECK(!options.fast && options.model != ShadingModel::kFast,
                  "the fast model shades the whole Frame (its mean normals)");
    // An empty list of spans shades nothing (RowKinds would read it as every row).
    const std::vector<std::uint8_t> rows =
        spans.empty() ? std::vector<std::uint8_t>(static_cast<std::size_t>(frame.height), 0)
                      : RowKinds(spans, frame.height);
    // The wide-node trees once for both passes (PixelShader).
    std::shared_ptr<const WideNodeTrees> wide =
        (options.shadows || options.aaSamples > 1) && options.spatialIndex
            ? WideNodeTrees::Shared(scene, true)
            : nullptr;
    Image image = ShadeRowKinds(frame, scene, options, rows, wide);
    if (options.aaSamples > 1) AntialiasRowKinds(frame, scene, options, image, rows, wide);
    if (options.hatch) HatchSectionRowKinds(frame, scene, options, image, rows);
    if (options.edges) DrawEdgeLinesRowKinds(frame, options, image, rows);
    return image;
}

}  // namespace quadrix
