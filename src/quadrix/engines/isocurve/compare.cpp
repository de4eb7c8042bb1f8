#include "quadrix/engines/isocurve/compare.h"

#include <fmt/format.h>

#include <chrono>

#include "quadrix/engines/isocurve/polygon_mesh.h"

namespace quadrix::isocurve {

namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

void CountAgainst(const std::vector<std::uint8_t>& reference, const std::vector<bool>& covered,
                  MethodRow& row) {
    for (std::size_t i = 0; i < reference.size(); ++i) {
        row.holes += reference[i] && !covered[i];
        row.extra += !reference[i] && covered[i];
    }
}

MethodRow CurvesRow(const std::string& name, const std::vector<FreeformDrawable>& drawables,
                    const Projection& projection, IsocurveOptions o, bool uniform, int width,
                    int height, const std::vector<std::uint8_t>& reference) {
    o.uniform = uniform;
    Frame frame(width, height);
    IsocurveStats st = RenderFreeform(drawables, projection, o, frame);
    MethodRow row;
    row.method = name;
    row.primitives = st.curves;
    row.length = st.length;
    row.pixelsDrawn = st.raster.pixelsDrawn;
    row.distinctPixels = st.raster.distinctPixels;
    row.multiplyDrawn = st.raster.multiplyDrawn;
    row.extractSeconds = st.extractSeconds;
    row.drawSeconds = st.drawSeconds;
    std::vector<bool> covered(frame.surface.size());
    for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = frame.surface[i] != Frame::kNone;
    CountAgainst(reference, covered, row);
    return row;
}

}  // namespace

std::vector<std::uint8_t> ReferenceMask(const std::vector<FreeformDrawable>& drawables,
                                        const Projection& projection, int width, int height) {
    double tolerance = DeltaForImage(drawables, projection, 0.05);
    TriangleCoverage cov(width, height);
    for (const FreeformDrawable& d : drawables)
        cov.Add(MeshForTolerance(*d.surface, tolerance), projection);
    std::vector<std::uint8_t> mask(cov.Counts().size());
    for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = cov.Counts()[i] > 0;
    return mask;
}

Comparison CompareCoverage(const std::vector<FreeformDrawable>& drawables,
                           const Projection& projection, const IsocurveOptions& options, int width,
                           int height) {
    Comparison c;
    IsocurveOptions o = options;
    o.delta = options.delta > 0 ? options.delta
                                : DeltaForImage(drawables, projection, options.pixelSpacing);
    o.thickness = options.thickness > 0 ? options.thickness : 1.5 * options.pixelSpacing + 0.25;
    c.delta = o.delta;
    c.thickness = o.thickness;
    std::vector<std::uint8_t> reference = ReferenceMask(drawables, projection, width, height);
    for (std::uint8_t r : reference) c.referencePixels += r;

    c.rows.push_back(
        CurvesRow("adaptive isocurves", drawables, projection, o, false, width, height, reference));
    c.rows.push_back(
        CurvesRow("uniform isocurves", drawables, projection, o, true, width, height, reference));

    MethodRow poly;
    poly.method = "polygons";
    auto start = std::chrono::steady_clock::now();
    std::vector<PolygonMesh> meshes;
    for (const FreeformDrawable& d : drawables)
        meshes.push_back(MeshForTolerance(*d.surface, o.delta));
    poly.extractSeconds = Seconds(start);
    start = std::chrono::steady_clock::now();
    TriangleCoverage cov(width, height);
    for (const PolygonMesh& m : meshes) cov.Add(m, projection);
    poly.drawSeconds = Seconds(start);
    poly.primitives = cov.Triangles();
    poly.pixelsDrawn = cov.PixelsDrawn();
    std::vector<bool> covered(reference.size());
    for (std::size_t i = 0; i < covered.size(); ++i) {
        covered[i] = cov.Counts()[i] > 0;
        poly.distinctPixels += covered[i];
        poly.multiplyDrawn += cov.Counts()[i] > 1;
    }
    CountAgainst(reference, covered, poly);
    c.rows.push_back(poly);
    return c;
}

std::string Comparison::Format() const {
    std::string s = fmt::format(
        "coverage comparison at delta {:.6g} (world), curves {:.3g} px wide, reference {} px\n"
        "  {:<20} {:>9} {:>11} {:>11} {:>9} {:>10} {:>7} {:>7} {:>7} {:>9} {:>9}\n",
        delta, thickness, referencePixels, "method", "prims", "length", "drawn", "distinct",
        "multiple", "redund", "holes", "extra", "extract s", "draw s");
    for (const MethodRow& r : rows)
        s += fmt::format(
            "  {:<20} {:>9} {:>11.5g} {:>11} {:>9} {:>10} {:>7.3f} {:>7} {:>7} {:>9.4f} "
            "{:>9.4f}\n",
            r.method, r.primitives, r.length, r.pixelsDrawn, r.distinctPixels, r.multiplyDrawn,
            r.Redundancy(), r.holes, r.extra, r.extractSeconds, r.drawSeconds);
    return s;
}

}  // namespace quadrix::isocurve
