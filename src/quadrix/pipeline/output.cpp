#include "quadrix/pipeline/output.h"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <vector>

#include "quadrix/io/exr.h"
#include "quadrix/io/output_file.h"

namespace quadrix {

bool OutputFormat(const OutputRequest& request, ImageFormat& format, PnmKind& pnm) {
    pnm = PnmKind::kFromPath;
    if (request.format.empty()) {
        if (request.image == "-") {
            format = ImageFormat::kPng;
            return true;
        }
        return ImageFormatFromPath(request.image, format);
    }
    if (request.format == "pnm") {
        format = ImageFormat::kPnm;
        pnm = PnmKind::kAsImage;
        return true;
    }
    if (!ImageFormatFromPath("x." + request.format, format)) return false;
    if (request.format == "ppm") pnm = PnmKind::kColor;
    if (request.format == "pgm") pnm = PnmKind::kGray;
    return true;
}

std::string CheckOutputs(const OutputRequest& request) {
    ImageFormat format;
    PnmKind pnm;
    if (!request.format.empty() && !OutputFormat(request, format, pnm))
        return fmt::format("--format: unknown format '{}' (png, ppm, pgm, pnm, exr or qxf)",
                           request.format);
    if (!OutputFormat(request, format, pnm))
        return fmt::format(
            "cannot tell the image format of '{}' (use .png, .pgm, .ppm, .pnm, .exr or .qxf, or "
            "--format)",
            request.image);
    if (format == ImageFormat::kExr && !HaveOpenExr()) return OpenExrUnavailable();
    // Never a device, FIFO, directory or file already read (io/output_file.h).
    if (auto e =
            CheckOutputPaths({request.image, request.dumpFrame.empty() ? "-" : request.dumpFrame});
        !e.empty())
        return e;
    if (!request.exr.empty()) {
        ImageFormat exr;
        if (!ImageFormatFromPath(request.exr, exr) || exr != ImageFormat::kExr)
            return fmt::format("exr output: '{}' is not a .exr file", request.exr);
        if (!HaveOpenExr()) return OpenExrUnavailable();
        if (auto e = CheckOutputPaths({request.exr}); !e.empty()) return e;
        std::error_code ec;
        for (const std::string* other : {&request.image, &request.dumpFrame})
            if (*other == request.exr || std::filesystem::weakly_canonical(request.exr, ec) ==
                                             std::filesystem::weakly_canonical(*other, ec))
                return fmt::format("the exr output and another output name the same file '{}'",
                                   request.exr);
    }
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
    PnmKind pnm;
    return !request.exr.empty() ||
           (OutputFormat(request, format, pnm) && format != ImageFormat::kFrameDump);
}

bool NeedsLinear(const OutputRequest& request) {
    ImageFormat format;
    PnmKind pnm;
    if (!OutputFormat(request, format, pnm)) return true;
    return !request.exr.empty() || format == ImageFormat::kExr ||
           (format == ImageFormat::kPng && request.png.bitDepth == 16);
}

bool NeedsFrame(const OutputRequest& request) {
    ImageFormat format;
    PnmKind pnm;
    if (!OutputFormat(request, format, pnm)) return true;
    return !request.dumpFrame.empty() || !request.exr.empty() ||
           format == ImageFormat::kFrameDump || format == ImageFormat::kExr;
}

std::string WriteOutputs(const OutputRequest& request, const Frame& frame, const Image* image) {
    if (auto e = CheckOutputs(request); !e.empty()) return e;
    ImageFormat format;
    PnmKind pnm;
    OutputFormat(request, format, pnm);
    // Both outputs go to temporary files first and are renamed together (io/output_file.h), so a
    // failed dump never follows a written image.
    OutputFile main(request.image);
    std::optional<OutputFile> dump;
    if (!request.dumpFrame.empty()) dump.emplace(request.dumpFrame);
    std::optional<OutputFile> exr;
    if (!request.exr.empty()) exr.emplace(request.exr);
    std::string error;
    if (format == ImageFormat::kFrameDump)
        error = WriteFrameDump(main, frame);
    else if (format == ImageFormat::kExr)
        error = WriteExr(main, frame, image);
    else if (!image)
        error = "internal error: no image to write";
    else if (format == ImageFormat::kPng)
        error = WritePng(main, *image, request.png);
    else
        error = WritePnm(main, *image, pnm);
    if (error.empty() && dump) error = WriteFrameDump(*dump, frame);
    if (error.empty() && exr) error = WriteExr(*exr, frame, image);
    if (error.empty()) {
        std::vector<OutputFile*> files{&main};
        if (dump) files.push_back(&*dump);
        if (exr) files.push_back(&*exr);
        error = CommitAll(files);
    }
    return error;
}

}  // namespace quadrix
