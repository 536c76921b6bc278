#include "brdf/bihemispherical.hpp"

#include "brdf/integrate.hpp"

namespace hilite::brdf {

dvec3 bihemisphericalAlbedo(const Params& p) {
    const bool aniso = p.anisotropic() && allowsAnisotropy(p.model);
    const int azimuths = aniso ? 16 : 1;
    dvec3 sum(0.0);
    for (int j = 0; j < azimuths; ++j) {
        const double phiDeg = 360.0 * j / azimuths;
        auto integrand = [&](double t) { return albedo(p, rad2deg(t), phiDeg) * (std::cos(t) * std::sin(t)); };
        const double split = deg2rad(60.0);
        sum += integratePanel(integrand, 0.0, split) + integratePanel(integrand, split, 0.5 * kPi);
    }
    // (1/pi) * (2 pi / azimuths) * sum over azimuths of the theta integral
    return sum * (2.0 / azimuths);
}

}  // namespace hilite::brdf
