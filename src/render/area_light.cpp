#include "hilite/render/area_light.hpp"
#include "render/area_bounds.hpp"

#include "brdf/integrate.hpp"
#include "core/quadrature.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "hilite/render/ltc.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hilite::render {

namespace {

/// 2 sin^2(x / 2) = 1 - cos(x) without the cancellation of small x.
double oneMinusCos(double x) {
    const double s = std::sin(0.5 * x);
    return 2.0 * s * s;
}

/// A tangent frame at the unit vector c: a in the vertical plane through c pointing down (a.z <= 0), b
/// horizontal; any orthonormal pair at the zenith.
void tangentFrame(const dvec3& c, dvec3& a, dvec3& b) {
    const double s = std::hypot(c.x, c.y);
    if (s < 1e-300) {
        a = dvec3(1, 0, 0), b = dvec3(0, 1, 0);
        return;
    }
    a = dvec3(c.x * c.z / s, c.y * c.z / s, -s);
    b = dvec3(-c.y / s, c.x / s, 0.0);
}

}  // namespace

LightCap lightCap(const Light& light, const dvec3& p) {
    LightCap cap;
    if (light.type == LightType::Sphere) {
        const dvec3 toCentre = light.position() - p;
        const double d = glm::length(toCentre);
        cap.center = toCentre / d;
        const double s = std::min(1.0, light.radius / d);
        cap.halfAngle = std::asin(s);
        cap.uMax = s * s / (1.0 + std::sqrt(1.0 - s * s));
        cap.radiance = light.intensity / (kPi * light.radius * light.radius);
    } else if (light.type == LightType::Disk) {
        cap.center = light.direction();
        cap.halfAngle = deg2rad(light.angleDeg);
        cap.uMax = oneMinusCos(cap.halfAngle);
        const double s = std::sin(cap.halfAngle);
        cap.radiance = light.irradiance / (kPi * s * s);
    } else {
        throw std::logic_error("render::lightCap: a point or directional light has no cap");
    }
    tangentFrame(cap.center, cap.a, cap.b);
    return cap;
}

double horizonEdge(double cz, double k) {
    // wi(beta) = cos(beta) c + sin(beta) (cos(phi) a + sin(phi) b) has wi.z = c.z cos(beta) + k sin(beta), k = cos(phi) a.z
    // (b.z = 0; c.z >= 0): positive up to beta_h = atan2(k, c.z) + pi/2, where 1 - cos(beta_h) = 1 + k / r,
    // r = hypot(k, c.z), written c.z^2 / (r (r - k)) for k < 0 (no cancellation); for k >= 0, beta_h >= 90 deg.
    if (k >= 0) return 2.0;
    const double r = std::hypot(k, cz);
    return r > 0 ? cz * cz / (r * (r - k)) : 0.0;
}

double capEdge(const LightCap& cap, double phi) {
    return std::min(cap.uMax, horizonEdge(cap.center.z, std::cos(phi) * cap.a.z));
}

double capVisibleFraction(const LightCap& cap) {
    const double full = cap.uMax;
    if (!(full > 0)) return 0.0;
    // The visible solid angle int u_max(phi) dphi, by the rule's own azimuths at kMaxRings (4 x 32 = 128) refined
    // 8-fold: the horizon's kink in phi is the only error (below 1e-5 at 1024 azimuths).
    constexpr int m = 1024;
    double sum = 0;
    for (int j = 0; j < m; ++j) sum += capEdge(cap, 2.0 * kPi * (j + 0.5) / m);
    return std::min(1.0, sum / (m * full));
}

const RingRule& ringRule(int n) {
    static const std::vector<RingRule> rules = [] {
        std::vector<RingRule> r(size_t(kMaxRings) + 1);
        for (int k = 1; k <= kMaxRings; ++k) {
            gaussLegendre(k, r[size_t(k)].x, r[size_t(k)].w);
            for (double& x : r[size_t(k)].x) x = 0.5 * (x + 1.0);  // [-1, 1] -> (0, 1)
            for (double& w : r[size_t(k)].w) w *= 0.5;
        }
        return r;
    }();
    if (n < 1 || n > kMaxRings) throw std::logic_error("render::ringRule: rings outside [1, 32]");
    return rules[size_t(n)];
}

void capRulePoints(const LightCap& cap, int n, const std::function<void(const dvec3& wi, double w)>& visit) {
    if (n == kCentreRule) {  // the centre, weighed by the 1-ring rule's shares of the cap (the horizon's cut)
        double share = 0;
        for (int j = 0; j < 4; ++j) share += std::max(0.0, capEdge(cap, 2.0 * kPi * (j + 0.5) / 4));
        if (share > 0) visit(cap.center, share);
        return;
    }
    const RingRule& rule = ringRule(n);
    const int m = 4 * n;
    for (int j = 0; j < m; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / m;
        const double uMax = capEdge(cap, phi);
        if (!(uMax > 0)) continue;
        const dvec3 d = std::cos(phi) * cap.a + std::sin(phi) * cap.b;
        for (int i = 0; i < n; ++i) {
            const double u = uMax * rule.x[size_t(i)];
            visit((1.0 - u) * cap.center + std::sqrt(u * (2.0 - u)) * d, rule.w[size_t(i)] * uMax);
        }
    }
}

dvec3 capRule(const LightCap& cap, int n, const std::function<dvec3(const dvec3&)>& g) {
    dvec3 sum(0.0);
    capRulePoints(cap, n, [&](const dvec3& wi, double w) { sum += w * g(wi); });
    return sum * capRuleScale(n);
}

namespace {

/// The lobe's ellipse about q in the tangent plane (e1, e2): -log g at distance `width` toward 0, 45 and 90 deg
/// is a quadratic form; its long axis (angle theta from e1) and its axis ratio (short / long, in [0.02, 1]).
/// Only a change of the integration variable rests on it (capExact stays exact whatever it says); a lobe that
/// does not fall away from q in every direction gets ratio 1.
struct LobeAxes {
    double theta = 0, ratio = 1;
};
LobeAxes lobeAxes(const dvec3& q, const dvec3& e1, const dvec3& e2, double width,
                  const std::function<dvec3(const dvec3&)>& g) {
    LobeAxes axes;
    const double g0 = quadratureNorm(g(q));
    auto fall = [&](double psi) {
        const dvec3 w = std::cos(width) * q + std::sin(width) * (std::cos(psi) * e1 + std::sin(psi) * e2);
        const double v = quadratureNorm(g(w));
        return v > 0 && g0 > v ? std::log(g0 / v) : 0.0;
    };
    const double A = fall(0.0), C = fall(0.5 * kPi), B = fall(0.25 * kPi) - 0.5 * (A + C);
    const double mean = 0.5 * (A + C), spread = std::hypot(0.5 * (A - C), B);
    if (!(A > 0 && C > 0 && mean - spread > 0)) return axes;
    axes.ratio = std::clamp(std::sqrt((mean - spread) / (mean + spread)), 0.02, 1.0);
    axes.theta = 0.5 * std::atan2(2.0 * B, A - C) + 0.5 * kPi;  // the direction of the smallest fall
    return axes;
}

}  // namespace

CapIntegral capExact(const LightCap& cap, const dvec3& q, double width, const std::function<dvec3(const dvec3&)>& g) {
    CapIntegral out;
    const dvec3& c = cap.center;
    const double alpha = cap.halfAngle;
    if (!(alpha > 0)) return out;
    dvec3 e1, e2;
    tangentFrame(q, e1, e2);
    const double sinHalf = std::sin(0.5 * alpha), sinAlpha = std::sin(alpha);
    // A scale for the absolute tolerances: the rule's estimate (0 only when every node misses a spike, when
    // the relative tolerances alone decide).
    const double scale = quadratureNorm(capRule(cap, 4, g));
    const double relTol = kExactTolerance;
    auto add = [&](const QuadratureResult<dvec3>& r) {
        out.evaluations += r.evaluations;
        out.converged = out.converged && r.converged;
        return r.value;
    };

    // The ray from q towards e: w(rho) = cos(rho) q + sin(rho) e, dw = sin(rho) drho dpsi.
    // rho = b (e^s - 1), b half the lobe's width: its peak at rho = 0 and its tail are both smooth in s (b = width / 8:
    // 18% more evaluations for the same values).
    const double b = width / 2;
    auto ray = [&](double psi) -> dvec3 {
        const dvec3 e = std::cos(psi) * e1 + std::sin(psi) * e2;
        // Its great circle passes the cap's centre at angle d (sin d = |c . (q x e)|), nearest at rho_c; it runs
        // inside the cap for |rho - rho_c| <= h, sin^2(h / 2) = (sin^2(alpha / 2) - sin^2(d / 2)) / cos(d)
        // (cos h = cos(alpha) / cos(d), written without the cancellation of tiny caps).
        const double sinD = std::min(1.0, std::abs(glm::dot(c, glm::cross(q, e))));
        if (sinD >= sinAlpha) return dvec3(0.0);
        const double d = std::asin(sinD), sinHalfD = std::sin(0.5 * d);
        const double s2 = (sinHalf - sinHalfD) * (sinHalf + sinHalfD) / std::cos(d);
        const double h = 2.0 * std::asin(std::min(1.0, std::sqrt(std::max(0.0, s2))));
        const double rhoC = std::atan2(glm::dot(c, e), glm::dot(c, q));
        // The horizon: w.z = q.z cos(rho) + e.z sin(rho) > 0 up to atan2(e.z, q.z) + pi/2 (q.z > 0).
        const double rhoHorizon = std::atan2(e.z, q.z) + 0.5 * kPi;
        auto f = [&](double sv) -> dvec3 {
            const double rho = b * std::expm1(sv);
            const dvec3 w = std::cos(rho) * q + std::sin(rho) * e;
            return ((rho + b) * std::sin(rho)) * g(w);
        };
        dvec3 sum(0.0);
        for (double shift : {-2.0 * kPi, 0.0, 2.0 * kPi}) {
            const double r1 = std::max(0.0, rhoC - h + shift), r2 = std::min({kPi, rhoC + h + shift, rhoHorizon});
            if (!(r2 > r1)) continue;
            // Panels at most 2 long in s (a factor e^2 in rho + b), so the analytic error model holds on each.
            const double s1 = std::log1p(r1 / b), sEnd = std::log1p(r2 / b);
            const int panels = std::max(1, int(std::ceil((sEnd - s1) / 2.0)));
            for (int k = 0; k < panels; ++k)
                sum +=
                    add(integrateAdaptive<dvec3>(f, s1 + (sEnd - s1) * k / panels, s1 + (sEnd - s1) * (k + 1) / panels,
                                                 relTol, 0.1 * relTol * scale, 256, PanelError::Analytic));
        }
        return sum;
    };
    // The rays' angle psi = theta + atan2(ratio sin(chi), cos(chi)): uniform in chi, the rays crowd along the
    // lobe's long axis, where a lobe narrowed by cos(theta_i) (a microfacet lobe at grazing incidence) reaches
    // furthest; its share of each ray's integral becomes even in chi. ray() is 2 pi periodic in psi, so the
    // jump of atan2 at chi = pi does not matter.
    const LobeAxes axes = lobeAxes(q, e1, e2, width, g);
    out.evaluations += 4;
    const double ratio = axes.ratio;
    auto psiOf = [&](double chi) { return axes.theta + std::atan2(ratio * std::sin(chi), std::cos(chi)); };
    auto chiOf = [&](double psi) { return std::atan2(std::sin(psi - axes.theta) / ratio, std::cos(psi - axes.theta)); };
    auto inChi = [&](double chi) -> dvec3 {
        const double cc = std::cos(chi), ss = std::sin(chi);
        return (ratio / (cc * cc + ratio * ratio * ss * ss)) * ray(psiOf(chi));  // dpsi / dchi
    };
    const double sinDq = glm::length(glm::cross(q, c)), D = std::atan2(sinDq, glm::dot(q, c));
    // The outer integral keeps the bound G7's error gives: a ray's integral can change sharply in chi (where q lies
    // just inside the cap's edge, the rays toward it end within the lobe), and the analytic model, trusted there,
    // accepted panels 1e-4 off (GGX 0.02 + Smith under a 5 deg disk at 80 deg, at 1 of 2048 contour rays).
    if (D < alpha) {  // q inside the cap: every ray leaves it once, a smooth periodic integrand in chi
        for (int k = 0; k < 4; ++k)
            out.value +=
                add(integrateAdaptive<dvec3>(inChi, 0.5 * kPi * k, 0.5 * kPi * (k + 1), relTol, relTol * scale));
        return out;
    }
    // q outside: the rays that meet the cap fill psi_c +- Delta, sin(Delta) = sin(alpha) / sin(D) (the tangent rays);
    // chi = chi_m + chi_h sin(t) over that range turns the chord's square-root ends into smooth ones.
    const double psiC = std::atan2(glm::dot(c, e2), glm::dot(c, e1));
    const double delta = std::asin(std::min(1.0, sinAlpha / std::sin(D)));
    const double chi1 = chiOf(psiC - delta);
    double span = chiOf(psiC + delta) - chi1;  // the map is increasing: the range's length in chi, in (0, 2 pi)
    if (span <= 0) span += 2.0 * kPi;
    const double chiM = chi1 + 0.5 * span, chiH = 0.5 * span;
    auto inT = [&](double t) -> dvec3 { return (chiH * std::cos(t)) * inChi(chiM + chiH * std::sin(t)); };
    out.value = add(integrateAdaptive<dvec3>(inT, -0.5 * kPi, 0.5 * kPi, relTol, relTol * scale));
    return out;
}

CapIntegral capCentred(const LightCap& cap, const std::function<dvec3(const dvec3&)>& g) {
    CapIntegral out;
    if (!(cap.uMax > 0)) return out;
    const double scale = quadratureNorm(capRule(cap, 4, g)), relTol = kExactTolerance;
    // Along azimuth phi, rho = 2 sin(beta / 2) runs to sqrt(2 u_max(phi)); u = rho^2 / 2 and du = rho drho, so
    // g rho is smooth in rho (polynomial terms in the tangent coordinates), unlike g in u (square roots at 0).
    auto ray = [&](double phi) -> dvec3 {
        const double rhoMax = std::sqrt(2.0 * capEdge(cap, phi));
        const dvec3 d = std::cos(phi) * cap.a + std::sin(phi) * cap.b;
        auto f = [&](double rho) -> dvec3 {
            const double u = 0.5 * rho * rho;
            return rho * g((1.0 - u) * cap.center + std::sqrt(u * (2.0 - u)) * d);
        };
        const auto r = integrateAdaptive<dvec3>(f, 0.0, rhoMax, relTol, 1e-3 * relTol * scale);
        out.evaluations += r.evaluations;
        out.converged = out.converged && r.converged;
        return r.value;
    };
    // The horizon cuts the rays with cos(phi) > c.z cot(alpha) / sin(theta_c) (a.z = -sin(theta_c)): the kinks
    // of u_max(phi) are panel edges, so the integrand in phi is smooth on each panel.
    std::vector<double> edges{0.0, kPi, 2.0 * kPi};
    const double sinTheta = -cap.a.z;
    if (sinTheta > 0 && cap.halfAngle < 0.5 * kPi) {
        const double x = cap.center.z / std::tan(cap.halfAngle) / sinTheta;
        if (x > -1.0 && x < 1.0) {
            const double p = std::acos(x);
            edges = {-p, p, 2.0 * kPi - p};
        }
    }
    for (size_t k = 0; k + 1 < edges.size(); ++k) {
        const auto r = integrateAdaptive<dvec3>(ray, edges[k], edges[k + 1], relTol, relTol * scale);
        out.value += r.value;
        out.evaluations += r.evaluations;
        out.converged = out.converged && r.converged;
    }
    return out;
}

namespace {

/// Where the lobe of f(., we) peaks in wi: the mirror image of we (microfacet and reflection lobes, tables
/// over the half vector), or we itself (a retroreflector).
dvec3 lobeCentre(const brdf::Params& p, const dvec3& we) {
    if (p.model == brdf::Model::Retro) return we;
    return dvec3(-we.x, -we.y, we.z);
}

/// The lobe's angular scale in wi about its centre: the model's width (brdf::lobeWidth) shrunk by the
/// cos(theta) of the perpendicular narrowing, at most 1e-3 rad for tables and measured data.
double lobeScale(const brdf::Params& p, const dvec3& q) {
    double w = brdf::lobeWidth(p);
    if (p.isMeasured() || p.model == brdf::Model::None || p.model == brdf::Model::Tabulated) w = std::min(w, 1e-3);
    return std::max(1e-9, 2.0 * w * std::max(q.z, 1e-3));
}

}  // namespace

namespace {

/// The public radiance queries take what a caller passes (the library, Python): InputError for what they cannot
/// integrate, never a logic_error or a silent 0.
void checkRadianceQuery(const Scene& s, const dvec3& p, const dvec3& we, const char* fn) {
    if (!s.light.area())
        throw InputError(std::string(fn) + ": the scene's light is " + toString(s.light.type) +
                         ": only a sphere or disk light has a cap to integrate");
    const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(we.x) &&
                        std::isfinite(we.y) && std::isfinite(we.z);
    if (!finite || !(glm::length(we) > 0.0))
        throw InputError(std::string(fn) + ": needs a finite point of the plane and a finite exitant direction");
}

}  // namespace

dvec3 areaRadianceExact(const Scene& s, const dvec3& p, const dvec3& we) {
    checkRadianceQuery(s, p, we, "areaRadianceExact");
    const LightCap cap = lightCap(s.light, p);
    const dvec3 q = lobeCentre(s.brdf, we);
    auto g = [&](const dvec3& wi) { return wi.z > 0 ? brdf::radiance(s.brdf, wi, we, cap.radiance) : dvec3(0.0); };
    const double width = lobeScale(s.brdf, q);
    // Where the lobe cannot be sharp between the rule's nodes (the cap no wider than two lobe widths, so 8 rings
    // space their nodes within a quarter of one; or the lobe's centre many widths away) the rule converges
    // spectrally: two orders that agree to the tolerance are the integral (16 + 64 (+ 256 + 1024) evaluations instead of
    // the polar integral's 700-80000). A horizon cut or a lobe sharper than that fails the test.
    const double distance = std::atan2(glm::length(glm::cross(q, cap.center)), glm::dot(q, cap.center));
    if (cap.halfAngle < 2.0 * width || distance - cap.halfAngle > 4.0 * width) {
        dvec3 previous = capRule(cap, 2, g);
        for (int n : {4, 8, 16}) {
            const dvec3 next = capRule(cap, n, g);
            if (quadratureNorm(next - previous) <= kExactTolerance * quadratureNorm(next)) return next;
            previous = next;
        }
        // The rule stalls on the horizon's kink: the same smooth lobe integrated with the kinks as panel edges.
        if (cap.center.z < std::sin(cap.halfAngle)) return capCentred(cap, g).value;
        // Or on a table's: its interpolation is C0 across bins. No lobe is sharp in the cap here, so the cap's own
        // polar coordinates, adaptive, converge (a MERL table of GGX 0.2 under the sun: 0.1 s a fresh row
        // instead of 1.3 s in capExact's rays about the far lobe centre).
        const CapIntegral centred = capCentred(cap, g);
        if (centred.converged) return centred.value;
    }
    return capExact(cap, q, width, g).value;
}

bool areaLuminanceBounds(const Scene& s, const dvec3& p, const dvec3& we, double& lo, double& hi) {
    checkRadianceQuery(s, p, we, "areaLuminanceBounds");
    const LightCap cap = lightCap(s.light, p);
    const dvec3 q = lobeCentre(s.brdf, we);
    const double width = lobeScale(s.brdf, q);
    const double distance = std::atan2(glm::length(glm::cross(q, cap.center)), glm::dot(q, cap.center));
    // The far tail only (areaRadianceExact's own test for where the rule cannot miss a spike), uncut by the horizon.
    if (!(distance - cap.halfAngle > 4.0 * width) || cap.center.z < std::sin(cap.halfAngle)) return false;
    auto g = [&](const dvec3& wi) { return wi.z > 0 ? brdf::radiance(s.brdf, wi, we, cap.radiance) : dvec3(0.0); };
    const double coarse = brdf::luminance(capRule(cap, 4, g)), fine = brdf::luminance(capRule(cap, 8, g));
    // Only a rule in its asymptotic regime (4 and 8 rings within 10%): where they differ by more, both may be far
    // off alike (a tail steep across a large cap), and 4x their difference is no bound.
    if (!(std::abs(fine - coarse) <= 0.1 * std::abs(fine))) return false;
    const double margin = 4.0 * std::abs(fine - coarse) + 1e-6 * std::abs(fine);
    lo = fine - margin, hi = fine + margin;
    return std::isfinite(lo) && std::isfinite(hi);
}

dvec3 areaRadianceRule(const Scene& s, const dvec3& p, const dvec3& we, int rings) {
    checkRadianceQuery(s, p, we, "areaRadianceRule");
    if (!validRings(rings))
        throw InputError("areaRadianceRule: rings must be a whole number in [1, " + std::to_string(kMaxRings) +
                         "] or render::kCentreRule (got " + std::to_string(rings) + ")");
    const LightCap cap = lightCap(s.light, p);
    auto g = [&](const dvec3& wi) { return wi.z > 0 ? brdf::radiance(s.brdf, wi, we, cap.radiance) : dvec3(0.0); };
    return capRule(cap, rings, g);
}

namespace {

/// The plane point the eye sees along exitant direction we.
dvec3 seenPoint(const dvec3& eye, const dvec3& we) { return eye - (eye.z / we.z) * we; }

std::string ruleKey(const Scene& s) {
    std::ostringstream key;
    key.precision(17);
    key << s << " eye=" << s.eyeDistance << " table=" << s.brdf.ndfTable.get() << " measured=" << s.brdf.measured.get()
        << " rgl=" << s.brdf.rgl.get() << " spectrum=" << s.brdf.spectrum.get() << " target=" << s.light.ruleTarget
        << " rings=" << s.light.rings;
    return key.str();
}

RuleCheck chooseRule(const Scene& s) {
    const dvec3 eye = eyePosition(s);
    auto exact = [&](const dvec3& we) { return brdf::luminance(areaRadianceExact(s, seenPoint(eye, we), we)); };
    // Where the lobe falls to 2% needs no exact value: the rule of 2 rings (16 evaluations) finds the rays' ends
    // (the walk's ~200 exact integrals were two thirds of a fresh sun-disk measurement's CPU time).
    auto rough = [&](const dvec3& we) { return brdf::luminance(areaRadianceRule(s, seenPoint(eye, we), we, 2)); };
    // The lobe's centre: the brightest of the mirror direction, the light's and the normal.
    const MirrorChart mirror = s.light.chart();
    dvec3 c0 = mirror.wr();
    double l0 = -1;
    for (dvec3 c : {mirror.wr(), s.light.direction(), dvec3(0, 0, 1)}) {
        c = glm::normalize(dvec3(c.x, c.y, std::max(c.z, 1e-6)));
        const double v = exact(c);
        if (v > l0) l0 = v, c0 = c;
    }
    Scene about = s;
    about.light.chartCenter = c0;
    const MirrorChart chart = about.light.chart();
    std::vector<dvec3> points{c0};
    std::vector<double> values{l0};
    if (l0 > 0) {
        for (int k = 0; k < 8; ++k) {
            const double psi = 2.0 * kPi * k / 8;
            const dvec2 dir(std::cos(psi), std::sin(psi));
            double r = 1e-6;  // out until the lobe falls below 2% of the centre's value, or the horizon
            for (; r < 0.5 * kPi; r *= 1.5) {
                const dvec3 we = chart.direction(r * dir.x, r * dir.y);
                if (!(we.z > 0) || rough(we) < 0.02 * l0) break;
            }
            for (int f = 1; f <= 8; ++f) {
                const dvec3 we = chart.direction(r * f / 8 * dir.x, r * f / 8 * dir.y);
                if (!(we.z > 0)) break;
                points.push_back(we);
                values.push_back(exact(we));
            }
        }
    }
    const double peak = *std::max_element(values.begin(), values.end());
    auto errorOf = [&](int n) {
        if (!(peak > 0)) return 0.0;
        double e = 0;
        for (size_t i = 0; i < points.size(); ++i) {
            const dvec3& we = points[i];
            const double rule = brdf::luminance(areaRadianceRule(s, seenPoint(eye, we), we, n));
            e = std::max(e, std::abs(rule - values[i]) / peak);
        }
        return e;
    };
    if (s.light.ltc) {  // no rings: the error is the linearly transformed cosine's, at the same points
        double e = 0;
        for (size_t i = 0; peak > 0 && i < points.size(); ++i) {
            const double ltc = brdf::luminance(areaRadianceLtc(s, seenPoint(eye, points[i]), points[i]));
            e = std::max(e, std::abs(ltc - values[i]) / peak);
        }
        return {0, e};
    }
    if (s.light.rings != 0) return {s.light.rings, errorOf(s.light.rings)};
    RuleCheck best{kMaxRings, 0.0};
    for (int n : kRingLadder) {
        const double e = errorOf(n);
        best = {n, e};
        if (e <= s.light.ruleTarget) break;
    }
    return best;
}

}  // namespace

Scene withRuleTwin(const Scene& s) {
    Scene out = s;
    if (s.light.area() && !s.brdfFile) out.light.twinRings = s.light.ltc ? 1 : lightRings(s);
    return out;
}

RuleCheck lightRule(const Scene& s) {
    if (!s.light.area()) return {};
    thread_local std::string lastKey;
    thread_local RuleCheck last;
    std::string key = ruleKey(s);
    if (key != lastKey) {
        last = chooseRule(s);
        lastKey = std::move(key);
    }
    return last;
}

}  // namespace hilite::render
