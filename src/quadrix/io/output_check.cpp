#include "quadrix/io/output_check.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <fstream>

#include "quadrix/io/exr.h"
#include "quadrix/io/writers.h"

namespace quadrix {

namespace {

std::uint32_t BigEndian(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
           std::uint32_t{p[3]};
}

std::string SizeMismatch(long long w, long long h, int width, int height) {
    return fmt::format("{}×{} pixels, not {}×{}", w, h, width, height);
}

std::string CheckPng(std::ifstream& in, long long length, int width, int height) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    unsigned char head[24] = {};
    if (length < 24 + 12 || !in.read(reinterpret_cast<char*>(head), 24) ||
        std::memcmp(head, kSignature, 8) != 0 || std::memcmp(head + 12, "IHDR", 4) != 0)
        return "not a PNG file";
    const std::uint32_t w = BigEndian(head + 16), h = BigEndian(head + 20);
    if (w != static_cast<std::uint32_t>(width) || h != static_cast<std::uint32_t>(height))
        return SizeMismatch(w, h, width, height);
    unsigned char tail[12] = {};
    in.seekg(length - 12);
    if (!in.read(reinterpret_cast<char*>(tail), 12) || std::memcmp(tail, kIend, 12) != 0)
        return "incomplete (no IEND chunk at the end)";
    return {};
}

std::string CheckPnm(std::ifstream& in, long long length, int width, int height) {
    char magic[3] = {};
    int w = 0, h = 0, max = 0;
    if (!in.read(magic, 2) || magic[0] != 'P' || (magic[1] != '5' && magic[1] != '6') ||
        !(in >> w >> h >> max) || max <= 0 || max > 65535 || in.get() != '\n')
        return "not a binary PGM/PPM file";
    if (w != width || h != height) return SizeMismatch(w, h, width, height);
    const long long samples = static_cast<long long>(w) * h * (magic[1] == '6' ? 3 : 1);
    const long long expected = static_cast<long long>(in.tellg()) + samples * (max > 255 ? 2 : 1);
    if (length != expected) return fmt::format("incomplete ({} bytes, not {})", length, expected);
    return {};
}

std::string CheckFrameDump(std::ifstream& in, long long length, int width, int height) {
    std::string magic;
    int w = 0, h = 0;
    if (!(in >> magic >> w >> h) || magic != "QXF1") return "not a Quadrix frame dump";
    if (w != width || h != height) return SizeMismatch(w, h, width, height);
    char last = 0;
    in.clear();
    in.seekg(length - 1);
    if (!in.get(last) || last != '\n') return "incomplete (the last line does not end)";
    return {};
}

}  // namespace

std::string CheckCompleteOutput(const std::string& path, int width, int height) {
    ImageFormat format;
    if (!ImageFormatFromPath(path, format)) return "of an unknown format";
    if (format == ImageFormat::kExr) return CheckExrFile(path, width, height);
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot be read";
    in.seekg(0, std::ios::end);
    const long long length = static_cast<long long>(in.tellg());
    in.seekg(0);
    if (length <= 0) return "empty";
    switch (format) {
        case ImageFormat::kPng:
            return CheckPng(in, length, width, height);
        case ImageFormat::kPnm:
            return CheckPnm(in, length, width, height);
        case ImageFormat::kFrameDump:
            return CheckFrameDump(in, length, width, height);
        default:
            return {};
    }
}

}  // namespace quadrix
