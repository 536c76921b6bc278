#include "experiments/fit_values.hpp"

#include "brdf/merl.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

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
    auto run = [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
            const dvec3 rgb = brdf::evaluate(p, d.wi[k], d.wo[k]);
            const double f = channel < 0 ? brdf::luminance(rgb) : rgb[channel];
            out[k] = std::isfinite(f) && f >= 0 ? d.wi[k].z * f : std::numeric_limits<double>::quiet_NaN();
        }
    };
    // Every core: a values fit evaluates the grid a few hundred times while nothing else runs.
    const size_t threads = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 16);
    const size_t chunk = (out.size() + threads - 1) / threads;
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads && t * chunk < out.size(); ++t)
        pool.emplace_back(run, t * chunk, std::min(out.size(), (t + 1) * chunk));
    run(0, std::min(out.size(), chunk));
    for (std::thread& t : pool) t.join();
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
