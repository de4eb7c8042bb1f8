// Closed mesh → union of convex plane bodies; the method is described in mesh_solid.h.
#include "quadrix/import/shapes/mesh_solid.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>

namespace quadrix::import {

namespace {

struct Poly {
    std::vector<Vec3> pts;
    int plane = -1;  // index into the plane table (outward unit normal)
};

// Unit-normal plane n·x + d through a triangle, normal by the right-hand rule.
std::optional<Plane> TrianglePlane(const Vec3& a, const Vec3& b, const Vec3& c) {
    Vec3 n = Cross(b - a, c - a);
    double l = Length(n);
    if (!(l > 0)) return std::nullopt;
    n = n / l;
    return Plane{n.x, n.y, n.z, -Dot(n, a)};
}

double Eval(const Plane& p, const Vec3& x) { return p.a * x.x + p.b * x.y + p.c * x.z + p.d; }
Plane Negated(const Plane& p) { return Plane{-p.a, -p.b, -p.c, -p.d}; }

ShapeHalfSpace Half(const Plane& p) {
    ShapeHalfSpace h;
    h.isPlane = true;
    h.plane = p;
    return h;
}

class Bsp {
  public:
    Bsp(std::vector<Plane> planes, double eps) : planes_(std::move(planes)), eps_(eps) {}

    // Returns false when the cell limit is reached.
    bool Build(std::vector<Poly> polys) {
        struct Job {
            std::vector<Poly> polys;
            std::vector<std::pair<int, bool>> path;  // (plane, back side)
        };
        std::vector<Job> stack;
        stack.push_back({std::move(polys), {}});
        while (!stack.empty()) {
            Job job = std::move(stack.back());
            stack.pop_back();
            const int split = PickSplitter(job.polys);
            const Plane& sp = planes_[job.polys[split].plane];
            std::vector<Poly> front, back;
            for (std::size_t i = 0; i < job.polys.size(); ++i) {
                if (static_cast<int>(i) == split) continue;
                Classify(job.polys[i], sp, front, back);
            }
            auto path = job.path;
            path.push_back({job.polys[split].plane, true});
            if (back.empty()) {
                ShapeBody body;
                for (const auto& [pi, isBack] : path)
                    body.push_back(Half(isBack ? planes_[pi] : Negated(planes_[pi])));
                cells_.push_back(std::move(body));
                if (cells_.size() > kMaxMeshCells) return false;
            } else {
                stack.push_back({std::move(back), path});
            }
            if (!front.empty()) {
                path.back().second = false;
                stack.push_back({std::move(front), std::move(path)});
            }
        }
        return true;
    }

    std::vector<ShapeBody>& cells() { return cells_; }

  private:
    // The candidate (of up to 8 spread over the list) that splits the fewest polygons, ties to
    // the best balance.
    int PickSplitter(const std::vector<Poly>& polys) const {
        const std::size_t n = polys.size();
        const std::size_t step = std::max<std::size_t>(1, n / 8);
        int best = 0;
        long long bestScore = -1;
        for (std::size_t c = 0; c < n; c += step) {
            const Plane& p = planes_[polys[c].plane];
            long long splits = 0, fr = 0, bk = 0;
            for (std::size_t i = 0; i < n; ++i) {
                if (i == c) continue;
                bool f = false, b = false;
                for (const Vec3& v : polys[i].pts) {
                    double s = Eval(p, v);
                    f = f || s > eps_;
                    b = b || s < -eps_;
                }
                splits += f && b;
                fr += f && !b;
                bk += b && !f;
            }
            long long score = 8 * splits + std::llabs(fr - bk);
            if (bestScore < 0 || score < bestScore) bestScore = score, best = static_cast<int>(c);
        }
        return best;
    }

    void Classify(const Poly& poly, const Plane& p, std::vector<Poly>& front,
                  std::vector<Poly>& back) const {
        std::vector<double> s(poly.pts.size());
        bool f = false, b = false;
        for (std::size_t i = 0; i < poly.pts.size(); ++i) {
            s[i] = Eval(p, poly.pts[i]);
            f = f || s[i] > eps_;
            b = b || s[i] < -eps_;
        }
        if (!f && !b) return;  // coplanar: consumed by this node
        if (!b) {
            front.push_back(poly);
            return;
        }
        if (!f) {
            back.push_back(poly);
            return;
        }
        Poly pf, pb;
        pf.plane = pb.plane = poly.plane;
        const std::size_t n = poly.pts.size();
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t j = (i + 1) % n;
            const Vec3 &a = poly.pts[i], &c = poly.pts[j];
            const double sa = std::fabs(s[i]) <= eps_ ? 0 : s[i];
            const double sc = std::fabs(s[j]) <= eps_ ? 0 : s[j];
            if (sa >= 0) pf.pts.push_back(a);
            if (sa <= 0) pb.pts.push_back(a);
            if ((sa > 0 && sc < 0) || (sa < 0 && sc > 0)) {
                const Vec3 x = a + (c - a) * (sa / (sa - sc));
                pf.pts.push_back(x);
                pb.pts.push_back(x);
            }
        }
        if (pf.pts.size() >= 3) front.push_back(std::move(pf));
        if (pb.pts.size() >= 3) back.push_back(std::move(pb));
    }

    std::vector<Plane> planes_;
    double eps_;
    std::vector<ShapeBody> cells_;
};

// Orients the faces consistently and outward (mesh_solid.h step 1); false with a problem.
bool Orient(const std::vector<Vec3>& v, std::vector<std::vector<int>>& faces,
            std::string& problem) {
    // Undirected edge → the faces using it, with the direction each uses it in.
    std::map<std::pair<int, int>, std::vector<std::pair<int, bool>>> edges;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& fc = faces[f];
        for (std::size_t k = 0; k < fc.size(); ++k) {
            int a = fc[k], b = fc[(k + 1) % fc.size()];
            edges[{std::min(a, b), std::max(a, b)}].push_back({static_cast<int>(f), a < b});
        }
    }
    for (const auto& [e, users] : edges)
        if (users.size() != 2) {
            problem = fmt::format(
                "the edge between vertices {} and {} belongs to {} face{} (a "
                "closed mesh has exactly 2 on every edge): it bounds no solid",
                e.first, e.second, users.size(), users.size() == 1 ? "" : "s");
            return false;
        }
    std::vector<int> flip(faces.size(), -1);  // -1 unvisited, 0 keep, 1 flip
    for (std::size_t start = 0; start < faces.size(); ++start) {
        if (flip[start] >= 0) continue;
        std::vector<int> component;
        std::queue<int> q;
        flip[start] = 0;
        q.push(static_cast<int>(start));
        while (!q.empty()) {
            int f = q.front();
            q.pop();
            component.push_back(f);
            const auto& fc = faces[f];
            for (std::size_t k = 0; k < fc.size(); ++k) {
                int a = fc[k], b = fc[(k + 1) % fc.size()];
                const auto& users = edges[{std::min(a, b), std::max(a, b)}];
                const bool fwd = (a < b) != (flip[f] == 1);
                for (const auto& [g, gfwd] : users) {
                    if (g == f) continue;
                    // Consistent neighbours use the shared edge in opposite directions.
                    const int want = gfwd == fwd ? 1 : 0;
                    if (flip[g] < 0) {
                        flip[g] = want;
                        q.push(g);
                    } else if (flip[g] != want) {
                        problem =
                            "the faces cannot be oriented consistently (the surface is "
                            "one-sided): it bounds no solid";
                        return false;
                    }
                }
            }
        }
        // Signed volume of the component (divergence theorem over fanned triangles).
        double vol = 0;
        for (int f : component) {
            const auto& fc = faces[f];
            for (std::size_t k = 1; k + 1 < fc.size(); ++k) {
                const Vec3 &a = v[fc[0]], &b = v[fc[k]], &c = v[fc[k + 1]];
                double t = Dot(a, Cross(b, c));
                vol += flip[f] == 1 ? -t : t;
            }
        }
        if (vol < 0)
            for (int f : component) flip[f] = 1 - flip[f];
        if (vol == 0) {
            problem = "a closed piece of the mesh encloses no volume";
            return false;
        }
    }
    for (std::size_t f = 0; f < faces.size(); ++f)
        if (flip[f] == 1) std::reverse(faces[f].begin(), faces[f].end());
    return true;
}

}  // namespace

MeshSolid MeshToSolid(const std::vector<Vec3>& vertices,
                      const std::vector<std::vector<int>>& facesIn) {
    MeshSolid r;
    if (vertices.size() < 4 || facesIn.size() < 4) {
        r.problem = "a closed mesh needs at least 4 vertices and 4 faces";
        return r;
    }
    Box3 box;
    for (const Vec3& p : vertices) {
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
            r.problem = "a vertex is not finite";
            return r;
        }
        box.Extend(p);
    }
    const double eps = 1e-9 * std::max(Length(box.Size()), 1e-300);
    // Vertices at the same position are one vertex (meshes often repeat them per face).
    std::map<std::array<double, 3>, int> byPosition;
    std::vector<int> canon(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
        canon[i] = byPosition
                       .emplace(std::array<double, 3>{vertices[i].x, vertices[i].y, vertices[i].z},
                                static_cast<int>(i))
                       .first->second;
    // Faces: indices in range, repeated consecutive vertices removed.
    std::vector<std::vector<int>> faces;
    for (std::size_t f = 0; f < facesIn.size(); ++f) {
        std::vector<int> fc;
        for (int k : facesIn[f]) {
            if (k < 0 || k >= static_cast<int>(vertices.size())) {
                r.problem = fmt::format("face {} names vertex {} of {}", f, k, vertices.size());
                return r;
            }
            k = canon[k];
            if (fc.empty() || fc.back() != k) fc.push_back(k);
        }
        while (fc.size() > 1 && fc.front() == fc.back()) fc.pop_back();
        if (fc.size() < 3) {
            r.problem = fmt::format("face {} has fewer than 3 distinct vertices", f);
            return r;
        }
        faces.push_back(std::move(fc));
    }
    if (!Orient(vertices, faces, r.problem)) return r;
    // Triangles (fans) and their planes; a plane table shared by coplanar, same-facing triangles.
    std::vector<Plane> planes;
    std::vector<Poly> polys;
    for (const auto& fc : faces)
        for (std::size_t k = 1; k + 1 < fc.size(); ++k) {
            auto p = TrianglePlane(vertices[fc[0]], vertices[fc[k]], vertices[fc[k + 1]]);
            if (!p) continue;  // a sliver of zero area adds no boundary
            int idx = -1;
            for (std::size_t i = 0; i < planes.size() && idx < 0; ++i)
                if (Dot(planes[i].Normal(), p->Normal()) > 1 - 1e-12 &&
                    std::fabs(planes[i].d - p->d) <= eps)
                    idx = static_cast<int>(i);
            if (idx < 0) {
                idx = static_cast<int>(planes.size());
                planes.push_back(*p);
            }
            polys.push_back({{vertices[fc[0]], vertices[fc[k]], vertices[fc[k + 1]]}, idx});
        }
    if (planes.size() < 4) {
        r.problem = "the faces span fewer than 4 planes: the mesh encloses no volume";
        return r;
    }
    for (const Vec3& p : vertices) r.shape.extent.push_back({p, {}, {}, {}});
    bool convex = true;
    for (const Plane& p : planes)
        for (const Vec3& v : vertices) convex = convex && Eval(p, v) <= eps;
    if (convex) {
        ShapeBody body;
        for (const Plane& p : planes) body.push_back(Half(p));
        r.shape.bodies.push_back(std::move(body));
        r.convex = r.ok = true;
        return r;
    }
    Bsp bsp(planes, eps);
    if (!bsp.Build(std::move(polys))) {
        r.problem =
            fmt::format("the mesh decomposes into more than {} convex cells", kMaxMeshCells);
        return r;
    }
    r.shape.bodies = std::move(bsp.cells());
    r.ok = !r.shape.bodies.empty();
    if (!r.ok) r.problem = "the mesh encloses no volume";
    return r;
}

MeshSolid PlatesToSolid(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& faces,
                        const std::vector<double>& thickness) {
    MeshSolid r;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Vec3 &a = v[faces[f][0]], &b = v[faces[f][1]], &c = v[faces[f][2]];
        auto p = TrianglePlane(a, b, c);
        const double t = f < thickness.size() ? thickness[f] : 0;
        if (!p || !(t > 0)) continue;  // no area or no thickness: no volume
        const Vec3 n = p->Normal();
        ShapeBody body;
        body.push_back(Half(Plane{n.x, n.y, n.z, p->d - 0.5 * t}));
        body.push_back(Half(Plane{-n.x, -n.y, -n.z, -p->d - 0.5 * t}));
        const Vec3* tri[3] = {&a, &b, &c};
        for (int k = 0; k < 3; ++k) {
            const Vec3 &e0 = *tri[k], &e1 = *tri[(k + 1) % 3], &opp = *tri[(k + 2) % 3];
            Vec3 m = Normalize(Cross(e1 - e0, n));
            Plane side{m.x, m.y, m.z, -Dot(m, e0)};
            if (Eval(side, opp) > 0) side = Negated(side);
            body.push_back(Half(side));
        }
        r.shape.bodies.push_back(std::move(body));
        for (const Vec3* x : tri) {
            r.shape.extent.push_back({*x + n * (0.5 * t), {}, {}, {}});
            r.shape.extent.push_back({*x - n * (0.5 * t), {}, {}, {}});
        }
    }
    r.ok = !r.shape.bodies.empty();
    if (!r.ok) r.problem = "no face has both an area and a thickness";
    return r;
}

}  // namespace quadrix::import
