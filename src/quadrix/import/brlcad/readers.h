// The three BRL-CAD text readers (FORMAT.md §2 v4 records, §3 v5 `put` script, §4 COMGEOM deck).
// They fill a Database and report problems with file:line:column; the converter does the rest.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/import/brlcad/database.h"
#include "quadrix/import/text_map.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::import::brlcad {

enum class TextFormat { kV4, kV5, kComgeom, kUnknown };

// By content: "I <units> v4" on the first line → v4; a first command title/units/put/attr/color
// → v5; a second line of two integers (solid and region counts) → COMGEOM.
TextFormat DetectFormat(std::string_view text);

bool ParseV4(std::string_view text, const std::string& file, Database& db, Diagnostics& diags);
bool ParseV5(std::string_view text, const std::string& file, Database& db, Diagnostics& diags);
bool ParseComgeom(std::string_view text, const std::string& file, Database& db, Diagnostics& diags);

// The binary v5 database (g_reader.cpp; layout in g_format.h). IsV5Binary: the file starts with
// the v5 header object (76 01 .. 35).
bool IsV5Binary(std::string_view bytes);
bool ParseG(std::string_view bytes, const std::string& file, Database& db, Diagnostics& diags);

// One member of a GIFT-precedence list (v4 'M' records, COMGEOM region cards).
struct GiftMember {
    char op = 'u';  // 'u' union, '+' intersection, '-' difference
    std::string name;
    Mat4 matrix = Mat4::Identity();
    SourceLoc loc;
};
// + and - bind tighter than u; the first operator counts as a union (FORMAT.md §2.4).
void BuildGiftTree(Combination& comb, const std::vector<GiftMember>& members);

}  // namespace quadrix::import::brlcad
