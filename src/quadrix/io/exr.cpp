// OpenEXR writer; see exr.h for the channel layout.
#include "quadrix/io/exr.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <vector>

#ifdef QUADRIX_HAVE_OPENEXR
#include <ImfChannelList.h>
#include <ImfChromaticitiesAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#endif

namespace quadrix {

#ifdef QUADRIX_HAVE_OPENEXR

namespace {

// OpenEXR writes through an OStream; this one writes into the stdio stream of an OutputFile
// (temporary file + rename, io/output_file.h), so an EXR is as atomic as every other output.
class StdioOStream : public Imf::OStream {
  public:
    StdioOStream(std::FILE* file, const std::string& name)
        : Imf::OStream(name.c_str()), file_(file) {}
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

}  // namespace

bool HaveOpenExr() { return true; }

std::string WriteExr(OutputFile& file, const Frame& frame, const Image* image) {
    if (!file.ok()) return file.error();
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
        z[i] = static_cast<float>(frame.depth[i]);
        nrm[0][i] = static_cast<float>(frame.normal[i].x);
        nrm[1][i] = static_cast<float>(frame.normal[i].y);
        nrm[2][i] = static_cast<float>(frame.normal[i].z);
        ids[0][i] = static_cast<std::uint32_t>(frame.surface[i] + 1);
        ids[1][i] = static_cast<std::uint32_t>(frame.body[i] + 1);
        ids[2][i] = static_cast<std::uint32_t>(frame.solid[i] + 1);
    }

    try {
        Imf::Header header(w, h);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.insert("software", Imf::StringAttribute(std::string("Quadrix ") + QUADRIX_VERSION));
        Imf::addChromaticities(header, Imf::Chromaticities());  // sRGB / BT.709 primaries, D65
        Imf::FrameBuffer fb;
        auto addFloat = [&](const char* name, std::vector<float>& data) {
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.data()),
                                       sizeof(float), sizeof(float) * static_cast<std::size_t>(w)));
        };
        auto addUint = [&](const char* name, std::vector<std::uint32_t>& data) {
            header.channels().insert(name, Imf::Channel(Imf::UINT));
            fb.insert(name, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(data.data()),
                                       sizeof(std::uint32_t),
                                       sizeof(std::uint32_t) * static_cast<std::size_t>(w)));
        };
        if (image) {
            addFloat("R", rgba[0]);
            addFloat("G", rgba[1]);
            addFloat("B", rgba[2]);
            addFloat("A", rgba[3]);
        }
        addFloat("Z", z);
        addFloat("N.x", nrm[0]);
        addFloat("N.y", nrm[1]);
        addFloat("N.z", nrm[2]);
        addUint("id.surface", ids[0]);
        addUint("id.body", ids[1]);
        addUint("id.solid", ids[2]);
        StdioOStream stream(file.stream(), file.path());
        Imf::OutputFile out(stream, header, 1);
        out.setFrameBuffer(fb);
        out.writePixels(h);
    } catch (const std::exception& e) {
        return fmt::format("cannot write '{}': OpenEXR: {}", file.path(), e.what());
    }
    return {};
}

std::string CheckExrFile(const std::string& path, int width, int height) {
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i dw = in.header().dataWindow();
        if (dw.max.x - dw.min.x + 1 != width || dw.max.y - dw.min.y + 1 != height)
            return fmt::format("{}×{} pixels, not {}×{}", dw.max.x - dw.min.x + 1,
                               dw.max.y - dw.min.y + 1, width, height);
        if (!in.isComplete()) return "incomplete (scan lines missing)";
        // Every chunk decoded (one channel's worth of memory): a file cut inside its last chunk
        // still has a complete offset table.
        const Imf::ChannelList& channels = in.header().channels();
        if (channels.begin() != channels.end()) {
            std::vector<float> scratch(static_cast<std::size_t>(width) *
                                       static_cast<std::size_t>(height));
            Imf::FrameBuffer fb;
            fb.insert(
                channels.begin().name(),
                Imf::Slice(Imf::FLOAT,
                           reinterpret_cast<char*>(scratch.data() - dw.min.x -
                                                   static_cast<std::ptrdiff_t>(dw.min.y) * width),
                           sizeof(float), sizeof(float) * static_cast<std::size_t>(width)));
            in.setFrameBuffer(fb);
            in.readPixels(dw.min.y, dw.max.y);
        }
    } catch (const std::exception& e) {
        return fmt::format("not a readable OpenEXR file ({})", e.what());
    }
    return {};
}

#else

std::string CheckExrFile(const std::string& path, int, int) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "cannot be read";
    unsigned char magic[4] = {};
    const bool ok = std::fread(magic, 1, 4, f) == 4 && magic[0] == 0x76 && magic[1] == 0x2f &&
                    magic[2] == 0x31 && magic[3] == 0x01;
    std::fclose(f);
    return ok ? std::string() : "not an OpenEXR file";
}

bool HaveOpenExr() { return false; }

std::string WriteExr(OutputFile& file, const Frame&, const Image*) {
    return fmt::format(
        "cannot write '{}': this quadrix was built without OpenEXR (install libopenexr-dev and "
        "rebuild; see docs/dependencies.md)",
        file.path());
}

#endif

std::string WriteExr(const std::string& path, const Frame& frame, const Image* image) {
    OutputFile f(path);
    if (auto e = WriteExr(f, frame, image); !e.empty()) return e;
    return f.Commit();
}

}  // namespace quadrix
