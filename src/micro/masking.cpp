#include "micro/masking.hpp"

#include <random>
#include <stdexcept>

namespace hilite::micro {

double lambdaBeckmannExact(double cosTheta, double m) {
    const double sinTheta = safeSqrt(1.0 - cosTheta * cosTheta);
    if (sinTheta == 0.0) return 0.0;  // normal incidence: nothing is masked
    const double a = cosTheta / (m * sinTheta);
    return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

namespace {

/// Does the ray from p (tile lengths) along w leave the height field? Marched in half-texel steps of
/// horizontal travel until it is above the highest point of the tile.
bool visible(const BumpField& f, const dvec3& p, const dvec3& w) {
    const double horiz = std::hypot(w.x, w.y);
    if (horiz == 0.0) return true;  // straight up: nothing is above a height field
    const double dx = w.x / horiz, dy = w.y / horiz, rise = w.z / horiz;
    if (rise <= 0.0) return false;  // at or below the horizon
    const double step = 0.25 / f.n, tEnd = (f.heightMax - p.z) / rise + step;
    for (double t = step; t <= tEnd; t += step)
        if (f.height(p.x + dx * t, p.y + dy * t) > p.z + rise * t) return false;
    return true;
}

struct Ratio {
    double num = 0, den = 0, sq = 0;  // sum aV, sum a, and the pieces for the variance
    std::vector<std::pair<double, double>> terms;
    void add(double a, bool v) { num += a * v, den += a, terms.emplace_back(a, v ? 1.0 : 0.0); }
    double value() const { return den > 0 ? num / den : 0.0; }
    /// Standard error of a ratio estimate: sqrt(sum a^2 (V - R)^2) / sum a (delta method).
    double error() const {
        const double r = value();
        double s = 0;
        for (const auto& [a, v] : terms) s += a * a * (v - r) * (v - r);
        return den > 0 ? std::sqrt(s) / den : 0.0;
    }
};

}  // namespace

std::vector<MaskingRow> traceMasking(const BumpField& f, const std::vector<double>& thetasDeg, long samples,
                                     uint64_t seed) {
    if (f.spec.kind != BumpKind::Beckmann)
        throw std::invalid_argument("masking is traced on Beckmann height fields only (a GGX field is a normal map)");
    // The same facets for every angle (common random numbers): the rows' differences are not sampling noise.
    std::mt19937_64 engine(seed);
    auto uniform = [&] { return double(engine() >> 11) * 0x1.0p-53; };
    std::vector<dvec2> points(static_cast<size_t>(samples));
    for (auto& q : points) q = {uniform(), uniform()};
    std::vector<MaskingRow> rows;
    for (double thetaDeg : thetasDeg) {
        const dvec3 wo = sphericalDirectionDeg(thetaDeg, 0.0), wiSpec(-wo.x, -wo.y, wo.z);  // h = n
        Ratio g1, g1h, g2;
        const double near2 = 0.25 * f.spec.roughness * f.spec.roughness;  // |s - s_h| < roughness / 2, s_h = 0
        for (const dvec2& q : points) {
            const BumpSample b = f.sample(q.x, q.y);
            const dvec3 m = glm::normalize(dvec3(-b.s.x, -b.s.y, 1.0));
            const double a = std::max(0.0, glm::dot(wo, m)) / m.z;
            if (a == 0.0) continue;  // back-facing to the eye: no projected area
            const dvec3 p(q.x, q.y, b.h);
            const bool vo = visible(f, p, wo);
            g1.add(a, vo);
            if (glm::dot(b.s, b.s) < near2 && glm::dot(wiSpec, m) > 0.0) {
                g1h.add(a, vo);
                g2.add(a, vo && visible(f, p, wiSpec));
            }
        }
        MaskingRow r;
        r.thetaDeg = thetaDeg;
        r.samples = samples;
        r.highlightFacets = long(g2.terms.size());
        const double lambda = lambdaBeckmannExact(wo.z, f.spec.roughness);
        r.g1 = g1.value(), r.g1Err = g1.error(), r.g1Smith = 1.0 / (1.0 + lambda);
        r.g1Realized = g1.den > 0 ? wo.z * double(samples) / g1.den : 0.0;
        r.g1h = g1h.value(), r.g1hErr = g1h.error();
        r.g2 = g2.value(), r.g2Err = g2.error(), r.g2Smith = 1.0 / (1.0 + 2.0 * lambda);
        r.g2Uncorrelated = r.g1Smith * r.g1Smith;
        rows.push_back(r);
    }
    return rows;
}

}  // namespace hilite::micro
