#include "quadrix/io/png_encoder.h"

#include <tbb/parallel_for.h>
#include <zlib.h>
#if QUADRIX_HAVE_LIBDEFLATE
#include <libdeflate.h>
#endif

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "quadrix/frame/frame.h"
#include "quadrix/io/phase_times.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

// The Adler-32 of a strip's filtered rows: libdeflate's, vectorised (0.05 ms for the 2.7 MB of
// a 1280×720 RGB image, against zlib's 0.8 ms, which was a fifth of the encoder's work), when the
// build found it; the same value either way.
uLong Adler32(uLong adler, const std::uint8_t* data, std::size_t n) {
#if QUADRIX_HAVE_LIBDEFLATE
    return libdeflate_adler32(static_cast<std::uint32_t>(adler), data, n);
#else
    return adler32_z(adler, data, n);
#endif
}

void Put32(std::vector<std::uint8_t>& v, std::uint32_t x) {
    v.push_back(static_cast<std::uint8_t>(x >> 24));
    v.push_back(static_cast<std::uint8_t>(x >> 16));
    v.push_back(static_cast<std::uint8_t>(x >> 8));
    v.push_back(static_cast<std::uint8_t>(x));
}

// Appends a whole chunk: length, type, data, CRC-32 of type and data.
void Chunk(std::vector<std::uint8_t>& v, const char* type, const std::uint8_t* data,
           std::size_t n) {
    Put32(v, static_cast<std::uint32_t>(n));
    const std::size_t at = v.size();
    v.insert(v.end(), type, type + 4);
    if (n) v.insert(v.end(), data, data + n);
    const uLong crc = crc32(0L, v.data() + at, static_cast<uInt>(4 + n));
    Put32(v, static_cast<std::uint32_t>(crc));
}

void Chunk(std::vector<std::uint8_t>& v, const char* type, const std::vector<std::uint8_t>& d) {
    Chunk(v, type, d.data(), d.size());
}

struct Strip {
    std::vector<std::uint8_t> chunk;  // the whole IDAT chunk
    uLong adler = 1;
    std::size_t rawBytes = 0;
    bool ok = true;
};

// A thread's working memory for strips, kept between strips and between images: zlib's deflate
// state (reset for each strip), the filtered rows and the deflate output before it is copied into
// its chunk. Fresh memory costs more than the compression itself on rendered pictures: each 4 KiB
// page's first touch is a page fault of about 18 µs on this project's virtual machines, and the
// state and buffers of a 128 KiB strip are 130 pages. So they live in one 2 MiB mapping in a huge
// page (frame/frame.h AllocateFrameBytes: one fault): zlib's state first (its allocator, below),
// then the rows and the output; buffers that do not fit after it are allocated on their own.
struct StripScratch {
    static constexpr std::size_t kArenaBytes = kFrameHugeBytes;
    std::uint8_t* arena = nullptr;
    std::size_t arenaUsed = 0;                 // by zlib's state, which is allocated once
    std::unique_ptr<std::uint8_t[]> raw, out;  // when the rows and output do not fit the arena
    std::size_t rawCapacity = 0, outCapacity = 0;
    z_stream z{};
    bool ready = false;  // z initialised
    StripScratch() {
        try {
            arena = static_cast<std::uint8_t*>(AllocateFrameBytes(kArenaBytes));
        } catch (const std::bad_alloc&) {
            arena = nullptr;  // zlib's own allocator and the heap, then
        }
        if (arena) {
            z.zalloc = [](voidpf self, uInt items, uInt size) -> voidpf {
                return static_cast<StripScratch*>(self)->Take(std::size_t{items} * size);
            };
            z.zfree = [](voidpf self, voidpf p) { static_cast<StripScratch*>(self)->Give(p); };
            z.opaque = this;
        }
    }
    StripScratch(const StripScratch&) = delete;
    StripScratch& operator=(const StripScratch&) = delete;
    ~StripScratch() {
        if (ready) deflateEnd(&z);
        FreeFrameBytes(arena, kArenaBytes);
    }
    // zlib's allocator: from the arena while it lasts (nothing is freed before deflateEnd).
    voidpf Take(std::size_t n) {
        n = (n + 63) / 64 * 64;
        if (arenaUsed + n <= kArenaBytes) {
            void* p = arena + arenaUsed;
            arenaUsed += n;
            return p;
        }
        return std::malloc(n);
    }
    void Give(voidpf p) {
        const auto* b = static_cast<std::uint8_t*>(p);
        if (!(b >= arena && b < arena + kArenaBytes)) std::free(p);
    }
    // The rows (n bytes) and the output (m bytes): after zlib's state in the arena when both fit.
    void Buffers(std::size_t n, std::size_t m, std::uint8_t*& rows, std::uint8_t*& output) {
        const std::size_t at = (arenaUsed + 63) / 64 * 64;
        if (arena && at + n + m <= kArenaBytes) {
            rows = arena + at;
            output = rows + n;
            return;
        }
        rows = Reserve(raw, rawCapacity, n);
        output = Reserve(out, outCapacity, m);
    }
    static std::uint8_t* Reserve(std::unique_ptr<std::uint8_t[]>& p, std::size_t& capacity,
                                 std::size_t n) {
        if (n > capacity) {
            p.reset(new std::uint8_t[n]);  // not value-initialised: every byte used is written
            capacity = n;
        }
        return p.get();
    }
};

StripScratch& ThreadScratch() {
    thread_local StripScratch scratch;
    return scratch;
}

// Rows y0..y1 filtered into `raw` (rawBytes of them) and their Adler-32.
void FilterRows(const PngRaster& r, std::size_t rowBytes, int y0, int y1, std::uint8_t* raw,
                Strip& s) {
    const std::size_t stride = rowBytes + 1;
    for (int y = y0; y < y1; ++y) {
        std::uint8_t* p = raw + static_cast<std::size_t>(y - y0) * stride;
        p[0] = static_cast<std::uint8_t>(r.filter);
        r.row(y, p + 1);
        if (r.filter == 1) {  // Sub, in place from the right: byte k - bpp is still unfiltered
            const std::size_t bpp = static_cast<std::size_t>(r.channels * r.bitDepth / 8);
            for (std::size_t k = rowBytes; k-- > bpp;) p[1 + k] -= p[1 + k - bpp];
        }
    }
    s.rawBytes = static_cast<std::size_t>(y1 - y0) * stride;
    s.adler = Adler32(1L, raw, s.rawBytes);
}

// The rows in `raw` deflated by `z` into s.chunk after room for the chunk's length and type and,
// when `header` (the first strip) is not null, the zlib header's two bytes; `out` holds `bound`
// bytes. The Adler-32 (last strip) and the CRC are appended by the caller.
void Deflate(z_stream& z, std::uint8_t* raw, std::uint8_t* out, std::size_t bound, bool last,
             const std::uint8_t* header, Strip& s) {
    z.next_in = raw;
    z.avail_in = static_cast<uInt>(s.rawBytes);
    z.next_out = out;
    z.avail_out = static_cast<uInt>(bound);
    const int rc = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
    const bool done = last ? rc == Z_STREAM_END : (rc == Z_OK && z.avail_in == 0);
    if (!done) {
        s.ok = false;
        return;
    }
    const std::size_t n = bound - z.avail_out;
    const std::size_t head = 8 + (header ? 2 : 0);
    std::vector<std::uint8_t>& c = s.chunk;
    c.reserve(head + n + 8);
    c.resize(head);
    if (header) c[8] = header[0], c[9] = header[1];
    c.insert(c.end(), out, out + n);
}

// Filtered rows y0..y1 deflated (raw, level 1, 32 KiB window); the first strip carries the zlib
// header.
void CompressStrip(const PngRaster& r, std::size_t rowBytes, int y0, int y1, bool last, Strip& s) {
    StripScratch& t = ThreadScratch();
    z_stream& z = t.z;
    if (!t.ready) {
        if (deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
            s.ok = false;
            return;
        }
        t.ready = true;
    } else if (deflateReset(&z) != Z_OK) {
        s.ok = false;
        return;
    }
    const std::size_t rawBytes = static_cast<std::size_t>(y1 - y0) * (rowBytes + 1);
    const std::size_t bound = deflateBound(&z, rawBytes) + 16;
    std::uint8_t *raw = nullptr, *out = nullptr;
    t.Buffers(rawBytes, bound, raw, out);
    FilterRows(r, rowBytes, y0, y1, raw, s);
    static constexpr std::uint8_t kHeader[2] = {0x78, 0x01};  // CM 8, 32 KiB window; FLEVEL 0
    Deflate(z, raw, out, bound, last, y0 == 0 ? kHeader : nullptr, s);
}

// A small image (one strip of fewer than kSmallImage bytes of filtered rows) in one deflate
// stream whose window just holds it: 2^w bytes, w = 9..15, and a hash table of as many entries
// (memLevel w − 7), allocated on the heap for this image. The thread's 2 MiB arena and its 32 KiB
// window state would be first touched for a few KiB of rows: its huge page costs 0.26 ms on this
// project's Intel machine, where the about 30 small pages this state and these buffers touch cost
// 0.04 ms (0.5 ms at the 18 µs a fault of the AMD machines, about what a huge page costs there;
// docs/performance.md "Small pictures"). The zlib header says the window (CINFO = w − 8), so a
// decoder may use no more.
constexpr std::size_t kSmallImage = 64u << 10;
void CompressSmall(const PngRaster& r, std::size_t rowBytes, Strip& s) {
    const std::size_t rawBytes = static_cast<std::size_t>(r.height) * (rowBytes + 1);
    int w = 9;
    while (w < 15 && (std::size_t{1} << w) < rawBytes) ++w;
    z_stream z{};
    if (deflateInit2(&z, 1, Z_DEFLATED, -w, w - 7, Z_DEFAULT_STRATEGY) != Z_OK) {
        s.ok = false;
        return;
    }
    const std::size_t bound = deflateBound(&z, rawBytes) + 16;
    std::vector<std::uint8_t> buffer(rawBytes + bound);
    FilterRows(r, rowBytes, 0, r.height, buffer.data(), s);
    // CMF: CM 8, CINFO w − 8; FLG: FLEVEL 0, no dictionary, FCHECK making CMF·256 + FLG ≡ 0 (31).
    const auto cmf = static_cast<std::uint8_t>(0x08 | ((w - 8) << 4));
    const std::uint8_t header[2] = {cmf, static_cast<std::uint8_t>((31 - cmf * 256 % 31) % 31)};
    Deflate(z, buffer.data(), buffer.data() + rawBytes, bound, true, header, s);
    deflateEnd(&z);
}

}  // namespace

std::string EncodePng(const PngRaster& r, std::FILE* out) {
    if (r.width <= 0 || r.height <= 0 || (r.channels != 1 && r.channels != 3) ||
        (r.bitDepth != 8 && r.bitDepth != 16) || (r.filter != 0 && r.filter != 1) || !r.row)
        return "internal error: malformed PNG raster";
    const std::size_t rowBytes = static_cast<std::size_t>(r.width) *
                                 static_cast<std::size_t>(r.channels) *
                                 static_cast<std::size_t>(r.bitDepth / 8);
    // Strips of about 128 KiB of filtered rows (and fewer than 2^31 bytes each for zlib).
    const int rowsPerStrip =
        static_cast<int>(std::clamp<std::size_t>((128u << 10) / (rowBytes + 1), 1, 1u << 14));
    const int strips = (r.height + rowsPerStrip - 1) / rowsPerStrip;
    std::vector<Strip> s(static_cast<std::size_t>(strips));
    if (strips == 1 && static_cast<std::size_t>(r.height) * (rowBytes + 1) < kSmallImage)
        CompressSmall(r, rowBytes, s[0]);
    else
        ParallelFor(0, strips, [&](int k) {
            const int y0 = k * rowsPerStrip, y1 = std::min(r.height, y0 + rowsPerStrip);
            CompressStrip(r, rowBytes, y0, y1, k + 1 == strips, s[static_cast<std::size_t>(k)]);
        });
    MarkPhase("encode");  // io/phase_times.h: what follows is the file's writing
    uLong adler = 1;
    for (const Strip& x : s) {
        if (!x.ok) return "PNG encoding failed (zlib)";
        adler = adler32_combine(adler, x.adler, static_cast<z_off_t>(x.rawBytes));
    }

    std::vector<std::uint8_t> head = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<std::uint8_t> d;
    Put32(d, static_cast<std::uint32_t>(r.width));
    Put32(d, static_cast<std::uint32_t>(r.height));
    d.push_back(static_cast<std::uint8_t>(r.bitDepth));
    d.push_back(r.channels == 3 ? 2 : 0);  // colour type: truecolour or greyscale
    d.push_back(0);                        // compression: deflate
    d.push_back(0);                        // filter method 0
    d.push_back(0);                        // no interlace
    Chunk(head, "IHDR", d);
    if (r.srgb) {
        d.clear();
        Put32(d, 45455);  // gamma 1/2.2 × 100000
        Chunk(head, "gAMA", d);
        d = {0};  // rendering intent: perceptual
        Chunk(head, "sRGB", d);
        d.clear();
        for (std::uint32_t v : {31270u, 32900u, 64000u, 33000u, 30000u, 60000u, 15000u, 6000u})
            Put32(d, v);  // white, red, green, blue chromaticities × 100000
        Chunk(head, "cHRM", d);
    }
    if (!r.software.empty()) {
        d.assign({'S', 'o', 'f', 't', 'w', 'a', 'r', 'e', 0});
        d.insert(d.end(), r.software.begin(), r.software.end());
        Chunk(head, "tEXt", d);
    }
    bool ok = std::fwrite(head.data(), 1, head.size(), out) == head.size();
    for (std::size_t k = 0; k < s.size() && ok; ++k) {
        std::vector<std::uint8_t>& c = s[k].chunk;
        if (k + 1 == s.size()) {
            const std::size_t n = c.size();
            c.resize(n + 4);
            for (int b = 0; b < 4; ++b) c[n + b] = static_cast<std::uint8_t>(adler >> (24 - 8 * b));
        }
        const std::size_t n = c.size() - 8;  // the data: after the length and the type
        for (int b = 0; b < 4; ++b) c[b] = static_cast<std::uint8_t>(n >> (24 - 8 * b));
        std::memcpy(c.data() + 4, "IDAT", 4);
        const uLong crc = crc32(0L, c.data() + 4, static_cast<uInt>(n + 4));
        for (int b = 0; b < 4; ++b) c.push_back(static_cast<std::uint8_t>(crc >> (24 - 8 * b)));
        ok = std::fwrite(c.data(), 1, c.size(), out) == c.size();
    }
    std::vector<std::uint8_t> tail;
    Chunk(tail, "IEND", nullptr, 0);
    ok = ok && std::fwrite(tail.data(), 1, tail.size(), out) == tail.size();
    return ok ? std::string() : std::string("write error");
}

}  // namespace quadrix
