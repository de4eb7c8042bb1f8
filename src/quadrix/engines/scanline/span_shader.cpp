#include "quadrix/engines/scanline/span_shader.h"

#include <algorithm>

namespace quadrix::scanline {

void SpanShader::AddExactFace(const eval::RayEvaluator::Hit& hit, int unit, int sample, double y) {
    StackFace f = MakeFaceAt(ctx_.eval, hit.halfSpace, hit.t, sample + 0.5, y);
    f.unit = unit;
    f.body = hit.body;
    f.solid = ctx_.UnitOf(unit).solid;
    if (ctx_.settings.fastShading) f.fastNormal = Normal(f.halfSpace, sample + 0.5, y, hit.t);
    InsertFace(f, sample + 0.5, y);
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

inline void SpanShader::InsertFace(const StackFace& f, double x, double y) {
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
