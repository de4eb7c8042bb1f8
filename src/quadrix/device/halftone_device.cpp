// Bilevel devices (seed 001 §6.5.3): "The Sun's monochrome screen and the Varian and Versatek
// plotters are bilevel devices. These drivers use stipple patterns to emulate the dots of
// lithographic half-tones. Device span intensity provides an index into a stipple table that
// contains bit-images of the patterns."
//
// Both patterns here are 8 × 8 threshold matrices holding each rank 0..63 once, so a flat area
// of intensity v sets exactly round(64 v / 255) of every 64 dots (the mean intensity is kept to
// within 1/128):
//   - kBayer: the dispersed ordered dither (Bayer's recursive matrix), finest texture;
//   - kCluster: a clustered dot that grows from the cell centre, as a lithographic half-tone
//     screen (at 200 dots per inch, 25 cells per inch) — the look of the plotter stipples.
// Output: PBM (P4, 1 = black) or PNG (8-bit gray, 0 or 255), by the file's extension.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "quadrix/device/device_internal.h"
#include "quadrix/io/writers.h"

namespace quadrix::device {

namespace {

using Matrix = std::array<std::array<int, 8>, 8>;

Matrix MakeBayer() {
    // M(2n) = [[4M, 4M+2], [4M+3, 4M+1]] starting from M(1) = [0].
    Matrix m{};
    int size = 1;
    while (size < 8) {
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                int v = 4 * m[y][x];
                m[y][x] = v;
                m[y][x + size] = v + 2;
                m[y + size][x] = v + 3;
                m[y + size][x + size] = v + 1;
            }
        size *= 2;
    }
    return m;
}

Matrix MakeCluster() {
    // Rank the 64 cells by distance from the cell centre (ties by angle), so the set dots form
    // one growing round dot: dark areas are small dots of white on black, as printed halftones.
    std::array<int, 64> order;
    std::iota(order.begin(), order.end(), 0);
    auto key = [](int i) {
        double dx = i % 8 - 3.5, dy = i / 8 - 3.5;
        return std::pair<double, double>(dx * dx + dy * dy, std::atan2(dy, dx));
    };
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
    Matrix m{};
    for (int rank = 0; rank < 64; ++rank) m[order[rank] / 8][order[rank] % 8] = rank;
    return m;
}

}  // namespace

int ThresholdRank(Pattern pattern, int x, int y) {
    static const Matrix kBayer = MakeBayer();
    static const Matrix kCluster = MakeCluster();
    const Matrix& m = pattern == Pattern::kBayer ? kBayer : kCluster;
    return m[static_cast<unsigned>(y) % 8][static_cast<unsigned>(x) % 8];
}

namespace internal {

namespace {

class HalftoneDevice : public BufferedDevice {
  public:
    HalftoneDevice(DeviceInfo info, Pattern pattern) : pattern_(pattern) {
        info_ = std::move(info);
    }

  protected:
    std::string Write(const Image& gray) override {
        const std::vector<std::uint8_t> set = Stipple(gray);
        auto on = [&](int x, int y) {
            return set[static_cast<std::size_t>(y) * gray.width + x] != 0;
        };
        if (Extension(info_.path) == ".png") {
            Image bits(gray.width, gray.height, 1);
            for (int y = 0; y < gray.height; ++y)
                for (int x = 0; x < gray.width; ++x) bits.At(x, y)[0] = on(x, y) ? 255 : 0;
            return WritePng(info_.path, bits);
        }
        // PBM P4: rows of bits, most significant first, padded to bytes; 1 is black.
        std::string out =
            "P4\n" + std::to_string(gray.width) + " " + std::to_string(gray.height) + "\n";
        const int rowBytes = (gray.width + 7) / 8;
        for (int y = 0; y < gray.height; ++y) {
            std::string row(static_cast<std::size_t>(rowBytes), '\0');
            for (int x = 0; x < gray.width; ++x)
                if (!on(x, y))
                    row[static_cast<std::size_t>(x / 8)] |= static_cast<char>(0x80 >> (x % 8));
            out += row;
        }
        return WriteOutputFile(info_.path, out);
    }

  private:
    // The stipple table lookup, cell by cell. In a flat area a pixel is set (white) when
    // v/255 > (rank + 0.5)/64, so round(64 v / 255) dots of each 8 × 8 cell are set: the pattern's
    // own look. Where the intensity varies inside a cell (silhouettes, highlights), plain
    // thresholding can miss the cell's mean by several percent, so each cell sets exactly
    // N = round(Σ v/255) dots, choosing the pixels by their margin v/255 − (rank + 0.5)/64 (ties
    // by rank): in a flat area that is the same choice as thresholding, elsewhere it keeps every
    // cell's mean intensity to within half a dot (issue 7: "the halftone's mean intensity
    // matches the gray image's within 2 % per 16×16 block").
    std::vector<std::uint8_t> Stipple(const Image& gray) const {
        std::vector<std::uint8_t> bits(static_cast<std::size_t>(gray.width) * gray.height, 0);
        struct Cell {
            double margin;
            int rank, x, y;
        };
        std::vector<Cell> cell;
        for (int cy = 0; cy < gray.height; cy += 8)
            for (int cx = 0; cx < gray.width; cx += 8) {
                cell.clear();
                double sum = 0;
                for (int y = cy; y < std::min(cy + 8, gray.height); ++y)
                    for (int x = cx; x < std::min(cx + 8, gray.width); ++x) {
                        double v = gray.At(x, y)[0] / 255.0;
                        int rank = ThresholdRank(pattern_, x, y);
                        sum += v;
                        cell.push_back({v - (rank + 0.5) / 64.0, rank, x, y});
                    }
                std::sort(cell.begin(), cell.end(), [](const Cell& a, const Cell& b) {
                    return a.margin != b.margin ? a.margin > b.margin : a.rank < b.rank;
                });
                const auto dots = static_cast<std::size_t>(std::lround(sum));
                for (std::size_t i = 0; i < dots && i < cell.size(); ++i)
                    bits[static_cast<std::size_t>(cell[i].y) * gray.width + cell[i].x] = 1;
            }
        return bits;
    }

    Pattern pattern_;
};

}  // namespace

std::unique_ptr<Device> MakeHalftoneDevice(DeviceInfo info, Pattern pattern) {
    return std::make_unique<HalftoneDevice>(std::move(info), pattern);
}

}  // namespace internal

}  // namespace quadrix::device
