#include "quadrix/lang/keywords.h"

#include <array>
#include <cstdint>

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

// Which (length, first letter) pairs some spelling has: most words the lexer reads are ids
// (q12345), and this rules them out before any comparison.
constexpr std::size_t kMaxLength = 10;
struct Starts {
    std::array<std::uint32_t, kMaxLength + 1> lettersOfLength{};  // bit c - 'a'
    constexpr Starts() {
        for (const Spelling& s : kSpellings)
            lettersOfLength[s.word.size()] |= 1u << (s.word[0] - 'a');
    }
};
constexpr Starts kStarts;
static_assert([] {
    for (const Spelling& s : kSpellings)
        if (s.word.empty() || s.word.size() > kMaxLength || s.word[0] < 'a' || s.word[0] > 'z')
            return false;
    return true;
}());

}  // namespace

Keyword LookupKeyword(std::string_view word) {
    if (word.empty() || word.size() > kMaxLength || word[0] < 'a' || word[0] > 'z' ||
        !(kStarts.lettersOfLength[word.size()] >> (word[0] - 'a') & 1u))
        return Keyword::kNone;
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
