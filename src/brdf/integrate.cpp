#include "brdf/integrate.hpp"

#include "brdf/merl.hpp"

#include "brdf/energy.hpp"
#include "brdf/ndf_table.hpp"
#include "core/quadrature.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace hilite::brdf {

namespace {

GaussLegendre makeGaussLegendre() {
    GaussLegendre g;
    std::vector<double> x, w;
    hilite::gaussLegendre(GaussLegendre::kN, x, w);
    std::copy(x.begin(), x.end(), g.x.begin());
    std::copy(w.begin(), w.end(), g.w.begin());
    return g;
}

constexpr double kNoGrading = std::numeric_limits<double>::infinity();

/// A break of the azimuth integral: a point where the integrand is not smooth (an edge), or near which it
/// varies on the short scale `scale` (a pole that far off the real axis: panels graded toward it).
struct AzimuthBreak {
    double at;
    double scale = kNoGrading;
};

/// The longest azimuth panel: 4 panels of 32 points on the circle resolve what the former 128-point
/// periodic trapezoid did (the stretched anisotropic lobe: a pole atanh(ay / ax) off the axis).
constexpr double kMaxAzimuthPanel = 0.5 * kPi;

/// int over the circle of f(u) du: Gauss-Legendre panels with an edge at every break, graded
/// geometrically toward a break of finite scale (first panel 4 scale: a pole at distance `scale` from
/// a panel's end leaves a Bernstein ellipse of rho >= 2, 32 points then below 1e-19), the rest of each
/// arc in panels of at most kMaxAzimuthPanel.
template <class F>
auto integrateCircle(F&& f, std::vector<AzimuthBreak> breaks) -> decltype(f(0.0)) {
    using R = decltype(f(0.0));
    for (AzimuthBreak& b : breaks) b.at -= 2.0 * kPi * std::floor(b.at / (2.0 * kPi));
    std::sort(breaks.begin(), breaks.end(), [](const AzimuthBreak& a, const AzimuthBreak& b) { return a.at < b.at; });
    std::vector<AzimuthBreak> merged;  // breaks closer than 1e-12 are one (the smaller scale)
    for (const AzimuthBreak& b : breaks) {
        if (!merged.empty() && b.at - merged.back().at < 1e-12)
            merged.back().scale = std::min(merged.back().scale, b.scale);
        else merged.push_back(b);
    }
    if (merged.size() > 1 && merged.front().at + 2.0 * kPi - merged.back().at < 1e-12) {
        merged.front().scale = std::min(merged.front().scale, merged.back().scale);
        merged.pop_back();
    }
    if (merged.empty()) merged.push_back({0.0});
    R sum = R(0.0);
    std::vector<double> edges;
    for (size_t k = 0; k < merged.size(); ++k) {
        const AzimuthBreak& lo = merged[k];
        const AzimuthBreak hi =
            k + 1 < merged.size() ? merged[k + 1] : AzimuthBreak{merged[0].at + 2.0 * kPi, merged[0].scale};
        const double mid = 0.5 * (lo.at + hi.at);
        edges.assign({lo.at});
        for (double s = 4.0 * lo.scale; lo.at + s < mid; s *= 2.0) edges.push_back(lo.at + s);
        std::vector<double> top;
        for (double s = 4.0 * hi.scale; hi.at - s > mid; s *= 2.0) top.push_back(hi.at - s);
        const double from = edges.back(), to = top.empty() ? hi.at : top.back();
        const int n = std::max(1, int(std::ceil((to - from) / kMaxAzimuthPanel)));
        for (int i = 1; i < n; ++i) edges.push_back(from + (to - from) * i / n);
        edges.insert(edges.end(), top.rbegin(), top.rend());
        edges.push_back(hi.at);
        for (size_t i = 0; i + 1 < edges.size(); ++i) sum += integratePanel(f, edges[i], edges[i + 1]);
    }
    return sum;
}

/// How steeply the horizon cut moves with the azimuth at incidence theta_i: the cut angle is a function of
/// tan(theta_i) cos(azimuth), whose atan has poles asinh(1 / tan theta_i) off the axis at cos(azimuth) = 0.
double horizonScale(const dvec3& wi) {
    const double s = std::sqrt(wi.x * wi.x + wi.y * wi.y);
    return s == 0.0 ? kNoGrading : std::asinh(wi.z / s);
}

/// The azimuth substitution of an anisotropic NDF: tan(phi) = (ay / ax) tan(psi), so that the stretched
/// lobe becomes round in psi; returns phi and dphi/dpsi = ax ay / (ax^2 cos^2 psi + ay^2 sin^2 psi), and
/// the directional width alpha(phi) = sqrt(ax^2 cos^2 psi + ay^2 sin^2 psi).
struct Azimuth {
    double phi, jacobian, alpha;
};
Azimuth stretchedAzimuth(double psi, double ax, double ay) {
    const double c = std::cos(psi), s = std::sin(psi), r2 = ax * ax * c * c + ay * ay * s * s;
    return {std::atan2(ay * s, ax * c), ax * ay / r2, std::sqrt(r2)};
}
/// The inverse: psi of the tangent-frame azimuth phi.
double unstretchedAzimuth(double phi, double ax, double ay) {
    return std::atan2(ax * std::sin(phi), ay * std::cos(phi));
}

/// The horizon in the half-vector domain. For h at polar angle t and azimuth phi, wi.h = A sin t + B cos t
/// with A = sin(theta_i) cos(phi - phi_i), B = cos(theta_i); then wo = 2 (wi.h) h - wi has
/// wo.z = 2 (wi.h) cos t - B = A sin 2t + B cos 2t = R cos(2t - delta), R = hypot(A, B), delta = atan2(A, B)
/// in (-pi/2, pi/2) as B > 0. So wo is above the horizon exactly for t < (delta + pi/2) / 2 (which also
/// keeps wi.h = R cos(t - delta) > 0): the cut, in closed form, becomes the last panel edge.
struct HalfVectorHorizon {
    double delta, R, tHorizon;
};
HalfVectorHorizon halfVectorHorizon(const dvec3& wi, double phi) {
    const double A = wi.x * std::cos(phi) + wi.y * std::sin(phi), B = wi.z;
    const double delta = std::atan2(A, B);
    return {delta, std::hypot(A, B), 0.5 * (delta + 0.5 * kPi)};
}

/// Edges in (0, tHorizon) where the Cook-Torrance G = min(1, 2 NoH NoV / VoH, 2 NoH NoL / VoH) switches
/// branch, in closed form with NoL = R cos(delta), VoH = R cos(t - delta), NoV = R cos(2t - delta):
/// 2 NoH NoL = VoH at cos(t + delta) = 0, 2 NoH NoV = VoH at cos(3t - delta) = 0 (2 cos a cos b =
/// cos(a + b) + cos(a - b)), NoV = NoL at t = delta.
void cookTorranceEdges(const HalfVectorHorizon& hz, std::vector<double>& edges) {
    for (double t : {0.5 * kPi - hz.delta, (hz.delta + 0.5 * kPi) / 3.0, hz.delta})
        if (t > 0.0 && t < hz.tHorizon) edges.push_back(t);
}
/// Azimuths where those edges meet the horizon or each other (delta = pi/6: 2 NoH NoL = VoH reaches the
/// cut; delta = pi/4: all three meet): there the azimuthal integrand is not smooth.
void cookTorranceAzimuths(const dvec3& wi, std::vector<double>& phis) {
    const double s = std::sqrt(wi.x * wi.x + wi.y * wi.y);
    if (s == 0.0) return;
    const double phiI = std::atan2(wi.y, wi.x);
    for (double delta : {kPi / 6.0, 0.25 * kPi}) {
        const double c = std::tan(delta) * wi.z / s;  // tan(delta) = tan(theta_i) cos(phi - phi_i)
        if (c < 1.0) phis.insert(phis.end(), {phiI + std::acos(c), phiI - std::acos(c)});
    }
}

/// Rows of a tabulated NDF (D linear between them: kinks in theta_h) below `end`, for tables of at most
/// kMaxTableEdges rows: a panel per row of a 401-row table costs ~1 s per albedo, and a table that dense
/// has kinks small enough for the graded panels.
constexpr size_t kMaxTableEdges = 64;
void tableEdges(const Params& p, double end, std::vector<double>& edges) {
    if (p.measured) {  // a MERL table is multilinear between theta_h bin centres (kinks there; graded near 0)
        for (int i = 0; i < merl::kThetaHBins; ++i)
            if (const double t = merl::thetaHalfAt(i + 0.5); t > 0.0 && t < end) edges.push_back(t);
        return;
    }
    if (p.model != Model::Tabulated || !p.ndfTable || p.ndfTable->theta.size() > kMaxTableEdges) return;
    for (double t : p.ndfTable->theta)
        if (t > 0.0 && t < end) edges.push_back(t);
}

/// int of g(h) dwh over the half vectors h whose reflection wo = 2 (wi.h) h - wi is above the horizon, in
/// the tangent frame stretched for anisotropy. Per azimuth, t runs over [0, tHorizon] in panels graded
/// about the lobe, with edges where the geometry term or a table has kinks; the azimuth in panels broken
/// where the integrand is not smooth and graded where the cut moves steeply (grazing light).
template <class G>
auto integrateOverReflectedH(const Params& p, const dvec3& wi, G&& g) -> decltype(g(dvec3(0.0))) {
    const bool aniso = p.anisotropic() && allowsAnisotropy(p.model);
    const double ax = p.alphaX(), ay = p.alphaY(), tangent = aniso ? deg2rad(p.tangentAngleDeg) : 0.0;
    // The azimuth variable u: psi (stretched) when anisotropic, else phi itself.
    auto toU = [&](double phi) { return aniso ? unstretchedAzimuth(phi - tangent, ax, ay) : phi; };
    auto uScale = [&](double u, double phiScale) {  // a scale in phi, as a scale in u: over dphi/du
        return aniso ? phiScale / stretchedAzimuth(u, ax, ay).jacobian : phiScale;
    };
    std::vector<AzimuthBreak> breaks;
    const double phiI = std::atan2(wi.y, wi.x), eta = horizonScale(wi);
    if (eta < kNoGrading)
        for (double phi : {phiI + 0.5 * kPi, phiI - 0.5 * kPi}) breaks.push_back({toU(phi), uScale(toU(phi), eta)});
    if (aniso && ax != ay) {  // the stretch's poles: atanh of the axis ratio off the narrow axis
        const double along = ax > ay ? 0.5 * kPi : 0.0, scale = std::atanh(std::min(ax, ay) / std::max(ax, ay));
        breaks.insert(breaks.end(), {{along, scale}, {along + kPi, scale}});
    }
    if (p.geometry == Geometry::CookTorrance) {
        std::vector<double> phis;
        cookTorranceAzimuths(wi, phis);
        for (double phi : phis) breaks.push_back({toU(phi)});
    }
    std::vector<double> edges;
    auto overT = [&](double u) {
        const Azimuth az = aniso ? stretchedAzimuth(u, ax, ay) : Azimuth{u, 1.0, 0.0};
        const double phi = az.phi + tangent;
        const double width = aniso ? std::atan(az.alpha) : lobeWidth(p);
        const HalfVectorHorizon hz = halfVectorHorizon(wi, phi);
        edges.clear();
        if (p.geometry == Geometry::CookTorrance) cookTorranceEdges(hz, edges);
        tableEdges(p, hz.tHorizon, edges);
        return az.jacobian * integrateGraded([&](double t) { return g(sphericalDirection(t, phi)) * std::sin(t); },
                                             hz.tHorizon, width, edges);
    };
    return integrateCircle(overT, breaks);
}

dvec3 microfacetAlbedo(const Params& p, const dvec3& wi) {
    return integrateOverReflectedH(p, wi, [&](const dvec3& h) {
        const double WoH = glm::dot(wi, h);
        const dvec3 wo = 2.0 * WoH * h - wi;
        // wo.z > 0 and wi.h > 0 on [0, tHorizon] but for rounding at its end; evaluateSpecular says 0 there.
        return evaluateSpecular(p, wi, wo) * (std::max(0.0, wo.z) * 4.0 * std::max(0.0, WoH));  // dwo = 4 (wi.h) dwh
    });
}

/// Reflection lobes, integrated about their axis wr (the mirror direction; wi itself for the retroreflective
/// lobe): wo = cos(b) wr + sin(b)(cos(g) e1 + sin(g) e2), e1 horizontal, so wo.z = cos(b) wr.z + sin(b) sin(g) s
/// with s = |wr x n|: wo.z = S cos(b - beta), beta = atan2(s sin g, wr.z) in (-pi/2, pi/2), and wo is above
/// the horizon exactly for b < beta + pi/2, the last panel edge. The cut moves steeply with g near g = 0, pi.
dvec3 reflectionLobeAlbedo(const Params& p, const dvec3& wi) {
    const dvec3 wr = p.model == Model::Retro ? wi : dvec3(-wi.x, -wi.y, wi.z);
    const double s = std::sqrt(wr.x * wr.x + wr.y * wr.y);
    const dvec3 e1 = s > 0.0 ? dvec3(-wr.y / s, wr.x / s, 0.0) : dvec3(1.0, 0.0, 0.0);
    const dvec3 e2 = glm::cross(wr, e1);  // e2.z = s
    const double eta = horizonScale(wr);
    std::vector<AzimuthBreak> breaks;
    if (eta < kNoGrading) breaks = {{0.0, eta}, {kPi, eta}};
    const std::vector<double> none;
    return integrateCircle(
        [&](double g) {
            const double cg = std::cos(g), sg = std::sin(g);
            const double end = std::atan2(s * sg, wr.z) + 0.5 * kPi;
            return integrateGraded(
                [&](double b) {
                    const dvec3 wo = std::cos(b) * wr + std::sin(b) * (cg * e1 + sg * e2);
                    return evaluateSpecular(p, wi, wo) * (std::max(0.0, wo.z) * std::sin(b));
                },
                end, lobeWidth(p), none);
        },
        breaks);
}

/// The diffuse part over wo, panels split where Oren-Nayar has kinks: theta_o = theta_i (max/min swap)
/// and phi_o - phi_i = +-90 degrees (max(0, cos dphi)).
dvec3 diffuseAlbedo(const Params& p, const dvec3& wi) {
    const double thetaI = std::atan2(std::sqrt(wi.x * wi.x + wi.y * wi.y), wi.z), phiI = std::atan2(wi.y, wi.x);
    auto overPhi = [&](double t) {
        dvec3 s(0.0);
        for (int q = 0; q < 4; ++q) {
            const double a = phiI - 0.5 * kPi + q * 0.5 * kPi;
            s += integratePanel([&](double phi) { return evaluateDiffuse(p, wi, sphericalDirection(t, phi)); }, a,
                                a + 0.5 * kPi);
        }
        return s * (std::cos(t) * std::sin(t));
    };
    dvec3 sum = integratePanel(overPhi, thetaI, 0.5 * kPi);
    if (thetaI > 0.0) sum += integratePanel(overPhi, 0.0, thetaI);
    return sum;
}

/// The energy terms (multiple scattering, the coupled diffuse) depend on wo through mu_o = wo.z alone, so
/// int f cos dwo = 2 pi int_0^1 f(mu_o) mu_o dmu_o = 2 pi int_0^1 f(u^2) 2 u^3 du, on panels between their
/// tables' entries (brdf/energy.hpp: linear in u = sqrt(mu) there, so the panels are exact for them).
template <class F>
dvec3 energyAlbedo(const dvec3& wi, F&& f) {
    dvec3 sum(0.0);
    const double du = 1.0 / double(kEnergyTableSize - 1);
    for (int i = 0; i + 1 < kEnergyTableSize; ++i)
        sum += integratePanel(
            [&](double u) {
                const double mu = u * u;
                return f(wi, dvec3(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu)) * (2.0 * u * mu);
            },
            i * du, (i + 1) * du);
    return 2.0 * kPi * sum;
}

}  // namespace

const GaussLegendre& gaussLegendre() {
    static const GaussLegendre g = makeGaussLegendre();
    return g;
}

double lobeWidth(const Params& p) {
    double w = 0.5 * kPi;
    if (usesExponent(p.model)) w = std::sqrt(2.0 / (p.exponent + 2.0));
    else if (p.model == Model::Tabulated && p.ndfTable) w = p.ndfTable->halfWidth;
    else if (p.model == Model::ABC) w = p.abcB * p.abcC > 0.0 ? 1.0 / std::sqrt(p.abcB * p.abcC) : w;  // exp(-BC t^2/2)
    else if (p.model == Model::SGD) {  // exp(-tan^2 / alpha) a^-p: sqrt(alpha) wide, alpha where a^-p falls first
        for (int c = 0; c < 3; ++c) w = std::min(w, std::min(p.sgd.alpha[c], std::sqrt(p.sgd.alpha[c])));
    } else if (p.model != Model::None) w = std::atan(std::min(p.alphaX(), p.alphaY()));
    // 1e-6: n = 1e8 would give 1.4e-4 anyway; the floor only keeps the first panel of a degenerate
    // width non-empty. pi/2: the hemisphere.
    return std::clamp(w, 1e-6, 0.5 * kPi);
}

double ndfIntegral(const Params& p) {
    if (!isMicrofacet(p.model)) return 0.0;
    // Over the whole hemisphere of h: the azimuth as before (stretched when anisotropic), t to pi/2.
    const bool aniso = p.anisotropic() && allowsAnisotropy(p.model);
    const double ax = p.alphaX(), ay = p.alphaY(), tangent = aniso ? deg2rad(p.tangentAngleDeg) : 0.0;
    std::vector<AzimuthBreak> breaks;
    if (aniso && ax != ay) {
        const double along = ax > ay ? 0.5 * kPi : 0.0, scale = std::atanh(std::min(ax, ay) / std::max(ax, ay));
        breaks = {{along, scale}, {along + kPi, scale}};
    }
    std::vector<double> edges;
    tableEdges(p, 0.5 * kPi, edges);
    return integrateCircle(
        [&](double u) {
            const Azimuth az = aniso ? stretchedAzimuth(u, ax, ay) : Azimuth{u, 1.0, 0.0};
            const double phi = az.phi + tangent, width = aniso ? std::atan(az.alpha) : lobeWidth(p);
            return az.jacobian * integrateGraded(
                                     [&](double t) {
                                         const dvec3 h = sphericalDirection(t, phi);
                                         return distribution(p, h) * h.z * std::sin(t);
                                     },
                                     0.5 * kPi, width, edges);
        },
        breaks);
}

dvec3 albedo(const Params& p, double thetaDeg, double phiDeg) {
    const dvec3 wi = sphericalDirectionDeg(thetaDeg, phiDeg);
    if (wi.z <= 0.0) return dvec3(0.0);  // light at or below the horizon: nothing is received
    dvec3 rho = p.diffuse == Diffuse::None ? dvec3(0.0)
                : p.diffuse == Diffuse::Coupled
                    ? energyAlbedo(wi, [&](const dvec3& a, const dvec3& b) { return evaluateDiffuse(p, a, b); })
                    : diffuseAlbedo(p, wi);
    if (p.multiscatter != Multiscatter::None)
        rho += energyAlbedo(wi, [&](const dvec3& a, const dvec3& b) { return evaluateMultiscatter(p, a, b); });
    // A table over half vectors, and the literature's microfacet models: integrated over h too.
    if (isMicrofacet(p.model) || p.isMeasured() || p.model == Model::ABC || p.model == Model::SGD)
        rho += microfacetAlbedo(p, wi);
    else if (p.model == Model::Phong || p.model == Model::PhongClassic || p.model == Model::Retro ||
             p.model == Model::Lafortune)
        rho += reflectionLobeAlbedo(p, wi);
    return rho;
}

}  // namespace hilite::brdf
