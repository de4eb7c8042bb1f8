#include "quadrix/freeform/surface.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>

namespace quadrix::freeform {

namespace {
bool ExtendByPatch(const BezierSurface& p, int depth, Box3& box);
}  // namespace

Surface::Surface(BSplineSurface net, std::string name)
    : net_(std::move(net)), name_(std::move(name)) {
    assert(net_.Dim() == 3 || net_.Dim() == 4);
    patches_ = net_.ToPatches();
    normals_ = freeform::NormalField(net_);
    for (const BezierSurface& p : normals_.Patches())
        for (double c : p.Coefficients()) normalScale_ = std::max(normalScale_, std::fabs(c));
    if (Rational()) {
        for (const BezierSurface& p : patches_.Patches()) {
            Box3 unused;
            weightPositive_ = weightPositive_ && ExtendByPatch(p, 6, unused);
        }
    }
}

Surface Surface::FromBezier(const BezierSurface& patch, std::string name) {
    return Surface(BSplineSurface::FromBezier(patch), std::move(name));
}

Vec4 Surface::HomogeneousPoint(double u, double v) const {
    double out[4] = {0, 0, 0, 1};
    patches_.Evaluate(u, v, out);
    return {out[0], out[1], out[2], Rational() ? out[3] : 1.0};
}

Vec3 Surface::Point(double u, double v) const { return Dehomogenize(HomogeneousPoint(u, v)); }

Vec3 Surface::NormalField(double u, double v) const {
    double out[3];
    normals_.Evaluate(u, v, out);
    return {out[0], out[1], out[2]};
}

std::optional<Vec3> Surface::UnitNormal(double u, double v) const {
    Vec3 n = NormalField(u, v);
    // "Zero" relative to the size of the normal field over the surface: the normal-field control
    // points bound |N|, so compare against their magnitude.
    double tiny = 1e-12 * normalScale_;
    if (Length(n) > tiny) return Normalize(n);
    double du = U1() - U0(), dv = V1() - V0();
    double mu = 0.5 * (U0() + U1()), mv = 0.5 * (V0() + V1());
    for (double h : {1e-7, 1e-5, 1e-3, 1e-2}) {
        // Step toward the middle of the domain in both parameters: at a collapsed edge the limit
        // normal is approached from the inside.
        double uu = u + (u < mu ? h : -h) * du;
        double vv = v + (v < mv ? h : -h) * dv;
        for (auto [a, b] : {std::pair{u, vv}, std::pair{uu, v}, std::pair{uu, vv}}) {
            Vec3 m = NormalField(a, b);
            if (Length(m) > tiny) return Normalize(m);
        }
    }
    return std::nullopt;
}

Surface Surface::Transposed() const { return Surface(net_.Transposed(), name_); }

Surface Surface::Transformed(const Mat4& m) const {
    bool affine = m(3, 0) == 0 && m(3, 1) == 0 && m(3, 2) == 0 && m(3, 3) == 1;
    const std::vector<double>& c = net_.Coefficients();
    int dim = net_.Dim();
    std::size_t count = c.size() / static_cast<std::size_t>(dim);
    bool outRational = Rational() || !affine;
    int outDim = outRational ? 4 : 3;
    std::vector<double> out(count * static_cast<std::size_t>(outDim));
    for (std::size_t i = 0; i < count; ++i) {
        const double* p = c.data() + i * static_cast<std::size_t>(dim);
        Vec4 h{p[0], p[1], p[2], dim == 4 ? p[3] : 1.0};
        Vec4 r = m * h;
        double* o = out.data() + i * static_cast<std::size_t>(outDim);
        for (int k = 0; k < outDim; ++k) o[k] = r[static_cast<std::size_t>(k)];
    }
    return Surface(BSplineSurface(outDim, net_.DegreeU(), net_.DegreeV(), net_.KnotsU(),
                                  net_.KnotsV(), std::move(out)),
                   name_);
}

namespace {

// Adds the Euclidean hull of a patch to `box`; subdivides while some weight is not positive.
bool ExtendByPatch(const BezierSurface& p, int depth, Box3& box) {
    int count = p.SizeU() * p.SizeV();
    if (p.Dim() == 3) {
        for (int k = 0; k < count; ++k) {
            const double* c = p.Coefficients().data() + k * 3;
            box.Extend(Vec3{c[0], c[1], c[2]});
        }
        return true;
    }
    bool positive = true;
    for (int k = 0; k < count; ++k)
        positive = positive && p.Coefficients()[static_cast<std::size_t>(k * 4 + 3)] > 0;
    if (positive) {
        // With positive weights the rational patch lies in the hull of its Euclidean points.
        for (int k = 0; k < count; ++k) {
            const double* c = p.Coefficients().data() + k * 4;
            box.Extend(Vec3{c[0] / c[3], c[1] / c[3], c[2] / c[3]});
        }
        return true;
    }
    if (depth == 0) return false;
    double um = 0.5 * (p.U0() + p.U1()), vm = 0.5 * (p.V0() + p.V1());
    auto [a, b] = p.SplitU(um);
    for (const BezierSurface& h : {a, b}) {
        auto [c, d] = h.SplitV(vm);
        if (!ExtendByPatch(c, depth - 1, box) || !ExtendByPatch(d, depth - 1, box)) return false;
    }
    return true;
}

}  // namespace

Box3 Surface::Bounds() const {
    Box3 box;
    for (const BezierSurface& p : patches_.Patches())
        if (!ExtendByPatch(p, 6, box)) return Box3::Everything();
    return box;
}

double Surface::MinWeight() const {
    if (!Rational()) return 1;
    double w = HUGE_VAL;
    for (const BezierSurface& p : patches_.Patches())
        for (std::size_t k = 3; k < p.Coefficients().size(); k += 4)
            w = std::min(w, p.Coefficients()[k]);
    return w;
}

}  // namespace quadrix::freeform
