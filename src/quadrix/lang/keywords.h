// The reserved words of the UniQuadrix language and their synonyms (seed 001 §2.1.9), plus the
// words of the interactive statements (§2.3) and of the Quadrix CSG extension (docs/language.md).
//
// Keywords are lower case and case-sensitive. Every keyword and every synonym is reserved: none
// may be used as an id (§2.1.9 "All keywords and synonyms are reserved from use as id's").
#pragma once

#include <string_view>

namespace quadrix::lang {

enum class Keyword {
    kNone,
    // Statements (seed 001 §2.1, §2.3) and the CSG extension.
    kPlane,
    kQuadric,
    kBody,
    kDefinition,
    kEnddef,
    kInstance,
    kArray,
    kLight,
    kView,
    kRead,
    kDevice,
    kRedef,
    kShow,
    kQuit,
    kCsg,
    kSolid,   // solids by dimensions (extension, stmt_solids.cpp)
    kPatch,   // quadric patch (extension, stmt_patch.cpp)
    kBezier,  // freeform surfaces (extension, stmt_freeform.cpp)
    kBspline,
    kPatches,
    kBackground,  // background color or gradient (extension, stmt_background.cpp)
    // View parameters (§2.1.6).
    kVrp,
    kVpn,
    kVup,
    kDop,
    kCop,
    kWhh,
    kWhw,
    kFbp,
    // Words inside interactive statements (§2.3).
    kFast,
    kKeep,
    kNokeep,
    kXsize,
    kYsize,
    kCount  // number of entries; not a keyword
};

// The keyword spelled `word` (a keyword or one of its synonyms), or kNone.
Keyword LookupKeyword(std::string_view word);
// The canonical spelling ("array" for Keyword::kArray).
std::string_view KeywordName(Keyword keyword);
// True for the view parameters vrp, vpn, vup, dop, cop, whh, whw, fbp.
bool IsViewParameter(Keyword keyword);

}  // namespace quadrix::lang
