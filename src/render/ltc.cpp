#include "hilite/render/ltc.hpp"

#include "brdf/integrate.hpp"
#include "core/quadrature.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "hilite/render/area_light.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

namespace hilite::render {

namespace {

/// Below this angular size of the mapped polygon (its tangent radius over |M^-1 c|), the cap is a point of solid
/// angle 2 pi (1 - cos(alpha)) at its centre (shade.frag's HILITE_LTC_SMALL_CAP must agree).
constexpr double kLtcSmallCap = 0.01;

/// The fit's quadrature grid about the mirror direction q: points, weights, the lobe F (unit mass, luminance)
/// and f cos per channel.
struct Grid {
    std::vector<dvec3> w;
    std::vector<double> weight, F;
};

/// Nelder-Mead in N dimensions (deterministic; the objective is a fixed quadrature).
template <size_t N, class Fn>
std::array<double, N> nelderMead(Fn&& f, std::array<double, N> x0, std::array<double, N> step, int maxIter,
                                 int& evaluations) {
    using P = std::array<double, N>;
    std::array<P, N + 1> s;
    std::array<double, N + 1> v;
    for (size_t i = 0; i <= N; ++i) {
        s[i] = x0;
        if (i > 0) s[i][i - 1] += step[i - 1];
        v[i] = f(s[i]);
        ++evaluations;
    }
    auto lerp = [](const P& a, const P& b, double t) {
        P r;
        for (size_t k = 0; k < N; ++k) r[k] = a[k] + t * (b[k] - a[k]);
        return r;
    };
    for (int it = 0; it < maxIter; ++it) {
        std::array<size_t, N + 1> o;
        for (size_t i = 0; i <= N; ++i) o[i] = i;
        std::sort(o.begin(), o.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
        std::array<P, N + 1> s2;
        std::array<double, N + 1> v2;
        for (size_t i = 0; i <= N; ++i) s2[i] = s[o[i]], v2[i] = v[o[i]];
        s = s2, v = v2;
        if (v[N] - v[0] <= 1e-7 * std::abs(v[0]) + 1e-300) break;
        P c{};
        for (size_t i = 0; i < N; ++i)
            for (size_t k = 0; k < N; ++k) c[k] += s[i][k] / double(N);
        const P r = lerp(c, s[N], -1.0);
        const double fr = f(r);
        ++evaluations;
        if (fr < v[0]) {
            const P e = lerp(c, s[N], -2.0);
            const double fe = f(e);
            ++evaluations;
            if (fe < fr) s[N] = e, v[N] = fe;
            else s[N] = r, v[N] = fr;
        } else if (fr < v[N - 1]) {
            s[N] = r, v[N] = fr;
        } else {
            const P k = fr < v[N] ? lerp(c, s[N], -0.5) : lerp(c, s[N], 0.5);
            const double fk = f(k);
            ++evaluations;
            if (fk < std::min(fr, v[N])) {
                s[N] = k, v[N] = fk;
            } else {
                for (size_t i = 1; i <= N; ++i) {
                    s[i] = lerp(s[0], s[i], 0.5);
                    v[i] = f(s[i]);
                    ++evaluations;
                }
            }
        }
    }
    size_t best = 0;
    for (size_t i = 1; i <= N; ++i)
        if (v[i] < v[best]) best = i;
    return s[best];
}

/// M^-1 (row-major) of M = [[a, 0, b], [0, c, 0], [d, 0, 1]] in the view's frame, x = (log a, log c, b, d): the
/// cosine's own horizon may tilt (d) and its peak lean along (b, 0, 1). Empty (all 0) where a - b d <= 0.
std::array<double, 9> inverseOf4(const std::array<double, 4>& x) {
    const double a = std::exp(x[0]), c = std::exp(x[1]), b = x[2], d = x[3], D = a - b * d;
    if (!(D > 0)) return {};
    return {1.0 / D, 0.0, -b / D, 0.0, 1.0 / c, 0.0, -d / D, 0.0, a / D};
}

dvec3 mulMat(const std::array<double, 9>& m, const dvec3& v) {
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
            m[6] * v.x + m[7] * v.y + m[8] * v.z};
}

double det3(const std::array<double, 9>& m) {
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}

/// The LTC's density at unit w: D_o(M^-1 w / |M^-1 w|) |M^-1| / |M^-1 w|^3.
double density(const std::array<double, 9>& m, double det, const dvec3& w) {
    const dvec3 o = mulMat(m, w);
    if (!(o.z > 0)) return 0.0;
    const double l2 = glm::dot(o, o);
    return o.z * det / (kPi * l2 * l2);
}

void fitTable(const brdf::Params& p, LtcTable& t) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> gx, gw;
    gaussLegendre(8, gx, gw);
    const double width0 = std::max(1e-4, std::min(0.5 * kPi, brdf::lobeWidth(p)));
    const double uMax = std::sqrt(1.0 - std::cos(deg2rad(kLtcMaxElevationDeg)));
    std::array<double, 4> x{std::log(width0), std::log(width0), 0.0, 0.0};
    t.minv.assign(kLtcElevations, {}), t.norm.assign(kLtcElevations, dvec3(0.0));
    t.fitError.assign(kLtcElevations, 0.0);
    for (int k = 0; k < kLtcElevations; ++k) {
        const double u = uMax * k / (kLtcElevations - 1);
        const double cosT = 1.0 - u * u, sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
        const dvec3 we(sinT, 0.0, cosT), q(-sinT, 0.0, cosT);
        // The polar grid about q: 16 panels x 8 nodes in psi; in rho panels graded from a sixteenth of the lobe's
        // width (narrowed across by cos(theta)) to the horizon, 8 nodes each.
        const double width = std::max(1e-9, width0 * std::max(cosT, 1e-3));
        const dvec3 e1 = sinT > 0 ? dvec3(q.z, 0.0, -q.x) : dvec3(1, 0, 0), e2(0, 1, 0);
        Grid g;
        dvec3 norm(0.0);
        std::vector<dvec3> frgb;
        for (int pp = 0; pp < 16; ++pp)
            for (size_t i = 0; i < gx.size(); ++i) {
                const double psi = 2.0 * kPi * (pp + 0.5 * (gx[i] + 1.0)) / 16, wpsi = 2.0 * kPi / 16 * 0.5 * gw[i];
                const dvec3 e = std::cos(psi) * e1 + std::sin(psi) * e2;
                const double rhoH = std::atan2(e.z, q.z) + 0.5 * kPi;
                std::vector<double> edges{0.0};
                for (double r = width / 16; r < rhoH; r *= 2) edges.push_back(r);
                edges.push_back(rhoH);
                for (size_t j = 0; j + 1 < edges.size(); ++j)
                    for (size_t n = 0; n < gx.size(); ++n) {
                        const double h = 0.5 * (edges[j + 1] - edges[j]);
                        const double rho = edges[j] + h * (gx[n] + 1.0);
                        const dvec3 wi = std::cos(rho) * q + std::sin(rho) * e;
                        if (!(wi.z > 0)) continue;
                        const double wt = wpsi * h * gw[n] * std::sin(rho);
                        const dvec3 f = brdf::evaluate(p, wi, we) * wi.z;
                        g.w.push_back(wi), g.weight.push_back(wt), g.F.push_back(brdf::luminance(f));
                        norm += wt * f;
                    }
            }
        const double lum = brdf::luminance(norm);
        if (!(lum > 0)) throw InputError("light_rule ltc: the BRDF reflects nothing to fit a cosine to");
        for (double& F : g.F) F /= lum;
        auto error3 = [&](const std::array<double, 9>& m) {
            const double det = det3(m);
            if (!(det > 0)) return 1e300;
            double e = 0;
            for (size_t i = 0; i < g.F.size(); ++i) {
                const double d = std::abs(density(m, det, g.w[i]) - g.F[i]);
                e += g.weight[i] * d * d * d;
            }
            return e;
        };
        // From the previous elevation's solution (Nelder-Mead twice: the second restarts the simplex).
        auto objective = [&](const std::array<double, 4>& y) { return error3(inverseOf4(y)); };
        for (int run = 0; run < 2; ++run)
            x = nelderMead(objective, x, {0.3, 0.3, 0.1 * std::exp(x[0]) + 0.05 * std::abs(x[2]), 0.1}, 300,
                           t.objectiveEvaluations);
        const std::array<double, 9> m = inverseOf4(x);
        const double c = std::exp(x[1]);
        const double det = det3(m);
        t.minv[size_t(k)] = {c * m[0], c * m[2], c * m[6], c * m[8]};
        t.norm[size_t(k)] = norm;
        double l1 = 0;
        for (size_t i = 0; i < g.F.size(); ++i) l1 += g.weight[i] * std::abs(density(m, det, g.w[i]) - g.F[i]);
        t.fitError[size_t(k)] = l1;
    }
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::string ltcRefusal(const Scene& s) {
    if (s.brdfFile) return "a .brdf file has no fitted cosine (its BRDF is GLSL only)";
    const brdf::Params& p = s.brdf;
    if (p.anisotropic()) return "the BRDF is anisotropic (the fit is per view elevation of an isotropic lobe)";
    if (p.isMeasured()) return "a measured table is not fitted (the fit is per analytic isotropic BRDF)";
    if (p.model == brdf::Model::Retro) return "a retroreflector's lobe is not about the mirror direction";
    if (p.model == brdf::Model::None) return "the BRDF reflects nothing";
    if (brdf::isDelta(p)) return "a perfect mirror has no lobe to fit";
    if (s.surface.bumps) return "explicit bumps are drawn under a soft sun of their own";
    return "";
}

LtcTable ltcFit(const brdf::Params& p) {
    LtcTable t;
    fitTable(p, t);
    return t;
}

double ltcPolygonScale(int vertices) {
    const double h = 2.0 * kPi / vertices;
    return std::sqrt(h / std::sin(h));
}

double ltcGridCoordinate(double cosTheta) {
    const double uMax = std::sqrt(1.0 - std::cos(deg2rad(kLtcMaxElevationDeg)));
    const double u = std::sqrt(std::max(0.0, 1.0 - cosTheta)) / uMax;
    return std::clamp(u * (kLtcElevations - 1), 0.0, double(kLtcElevations - 1));
}

const LtcTable& ltcTable(const Scene& s) {
    const std::string why = ltcRefusal(s);
    if (!why.empty()) throw InputError("--light-rule ltc: " + why + " (allowed here: rings)");
    std::ostringstream key;
    key.precision(17);
    key << s.brdf << " table=" << s.brdf.ndfTable.get() << " spectrum=" << s.brdf.spectrum.get();
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<LtcTable>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto& slot = cache[key.str()];
    if (!slot) {
        auto t = std::make_unique<LtcTable>();
        fitTable(s.brdf, *t);
        slot = std::move(t);
    }
    return *slot;
}

double ltcCapIntegral(const dvec3& c, const dvec3& a, const dvec3& b, double t, const std::array<double, 9>& minv,
                      int vertices) {
    // The polygon as offsets from its centre; each clip (Sutherland-Hodgman, one plane) keeps that form.
    std::vector<dvec3> o(size_t(std::max(3, vertices))), clipped;
    for (int k = 0; k < int(o.size()); ++k) {
        const double phi = 2.0 * kPi * k / double(o.size());
        o[size_t(k)] = t * (std::cos(phi) * a + std::sin(phi) * b);
    }
    auto clip = [&](const dvec3& centre, const std::vector<dvec3>& in, std::vector<dvec3>& out) {
        out.clear();
        for (size_t k = 0; k < in.size(); ++k) {
            const dvec3& cur = in[k];
            const dvec3& nxt = in[(k + 1) % in.size()];
            const double zc = centre.z + cur.z, zn = centre.z + nxt.z;
            if (zc > 0) out.push_back(cur);
            if ((zc > 0) != (zn > 0)) out.push_back(cur + (zc / (zc - zn)) * (nxt - cur));
        }
    };
    clip(c, o, clipped);
    const dvec3 C = mulMat(minv, c);
    for (dvec3& v : clipped) v = mulMat(minv, v);
    clip(C, clipped, o);
    double sum = 0;
    for (size_t k = 0; k < o.size(); ++k) {
        const dvec3 v = C + o[k], d = o[(k + 1) % o.size()] - o[k];
        const dvec3 cr = glm::cross(v, d);
        const double s = glm::length(cr);
        if (!(s > 0)) continue;
        sum += std::atan2(s, glm::dot(v, v + d)) / s * cr.z;
    }
    return sum / (2.0 * kPi);
}

dvec3 areaRadianceLtc(const Scene& s, const dvec3& p, const dvec3& we, int vertices) {
    if (!s.light.area())
        throw InputError(std::string("areaRadianceLtc: the scene's light is ") + toString(s.light.type) +
                         ": only a sphere or disk light has a cap to integrate");
    const LtcTable& table = ltcTable(s);
    const LightCap cap = lightCap(s.light, p);
    // The view's frame: x towards we's azimuth, z the normal.
    const double h = std::hypot(we.x, we.y);
    const dvec3 t1 = h > 0 ? dvec3(we.x / h, we.y / h, 0.0) : dvec3(1, 0, 0), t2(-t1.y, t1.x, 0.0);
    auto local = [&](const dvec3& v) { return dvec3(glm::dot(v, t1), glm::dot(v, t2), v.z); };
    const double g = ltcGridCoordinate(we.z / glm::length(we));
    const int i = std::min(int(g), kLtcElevations - 2);
    const double f = g - i;
    std::array<double, 4> m;
    for (size_t k = 0; k < 4; ++k) m[k] = (1.0 - f) * table.minv[size_t(i)][k] + f * table.minv[size_t(i) + 1][k];
    const dvec3 norm = (1.0 - f) * table.norm[size_t(i)] + f * table.norm[size_t(i) + 1];
    const std::array<double, 9> minv{m[0], 0.0, m[1], 0.0, 1.0, 0.0, m[2], 0.0, m[3]};
    const double cosA = 1.0 - cap.uMax, sinA = std::sqrt(cap.uMax * (2.0 - cap.uMax));
    const double t = ltcPolygonScale(vertices) * sinA / std::max(cosA, 1e-6);
    const dvec3 c = local(cap.center), C = mulMat(minv, c);
    const double spread =
        t * std::max(glm::length(mulMat(minv, local(cap.a))), glm::length(mulMat(minv, local(cap.b))));
    if (vertices == kLtcVertices && spread < kLtcSmallCap * glm::length(C)) {
        // A cap small against the lobe (as GL, shade.frag): L x solid angle x D at its centre; the polygon's edge
        // sum cancels to its area (relative error ~ 1e-7 / size in float), this to (size)^2.
        const double det = m[0] * m[3] - m[1] * m[2];
        const double l2 = glm::dot(C, C);
        const double D = std::max(C.z, 0.0) * det / (kPi * l2 * l2);
        return (cap.radiance * 2.0 * kPi * cap.uMax * D) * norm;
    }
    const double I = ltcCapIntegral(c, local(cap.a), local(cap.b), t, minv, vertices);
    return (cap.radiance * std::max(I, 0.0)) * norm;
}

}  // namespace hilite::render
