#include "quadrix/lang/transforms.h"

#include <fmt/format.h>

#include <array>

#include "quadrix/lang/parser.h"

namespace quadrix::lang {

namespace {

struct TransformSpec {
    std::string_view name;
    Transform (*make)(double value);
    bool isScale;  // a zero value would be singular
};

constexpr int kX = 0, kY = 1, kZ = 2;

// Shear "=v<from><to>": coordinate `to` grows by value times coordinate `from`.
template <int From, int To>
Transform MakeShear(double v) {
    return Transform::Shear(To, From, v);
}
template <int Axis>
Transform MakeRotate(double degrees) {
    return Transform::Rotate(Axis, degrees);
}

const std::array kTransforms = {
    TransformSpec{"tx",
                  [](double v) {
                      return Transform::Translate({v, 0, 0});
                  },
                  false},
    TransformSpec{"ty",
                  [](double v) {
                      return Transform::Translate({0, v, 0});
                  },
                  false},
    TransformSpec{"tz",
                  [](double v) {
                      return Transform::Translate({0, 0, v});
                  },
                  false},
    TransformSpec{"ta",
                  [](double v) {
                      return Transform::Translate({v, v, v});
                  },
                  false},
    TransformSpec{"sx",
                  [](double v) {
                      return Transform::Scale({v, 1, 1});
                  },
                  true},
    TransformSpec{"sy",
                  [](double v) {
                      return Transform::Scale({1, v, 1});
                  },
                  true},
    TransformSpec{"sz",
                  [](double v) {
                      return Transform::Scale({1, 1, v});
                  },
                  true},
    TransformSpec{"sa",
                  [](double v) {
                      return Transform::Scale({v, v, v});
                  },
                  true},
    TransformSpec{"rx", MakeRotate<kX>, false},
    TransformSpec{"ry", MakeRotate<kY>, false},
    TransformSpec{"rz", MakeRotate<kZ>, false},
    TransformSpec{"vxy", MakeShear<kX, kY>, false},
    TransformSpec{"vxz", MakeShear<kX, kZ>, false},
    TransformSpec{"vyx", MakeShear<kY, kX>, false},
    TransformSpec{"vyz", MakeShear<kY, kZ>, false},
    TransformSpec{"vzx", MakeShear<kZ, kX>, false},
    TransformSpec{"vzy", MakeShear<kZ, kY>, false},
};

const TransformSpec* FindTransform(std::string_view name) {
    for (const TransformSpec& t : kTransforms)
        if (t.name == name) return &t;
    return nullptr;
}

}  // namespace

bool IsTransformOption(std::string_view name) { return FindTransform(name) != nullptr; }

bool ParseTransforms(Parser& p, Transform& m) {
    while (p.PeekIs(TokenKind::kOption)) {
        const TransformSpec* spec = FindTransform(p.Peek().text);
        if (!spec) return true;  // not a transform: the caller decides what it is
        Token option = p.Take();
        SourceLoc valueLoc = p.Peek().loc;
        auto value = p.ExpectNumber(fmt::format("a number after {}", Describe(option)));
        if (!value) return false;
        if (spec->isScale && *value == 0) {
            p.Error(valueLoc, fmt::format("scale factor 0 in {} would flatten the definition "
                                          "(a singular transform)",
                                          Describe(option)));
            continue;
        }
        Transform next = spec->make(*value) * m;
        if (!next.Matrix().AllFinite() || !next.Inverse().AllFinite()) {
            p.Error(option.loc,
                    fmt::format("{} {} makes the transform overflow", Describe(option), *value));
            continue;
        }
        m = next;
    }
    return true;
}

}  // namespace quadrix::lang
