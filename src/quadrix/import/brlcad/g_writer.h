// Database → BRL-CAD binary v5 database (".g"), the layout of g_format.h: the inverse of
// g_reader.cpp for every object the Database can hold with its parameters (arb8, tgc, ell, half,
// arbn, part, rpc, rhc, epa, ehy, eto, tor, hyp, bot, combinations with their trees, matrices,
// region flags, ids and colours, the title and the colour table). Combinations whose tree is all
// unions are written as BRL-CAD writes them (rpn_len = 0, leaves in order). Used by the tests to
// turn the ASCII samples into .g files, and usable as `asc2g` without BRL-CAD.
#pragma once

#include <optional>
#include <string>

#include "quadrix/import/brlcad/database.h"

namespace quadrix::import::brlcad {

// The .g bytes, or nullopt with *error set (a primitive type whose parameters the Database does
// not keep, such as dsp or superell, cannot be written).
std::optional<std::string> WriteG(const Database& db, std::string* error);

}  // namespace quadrix::import::brlcad
