// What every importer is asked (which objects to draw, what to do with what it cannot draw) and
// what it reports back (format, census of primitives, what was left out, bounds); shared by the
// BRL-CAD and OpenSCAD importers and printed by the front ends.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "quadrix/math/vec.h"

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

}  // namespace quadrix::import
