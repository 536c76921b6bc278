#pragma once
// The measurement chart: azimuthal-equidistant angular coordinates (u, v) about the mirror direction,
// exactly as ../shared/notes/measurement.md defines them. Local frame: n = +z, the light at incidence
// theta_i and azimuth phi_i. Double-precision twin of chartCoords() in shaders/shade.frag.

#include "hilite/core/math.hpp"

namespace hilite {

class MirrorChart {
public:
    /// theta_i, phi_i in radians.
    MirrorChart(double theta_i, double phi_i);
    /// theta_i, phi_i in degrees, exact at multiples of 90 (see cosSinDeg).
    static MirrorChart fromDegrees(double thetaDeg, double phiDeg);

    const dvec3& wi() const { return m_wi; }  ///< towards the light
    const dvec3& wr() const { return m_wr; }  ///< mirror direction of wi
    const dvec3& eu() const { return m_eu; }  ///< +u: in the plane of incidence, towards the normal
    const dvec3& ev() const { return m_ev; }  ///< +v: perpendicular to the plane of incidence

    /// we = cos(rho) wr + sin(rho) (cos(psi) e_u + sin(psi) e_v), with rho = |(u,v)|, psi = atan2(v, u).
    dvec3 direction(double u, double v) const;
    /// Inverse of direction(): (u, v) in radians. Stable near wr: rho = atan2(|we x wr|, we.wr).
    dvec2 coords(const dvec3& we) const;
    /// Area of (u,v) per unit solid angle at we: rho / sin(rho) (the chart's Jacobian).
    double areaPerSolidAngle(const dvec3& we) const;

private:
    MirrorChart() = default;
    void set(double c, double s, double cp, double sp);
    dvec3 m_wi, m_wr, m_eu, m_ev;
};

}  // namespace hilite
