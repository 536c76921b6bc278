#include "experiments/fit_values.hpp"

#include "brdf/merl.hpp"
#include "core/parallel.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hilite::experiments::values {

Directions grid(bool anisotropic) {
    namespace merl = brdf::merl;
    const double maxTheta = deg2rad(80.0);
    std::vector<double> phiH{0.0};
    if (anisotropic) phiH = {0.0, deg2rad(45.0), deg2rad(90.0), deg2rad(135.0)};
    Directions d;
    for (double ph : phiH) {
        const double c = std::cos(ph), s = std::sin(ph);
        auto rot = [&](const dvec3& w) { return dvec3(c * w.x - s * w.y, s * w.x + c * w.y, w.z); };
        for (int ih = 0; ih < merl::kThetaHBins; ih += 2)
            for (int id = 0; id < merl::kThetaDBins; id += 3)
                for (int ip = 0; ip < merl::kPhiDBins; ip += 6) {
                    dvec3 wi, wo;
                    merl::fromHalfDiff(merl::thetaHalfAt(ih + 0.5), merl::thetaDiffAt(id + 0.5),
                                       merl::phiDiffAt(ip + 0.5), wi, wo);
                    if (wi.z <= std::cos(maxTheta) || wo.z <= std::cos(maxTheta)) continue;
                    d.wi.push_back(rot(wi));
                    d.wo.push_back(rot(wo));
                }
    }
    return d;
}

std::vector<double> sample(const brdf::Params& p, const Directions& d, int channel) {
    std::vector<double> out(d.wi.size());
    // Every core: a values fit evaluates the grid a few hundred times while nothing else runs. Blocks of 256
    // directions, so that a thread's items are contiguous in memory.
    const int blocks = int((out.size() + 255) / 256);
    parallelFor(blocks, [&](int b) {
        for (size_t k = size_t(b) * 256; k < std::min(out.size(), size_t(b + 1) * 256); ++k) {
            const dvec3 rgb = brdf::evaluate(p, d.wi[k], d.wo[k]);
            const double f = channel < 0 ? brdf::luminance(rgb) : rgb[channel];
            out[k] = std::isfinite(f) && f >= 0 ? d.wi[k].z * f : std::numeric_limits<double>::quiet_NaN();
        }
    });
    return out;
}

double residual(const std::vector<double>& model, const std::vector<double>& target) {
    double sum = 0;
    size_t n = 0;
    for (size_t k = 0; k < model.size() && k < target.size(); ++k) {
        if (!std::isfinite(model[k]) || !std::isfinite(target[k])) continue;
        const double e = std::log1p(model[k]) - std::log1p(target[k]);
        sum += e * e;
        ++n;
    }
    return n ? std::sqrt(sum / double(n)) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hilite::experiments::values
