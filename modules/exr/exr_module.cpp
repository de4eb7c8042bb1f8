// quadrix-exr.so: writes and checks OpenEXR files (src/quadrix/io/exr_module.h).
#include "quadrix/io/exr_module.h"

#include <ImfChannelList.h>
#include <ImfChromaticitiesAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <vector>

namespace quadrix {

namespace {

// OpenEXR writes through an OStream; this one writes into the stdio stream Quadrix gives (an
// OutputFile's temporary file, so an EXR is as atomic as every other output).
class StdioOStream : public Imf::OStream {
  public:
    StdioOStream(std::FILE* file, const char* name) : Imf::OStream(name), file_(file) {}
    void write(const char c[], int n) override {
        if (std::fwrite(c, 1, static_cast<std::size_t>(n), file_) != static_cast<std::size_t>(n))
            throw std::runtime_error("write failed");
    }
    uint64_t tellp() override { return static_cast<uint64_t>(ftello(file_)); }
    void seekp(uint64_t pos) override {
        if (fseeko(file_, static_cast<off_t>(pos), SEEK_SET) != 0)
            throw std::runtime_error("seek failed");
    }

  private:
    std::FILE* file_;
};

bool Write(std::FILE* file, const char* name, int width, int height, const ExrChannel* channels,
           int count, const char* software, std::string* error) {
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.insert("software", Imf::StringAttribute(software));
        Imf::addChromaticities(header, Imf::Chromaticities());  // sRGB / BT.709 primaries, D65
        Imf::FrameBuffer fb;
        for (int i = 0; i < count; ++i) {
            const ExrChannel& c = channels[i];
            const Imf::PixelType type = c.isUint ? Imf::UINT : Imf::FLOAT;
            const std::size_t size = c.isUint ? sizeof(std::uint32_t) : sizeof(float);
            header.channels().insert(c.name, Imf::Channel(type));
            fb.insert(c.name, Imf::Slice(type, static_cast<char*>(const_cast<void*>(c.data)), size,
                                         size * static_cast<std::size_t>(width)));
        }
        StdioOStream stream(file, name);
        Imf::OutputFile out(stream, header, 1);
        out.setFrameBuffer(fb);
        out.writePixels(height);
    } catch (const std::exception& e) {
        *error = std::string("OpenEXR: ") + e.what();
        return false;
    }
    return true;
}

std::string Check(const char* path, int width, int height) {
    try {
        Imf::InputFile in(path);
        const Imath::Box2i dw = in.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        if (w != width || h != height)
            return std::to_string(w) + "×" + std::to_string(h) + " pixels, not " +
                   std::to_string(width) + "×" + std::to_string(height);
        if (!in.isComplete()) return "incomplete (scan lines missing)";
        // Every chunk decoded (one channel's worth of memory): a file cut inside its last chunk
        // still has a complete offset table.
        const Imf::ChannelList& list = in.header().channels();
        if (list.begin() != list.end()) {
            std::vector<float> scratch(static_cast<std::size_t>(width) *
                                       static_cast<std::size_t>(height));
            Imf::FrameBuffer fb;
            fb.insert(
                list.begin().name(),
                Imf::Slice(Imf::FLOAT,
                           reinterpret_cast<char*>(scratch.data() - dw.min.x -
                                                   static_cast<std::ptrdiff_t>(dw.min.y) * width),
                           sizeof(float), sizeof(float) * static_cast<std::size_t>(width)));
            in.setFrameBuffer(fb);
            in.readPixels(dw.min.y, dw.max.y);
        }
    } catch (const std::exception& e) {
        return std::string("not a readable OpenEXR file (") + e.what() + ")";
    }
    return {};
}

}  // namespace

}  // namespace quadrix

extern "C" __attribute__((visibility("default"))) const quadrix::ExrModule* quadrix_exr_module() {
    static const quadrix::ExrModule table{quadrix::kExrModuleAbi, &quadrix::Write, &quadrix::Check};
    return &table;
}
