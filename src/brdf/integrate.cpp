#include "brdf/integrate.hpp"

#include "brdf/evaluate.hpp"
#include "brdf/ndf_table.hpp"

#include <cmath>

namespace hilite::brdf {

namespace {

GaussLegendre makeGaussLegendre() {
    // Roots of P_n by Newton's method from Chebyshev guesses; w = 2 / ((1 - x^2) P_n'(x)^2).
    GaussLegendre g;
    const int n = GaussLegendre::kN;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;  // converged to double precision (|x| < 1)
        }
        g.x[size_t(i)] = x;
        g.w[size_t(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return g;
}

/// Points of the periodic trapezoid rule in the azimuth: exact for trigonometric polynomials of degree
/// < N, and the integrands here are smooth in phi (the anisotropic ones after the substitution below).
constexpr int kAzimuths = 128;

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

/// int over the half-vector hemisphere of g(h) dwh, in the tangent frame stretched for anisotropy.
template <class G>
auto integrateOverH(const Params& p, G&& g) -> decltype(g(dvec3(0.0))) {
    using R = decltype(g(dvec3(0.0)));
    const bool aniso = p.anisotropic() && allowsAnisotropy(p.model);
    R sum = R(0.0);
    for (int j = 0; j < kAzimuths; ++j) {
        const double psi = 2.0 * kPi * j / kAzimuths;
        const Azimuth az = aniso ? stretchedAzimuth(psi, p.alphaX(), p.alphaY()) : Azimuth{psi, 1.0, 0.0};
        const double phi = az.phi + (aniso ? deg2rad(p.tangentAngleDeg) : 0.0);
        const double width = aniso ? std::atan(az.alpha) : lobeWidth(p);
        sum += az.jacobian *
               integrateGraded([&](double t) { return g(sphericalDirection(t, phi)) * std::sin(t); }, 0.5 * kPi, width);
    }
    return sum * (2.0 * kPi / kAzimuths);
}

dvec3 microfacetAlbedo(const Params& p, const dvec3& wi) {
    return integrateOverH(p, [&](const dvec3& h) {
        const double WoH = glm::dot(wi, h);
        if (WoH <= 0.0) return dvec3(0.0);  // h faces away from the light: not the half vector of any wo
        const dvec3 wo = 2.0 * WoH * h - wi;
        if (wo.z <= 0.0) return dvec3(0.0);                       // reflected below the horizon
        return evaluateSpecular(p, wi, wo) * (wo.z * 4.0 * WoH);  // dwo = 4 (wi.h) dwh
    });
}

/// Reflection lobes, integrated about their axis wr (the mirror direction; wi itself for the retroreflective
/// lobe): wo = cos(b) wr + sin(b)(cos(g) e1 + sin(g) e2).
dvec3 reflectionLobeAlbedo(const Params& p, const dvec3& wi) {
    const dvec3 wr = p.model == Model::Retro ? wi : dvec3(-wi.x, -wi.y, wi.z);
    const dvec3 e1 =
        glm::normalize(std::abs(wr.z) < 0.9 ? glm::cross(wr, dvec3(0, 0, 1)) : glm::cross(wr, dvec3(1, 0, 0)));
    const dvec3 e2 = glm::cross(wr, e1);
    dvec3 sum(0.0);
    for (int j = 0; j < kAzimuths; ++j) {
        const double g = 2.0 * kPi * j / kAzimuths, cg = std::cos(g), sg = std::sin(g);
        sum += integrateGraded(
            [&](double b) {
                const dvec3 wo = std::cos(b) * wr + std::sin(b) * (cg * e1 + sg * e2);
                return wo.z > 0.0 ? evaluateSpecular(p, wi, wo) * (wo.z * std::sin(b)) : dvec3(0.0);
            },
            kPi, lobeWidth(p));
    }
    return sum * (2.0 * kPi / kAzimuths);
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

}  // namespace

const GaussLegendre& gaussLegendre() {
    static const GaussLegendre g = makeGaussLegendre();
    return g;
}

double lobeWidth(const Params& p) {
    double w = 0.5 * kPi;
    if (usesExponent(p.model))
        w = std::sqrt(2.0 / (p.exponent + 2.0));
    else if (p.model == Model::Tabulated && p.ndfTable)
        w = p.ndfTable->halfWidth;
    else if (p.model != Model::None)
        w = std::atan(std::min(p.alphaX(), p.alphaY()));
    // 1e-6: n = 1e8 would give 1.4e-4 anyway; the floor only keeps the first panel of a degenerate
    // width non-empty. pi/2: the hemisphere.
    return std::clamp(w, 1e-6, 0.5 * kPi);
}

double ndfIntegral(const Params& p) {
    if (!isMicrofacet(p.model)) return 0.0;
    return integrateOverH(p, [&](const dvec3& h) { return distribution(p, h) * h.z; });
}

dvec3 albedo(const Params& p, double thetaDeg, double phiDeg) {
    const dvec3 wi = sphericalDirectionDeg(thetaDeg, phiDeg);
    if (wi.z <= 0.0) return dvec3(0.0);  // light at or below the horizon: nothing is received
    dvec3 rho = p.diffuse == Diffuse::None ? dvec3(0.0) : diffuseAlbedo(p, wi);
    if (isMicrofacet(p.model))
        rho += microfacetAlbedo(p, wi);
    else if (p.model == Model::Phong || p.model == Model::PhongClassic || p.model == Model::Retro)
        rho += reflectionLobeAlbedo(p, wi);
    return rho;
}

}  // namespace hilite::brdf
