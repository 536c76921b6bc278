#include "analysis/lobes.hpp"

#include "hilite/core/camera.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::test {

double D_GGX(double NoH, double alpha) {
    // Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
    const double a2 = alpha * alpha;
    const double d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

double Lambda_GGX(double cosTheta, double alpha) {
    // Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs"
    const double c2 = cosTheta * cosTheta;
    const double tan2 = (1.0 - c2) / c2;
    return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

DirLobe ggxNdfLobe(const MirrorChart& chart, double alpha) {
    const dvec3 wi = chart.wi();
    return [wi, alpha](const dvec3& we) {
        const dvec3 h = glm::normalize(wi + we);
        return D_GGX(h.z, alpha);
    };
}

DirLobe ggxBrdfLobe(const MirrorChart& chart, double alpha) {
    const dvec3 wi = chart.wi();
    return [wi, alpha](const dvec3& we) {
        const dvec3 h = glm::normalize(wi + we);
        const double G2 = 1.0 / (1.0 + Lambda_GGX(wi.z, alpha) + Lambda_GGX(we.z, alpha));
        return D_GGX(h.z, alpha) * G2 / (4.0 * wi.z * we.z);
    };
}

DirLobe phongLobe(const MirrorChart& chart, double n) {
    const dvec3 wr = chart.wr();
    return [wr, n](const dvec3& we) { return std::pow(std::max(0.0, glm::dot(we, wr)), n); };
}

analysis::LobeFunction chartLobe(const MirrorChart& chart, DirLobe lobe) {
    analysis::LobeFunction f;
    f.lobe = [chart, lobe](double u, double v) {
        const dvec3 we = chart.direction(u, v);
        return we.z > 0.0 ? lobe(we) : 0.0;
    };
    f.visible = [chart](double u, double v) { return chart.direction(u, v).z > 0.0; };
    return f;
}

ImageF renderView(const MirrorChart& chart, const DirLobe& lobe, const dvec3& center, double fovDeg, int width,
                  int height, dvec2 jitter) {
    const PinholeCamera cam = PinholeCamera::measurement(chart, center, fovDeg, width, height);
    ImageF img(width, height, 4);
    for (int iy = 0; iy < height; ++iy) {
        for (int ix = 0; ix < width; ++ix) {
            const dvec3 we = -cam.ray(ix + 0.5 + jitter.x, iy + 0.5 + jitter.y);
            if (we.z <= 0.0) continue;  // sky / below the horizon: (0, 0, 0, 0)
            const dvec2 uv = chart.coords(we);
            float* p = img.pixel(ix, iy);
            p[0] = float(lobe(we));
            p[1] = float(uv.x);
            p[2] = float(uv.y);
            p[3] = float(chart.areaPerSolidAngle(we) * cam.pixelSolidAngle(ix, iy));
        }
    }
    return img;
}

}  // namespace hilite::test
