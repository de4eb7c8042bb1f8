#include "quadrix/lang/keywords.h"

#include <array>

namespace quadrix::lang {

namespace {

struct Spelling {
    std::string_view word;
    Keyword keyword;
};

// Canonical names first (KeywordName returns the first spelling of each keyword), then the
// synonyms of seed 001 §2.1.9: array=a, body=b, definition=def, device=dev, instance=i,
// read=include, enddef=end, light=l, plane=p, quadric=q, view=vw, cop=ep, dop=ed, vrp=vc.
constexpr std::array kSpellings = {
    Spelling{"plane", Keyword::kPlane},
    Spelling{"quadric", Keyword::kQuadric},
    Spelling{"body", Keyword::kBody},
    Spelling{"definition", Keyword::kDefinition},
    Spelling{"enddef", Keyword::kEnddef},
    Spelling{"instance", Keyword::kInstance},
    Spelling{"array", Keyword::kArray},
    Spelling{"light", Keyword::kLight},
    Spelling{"view", Keyword::kView},
    Spelling{"read", Keyword::kRead},
    Spelling{"device", Keyword::kDevice},
    Spelling{"redef", Keyword::kRedef},
    Spelling{"show", Keyword::kShow},
    Spelling{"quit", Keyword::kQuit},
    Spelling{"csg", Keyword::kCsg},
    Spelling{"patch", Keyword::kPatch},
    Spelling{"bezier", Keyword::kBezier},
    Spelling{"bspline", Keyword::kBspline},
    Spelling{"patches", Keyword::kPatches},
    Spelling{"solid", Keyword::kSolid},
    Spelling{"background", Keyword::kBackground},
    Spelling{"vrp", Keyword::kVrp},
    Spelling{"vpn", Keyword::kVpn},
    Spelling{"vup", Keyword::kVup},
    Spelling{"dop", Keyword::kDop},
    Spelling{"cop", Keyword::kCop},
    Spelling{"whh", Keyword::kWhh},
    Spelling{"whw", Keyword::kWhw},
    Spelling{"fbp", Keyword::kFbp},
    Spelling{"fast", Keyword::kFast},
    Spelling{"keep", Keyword::kKeep},
    Spelling{"nokeep", Keyword::kNokeep},
    Spelling{"xsize", Keyword::kXsize},
    Spelling{"ysize", Keyword::kYsize},
    // Synonyms.
    Spelling{"a", Keyword::kArray},
    Spelling{"b", Keyword::kBody},
    Spelling{"def", Keyword::kDefinition},
    Spelling{"dev", Keyword::kDevice},
    Spelling{"i", Keyword::kInstance},
    Spelling{"include", Keyword::kRead},
    Spelling{"end", Keyword::kEnddef},
    Spelling{"l", Keyword::kLight},
    Spelling{"p", Keyword::kPlane},
    Spelling{"q", Keyword::kQuadric},
    Spelling{"vw", Keyword::kView},
    Spelling{"ep", Keyword::kCop},
    Spelling{"ed", Keyword::kDop},
    Spelling{"vc", Keyword::kVrp},
};

}  // namespace

Keyword LookupKeyword(std::string_view word) {
    // About forty entries: a linear scan is as fast as a hash here and keeps the table readable.
    for (const Spelling& s : kSpellings)
        if (s.word == word) return s.keyword;
    return Keyword::kNone;
}

std::string_view KeywordName(Keyword keyword) {
    for (const Spelling& s : kSpellings)
        if (s.keyword == keyword) return s.word;
    return "?";
}

bool IsViewParameter(Keyword keyword) {
    return keyword >= Keyword::kVrp && keyword <= Keyword::kFbp;
}

}  // namespace quadrix::lang
