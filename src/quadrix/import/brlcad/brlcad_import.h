// BRL-CAD ASCII databases (v4 records, v5 `put` scripts, COMGEOM decks) → scene::Scene, exactly:
// every quadric/planar primitive becomes Quadrix half-spaces, every rendered region a CSG solid
// of the top-level scope (docs/import.md; FORMAT.md in shared/data/brlcad).
//
// What is drawn follows rt (FORMAT.md §5): walking down from the top objects, the first region on
// each path is a region leaf and everything below it its CSG tree; booleans above the region level
// are distributed over unions (db_non_union_push), and each term of the resulting union is one
// solid named after its left-most region, with that region's colour (§5.5: inherit locks a colour
// from above, then the region's own rgb, then the colour table by region id). Air regions and
// envmap regions are skipped. Member matrices compose along the path (m15 = inverse scale).
//
// Coordinates: BRL-CAD is right-handed with Z up, Quadrix's viewing frame is left-handed with y up
// (scene.h View), so the importer maps (x, y, z) → (x, z, y) (QuadrixFromZUp in model_space.h): a
// reflection, which makes Quadrix views show what rt shows instead of its mirror image.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "quadrix/import/import_report.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

// Reads a BRL-CAD text database (format detected from the content) into `scene`.
bool ImportBrlcad(std::string_view text, const std::string& file, const ImportOptions& options,
                  scene::Scene& scene, Diagnostics& diags, ImportReport& report);

}  // namespace quadrix::import
