#include "render/bump_moments.hpp"

#include "render/bumps.hpp"

#include <algorithm>
#include <ostream>

namespace hilite::render {

std::ostream& operator<<(std::ostream& os, BumpFilter f) { return os << toString(f); }

void sunFrame(const dvec3& wi, dvec3& t1, dvec3& t2) {
    t1 = std::abs(wi.z) < 0.999 ? glm::normalize(dvec3(-wi.y, wi.x, 0.0)) : dvec3(1, 0, 0);
    t2 = glm::cross(wi, t1);
}

void reflectionJacobian(const dvec3& we, const dvec3& m, double len, double VoM, const dvec3& t1, const dvec3& t2,
                        double B[4]) {
    const dvec3 dmx = (dvec3(-1, 0, 0) + m * m.x) / len, dmy = (dvec3(0, -1, 0) + m * m.y) / len;
    const dvec3 drx = 2.0 * (m * glm::dot(we, dmx) + VoM * dmx), dry = 2.0 * (m * glm::dot(we, dmy) + VoM * dmy);
    B[0] = glm::dot(t1, drx), B[1] = glm::dot(t1, dry), B[2] = glm::dot(t2, drx), B[3] = glm::dot(t2, dry);
}

double bumpMomentsLobe(const micro::Moments& M, const dvec3& we, const dvec3& wi, double sigma, double& VoH) {
    const dvec3 h = glm::normalize(we + wi);  // both above the horizon: we + wi != 0
    VoH = glm::dot(we, h);
    const dvec2 s(-h.x / h.z, -h.y / h.z);
    dvec3 t1, t2;
    sunFrame(wi, t1, t2);
    double B[4];
    reflectionJacobian(we, h, 1.0 / h.z, VoH, t1, t2, B);
    // sigma^2 (B^T B)^-1: the sun's Gaussian carried back to slope space.
    const double g00 = B[0] * B[0] + B[2] * B[2], g01 = B[0] * B[1] + B[2] * B[3], g11 = B[1] * B[1] + B[3] * B[3];
    const double gdet = g00 * g11 - g01 * g01, s2 = sigma * sigma;
    const dvec3 cov = M.covariance();
    const double c00 = cov.x + s2 * g11 / gdet, c11 = cov.y + s2 * g00 / gdet, c01 = cov.z - s2 * g01 / gdet;
    const double det = c00 * c11 - c01 * c01;
    if (!(det > 0.0)) return 0.0;  // a degenerate covariance (never with the sun's term): no lobe
    const dvec2 d = s - M.mean;
    const double q = (c11 * d.x * d.x - 2.0 * c01 * d.x * d.y + c00 * d.y * d.y) / det;
    const double c2 = h.z * h.z;
    return std::exp(-0.5 * q) / (2.0 * kPi * std::sqrt(det)) / (c2 * c2) * wi.z * 0.25;
}

int centreBumpSamples(const Scene& scene, const PinholeCamera& cam) {
    return bumpSamplesAt(scene, cam, 0.5 * cam.width, 0.5 * cam.height);
}

int bumpSamplesAt(const Scene& scene, const PinholeCamera& cam, double fx, double fy) {
    if (scene.surface.samples > 0) return scene.surface.samples;
    auto hit = [&](double px, double py, dvec3& P) {
        const dvec3 d = cam.ray(px, py);
        if (d.z >= 0.0) return false;  // the ray never meets the plane
        P = cam.position + (-cam.position.z / d.z) * d;
        return true;
    };
    dvec3 P0, Px, Py;
    if (!hit(fx, fy, P0) || !hit(fx + 1, fy, Px) || !hit(fx, fy + 1, Py)) return kMaxBumpSamples + 1;
    const double period = bumpTileWorld(scene, cam) / scene.surface.bumpsPerTile;
    const double periods = std::max(glm::length(dvec2(Px - P0)), glm::length(dvec2(Py - P0))) / period;
    return int(std::min(1e6, std::ceil(scene.surface.samplesPerPeriod * periods)));
}

bool usesMoments(const Scene& scene, const PinholeCamera& cam) {
    switch (scene.surface.filter) {
        case BumpFilter::Supersample: return false;
        case BumpFilter::Moments: return true;
        case BumpFilter::Auto: break;
    }
    // The prefilter's Gaussian is the slope distribution of a Beckmann field only (see slope_moments.hpp):
    // a GGX normal map stays supersampled, capped.
    return scene.brdf.model == brdf::Model::Beckmann && centreBumpSamples(scene, cam) > kMaxBumpSamples;
}

}  // namespace hilite::render
