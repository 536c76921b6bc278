#include "hilite/core/chart.hpp"

namespace hilite {

MirrorChart::MirrorChart(double theta_i, double phi_i) {
    set(std::cos(theta_i), std::sin(theta_i), std::cos(phi_i), std::sin(phi_i));
}

MirrorChart MirrorChart::fromDegrees(double thetaDeg, double phiDeg) {
    double c, s, cp, sp;
    cosSinDeg(thetaDeg, c, s);
    cosSinDeg(phiDeg, cp, sp);
    MirrorChart chart;
    chart.set(c, s, cp, sp);
    return chart;
}

void MirrorChart::set(double c, double s, double cp, double sp) {
    m_wi = {s * cp, s * sp, c};
    m_wr = {-s * cp, -s * sp, c};
    m_eu = {c * cp, c * sp, s};
    m_ev = {-sp, cp, 0.0};
}

dvec3 MirrorChart::direction(double u, double v) const {
    const double rho = std::hypot(u, v);
    if (rho == 0.0) return m_wr;
    const double k = std::sin(rho) / rho;  // sin(rho) * (cos psi, sin psi) = k * (u, v)
    return std::cos(rho) * m_wr + k * (u * m_eu + v * m_ev);
}

dvec2 MirrorChart::coords(const dvec3& we) const {
    const double a = glm::dot(we, m_eu), b = glm::dot(we, m_ev), c = glm::dot(we, m_wr);
    const double s = std::hypot(a, b);
    if (s == 0.0) return {c >= 0.0 ? 0.0 : kPi, 0.0};  // exactly on wr (or its antipode: rho = pi, psi = 0)
    const double rho = std::atan2(s, c);
    return {rho * a / s, rho * b / s};
}

double MirrorChart::areaPerSolidAngle(const dvec3& we) const {
    const double a = glm::dot(we, m_eu), b = glm::dot(we, m_ev), c = glm::dot(we, m_wr);
    const double s = std::hypot(a, b);
    if (s < 1e-8) return 1.0;  // rho/sin(rho) = 1 + rho^2/6: below 1e-8 the correction is under 1e-16
    return std::atan2(s, c) / s;
}

}  // namespace hilite
