// brdf::albedo where the horizon cuts the lobe: exact against the closed forms at normal incidence (G = 1,
// F = 1: int over t < 45 deg of D (n.h) dwh) and against an independent reference at oblique incidence, an
// adaptive Gauss-Kronrod (7, 15) over wo in (theta_o, phi_o), where the horizon is theta_o = 90 deg, the
// integrand f cos(theta_o) sin(theta_o) evaluated through brdf::evaluate. Nothing here is shared with
// src/brdf/integrate.cpp (its Gauss-Legendre panels in the half-vector domain).

#include "brdf/integrate.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/ndf_tables.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <queue>
#include <sstream>
#include <vector>

using namespace hilite;
using brdf::Geometry;
using brdf::Model;

namespace {

// ---- The reference: global adaptive Gauss-Kronrod (7, 15), QUADPACK's qk15 nodes and weights. ----
const double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                        0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                        0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                        0.207784955007898467600689403773245, 0.0};
const double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                        0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                        0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                        0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
const double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                       0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Piece {
    double a, b, value, error;
    bool operator<(const Piece& o) const { return error < o.error; }
};

Piece kronrod15(const std::function<double(double)>& f, double a, double b) {
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    const double fc = f(c);
    double k = kWgk[7] * fc, g = kWg[3] * fc;
    for (int i = 0; i < 7; ++i) {
        const double s = f(c - h * kXgk[i]) + f(c + h * kXgk[i]);
        k += kWgk[i] * s;
        if (i % 2 == 1) g += kWg[i / 2] * s;
    }
    return {a, b, k * h, std::abs((k - g) * h)};
}

/// int f over [breaks.front(), breaks.back()], the pieces between breaks bisected (largest error first)
/// until the summed |K15 - G7| is below relTol |total| (or absTol).
double adaptive(const std::function<double(double)>& f, const std::vector<double>& breaks, double relTol,
                double absTol = 1e-300) {
    std::priority_queue<Piece> queue;
    double total = 0.0, error = 0.0;
    for (size_t i = 0; i + 1 < breaks.size(); ++i) {
        if (!(breaks[i + 1] > breaks[i])) continue;
        const Piece p = kronrod15(f, breaks[i], breaks[i + 1]);
        total += p.value;
        error += p.error;
        queue.push(p);
    }
    for (int n = 0; n < 4000 && error > std::max(absTol, relTol * std::abs(total)); ++n) {
        const Piece p = queue.top();
        queue.pop();
        const double m = 0.5 * (p.a + p.b);
        const Piece l = kronrod15(f, p.a, m), r = kronrod15(f, m, p.b);
        total += l.value + r.value - p.value;
        error += l.error + r.error - p.error;
        queue.push(l);
        queue.push(r);
    }
    return total;
}

/// rho(wi) = int_0^{pi/2} int_{-pi}^{pi} f(wi, wo) cos(theta_o) sin(theta_o) dphi_o dtheta_o, wi at
/// (thetaDeg, phiDeg); breaks where the lobes peak (theta_o = theta_i; phi_o = phi_i, phi_i + pi).
double referenceAlbedo(const brdf::Params& p, double thetaDeg, double phiDeg) {
    const dvec3 wi = sphericalDirectionDeg(thetaDeg, phiDeg);
    const double ti = deg2rad(thetaDeg), pi0 = deg2rad(phiDeg);
    // Breaks graded geometrically about each peak (1e-6 .. pi/2 away), so that a lobe squeezed to 1e-4 rad
    // in wo (a narrow NDF near grazing: dwo = 4 (wi.h) dwh) is seen by the first Kronrod nodes.
    std::vector<double> offsets{0.0};
    for (double d = 1e-6; d < 0.5 * kPi; d *= 2.0) offsets.insert(offsets.end(), {d, -d});
    offsets.insert(offsets.end(), {0.5 * kPi, -0.5 * kPi, kPi, -kPi});
    std::vector<double> phiBreaks;
    for (double d : offsets)  // the mirror and the retroreflective peaks
        phiBreaks.insert(phiBreaks.end(), {pi0 + kPi + d, pi0 + d, pi0 + 2.0 * kPi + d});
    std::sort(phiBreaks.begin(), phiBreaks.end());
    phiBreaks.erase(std::unique(phiBreaks.begin(), phiBreaks.end()), phiBreaks.end());
    phiBreaks.erase(std::remove_if(phiBreaks.begin(), phiBreaks.end(),
                                   [&](double x) { return x < pi0 - 1e-12 || x > pi0 + 2.0 * kPi + 1e-12; }),
                    phiBreaks.end());
    // The inner integral at 1e-12 so that its noise stays below the outer tolerance.
    auto inner = [&](double to) {
        const double c = std::cos(to), s = std::sin(to);
        return adaptive(
                   [&](double po) {
                       const dvec3 wo(s * std::cos(po), s * std::sin(po), c);
                       return brdf::evaluate(p, wi, wo).x;
                   },
                   phiBreaks, 1e-12, 1e-15) *
               c * s;
    };
    std::vector<double> thetaBreaks;
    for (double d : offsets) thetaBreaks.push_back(std::clamp(ti + d, 0.0, 0.5 * kPi));
    std::sort(thetaBreaks.begin(), thetaBreaks.end());
    thetaBreaks.erase(std::unique(thetaBreaks.begin(), thetaBreaks.end()), thetaBreaks.end());
    return adaptive(inner, thetaBreaks, 1e-10, 1e-14);
}

brdf::Params make(Model m, Geometry g, double param, double paramY = 0.0) {
    brdf::Params p;
    p.model = m;
    p.geometry = g;
    p.fresnel = brdf::Fresnel::None;
    (brdf::usesExponent(m) ? p.exponent : p.roughness) = param;
    if (paramY > 0.0) {
        p.roughnessY = paramY;
        p.tangentAngleDeg = 30.0;
    }
    return p;
}

std::string describe(const brdf::Params& p) {
    std::ostringstream s;
    s << p;
    return s.str();
}

}  // namespace

TEST_CASE("brdf::albedo with G = 1, F = 1 at normal incidence: the closed forms") {
    // rho(n) = 2 pi int_0^{pi/4} D(t) cos(t) sin(t) dt (wo = 2 (n.h) h - n is above the horizon for t < 45 deg):
    // GGX 1 / (1 + alpha^2), Beckmann 1 - exp(-1 / m^2), Blinn-Phong 1 - 2^(-(n + 2) / 2).
    struct Case {
        Model model;
        double param, exact;
    };
    const Case cases[] = {
        {Model::GGX, 0.3, 1.0 / (1.0 + 0.09)},
        {Model::GGX, 0.7, 1.0 / (1.0 + 0.49)},
        {Model::GGX, 2.0, 1.0 / (1.0 + 4.0)},
        {Model::GGX, 0.02, 1.0 / (1.0 + 0.0004)},
        {Model::Beckmann, 0.7, 1.0 - std::exp(-1.0 / 0.49)},
        {Model::Beckmann, 2.0, 1.0 - std::exp(-0.25)},
        {Model::Beckmann, 0.02, 1.0 - std::exp(-2500.0)},
        {Model::Blinn, 0.0, 1.0 - std::pow(2.0, -1.0)},
        {Model::Blinn, 1.0, 1.0 - std::pow(2.0, -1.5)},
        {Model::Blinn, 1e4, 1.0 - std::pow(2.0, -5001.0)},
    };
    double worst = 0.0;
    for (const Case& c : cases)
        for (double phi : {0.0, 10.0}) {
            const brdf::Params p = make(c.model, Geometry::None, c.param);
            const double a = brdf::albedo(p, 0.0, phi).x, rel = std::abs(a - c.exact) / c.exact;
            CAPTURE(describe(p));
            CAPTURE(a);
            CAPTURE(c.exact);
            CHECK(rel < 1e-9);
            worst = std::max(worst, rel);
        }
    MESSAGE("closed forms at theta_i = 0: largest relative error " << std::setprecision(3) << worst);
}

TEST_CASE("brdf::albedo against the adaptive Gauss-Kronrod reference over wo, every model and geometry term") {
    std::vector<brdf::Params> ps;
    for (Geometry g :
         {Geometry::None, Geometry::Implicit, Geometry::CookTorrance, Geometry::SmithSeparable, Geometry::Smith}) {
        ps.push_back(make(Model::GGX, g, 0.3));
        ps.push_back(make(Model::Beckmann, g, 0.7));
        ps.push_back(make(Model::GGX, g, 0.5, 0.15));  // anisotropic, tangent at 30 deg
    }
    ps.push_back(make(Model::Blinn, Geometry::None, 1.0));
    ps.push_back(make(Model::Blinn, Geometry::CookTorrance, 10.0));
    ps.push_back(make(Model::Gaussian, Geometry::Implicit, 0.4));
    ps.push_back(make(Model::Gaussian, Geometry::None, 0.4));
    ps.push_back(make(Model::Beckmann, Geometry::Smith, 0.6, 0.2));
    ps.push_back(make(Model::Phong, Geometry::Implicit, 20.0));
    ps.push_back(make(Model::PhongClassic, Geometry::Implicit, 5.0));
    ps.push_back(make(Model::Retro, Geometry::Implicit, 20.0));
    brdf::Params schlick = make(Model::GGX, Geometry::Smith, 0.4);
    schlick.fresnel = brdf::Fresnel::Schlick;
    ps.push_back(schlick);
    double worst = 0.0;
    std::string worstWhat;
    for (const brdf::Params& p : ps)
        for (double t : {30.0, 60.0, 85.0}) {
            const double ref = referenceAlbedo(p, t, 10.0), a = brdf::albedo(p, t, 10.0).x;
            const double rel = std::abs(a - ref) / ref;
            CAPTURE(describe(p));
            CAPTURE(t);
            CAPTURE(a);
            CAPTURE(ref);
            CHECK(rel < 1e-6);
            if (rel > worst) {
                worst = rel;
                worstWhat = describe(p) + " at " + std::to_string(t);
            }
        }
    MESSAGE("reference over wo: largest relative error " << std::setprecision(3) << worst << " (" << worstWhat << ")");
}

TEST_CASE("brdf::albedo narrow lobes at grazing: the grading and the horizon edge together") {
    double worst = 0.0;
    for (const brdf::Params& p :
         {make(Model::GGX, Geometry::None, 0.02), make(Model::GGX, Geometry::Smith, 0.02),
          make(Model::Blinn, Geometry::Implicit, 1e4), make(Model::Phong, Geometry::Implicit, 1e4)})
        for (double t : {60.0, 85.0, 89.0}) {
            const double ref = referenceAlbedo(p, t, 10.0), a = brdf::albedo(p, t, 10.0).x;
            const double rel = std::abs(a - ref) / ref;
            CAPTURE(describe(p));
            CAPTURE(t);
            CAPTURE(a);
            CAPTURE(ref);
            CHECK(rel < 1e-6);
            worst = std::max(worst, rel);
        }
    MESSAGE("narrow lobes: largest relative error " << std::setprecision(3) << worst);
}

TEST_CASE("brdf::albedo of a tabulated NDF at normal incidence (D linear between rows: the rows are panel edges)") {
    // At wi = n, wo = 2 cos(t) h - n: rho = 2 pi int_0^{pi/4} D(t) cos(t) g(t) sin(t) dt with g = 1 (G = 1) or
    // cos(2t) = wo.z (implicit G), a 1-D integral taken here by the Kronrod rule broken at the rows. (Oblique
    // incidence is not checked against the 2-D reference: its kinks along every row make it too slow.)
    brdf::Params coarse = make(Model::Tabulated, Geometry::Implicit, 0.0);
    coarse.ndfTable = brdf::parseNdfTable("0, 3\n5, 2.5\n12, 1\n20, 0.6\n35, 0.1\n50, 0.02\n70, 0\n", "coarse.csv");
    brdf::Params dense = coarse;
    dense.ndfTable = brdf::parseNdfTable(test::ggxTableText(0.2, 40), "ggx.csv");  // 41 rows
    double worst = 0.0;
    for (Geometry g : {Geometry::None, Geometry::Implicit})
        for (brdf::Params p : {coarse, dense}) {
            p.geometry = g;
            std::vector<double> breaks{0.0};
            for (double t : p.ndfTable->theta)
                if (t > 0.0 && t < 0.25 * kPi) breaks.push_back(t);
            breaks.push_back(0.25 * kPi);
            const double ref =
                2.0 * kPi *
                adaptive(
                    [&](double t) {
                        const double D = brdf::D_Tabulated(std::cos(t), std::sin(t) * std::sin(t), *p.ndfTable);
                        return D * std::cos(t) * std::sin(t) * (g == Geometry::None ? 1.0 : std::cos(2.0 * t));
                    },
                    breaks, 1e-13);
            const double a = brdf::albedo(p, 0.0, 10.0).x, rel = std::abs(a - ref) / ref;
            CAPTURE(describe(p));
            CAPTURE(p.ndfTable->theta.size());
            CAPTURE(a);
            CAPTURE(ref);
            CHECK(rel < 1e-9);
            worst = std::max(worst, rel);
        }
    MESSAGE("tabulated at normal incidence: largest relative error " << std::setprecision(3) << worst);
}

TEST_CASE("brdf::albedo time per call (printed, not asserted)") {
    for (const brdf::Params& p :
         {make(Model::GGX, Geometry::Smith, 0.3), make(Model::GGX, Geometry::CookTorrance, 0.5, 0.15),
          make(Model::Phong, Geometry::Implicit, 1e4)}) {
        const auto start = std::chrono::steady_clock::now();
        double sink = 0.0;
        int calls = 0;
        for (double t = 0.0; t < 89.5; t += 5.0, ++calls) sink += brdf::albedo(p, t, 10.0).x;
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        MESSAGE(describe(p) << ": " << std::setprecision(3) << ms / calls << " ms per albedo call (theta_i 0..85)");
        CHECK(sink > 0.0);
    }
}
