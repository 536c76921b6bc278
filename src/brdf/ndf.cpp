#include "brdf/ndf.hpp"

#include "brdf/integrate.hpp"

#include <algorithm>
#include <cmath>
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

double sgdNormalization(double alpha, double p) {
    // The last four (alpha, p) per thread: the three channels of one evaluation each hit their own.
    struct Entry {
        double alpha = -1, p = -1, K = 0;
    };
    thread_local Entry recent[4];
    thread_local int next = 0;
    for (const Entry& e : recent)
        if (e.alpha == alpha && e.p == p) return e.K;
    // Gamma(1 - p, alpha) = int_alpha^inf e^-s s^-p ds = int e^(-e^u) e^(u (1 - p)) du, u = ln s: smooth in u, to
    // s = alpha + 60 (e^-60 of the rest), on Gauss-Legendre panels 1/4 wide.
    const double a = std::log(alpha), b = std::log(alpha + 60.0);
    const int panels = std::max(1, int(std::ceil((b - a) / 0.25)));
    double sum = 0;
    for (int i = 0; i < panels; ++i)
        sum += integratePanel([p](double u) { return std::exp(-std::exp(u) + u * (1.0 - p)); },
                              a + (b - a) * i / panels, a + (b - a) * (i + 1) / panels);
    recent[next] = {alpha, p, 1.0 / (alpha * sum)};
    const double K = recent[next].K;
    next = (next + 1) % 4;
    return K;
}

namespace {
/// int_1^{1+B} t^q dt = ((1 + B)^(q+1) - 1) / (q + 1), as expm1((q + 1) L) / (q + 1), L = ln(1 + B): q = -1 is L.
double powerIntegral(double q, double L) {
    const double x = (q + 1.0) * L;
    return x == 0.0 ? L : std::expm1(x) / x * L;
}
}  // namespace

double abcShapeIntegral(double B, double C) {
    if (B < 0.5) {
        // int_0^1 u (1 + B (1 - u))^-C du = sum_k binom(-C, k) B^k / ((k + 1)(k + 2)), |terms| falling as B^k.
        double sum = 0, term = 1;  // binom(-C, k) B^k
        for (int k = 0; k < 200 && term != 0.0; ++k) {
            sum += term / ((k + 1.0) * (k + 2.0));
            term *= -(C + k) / (k + 1.0) * B;
        }
        return 2.0 * kPi * sum;
    }
    const double L = std::log1p(B);
    return 2.0 * kPi / (B * B) * ((1.0 + B) * powerIntegral(-C, L) - powerIntegral(1.0 - C, L));
}

}  // namespace hilite::brdf
