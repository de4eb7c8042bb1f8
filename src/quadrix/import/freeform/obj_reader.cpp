// The freeform subset of Wavefront OBJ (freeform_reader.h). Statement reference: the Wavefront
// "Object Files (.obj)" specification, sections "Free-form curve/surface attributes" (cstype, deg,
// parm) and "Elements" (surf), read here as documented in testdata/SOURCES.md.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "quadrix/freeform/bspline.h"
#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/import/freeform/readers_internal.h"

namespace quadrix::import::detail {

namespace {

enum class CurveType { kNone, kBezier, kBSpline };

// A `surf` statement being collected until its `end`.
struct PendingSurface {
    ScanToken at;  // the `surf` keyword
    CurveType type = CurveType::kNone;
    bool rational = false;
    int degreeU = 0, degreeV = 0;
    double s0 = 0, s1 = 1, t0 = 0, t1 = 1;
    std::vector<long long> vertices;  // resolved 0-based indices
    std::vector<ScanToken> vertexTokens;
    std::vector<double> parmU, parmV;
    ScanToken parmUAt, parmVAt;
    bool haveParmU = false, haveParmV = false;
    bool trimWarned = false;
};

class ObjReader {
  public:
    ObjReader(TextScanner& s, std::string baseName) : s_(s), baseName_(std::move(baseName)) {}

    std::vector<freeform::Surface> Read() {
        std::vector<ScanToken> line;
        while (s_.NextLine(line)) Statement(line);
        if (pending_) s_.Error(pending_->at, "'surf' without a matching 'end'");
        return std::move(out_);
    }

  private:
    void Statement(const std::vector<ScanToken>& line) {
        std::string_view kw = line[0].text;
        if (kw == "v") return Vertex(line);
        if (kw == "vt" || kw == "vn" || kw == "vp") return;  // counted by nobody: only v matters
        if (kw == "cstype") return CsType(line);
        if (kw == "deg") return Degree(line);
        if (kw == "surf") return Surf(line);
        if (kw == "parm") return Parm(line);
        if (kw == "end") return End(line);
        if (kw == "trim" || kw == "hole" || kw == "scrv" || kw == "sp") {
            if (!pending_) {
                s_.Error(line[0], "'" + std::string(kw) + "' outside a surf ... end block");
            } else if (!pending_->trimWarned) {
                pending_->trimWarned = true;
                s_.Warning(line[0],
                           "trimming and special curves are not supported; the surface "
                           "is drawn untrimmed");
            }
            return;
        }
        if (kw == "curv" || kw == "curv2") {
            WarnOnce(line[0], "free-form curves are not drawn and are skipped");
            skippingCurve_ = true;
            return;
        }
        if (kw == "f" || kw == "l" || kw == "p") {
            WarnOnce(line[0], "polygonal elements (f, l, p) are not read by the freeform importer");
            return;
        }
        if (kw == "o" || kw == "g") {
            if (line.size() > 1) groupName_ = std::string(line[1].text);
            return;
        }
        if (kw == "bmat" || kw == "step") {
            WarnOnce(line[0], "'" + std::string(kw) +
                                  "' is only used by basis-matrix and cardinal "
                                  "curves, which are not supported; ignored");
            return;
        }
        // Display and grouping attributes that do not change the geometry.
        static const std::set<std::string_view> kIgnored = {
            "s",         "mg",     "usemtl",   "mtllib",   "lod",   "shadow_obj",
            "trace_obj", "bevel",  "c_interp", "d_interp", "ctech", "stech",
            "con",       "maplib", "usemap",   "call",     "csh"};
        if (kIgnored.count(kw)) return;
        WarnOnce(line[0], "unknown OBJ statement '" + std::string(kw) + "' is ignored");
    }

    void WarnOnce(const ScanToken& at, const std::string& message) {
        if (warned_.insert(message).second) s_.Warning(at, message);
    }

    void Vertex(const std::vector<ScanToken>& line) {
        if (line.size() < 4 || line.size() > 5) {
            s_.Error(line[0], "a vertex needs 'v x y z [w]'");
            vertices_.push_back({0, 0, 0, 1});
            return;
        }
        double c[4] = {0, 0, 0, 1};
        for (std::size_t k = 1; k < line.size(); ++k) {
            std::optional<double> x = s_.Number(line[k], k == 4 ? "a weight" : "a coordinate");
            if (x) c[k - 1] = *x;
        }
        vertices_.push_back({c[0], c[1], c[2], c[3]});
    }

    void CsType(const std::vector<ScanToken>& line) {
        std::size_t k = 1;
        rational_ = false;
        if (k < line.size() && line[k].text == "rat") {
            rational_ = true;
            ++k;
        }
        if (k + 1 != line.size()) {
            s_.Error(line[0], "expected 'cstype [rat] bezier|bspline'");
            return;
        }
        std::string_view t = line[k].text;
        if (t == "bezier") {
            type_ = CurveType::kBezier;
        } else if (t == "bspline") {
            type_ = CurveType::kBSpline;
        } else if (t == "cardinal" || t == "taylor" || t == "bmatrix") {
            type_ = CurveType::kNone;
            s_.Error(line[k], "curve type '" + std::string(t) +
                                  "' is not supported (only bezier and bspline)");
        } else {
            type_ = CurveType::kNone;
            s_.Error(line[k], "unknown curve type '" + std::string(t) + "'");
        }
        typeAt_ = line[k];
    }

    void Degree(const std::vector<ScanToken>& line) {
        if (line.size() < 2 || line.size() > 3) {
            s_.Error(line[0], "expected 'deg du [dv]'");
            return;
        }
        for (std::size_t k = 1; k < line.size(); ++k) {
            std::optional<long long> d = s_.Integer(line[k], "a degree");
            if (!d) return;
            if (*d < 1 || *d > kMaxFreeformDegree) {
                s_.Error(line[k], "degree " + std::to_string(*d) + " is outside 1.." +
                                      std::to_string(kMaxFreeformDegree));
                return;
            }
            (k == 1 ? degreeU_ : degreeV_) = static_cast<int>(*d);
        }
        haveDegreeV_ = line.size() == 3;
    }

    // "7", "7/2", "7/2/3", "7//3" and negative (relative) indices.
    std::optional<long long> VertexIndex(const ScanToken& t) {
        std::string_view text = t.text.substr(0, t.text.find('/'));
        ScanToken head = t;
        head.text = text;
        std::optional<long long> i = s_.Integer(head, "a vertex index");
        if (!i) return std::nullopt;
        long long n = static_cast<long long>(vertices_.size());
        long long r = *i > 0 ? *i - 1 : n + *i;
        if (*i == 0 || r < 0 || r >= n) {
            s_.Error(t, "vertex index " + std::to_string(*i) + " does not name a vertex (" +
                            std::to_string(n) + " defined so far)");
            return std::nullopt;
        }
        return r;
    }

    void Surf(const std::vector<ScanToken>& line) {
        skippingCurve_ = false;
        if (pending_) {
            s_.Error(line[0], "'surf' inside another surf block (missing 'end')");
            pending_.reset();
        }
        PendingSurface p;
        p.at = line[0];
        if (type_ == CurveType::kNone) {
            s_.Error(line[0], "'surf' needs a supported 'cstype' before it");
            return;
        }
        if (degreeU_ == 0 || !haveDegreeV_) {
            s_.Error(line[0], "'surf' needs 'deg du dv' before it");
            return;
        }
        if (line.size() < 6) {
            s_.Error(line[0], "expected 'surf s0 s1 t0 t1 v1 v2 ...'");
            return;
        }
        double range[4];
        for (int k = 0; k < 4; ++k) {
            std::optional<double> x =
                s_.Number(line[static_cast<std::size_t>(k + 1)], "a parameter range value");
            if (!x) return;
            range[k] = *x;
        }
        p.s0 = range[0];
        p.s1 = range[1];
        p.t0 = range[2];
        p.t1 = range[3];
        for (std::size_t k = 5; k < line.size(); ++k) {
            std::optional<long long> i = VertexIndex(line[k]);
            if (!i) return;
            p.vertices.push_back(*i);
            p.vertexTokens.push_back(line[k]);
        }
        p.type = type_;
        p.rational = rational_;
        p.degreeU = degreeU_;
        p.degreeV = degreeV_;
        pending_ = std::move(p);
    }

    void Parm(const std::vector<ScanToken>& line) {
        if (skippingCurve_) return;
        if (!pending_) {
            s_.Error(line[0], "'parm' outside a surf ... end block");
            return;
        }
        if (line.size() < 3 || (line[1].text != "u" && line[1].text != "v")) {
            s_.Error(line[0], "expected 'parm u|v values...'");
            return;
        }
        bool u = line[1].text == "u";
        std::vector<double>& values = u ? pending_->parmU : pending_->parmV;
        values.clear();
        for (std::size_t k = 2; k < line.size(); ++k) {
            std::optional<double> x = s_.Number(line[k], "a parameter value");
            if (!x) return;
            values.push_back(*x);
        }
        (u ? pending_->haveParmU : pending_->haveParmV) = true;
        (u ? pending_->parmUAt : pending_->parmVAt) = line[1];
    }

    void End(const std::vector<ScanToken>& line) {
        if (skippingCurve_) {
            skippingCurve_ = false;
            return;
        }
        if (!pending_) {
            s_.Error(line[0], "'end' without a 'surf'");
            return;
        }
        PendingSurface p = std::move(*pending_);
        pending_.reset();
        Build(p);
    }

    // Knots along one direction from a parm list; the number of control points it implies.
    std::optional<std::vector<double>> Knots(const PendingSurface& p, bool u) {
        int degree = u ? p.degreeU : p.degreeV;
        const std::vector<double>& parm = u ? p.parmU : p.parmV;
        bool have = u ? p.haveParmU : p.haveParmV;
        const ScanToken& at = have ? (u ? p.parmUAt : p.parmVAt) : p.at;
        std::string dir = u ? "u" : "v";
        if (!have) {
            if (p.type == CurveType::kBezier) {
                // One segment on [0, 1] when no parm is given (lenient: the spec asks for parm).
                std::vector<double> k(static_cast<std::size_t>(degree + 1), 0.0);
                k.insert(k.end(), static_cast<std::size_t>(degree + 1), 1.0);
                return k;
            }
            s_.Error(at, "missing 'parm " + dir + "' (the knot vector) for this B-spline surface");
            return std::nullopt;
        }
        for (std::size_t i = 1; i < parm.size(); ++i)
            if (parm[i] < parm[i - 1]) {
                s_.Error(at, "parm " + dir + " values must not decrease");
                return std::nullopt;
            }
        if (p.type == CurveType::kBSpline) return parm;
        // Bézier: breakpoints b0 < b1 < ... < bK; segments of `degree` each.
        if (parm.size() < 2) {
            s_.Error(at, "a Bezier surface needs at least two parm " + dir + " values");
            return std::nullopt;
        }
        for (std::size_t i = 1; i < parm.size(); ++i)
            if (!(parm[i] > parm[i - 1])) {
                s_.Error(at, "Bezier breakpoints in parm " + dir + " must increase");
                return std::nullopt;
            }
        std::vector<double> k(static_cast<std::size_t>(degree + 1), parm.front());
        for (std::size_t i = 1; i + 1 < parm.size(); ++i)
            k.insert(k.end(), static_cast<std::size_t>(degree), parm[i]);
        k.insert(k.end(), static_cast<std::size_t>(degree + 1), parm.back());
        return k;
    }

    void Build(PendingSurface& p) {
        std::optional<std::vector<double>> ku = Knots(p, true), kv = Knots(p, false);
        if (!ku || !kv) return;
        long long nu = static_cast<long long>(ku->size()) - p.degreeU - 1;
        long long nv = static_cast<long long>(kv->size()) - p.degreeV - 1;
        long long have = static_cast<long long>(p.vertices.size());
        if (nu < p.degreeU + 1 || nv < p.degreeV + 1 || nu * nv != have) {
            s_.Error(p.at, "surf lists " + std::to_string(have) +
                               " control points, but its degrees and parameter vectors need " +
                               std::to_string(std::max(nu, 0LL)) + " x " +
                               std::to_string(std::max(nv, 0LL)));
            return;
        }
        std::string why = freeform::CheckKnots(*ku, p.degreeU, static_cast<int>(nu));
        if (why.empty()) why = freeform::CheckKnots(*kv, p.degreeV, static_cast<int>(nv));
        if (!why.empty()) {
            s_.Error(p.haveParmU ? p.parmUAt : p.at, "bad knot vector: " + why);
            return;
        }
        std::vector<double> c;
        c.reserve(static_cast<std::size_t>(have) * (p.rational ? 4 : 3));
        bool nonPositive = false;
        for (long long i : p.vertices) {
            const Vec4& v = vertices_[static_cast<std::size_t>(i)];
            if (p.rational) {
                c.insert(c.end(), {v.x * v.w, v.y * v.w, v.z * v.w, v.w});
                nonPositive = nonPositive || !(v.w > 0);
            } else {
                c.insert(c.end(), {v.x, v.y, v.z});
            }
        }
        if (nonPositive)
            s_.Warning(p.at,
                       "a control point has a weight <= 0; the surface may pass through "
                       "infinity there");
        freeform::BSplineSurface net(p.rational ? 4 : 3, p.degreeU, p.degreeV, *ku, *kv,
                                     std::move(c));
        double u0 = net.U0(), u1 = net.U1(), v0 = net.V0(), v1 = net.V1();
        if (!(p.s0 < p.s1) || !(p.t0 < p.t1) || p.s0 < u0 || p.s1 > u1 || p.t0 < v0 || p.t1 > v1) {
            s_.Error(p.at, "the surf range [" + Fmt(p.s0) + ", " + Fmt(p.s1) + "] x [" + Fmt(p.t0) +
                               ", " + Fmt(p.t1) + "] is not inside the parameter domain [" +
                               Fmt(u0) + ", " + Fmt(u1) + "] x [" + Fmt(v0) + ", " + Fmt(v1) + "]");
            return;
        }
        if (p.s0 > u0 || p.s1 < u1 || p.t0 > v0 || p.t1 < v1)
            net = net.Restricted(p.s0, p.s1, p.t0, p.t1);
        std::string base = groupName_.empty() ? baseName_ : groupName_;
        out_.emplace_back(std::move(net), SurfaceName(base, out_.size()));
    }

    static std::string Fmt(double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        return buf;
    }

    TextScanner& s_;
    std::string baseName_;
    std::string groupName_;
    std::vector<Vec4> vertices_;
    CurveType type_ = CurveType::kNone;
    ScanToken typeAt_;
    bool rational_ = false;
    int degreeU_ = 0, degreeV_ = 0;
    bool haveDegreeV_ = false;
    bool skippingCurve_ = false;
    std::optional<PendingSurface> pending_;
    std::set<std::string> warned_;
    std::vector<freeform::Surface> out_;
};

}  // namespace

std::vector<freeform::Surface> ReadObj(TextScanner& scanner, const std::string& baseName) {
    return ObjReader(scanner, baseName).Read();
}

}  // namespace quadrix::import::detail
