#include "brdf/ndf.hpp"

#include "brdf/integrate.hpp"

#include <map>
#include <mutex>

namespace hilite::brdf {

double gaussianNormalization(double m) {
    // Last value per thread first: the integrators call this once per sample with the same m.
    thread_local double lastM = -1.0, lastK = 0.0;
    if (m == lastM) return lastK;
    if (m == 0.0) return 0.0;  // a delta: infinite k_G, returned as 0 (see ndf.hpp)
    static std::mutex mutex;
    static std::map<double, double> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(m);
    if (it == cache.end()) {
        // Beyond 40 m the integrand is below exp(-1600): the range ends there or at the horizon.
        const double end = std::min(0.5 * kPi, 40.0 * m);
        const double I =
            integrateGraded([m](double t) { return std::exp(-(t / m) * (t / m)) * std::cos(t) * std::sin(t); }, end, m);
        it = cache.emplace(m, 1.0 / (2.0 * kPi * I)).first;
    }
    lastM = m;
    lastK = it->second;
    return lastK;
}

}  // namespace hilite::brdf
