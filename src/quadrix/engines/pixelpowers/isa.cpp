#include "quadrix/engines/pixelpowers/isa.h"

#include <algorithm>
#include <cstdio>

namespace quadrix::pixelpowers {

const char* OpcodeName(Opcode op) {
    switch (op) {
        case Opcode::kFlagSet:
            return "FSET";
        case Opcode::kFlagClear:
            return "FCLR";
        case Opcode::kFlagCopy:
            return "FCOPY";
        case Opcode::kFlagAnd:
            return "FAND";
        case Opcode::kFlagAndNot:
            return "FANDN";
        case Opcode::kFlagOr:
            return "FOR";
        case Opcode::kQeeKeepPositive:
            return "QPOS";
        case Opcode::kQeeKeepNonPositive:
            return "QNPOS";
        case Opcode::kZLoad:
            return "ZLOAD";
        case Opcode::kZMax:
            return "ZMAX";
        case Opcode::kZMin:
            return "ZMIN";
        case Opcode::kZKeepGE:
            return "ZGE";
        case Opcode::kZKeepLE:
            return "ZLE";
        case Opcode::kZKeepGT:
            return "ZGT";
        case Opcode::kZKeepLT:
            return "ZLT";
        case Opcode::kRoot:
            return "ROOT";
        case Opcode::kInside:
            return "INSIDE";
        case Opcode::kZTest:
            return "ZTEST";
        case Opcode::kZWrite:
            return "ZWRITE";
        case Opcode::kNLoad:
            return "NLOAD";
    }
    return "?";
}

PixelRect PixelRect::Intersected(const PixelRect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
}

int Instruction::Equations(bool literalIsPlane) const {
    switch (op) {
        case Opcode::kQeeKeepPositive:
        case Opcode::kQeeKeepNonPositive:
        case Opcode::kZLoad:
        case Opcode::kZMax:
        case Opcode::kZMin:
        case Opcode::kZKeepGE:
        case Opcode::kZKeepLE:
        case Opcode::kZKeepGT:
        case Opcode::kZKeepLT:
        case Opcode::kNLoad:
            return 1;
        case Opcode::kRoot:
        case Opcode::kInside:
            return literalIsPlane ? 1 : 2;
        default:
            return 0;
    }
}

std::uint64_t Program::Equations() const {
    std::uint64_t n = 0;
    for (const Instruction& in : code) {
        bool plane = in.arg >= 0 && static_cast<std::size_t>(in.arg) < literals.size() &&
                     literals[static_cast<std::size_t>(in.arg)].isPlane;
        n += static_cast<std::uint64_t>(in.Equations(plane));
    }
    return n;
}

std::string Program::Disassemble(std::size_t maxInstructions) const {
    std::string s;
    char line[256];
    std::size_t shown = 0;
    for (const Block& b : blocks) {
        std::snprintf(line, sizeof line, "block [%d,%d)x[%d,%d)\n", b.rect.x0, b.rect.x1, b.rect.y0,
                      b.rect.y1);
        s += line;
        for (std::int32_t k = b.first; k < b.first + b.count; ++k) {
            if (shown++ >= maxInstructions) return s + "...\n";
            const Instruction& in = code[static_cast<std::size_t>(k)];
            if (in.op == Opcode::kNLoad) {
                std::snprintf(line, sizeof line, "  %-6s F%d N%d\n", OpcodeName(in.op), in.a + 1,
                              in.b);
            } else {
                std::snprintf(line, sizeof line, "  %-6s F%d F%d arg=%d\n", OpcodeName(in.op),
                              in.a + 1, in.b + 1, in.arg);
            }
            s += line;
        }
    }
    return s;
}

}  // namespace quadrix::pixelpowers
