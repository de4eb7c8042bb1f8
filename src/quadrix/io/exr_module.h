// The interface between Quadrix and its OpenEXR module, quadrix-exr.so (modules/exr/), which
// writes and checks .exr files. The module is loaded only when an .exr is written or checked
// (util/module_loader.h says why and how it is found). Quadrix prepares the channels (exr.cpp
// holds their names, types and meaning, exr.h documents them); the module writes them with
// OpenEXR. It depends on nothing of Quadrix but this header.
#pragma once

#include <cstdio>
#include <string>

namespace quadrix {

// Raised whenever ExrChannel or ExrModule change, so that a module of another build is refused.
inline constexpr int kExrModuleAbi = 1;

// One channel: width × height values, rows top to bottom.
struct ExrChannel {
    const char* name = nullptr;
    bool isUint = false;  // UINT (std::uint32_t) channel, else FLOAT
    const void* data = nullptr;
};

// The module's table (quadrix_exr_module() returns it).
struct ExrModule {
    int abi = kExrModuleAbi;
    // Writes a scan-line, ZIP-compressed file of `count` channels into `file` (from its current
    // position; seeks within what it wrote), with the attribute "software" and sRGB/BT.709
    // chromaticities. `name` is for messages. False, with `*error` set, on failure.
    bool (*write)(std::FILE* file, const char* name, int width, int height,
                  const ExrChannel* channels, int count, const char* software,
                  std::string* error) = nullptr;
    // Whether `path` is a complete file of width × height pixels whose every chunk decodes:
    // empty, else why not.
    std::string (*check)(const char* path, int width, int height) = nullptr;
};

}  // namespace quadrix

// Defined by modules/exr/exr_module.cpp: in quadrix-exr.so, or linked into targets that link
// OpenEXR themselves (quadrix_modules_linked).
extern "C" const quadrix::ExrModule* quadrix_exr_module();
