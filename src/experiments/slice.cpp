#include "hilite/experiments/slice.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"

#include "hilite/core/math.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::experiments {

std::vector<SlicePoint> brdfSlices(const std::vector<SliceCurve>& curves, const std::vector<double>& incidencesDeg,
                                   double stepDeg) {
    if (!(stepDeg > 0 && stepDeg <= 10))
        throw InputError("--step: must be in (0, 10] degrees (got " + std::to_string(stepDeg) + ")");
    for (const SliceCurve& c : curves)
        if (c.scene.scene.brdfFile)
            throw InputError(c.label +
                             ": a .brdf file has no CPU evaluation (its BRDF() is GLSL); slice the "
                             "built-in model or a measured table instead");
    const int n = int(std::floor(90.0 / stepDeg + 1e-9));
    std::vector<SlicePoint> out;
    for (const SliceCurve& c : curves) {
        const double phi = deg2rad(c.scene.scene.light.azimuthDeg);
        const dvec3 toward(std::cos(phi), std::sin(phi), 0.0);   // the light's horizontal direction
        const dvec3 across(-std::sin(phi), std::cos(phi), 0.0);  // n x toward: the v axis of the chart
        for (double inc : incidencesDeg) {
            const double ti = deg2rad(inc);
            const dvec3 wi = std::sin(ti) * toward + dvec3(0, 0, std::cos(ti));
            const dvec3 wr = -std::sin(ti) * toward + dvec3(0, 0, std::cos(ti));
            for (const char* plane : {"in", "across"})
                for (int k = -n; k <= n; ++k) {
                    const double a = k * stepDeg;
                    if (std::abs(a) >= 90.0) continue;  // the horizon: f is 0 there by convention
                    const double t = deg2rad(a);
                    const dvec3 wo = plane[0] == 'i' ? -std::sin(t) * toward + dvec3(0, 0, std::cos(t))
                                                     : std::cos(t) * wr + std::sin(t) * across;
                    SlicePoint p;
                    p.curve = c.label, p.plane = plane, p.incidenceDeg = inc, p.angleDeg = a;
                    p.thetaODeg = rad2deg(std::acos(std::clamp(wo.z, -1.0, 1.0)));
                    for (int i = 0; i < 3; ++i) p.wo[i] = wo[i];
                    const dvec3 f = brdf::evaluate(c.scene.scene.brdf, wi, wo);
                    for (int i = 0; i < 3; ++i) p.f[i] = f[i];
                    p.luminance = brdf::luminance(f);
                    p.fCos = p.luminance * std::max(0.0, wo.z);
                    out.push_back(p);
                }
        }
    }
    return out;
}

const std::vector<std::string>& sliceColumns() {
    static const std::vector<std::string> c = {"curve", "incidence_deg", "plane", "angle_deg", "theta_o_deg", "wo_x",
                                               "wo_y",  "wo_z",          "f_r",   "f_g",       "f_b",         "f",
                                               "f_cos"};
    return c;
}

nlohmann::json toJson(const SlicePoint& p) {
    return {{"curve", p.curve},
            {"incidence_deg", p.incidenceDeg},
            {"plane", p.plane},
            {"angle_deg", p.angleDeg},
            {"theta_o_deg", p.thetaODeg},
            {"wo_x", p.wo[0]},
            {"wo_y", p.wo[1]},
            {"wo_z", p.wo[2]},
            {"f_r", p.f[0]},
            {"f_g", p.f[1]},
            {"f_b", p.f[2]},
            {"f", p.luminance},
            {"f_cos", p.fCos}};
}

}  // namespace hilite::experiments
