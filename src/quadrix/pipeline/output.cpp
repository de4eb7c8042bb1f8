#include "quadrix/pipeline/output.h"

#include <fmt/format.h>

#include <filesystem>

namespace quadrix {

std::string CheckOutputs(const OutputRequest& request) {
    ImageFormat format;
    if (!ImageFormatFromPath(request.image, format))
        return fmt::format(
            "cannot tell the image format of '{}' (use .png, .pgm, .ppm, .pnm or .qxf)",
            request.image);
    if (!request.dumpFrame.empty()) {
        ImageFormat dump;
        if (!ImageFormatFromPath(request.dumpFrame, dump) || dump != ImageFormat::kFrameDump)
            return fmt::format("--dump-frame: '{}' is not a .qxf file", request.dumpFrame);
        std::error_code ec;
        if (request.dumpFrame == request.image ||
            std::filesystem::weakly_canonical(request.dumpFrame, ec) ==
                std::filesystem::weakly_canonical(request.image, ec))
            return fmt::format("--dump-frame and -o name the same file '{}'", request.image);
    }
    return {};
}

bool NeedsImage(const OutputRequest& request) {
    ImageFormat format;
    return ImageFormatFromPath(request.image, format) && format != ImageFormat::kFrameDump;
}

std::string WriteOutputs(const OutputRequest& request, const Frame& frame, const Image* image) {
    if (auto e = CheckOutputs(request); !e.empty()) return e;
    ImageFormat format;
    ImageFormatFromPath(request.image, format);
    std::string error;
    if (format == ImageFormat::kFrameDump)
        error = WriteFrameDump(request.image, frame);
    else if (!image)
        error = "internal error: no image to write";
    else if (format == ImageFormat::kPng)
        error = WritePng(request.image, *image);
    else
        error = WritePnm(request.image, *image);
    if (error.empty() && !request.dumpFrame.empty()) error = WriteFrameDump(request.dumpFrame, frame);
    return error;
}

}  // namespace quadrix
