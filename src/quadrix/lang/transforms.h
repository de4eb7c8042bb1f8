// The transforms of instance and array statements (seed 001 §2.1.4):
//
//   =tx =ty =tz =ta d   translate by d along x, y, z, or all three axes
//   =sx =sy =sz =sa s   scale by s on x, y, z, or all three axes (s != 0)
//   =rx =ry =rz a       rotate by a degrees about x, y or z (about z +x turns toward +y; exact
//                       for 90° steps; docs/language.md §2 on handedness)
//   =vAB s              shear: s along the second axis B for each unit along the first axis A,
//                       i.e. B += s·A (=vxy 0.5 maps (1,0,0) to (1,0.5,0))
//
// "Transformations are concatenated left to right": the leftmost is applied to points first, so
// `=tx 2 =ry 90` translates, then rotates: M = T_n ⋯ T_2 T_1.
#pragma once

#include <string_view>

#include "quadrix/math/mat4.h"

namespace quadrix::lang {

class Parser;

// True when `name` (an option without '=') is one of the transforms above.
bool IsTransformOption(std::string_view name);

// Reads consecutive transform options, each with its number, composing them after `m`
// (m ← T · m for each T in order). Stops at the first token that is not a transform option.
// Returns false on a syntax error (reported); value errors (zero scale, overflow) are reported and
// the transform is skipped.
bool ParseTransforms(Parser& p, Transform& m);

}  // namespace quadrix::lang
