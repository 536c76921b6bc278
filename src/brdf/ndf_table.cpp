#include "brdf/ndf_table.hpp"

#include "brdf/rgl.hpp"
#include "core/csv.hpp"

#include "core/files.hpp"
#include "core/text.hpp"
#include "hilite/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace hilite::brdf {

namespace {

/// The two numbers of a row, or false. Separators: comma, whitespace.
/// int over [t0, t1] of (a + b t) cos(t) sin(t) dt, exactly: F(t) = -(a + b t) cos(2t) / 4 + b sin(2t) / 8.
double segmentIntegral(double t0, double d0, double t1, double d1) {
    const double b = (d1 - d0) / (t1 - t0), a = d0 - b * t0;
    auto F = [&](double t) { return -(a + b * t) * std::cos(2 * t) / 4 + b * std::sin(2 * t) / 8; };
    return F(t1) - F(t0);
}

/// int_0^{2 pi} max(0, a + b cos(phi)) dphi, b >= 0.
double clampedCosineRing(double a, double b) {
    if (a >= b) return 2.0 * kPi * a;
    if (a <= -b) return 0.0;
    const double phi0 = std::acos(-a / b);
    return 2.0 * (a * phi0 + b * std::sin(phi0));
}

/// int max(0, w.m) D(m) dm for w at theta_o: over theta_m by 8-point Gauss-Legendre on each table segment
/// (split where the clamp starts, theta_m = pi/2 - theta_o), the azimuth in closed form.
double projectedArea(const NdfTable& t, double thetaO) {
    static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const double co = std::cos(thetaO), so = std::sin(thetaO), kink = 0.5 * kPi - thetaO;
    auto integrand = [&](double tm) {
        return D_Tabulated(std::cos(tm), std::sin(tm) * std::sin(tm), t) * std::sin(tm) *
               clampedCosineRing(co * std::cos(tm), so * std::sin(tm));
    };
    double sum = 0;
    for (size_t k = 0; k + 1 < t.theta.size(); ++k) {
        std::vector<double> cuts = {t.theta[k], t.theta[k + 1]};
        if (kink > cuts[0] && kink < cuts[1]) cuts.insert(cuts.begin() + 1, kink);
        for (size_t c = 0; c + 1 < cuts.size(); ++c) {
            const double mid = 0.5 * (cuts[c] + cuts[c + 1]), half = 0.5 * (cuts[c + 1] - cuts[c]);
            for (int q = 0; q < 4; ++q)
                sum += half * w[q] * (integrand(mid - half * x[q]) + integrand(mid + half * x[q]));
        }
    }
    return sum;
}

}  // namespace

std::shared_ptr<const NdfTable> parseNdfTable(const std::string& text, const std::string& name) {
    auto t = std::make_shared<NdfTable>();
    t->file = name;
    const CsvNumbers csv = parseCsvNumbers(text, name, 2, "two numbers 'theta_h_deg, D'");  // rows 'theta_h_deg, D'
    int lastLine = 0;
    std::vector<double> raw;
    for (size_t r = 0; r < csv.rows.size(); ++r) {
        const double deg = csv.rows[r][0], d = csv.rows[r][1];
        const std::string at = name + ":" + std::to_string(csv.lines[r]) + ": ";
        if (!std::isfinite(deg) || !std::isfinite(d)) throw InputError(at + "theta_h and D must be finite numbers");
        if (d < 0) throw InputError(at + "D must be >= 0 (got " + std::to_string(d) + ")");
        if (deg < 0 || deg > 90) throw InputError(at + "theta_h must be in [0, 90] degrees");
        if (t->theta.empty() && deg != 0) throw InputError(at + "the table must start at theta_h = 0");
        if (!t->theta.empty() && !(deg2rad(deg) > t->theta.back()))
            throw InputError(at + "theta_h must increase from row to row (got " + std::to_string(deg) + " after " +
                             std::to_string(rad2deg(t->theta.back())) + ")");
        if (t->theta.size() == size_t(NdfTable::kMaxRows))
            throw InputError(at + "more than " + std::to_string(NdfTable::kMaxRows) + " rows");
        t->theta.push_back(deg2rad(deg));
        raw.push_back(d);
        lastLine = csv.lines[r];
    }
    const int lineNo = std::max(lastLine, int(std::count(text.begin(), text.end(), '\n')));
    if (t->theta.size() < size_t(NdfTable::kMinRows))
        throw InputError(name + ":" + std::to_string(std::max(lastLine, lineNo)) + ": too few rows (" +
                         std::to_string(t->theta.size()) + "; an NDF table needs at least " +
                         std::to_string(NdfTable::kMinRows) + ")");
    double integral = 0;
    for (size_t k = 0; k + 1 < raw.size(); ++k)
        integral += segmentIntegral(t->theta[k], raw[k], t->theta[k + 1], raw[k + 1]);
    integral *= 2.0 * kPi;
    if (!(integral > 0))
        throw InputError(name + ":" + std::to_string(lastLine) + ": D is 0 everywhere (nothing to normalize)");
    // D is normalized by 1/integral: both must be normal doubles, or the table turns into 0 or Inf.
    if (!std::isfinite(integral) || !std::isnormal(1.0 / integral))
        throw InputError(name + ":" + std::to_string(lastLine) + ": the integral of D (" + fmt(integral) +
                         ") is out of double range to normalize; scale the D column towards 1");
    t->normalization = 1.0 / integral;
    for (double d : raw) {
        t->D.push_back(d * t->normalization);
        if (!std::isfinite(t->D.back()))
            throw InputError(name + ": D x normalization overflows double; scale the D column towards 1");
    }
    const double top = *std::max_element(t->D.begin(), t->D.end());
    const size_t peak = size_t(std::max_element(t->D.begin(), t->D.end()) - t->D.begin());
    t->halfWidth = t->theta.back();
    for (size_t k = peak; k + 1 < t->D.size(); ++k)
        if (t->D[k + 1] <= 0.5 * top) {
            const double f = (t->D[k] - 0.5 * top) / (t->D[k] - t->D[k + 1]);
            t->halfWidth = t->theta[k] + f * (t->theta[k + 1] - t->theta[k]);
            break;
        }
    for (int k = 0; k < NdfTable::kLambdaRows; ++k)
        t->projectedArea.push_back(projectedArea(*t, deg2rad(90.0 * k / (NdfTable::kLambdaRows - 1))));
    return t;
}

std::shared_ptr<const NdfTable> loadNdfTable(const std::string& path) {
    return parseNdfTable(readInputFile(path, "--ndf-table"), path);
}

bool isRglNdfFile(const std::string& path) { return rgl::fileIsTensorFile(path); }

std::shared_ptr<const NdfTable> rglNdfTable(const std::string& path, const std::string& what,
                                            const std::string& dataDir) {
    const std::shared_ptr<const rgl::Material> m = rgl::load(path, what, dataDir);
    const rgl::ParamWeight none;
    constexpr int kRows = 512, kPhi = 128;
    // The mean over phi of a table bilinear in (x, phi): sampled at kPhi azimuths (exact for the nodes' linear
    // pieces when kPhi is a multiple of the intervals; the files have 2-64 phi nodes).
    const auto meanOverPhi = [&](std::size_t first, int nx, int ny, double x) {
        double sum = 0;
        for (int j = 0; j < kPhi; ++j) sum += m->grid(first, nx, ny, {x, (j + 0.5) / kPhi}, none, none, 0);
        return sum / kPhi;
    };
    std::string csv;
    char line[96];
    for (int k = 0; k < kRows; ++k) {
        const double u = double(k) / (kRows - 1), theta = 0.5 * kPi * u * u;
        const double d = meanOverPhi(m->at.ndfAt, m->at.ndfX, m->at.ndfY, u);
        std::snprintf(line, sizeof line, "%.17g, %.17g\n", k == kRows - 1 ? 90.0 : rad2deg(theta), std::max(d, 0.0));
        csv += line;
    }
    auto t = std::make_shared<NdfTable>(*parseNdfTable(csv, path));
    t->fromRgl = true;
    for (int k = 0; k < NdfTable::kLambdaRows; ++k) {
        const double thetaO = deg2rad(90.0 * k / (NdfTable::kLambdaRows - 1));
        const double sigma =
            t->normalization * meanOverPhi(m->at.sigmaAt, m->at.sigmaX, m->at.sigmaY, rgl::thetaToU(thetaO));
        if (90.0 * k / (NdfTable::kLambdaRows - 1) <= 80.0)
            t->projectedAreaMismatch =
                std::max(t->projectedAreaMismatch, std::abs(sigma / t->projectedArea[size_t(k)] - 1.0));
        t->projectedArea[size_t(k)] = sigma;
    }
    return t;
}

double D_Tabulated(double NoH, double sin2h, const NdfTable& t) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    const double th = std::atan2(std::sqrt(sin2h), NoH);
    const size_t n = t.theta.size();
    if (th >= t.theta[n - 1]) return th == t.theta[n - 1] ? t.D[n - 1] : 0.0;  // beyond the table: 0
    size_t lo = 0, hi = n - 1;                                                 // invariant: theta[lo] <= th < theta[hi]
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        (t.theta[mid] <= th ? lo : hi) = mid;
    }
    return t.D[lo] + (t.D[hi] - t.D[lo]) * ((th - t.theta[lo]) / (t.theta[hi] - t.theta[lo]));
}

double Lambda_Tabulated(double cosTheta, const NdfTable& t) {
    if (cosTheta >= 1.0) return 0.0;                   // normal incidence: nothing is masked
    const double c = cosTheta > 0.0 ? cosTheta : 0.0;  // NaN reads as grazing, never converted to an int
    const double x = rad2deg(std::atan2(std::sqrt(std::max(0.0, 1.0 - c * c)), c)) * (NdfTable::kLambdaRows - 1) / 90.0;
    const int k = std::min(int(x), NdfTable::kLambdaRows - 2);
    const double f = x - k;
    const double area = t.projectedArea[size_t(k)] + f * (t.projectedArea[size_t(k) + 1] - t.projectedArea[size_t(k)]);
    return std::max(0.0, area / cosTheta - 1.0);
}

}  // namespace hilite::brdf
