#pragma once
// NDF tables for the tests: a GGX lobe sampled into the hand-painted format.

#include "brdf/ndf.hpp"
#include "brdf/ndf_table.hpp"

#include <cstdio>
#include <string>

namespace hilite::test {

/// "theta_h_deg, D" rows of `scale` x GGX(alpha) at theta_k = 90 (k / n)^2 degrees (dense near the peak).
inline std::string ggxTableText(double alpha, int n = 400, double scale = 3.0) {
    std::string text = "# GGX alpha sampled for the tests\ntheta_h_deg, D\n";
    for (int k = 0; k <= n; ++k) {
        const double deg = 90.0 * double(k) * k / (double(n) * n), t = deg2rad(deg);
        char line[96];
        std::snprintf(line, sizeof line, "%.17g, %.17g\n", deg,
                      scale * brdf::D_GGX(std::cos(t), std::sin(t) * std::sin(t), alpha));
        text += line;
    }
    return text;
}

}  // namespace hilite::test
