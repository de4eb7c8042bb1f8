// OpenEXR output; see exr.h for the channel layout. The channels are prepared here; the module
// quadrix-exr.so writes them with OpenEXR (io/exr_module.h).
#include "quadrix/io/exr.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "quadrix/io/exr_module.h"
#include "quadrix/util/module_loader.h"

// Null unless the module's source is linked into this target (quadrix_modules_linked); the
// program loads quadrix-exr.so instead (util/module_loader.h).
#pragma weak quadrix_exr_module

namespace quadrix {

namespace {

struct Loaded {
    const ExrModule* module = nullptr;
    std::string error;  // why module is null
};

const Loaded& Module() {
    static const Loaded loaded = [] {
        Loaded l;
#ifndef QUADRIX_HAVE_OPENEXR
        l.error =
            "this quadrix was built without OpenEXR: .exr output is not available (install "
            "libopenexr-dev and rebuild; see docs/dependencies.md)";
        return l;
#else
        if (quadrix_exr_module) {
            l.module = quadrix_exr_module();
            return l;
        }
        const auto entry = reinterpret_cast<const ExrModule* (*)()>(
            LoadModuleSymbol("quadrix-exr.so", "quadrix_exr_module", &l.error));
        if (!entry) {
            l.error = ".exr output needs OpenEXR: " + l.error;
            return l;
        }
        const ExrModule* m = entry();
        if (m->abi != kExrModuleAbi || !m->write || !m->check) {
            l.error = fmt::format(
                "quadrix-exr.so is from another build of Quadrix (interface {}, this program's {})",
                m->abi, kExrModuleAbi);
            return l;
        }
        l.module = m;
        return l;
#endif
    }();
    return loaded;
}

}  // namespace

bool HaveOpenExr() { return Module().module != nullptr; }

std::string OpenExrUnavailable() { return Module().error; }

std::string WriteExr(OutputFile& file, const Frame& frame, const Image* image) {
    if (!file.ok()) return file.error();
    const ExrModule* exr = Module().module;
    if (!exr) return fmt::format("cannot write '{}': {}", file.path(), Module().error);
    const int w = frame.width, h = frame.height;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (w <= 0 || h <= 0 || frame.depth.size() != n) return "internal error: malformed frame";
    if (image && (image->width != w || image->height != h))
        return "internal error: the image and the frame differ in size";

    // Planar copies in the channel types of the file.
    std::vector<float> rgba[4], z(n), nrm[3];
    std::vector<std::uint32_t> ids[3];
    if (image) {
        const bool linear = image->linear.size() == image->pixels.size();
        for (auto& c : rgba) c.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) {
                const std::size_t k = i * image->channels + (image->channels == 3 ? c : 0);
                rgba[c][i] = linear ? image->linear[k] : image->pixels[k] / 255.0f;
            }
            rgba[3][i] = frame.surface[i] == Frame::kNone ? 0.0f : 1.0f;
        }
    }
    for (auto& c : nrm) c.resize(n);
    for (auto& c : ids) c.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        z[i] = frame.depth[i];
        const Vec3 normal = frame.normal[i];
        nrm[0][i] = static_cast<float>(normal.x);
        nrm[1][i] = static_cast<float>(normal.y);
        nrm[2][i] = static_cast<float>(normal.z);
        ids[0][i] = static_cast<std::uint32_t>(frame.surface[i] + 1);
        ids[1][i] = static_cast<std::uint32_t>(frame.body[i] + 1);
        ids[2][i] = static_cast<std::uint32_t>(frame.Solid(i) + 1);
    }

    std::vector<ExrChannel> channels;
    if (image) {
        channels.push_back({"R", false, rgba[0].data()});
        channels.push_back({"G", false, rgba[1].data()});
        channels.push_back({"B", false, rgba[2].data()});
        channels.push_back({"A", false, rgba[3].data()});
    }
    channels.push_back({"Z", false, z.data()});
    channels.push_back({"N.x", false, nrm[0].data()});
    channels.push_back({"N.y", false, nrm[1].data()});
    channels.push_back({"N.z", false, nrm[2].data()});
    channels.push_back({"id.surface", true, ids[0].data()});
    channels.push_back({"id.body", true, ids[1].data()});
    channels.push_back({"id.solid", true, ids[2].data()});
    const std::string software = std::string("Quadrix ") + QUADRIX_VERSION;
    std::string error;
    if (!exr->write(file.stream(), file.path().c_str(), w, h, channels.data(),
                    static_cast<int>(channels.size()), software.c_str(), &error))
        return fmt::format("cannot write '{}': {}", file.path(), error);
    return {};
}

std::string CheckExrFile(const std::string& path, int width, int height) {
    if (const ExrModule* exr = Module().module) return exr->check(path.c_str(), width, height);
    // Without OpenEXR only the magic number is checked.
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "cannot be read";
    unsigned char magic[4] = {};
    const bool ok = std::fread(magic, 1, 4, f) == 4 && magic[0] == 0x76 && magic[1] == 0x2f &&
                    magic[2] == 0x31 && magic[3] == 0x01;
    std::fclose(f);
    return ok ? std::string() : "not an OpenEXR file";
}

std::string WriteExr(const std::string& path, const Frame& frame, const Image* image) {
    OutputFile f(path);
    if (auto e = WriteExr(f, frame, image); !e.empty()) return e;
    return f.Commit();
}

}  // namespace quadrix
