#include "brdf/inspect.hpp"

#include "brdf/integrate.hpp"
#include "brdf/merl.hpp"
#include "brdf/rgl.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

namespace hilite::brdf {

namespace {

/// Rec. 709 luminance of linear sRGB.
double luminance(const dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

Reciprocity reciprocity(const Params& p) {
    std::mt19937_64 rng(20181206);  // fixed: the same pairs every run
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double cosMax = std::cos(deg2rad(80.0));
    auto sample = [&] {  // uniform over the cap within 80 deg of the normal
        const double z = cosMax + (1.0 - cosMax) * u(rng), phi = 2 * kPi * u(rng), s = std::sqrt(1 - z * z);
        return dvec3(s * std::cos(phi), s * std::sin(phi), z);
    };
    std::vector<std::pair<double, double>> values;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 a = sample(), b = sample();
        values.emplace_back(luminance(evaluate(p, a, b)), luminance(evaluate(p, b, a)));
    }
    std::vector<double> larger;
    for (const auto& v : values) larger.push_back(std::max(v.first, v.second));
    std::nth_element(larger.begin(), larger.begin() + std::ptrdiff_t(larger.size() / 2), larger.end());
    const double floor = 1e-3 * larger[larger.size() / 2];
    std::vector<double> errors;
    for (const auto& v : values) {
        const double m = std::max(v.first, v.second);
        if (m > floor && m > 0) errors.push_back(std::abs(v.first - v.second) / m);
    }
    Reciprocity r;
    r.pairs = int(errors.size());
    if (errors.empty()) return r;
    std::sort(errors.begin(), errors.end());
    r.median = errors[errors.size() / 2];
    r.p95 = errors[std::min(errors.size() - 1, errors.size() * 95 / 100)];
    r.max = errors.back();
    return r;
}

IncidenceInspection incidence(const Params& p, double thetaDeg, double azimuthDeg) {
    IncidenceInspection out;
    out.thetaDeg = thetaDeg;
    out.albedo = albedo(p, thetaDeg, azimuthDeg);
    const dvec3 wi = sphericalDirectionDeg(thetaDeg, azimuthDeg), wr(-wi.x, -wi.y, wi.z);
    double best = -1;
    for (int i = 0; i < 360; ++i)  // theta_o 0 .. 89.75 deg
        for (int j = 0; j < 720; ++j) {
            const double t = 0.25 * i, ph = 0.5 * j;
            const dvec3 wo = sphericalDirectionDeg(t, ph);
            const double v = luminance(evaluate(p, wi, wo)) * wo.z;
            if (v > best) best = v, out.peakThetaODeg = t, out.peakPhiODeg = ph;
        }
    const dvec3 peak = sphericalDirectionDeg(out.peakThetaODeg, out.peakPhiODeg);
    out.peakOffsetDeg = rad2deg(std::acos(std::clamp(glm::dot(peak, wr), -1.0, 1.0)));
    return out;
}

}  // namespace

Inspection inspect(const Params& p, const std::vector<double>& thetasDeg, double azimuthDeg) {
    if (!p.isMeasured()) throw std::invalid_argument("brdf::inspect: needs a measured material");
    Inspection out;
    std::ostringstream res;
    if (p.rgl) {
        const rgl::Material& m = *p.rgl;
        out.format = "rgl";
        out.path = m.path;
        out.description = m.description;
        for (int i = 0; i < m.at.nTheta; ++i) out.thetaINodesDeg.push_back(rad2deg(m.thetaI(i)));
        for (int i = 0; i < m.at.nPhi; ++i) out.phiINodesDeg.push_back(rad2deg(m.phiI(i)));
        res << (m.isotropic ? "isotropic" : "anisotropic") << "; ndf " << m.at.ndfX << " x " << m.at.ndfY << ", sigma "
            << m.at.sigmaX << " x " << m.at.sigmaY << ", vndf " << m.at.vndfX << " x " << m.at.vndfY
            << " per incidence, rgb " << m.at.rgbX << " x " << m.at.rgbY << " per incidence";
        out.missing = m.nodes - m.validNodes;
        out.total = m.nodes;
        out.mostNegative = m.mostNegative;
    } else {
        const merl::MeasuredBrdf& m = *p.measured;
        out.format = "merl";
        out.path = m.path;
        res << "isotropic; " << merl::kThetaHBins << " theta_h x " << merl::kThetaDBins << " theta_d x "
            << merl::kPhiDBins << " phi_d bins";
        out.missing = m.noData;
        out.total = merl::kEntries;
    }
    out.resolution = res.str();
    out.reciprocity = reciprocity(p);
    for (double t : thetasDeg) out.incidences.push_back(incidence(p, t, azimuthDeg));
    return out;
}

}  // namespace hilite::brdf
