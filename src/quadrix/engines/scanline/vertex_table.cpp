#include "quadrix/engines/scanline/vertex_table.h"

#include <algorithm>
#include <cmath>

#include "quadrix/engines/scanline/edge_list.h"

namespace quadrix::scanline {
namespace {

// x of an edge's end; a conic leg at its VEXTRM may round to no root: the insert line's x.
double EndX(const ShowEdge& s, double y, bool top) {
    if (s.horizontal) return top ? s.xTop : s.xBottom;
    double x = s.XAt(y);
    if (!std::isfinite(x) && s.conic && s.shape.a != 0)
        x = -(s.shape.c * y + s.shape.d) / (2 * s.shape.a);
    return std::isfinite(x) ? x : HUGE_VAL;
}

struct End {
    int band;
    double x, y;
    int edge;
    bool isTop;
};

// The ends of the stack bodies' show-edges that lie in a band of the image (and vt.toggling).
std::vector<End> CollectEnds(const std::vector<ShowEdge>& edges, const std::vector<char>& stack,
                             int h, VertexTable& vt) {
    const std::size_t n = edges.size();
    std::vector<End> ends;
    for (std::size_t e = 0; e < n; ++e) {
        const ShowEdge& s = edges[e];
        if (s.body < 0 || static_cast<std::size_t>(s.body) >= stack.size() ||
            !stack[static_cast<std::size_t>(s.body)])
            continue;
        const double yb = SnapToRow(s.yBottom), yt = SnapToRow(s.yTop);
        if (!(yb <= yt)) continue;
        const int bb = VertexBand(yb), bt = VertexBand(yt);
        if (s.horizontal && bb != bt) continue;  // (its y rounds across a band: links nothing)
        vt.toggling[e] = bb < bt;
        if (bb >= 0 && bb < h)
            ends.push_back({bb, EndX(s, s.yBottom, false), yb, static_cast<int>(e), false});
        if (bt >= 0 && bt < h)
            ends.push_back({bt, EndX(s, s.yTop, true), yt, static_cast<int>(e), true});
    }
    return ends;
}

}  // namespace

int VertexBand(double y) { return static_cast<int>(std::ceil(SnapToRow(y) - 0.5)); }

VertexTable BuildVertices(const std::vector<ShowEdge>& edges, const std::vector<char>& stack,
                          int h) {
    VertexTable vt;
    const std::size_t n = edges.size();
    vt.bottom.assign(n, -1);
    vt.top.assign(n, -1);
    vt.toggling.assign(n, 0);
    vt.startsAt.resize(static_cast<std::size_t>(std::max(h, 0)));
    std::vector<End> ends = CollectEnds(edges, stack, h, vt);
    std::sort(ends.begin(), ends.end(), [](const End& p, const End& q) {
        return p.band < q.band || (p.band == q.band && p.x < q.x);
    });
    std::size_t bandFirst = 0;  // first vertex of the current band
    for (std::size_t i = 0; i < ends.size(); ++i) {
        const End& p = ends[i];
        if (i == 0 || p.band != ends[i - 1].band) bandFirst = vt.vertices.size();
        int v = -1;
        for (std::size_t k = vt.vertices.size(); k-- > bandFirst;) {  // recent ones, x order
            const RVertex& c = vt.vertices[k];
            if (p.x - c.x > kVertexTol) break;
            if (std::fabs(p.y - c.y) <= kVertexTol) {
                v = static_cast<int>(k);
                break;
            }
        }
        if (v < 0) {
            v = static_cast<int>(vt.vertices.size());
            vt.vertices.push_back({p.x, p.y, p.band, {}, {}, {}});
        }
        RVertex& vx = vt.vertices[static_cast<std::size_t>(v)];
        const auto e = static_cast<std::size_t>(p.edge);
        (p.isTop ? vt.top : vt.bottom)[e] = v;
        if (!vt.toggling[e]) {
            if (vx.inBand.empty() || vx.inBand.back() != p.edge) vx.inBand.push_back(p.edge);
        } else {
            (p.isTop ? vx.finishing : vx.starting).push_back(p.edge);
        }
    }
    // Vertices were made in x order within each band.
    for (std::size_t v = 0; v < vt.vertices.size(); ++v)
        if (!vt.vertices[v].starting.empty())
            vt.startsAt[static_cast<std::size_t>(vt.vertices[v].band)].push_back(
                static_cast<int>(v));
    return vt;
}

}  // namespace quadrix::scanline
