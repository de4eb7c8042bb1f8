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

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/math/vec.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

struct ImportOptions {
    // Objects to draw; empty = every top-level object (referenced by no combination). "all" that
    // names no object also means every top-level object.
    std::vector<std::string> topObjects;
    // Nothing is dropped silently (docs/import.md): a primitive reached from the top objects that
    // cannot be drawn (tor, eto, pipe, quartic tgc, an OpenSCAD statement with no exact form, ...)
    // is an error naming it and its source line, unless allowMissing, which draws the rest and
    // reports the left-out primitives as a warning and in ImportReport::skipped. strict (the old
    // --strict) forces the error even with allowMissing.
    bool strict = false;
    bool allowMissing = false;
    bool MissingIsError() const { return strict || !allowMissing; }
};

struct ImportReport {
    std::string format;  // "BRL-CAD v4", "BRL-CAD v5", "COMGEOM", "OpenSCAD CSG"
    std::string title;
    std::map<std::string, int> census;     // every primitive in the file, by type
    std::map<std::string, int> skipped;    // primitives reached from the top objects, not drawn
    int solids = 0;                        // CSG solids added to the scene (rendered regions)
    Box3 bounds;                           // Quadrix coordinates, bounded solids only
    std::vector<std::string> topObjects;   // the objects actually drawn
    std::vector<std::string> missingTops;  // requested names absent from this file

    // "census: arb8 12, ell 3, tgc 4" (sorted by type name).
    std::string CensusText() const;
    // "tor ×11, tgc (quartic) ×2" or empty.
    std::string SkippedText() const;
};

// Reads a BRL-CAD text database (format detected from the content) into `scene`.
bool ImportBrlcad(std::string_view text, const std::string& file, const ImportOptions& options,
                  scene::Scene& scene, Diagnostics& diags, ImportReport& report);

}  // namespace quadrix::import
