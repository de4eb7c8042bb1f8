#include "quadrix/pipeline/output.h"

#include <fmt/format.h>

#include <filesystem>
#include <optional>

#include "quadrix/io/output_file.h"

namespace quadrix {

std::string CheckOutputs(const OutputRequest& request) {
    ImageFormat format;
    if (!ImageFormatFromPath(request.image, format))
        return fmt::format(
            "cannot tell the image format of '{}' (use .png, .pgm, .ppm, .pnm or .qxf)",
            request.image);
    // Never a device, FIFO, directory or file already read (io/output_file.h).
    if (auto e =
            CheckOutputPaths({request.image, request.dumpFrame.empty() ? "-" : request.dumpFrame});
        !e.empty())
        return e;
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
    // Both outputs go to temporary files first and are renamed together (io/output_file.h), so a
    // failed dump never follows a written image.
    OutputFile main(request.image);
    std::optional<OutputFile> dump;
    if (!request.dumpFrame.empty()) dump.emplace(request.dumpFrame);
    std::string error;
    if (format == ImageFormat::kFrameDump)
        error = WriteFrameDump(main, frame);
    else if (!image)
        error = "internal error: no image to write";
    else if (format == ImageFormat::kPng)
        error = WritePng(main, *image, request.png);
    else
        error = WritePnm(main, *image);
    if (error.empty() && dump) error = WriteFrameDump(*dump, frame);
    if (error.empty()) error = dump ? CommitAll({&main, &*dump}) : CommitAll({&main});
    return error;
}

}  // namespace quadrix
