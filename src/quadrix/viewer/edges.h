// Show-edges over the shading (issue 18 §5, the viewer's `L` key), in image space from the exact
// Frame: a pixel is on an edge when its surface id differs from its right or lower neighbour's
// (a crease or intersection curve between two half-spaces, or a silhouette against another
// surface or the background). The ids come from the exact engines, so the lines follow the true
// curves to the pixel; they are one pixel wide and drawn black.
#pragma once

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

namespace quadrix::viewer {

// Darkens the edge pixels of `image` (same size as `frame`); returns how many.
int DrawEdges(const Frame& frame, Image& image);

}  // namespace quadrix::viewer
