#include "quadrix/engines/scanline/span_shader.h"

#include <algorithm>

namespace quadrix::scanline {

void SpanShader::AddExactFace(const RayEvaluator::Hit& hit, int unit, int sample, double y) {
    StackFace f = MakeFaceAt(ctx_.eval, hit.halfSpace, hit.t, sample + 0.5, y);
    f.unit = unit;
    f.body = hit.body;
    f.solid = ctx_.UnitOf(unit).solid;
    if (ctx_.settings.fastShading) f.fastNormal = Normal(f.halfSpace, sample + 0.5, y, hit.t);
    InsertFace(f, sample + 0.5, y);
}

Vec3 SpanShader::ShadedNormal(StackFace& f, int i, int i0, int i1, int delta, double y, double t) {
    if (ctx_.settings.fastShading) return f.fastNormal;
    if (delta <= 1) return Normal(f.halfSpace, i + 0.5, y, t);
    int g0 = i0 + ((i - i0) / delta) * delta, g1 = std::min(g0 + delta, i1);
    if (g1 == g0) return Normal(f.halfSpace, i + 0.5, y, t);
    if (f.g0 != g0 || f.g1 != g1) {
        // Moving on by one interval: the old right end is the new left end.
        bool reuse = f.g1 == g0;
        double t0 = reuse ? 0 : FaceDepthAt(f, g0, y), t1 = FaceDepthAt(f, g1, y);
        if (!std::isfinite(t0) || !std::isfinite(t1)) return Normal(f.halfSpace, i + 0.5, y, t);
        f.n0 = reuse ? f.n1 : Normal(f.halfSpace, g0 + 0.5, y, t0);
        f.n1 = Normal(f.halfSpace, g1 + 0.5, y, t1);
        f.g0 = g0;
        f.g1 = g1;
    }
    if (i == g0) return f.n0;
    double s = static_cast<double>(i - g0) / (g1 - g0);
    Vec3 n = f.n0 * (1 - s) + f.n1 * s;
    double len = Length(n);
    return len > 0 ? n / len : f.n0;
}

void SpanShader::TakeStackFaces(const std::vector<int>& shown, int sample, double y) {
    stackHead_ = faces_.empty() ? 0 : -1;
    ++ctx_.c.stackSpans;
    ctx_.c.stackDepthSum += shown.size();
    taken_.clear();
    for (int f : shown) {
        const ShowFace& sf = ctx_.Face(f);
        const auto b = static_cast<std::size_t>(sf.body);
        if (bodyTaken_[b]) continue;
        bodyTaken_[b] = 1;
        taken_.push_back(sf.body);
        const int u = ctx_.bodyUnit[b];
        StackFace face;
        face.halfSpace = sf.halfSpace;
        face.sheet = ctx_.SheetOf(f);
        face.ray = &ctx_.eval.Ray(sf.halfSpace);
        face.unit = u;
        face.body = sf.body;
        face.solid = ctx_.UnitOf(u).solid;
        if (ctx_.settings.fastShading) {
            const double t = FaceDepthAt(face, sample, y);
            face.fastNormal =
                std::isfinite(t) ? Normal(face.halfSpace, sample + 0.5, y, t) : Vec3{0, 0, -1};
        }
        faces_.push_back(face);
    }
    for (int b : taken_) bodyTaken_[static_cast<std::size_t>(b)] = 0;
}

void SpanShader::InsertFace(const StackFace& f, double x, double y) {
    ++ctx_.c.faceInserts;
    std::size_t pos = faces_.size();
    FaceRef fr{f.halfSpace, f.sheet};
    for (std::size_t s = 0; s < faces_.size(); ++s) {
        FaceRef gr{faces_[s].halfSpace, faces_[s].sheet};
        double zf, zg, d1, d2, c1, c2;
        bool ok = FaceDerivatives(ctx_.scene, fr, x, y, zf, d1, c1) &&
                  FaceDerivatives(ctx_.scene, gr, x, y, zg, d2, c2);
        int cmp;
        if (ok && zf != zg) {
            cmp = zf < zg ? -1 : 1;
        } else {
            ++ctx_.c.tieBreaks;
            cmp = CompareFaces(ctx_.scene, fr, gr, x, y, ctx_.scene.depthTolerance);
        }
        if (cmp < 0) {
            pos = s;
            break;
        }
    }
    faces_.insert(faces_.begin() + static_cast<std::ptrdiff_t>(pos), f);
}

}  // namespace quadrix::scanline
