#include "brdf/energy.hpp"

#include "brdf/integrate.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace hilite::brdf {

namespace {

/// theta in degrees of mu = cos(theta). Entry 0 (mu = 0) is the limit at the horizon, where brdf::albedo
/// returns 0 by its convention: it is integrated at mu = 1e-6 (theta 89.99994 deg) instead.
double thetaDegOf(double mu) { return rad2deg(std::acos(std::clamp(mu, 1e-6, 1.0))); }

/// The table interpolated at mu, linear in x = sqrt(mu) (N - 1); the twin of the GLSL lookups.
template <class T>
T lookup(const std::vector<T>& table, double mu) {
    // A NaN mu (a NaN direction given to brdf::evaluate) gives NaN, not an index: casting NaN to size_t is
    // undefined (fuzz_entry_points found it: UBSan "nan is outside the range of representable values").
    if (std::isnan(mu)) return table[0] * std::numeric_limits<double>::quiet_NaN();
    const double x = std::sqrt(std::clamp(mu, 0.0, 1.0)) * double(table.size() - 1);
    const size_t i = std::min(size_t(x), table.size() - 2);
    const double t = x - double(i);
    return table[i] + (table[i + 1] - table[i]) * t;
}

/// 2 int_0^1 g(mu) mu dmu = 4 int_0^1 g(u^2) u^3 du over panels between the entries (g linear in u on each
/// panel for the tables, so 32 Gauss-Legendre points are exact).
template <class G>
auto cosineAverage(G&& g) -> decltype(g(0.0)) {
    using R = decltype(g(0.0));
    R sum = R(0.0);
    const double du = 1.0 / double(kEnergyTableSize - 1);
    for (int i = 0; i + 1 < kEnergyTableSize; ++i)
        sum += integratePanel([&](double u) { return g(u * u) * (4.0 * u * u * u); }, i * du, (i + 1) * du);
    return sum;
}

/// Single-scattering albedo of p's lobe with F = 1, no diffuse and no compensation, at mu.
Params whiteLobe(const Params& p) {
    Params q = p;
    q.fresnel = Fresnel::None;
    q.diffuse = Diffuse::None;
    q.multiscatter = Multiscatter::None;
    q.energy.reset();
    return q;
}

void makeE(const Params& p, EnergyTables& t) {
    const Params q = whiteLobe(p);
    auto E = [&](double mu) { return albedo(q, thetaDegOf(mu)).x; };
    t.E.resize(kEnergyTableSize);
    for (int i = 0; i < kEnergyTableSize; ++i) t.E[size_t(i)] = E(energyTableMu(i));
    for (int i = 0; i + 1 < kEnergyTableSize; ++i) {  // the interpolation error at the midpoints in sqrt(mu)
        const double u = (i + 0.5) / double(kEnergyTableSize - 1), mu = u * u;
        t.eError = std::max(t.eError, std::abs(energyE(mu, t) - E(mu)));
    }
    t.Eavg = cosineAverage([&](double mu) { return energyE(mu, t); });
    t.Favg = cosineAverage([&](double mu) { return fresnel(p, mu); });
    for (int c = 0; c < 3; ++c) {
        const double denominator = 1.0 - t.Favg[c] * (1.0 - t.Eavg);  // >= E_avg > 0 for F_avg <= 1
        t.Fms[c] = t.Favg[c] * t.Favg[c] * t.Eavg / denominator;
    }
}

void makeEs(const Params& p, EnergyTables& t, const std::shared_ptr<const EnergyTables>& withE) {
    Params q = p;  // the specular part alone: the lobe with its Fresnel, and the compensation if named
    q.diffuse = Diffuse::None;
    q.energy = withE;
    auto Es = [&](double mu) { return albedo(q, thetaDegOf(mu)); };
    t.Es.resize(kEnergyTableSize);
    for (int i = 0; i < kEnergyTableSize; ++i) {
        const dvec3 v = Es(energyTableMu(i));
        for (int c = 0; c < 3; ++c)
            if (!(v[c] <= 1.0 + 1e-9))
                throw std::invalid_argument("the specular albedo reaches " + std::to_string(v[c]) + " at theta " +
                                            std::to_string(thetaDegOf(energyTableMu(i))) +
                                            " deg (above 1: the body would get a negative share; Smith geometry "
                                            "conserves energy)");
        t.Es[size_t(i)] = v;
    }
    for (int i = 0; i + 1 < kEnergyTableSize; ++i) {
        const double u = (i + 0.5) / double(kEnergyTableSize - 1), mu = u * u;
        const dvec3 d = glm::abs(energyEs(mu, t) - Es(mu));
        t.esError = std::max({t.esError, d.x, d.y, d.z});
    }
    // Conservative: the entries raised by the worst midpoint error, so that the interpolated E_s does not fall
    // below the true one and the body (rho <= 1) never gets more than the surface leaves: the sum stays <= 1.
    for (dvec3& v : t.Es) v = glm::min(v + dvec3(t.esError), dvec3(1.0));
    t.EsAvg = cosineAverage([&](double mu) { return energyEs(mu, t); });
    for (int c = 0; c < 3; ++c)
        if (!(t.EsAvg[c] < 1.0 - 1e-9))
            throw std::invalid_argument("the specular albedo is 1 at every angle: nothing is left for the body");
}

}  // namespace

double energyTableMu(int i) {
    const double u = double(i) / double(kEnergyTableSize - 1);
    return u * u;
}

double energyE(double mu, const EnergyTables& t) { return lookup(t.E, mu); }
dvec3 energyEs(double mu, const EnergyTables& t) { return lookup(t.Es, mu); }

std::string energyRefusal(const Params& p) {
    if (p.isMeasured()) return "not with a measured table (it holds every bounce it measured)";
    const bool aniso = p.anisotropic() && allowsAnisotropy(p.model);
    if (aniso) return "isotropic models only (an anisotropic lobe's albedo depends on the azimuth too)";
    const bool roughnessModel = isMicrofacet(p.model) && !usesExponent(p.model) && p.model != Model::Tabulated;
    if (p.multiscatter != Multiscatter::None) {
        if (!isMicrofacet(p.model))
            return std::string("needs a microfacet model (blinn, gaussian, beckmann, ggx, tabulated; got ") +
                   toString(p.model) + ")";
        if (p.geometry != Geometry::Smith && p.geometry != Geometry::SmithSeparable)
            return std::string(
                       "needs --geometry smith or smith-separable: the energy it returns is what Smith "
                       "masking takes from single scattering (got ") +
                   toString(p.geometry) + ")";
    }
    if (roughnessModel && p.roughness < kMinIntegrableRoughness)
        return "the albedo tables integrate lobes of roughness >= 1e-4 (a mirror loses nothing to masking)";
    return "";
}

std::shared_ptr<const EnergyTables> energyTables(const Params& p) {
    const bool ms = p.multiscatter != Multiscatter::None, coupled = p.diffuse == Diffuse::Coupled;
    if (!ms && !coupled) return nullptr;
    if (const std::string why = energyRefusal(p); !why.empty()) throw std::invalid_argument(why);
    auto t = std::make_shared<EnergyTables>();
    if (ms) makeE(p, *t);
    if (coupled) {
        auto withE = ms ? std::make_shared<const EnergyTables>(*t) : nullptr;
        makeEs(p, *t, withE);
    }
    return t;
}

std::string describeEnergy(const Params& p) {
    if (!p.energy) return "";
    const EnergyTables& t = *p.energy;
    std::ostringstream s;
    s << std::setprecision(6);
    if (!t.E.empty())
        s << "multiple scattering (Kulla & Conty 2017): E(mu) of the lobe with F = 1, " << kEnergyTableSize
          << " entries even in sqrt(mu) by hilite's albedo quadrature, linear between them (worst error at the "
             "midpoints "
          << t.eError << "); E(1) = " << t.E.back() << ", E_avg = " << t.Eavg << ", F_avg = " << t.Favg.x << ","
          << t.Favg.y << "," << t.Favg.z << ", F_ms = " << t.Fms.x << "," << t.Fms.y << "," << t.Fms.z;
    if (!t.E.empty() && !t.Es.empty()) s << "; ";
    if (!t.Es.empty())
        s << "coupled diffuse: E_s(mu) the specular albedo, " << kEnergyTableSize
          << " entries (worst error at the midpoints " << t.esError << "), E_s_avg = " << t.EsAvg.x << "," << t.EsAvg.y
          << "," << t.EsAvg.z;
    return s.str();
}

}  // namespace hilite::brdf
