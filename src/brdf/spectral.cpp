#include "brdf/spectral.hpp"

#include "core/csv.hpp"

#include "hilite/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

namespace hilite::brdf {

namespace {

/// XYZ -> linear sRGB, IEC 61966-2-1:1999 (D65 white), rows R, G, B.
constexpr double kXyzToSrgb[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};

/// The visible range the colour matching functions cover (CIE 1931 2-degree, 1 nm rows).
constexpr int kCmfFirstNm = 360, kCmfLastNm = 830;
/// The GPU sample set spans 380..780 nm, where the observer's weight is: outside it xbar D65, ybar D65
/// and zbar D65 stay below 6.5e-4, 1.7e-5 and 1.4e-3 of their peaks (the end samples carry those rows).
constexpr int kGpuFirstNm = 380, kGpuLastNm = 780;

std::string fileOf(const std::string& metal) {
    if (metal == "copper") return "metals/Cu_eta_k.csv";
    if (metal == "gold") return "metals/Au_eta_k.csv";
    throw InputError("no spectral data for '" + metal + "' (have: copper, gold)");
}

/// Linear interpolation in a table sorted by x; outside it, the end value (never reached: the tables
/// cover 299..886 nm and the observer 360..830 nm).
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
    if (at <= x.front()) return y.front();
    if (at >= x.back()) return y.back();
    const size_t i = size_t(std::upper_bound(x.begin(), x.end(), at) - x.begin());
    const double t = (at - x[i - 1]) / (x[i] - x[i - 1]);
    return y[i - 1] + t * (y[i] - y[i - 1]);
}

/// The observer under D65 at 1 nm over 360..830 nm: the weights M (xbar, ybar, zbar) D65, not yet
/// normalized, and the sum of ybar D65 (the Y of the white).
struct Observer {
    std::vector<dvec3> rgb, xyz;
    double ySum = 0.0;
};

Observer observer(const std::string& dataDir) {
    const CsvTable cmf = readCsv(dataDir + "/colorimetry/cie1931_2deg_cmf.csv", 4);
    const CsvTable d65 = readCsv(dataDir + "/colorimetry/cie_d65.csv", 2);
    Observer o;
    for (int nm = kCmfFirstNm; nm <= kCmfLastNm; ++nm) {
        const double s = interpolate(d65.columns[0], d65.columns[1], nm);
        double xyz[3];
        for (int c = 0; c < 3; ++c) xyz[c] = s * interpolate(cmf.columns[0], cmf.columns[size_t(c) + 1], nm);
        dvec3 rgb(0.0);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) rgb[r] += kXyzToSrgb[r][c] * xyz[c];
        o.rgb.push_back(rgb);
        o.xyz.emplace_back(xyz[0], xyz[1], xyz[2]);
        o.ySum += xyz[1];
    }
    return o;
}

}  // namespace

std::vector<dvec3> rgbWeights(const std::string& dataDir, const std::vector<double>& lambdaNm) {
    const Observer o = observer(dataDir);
    std::vector<dvec3> w(lambdaNm.size(), dvec3(0.0));
    if (lambdaNm.empty()) return w;
    dvec3 total(0.0);
    for (int nm = kCmfFirstNm; nm <= kCmfLastNm; ++nm) {
        const dvec3& rgb = o.rgb[size_t(nm - kCmfFirstNm)];
        total += rgb;
        // The hat functions of the linear interpolation between the samples.
        const auto hi = std::upper_bound(lambdaNm.begin(), lambdaNm.end(), double(nm));
        if (hi == lambdaNm.begin()) w.front() += rgb;
        else if (hi == lambdaNm.end()) w.back() += rgb;
        else {
            const size_t k = size_t(hi - lambdaNm.begin()) - 1;
            const double t = (nm - lambdaNm[k]) / (lambdaNm[k + 1] - lambdaNm[k]);
            w[k] += (1.0 - t) * rgb, w[k + 1] += t * rgb;
        }
    }
    for (dvec3& x : w) x /= total;
    return w;
}

namespace {

std::shared_ptr<const Spectrum> buildSpectrum(const std::string& dataDir, const std::string& metal, int stepNm) {
    if (stepNm < 1 || (kGpuLastNm - kGpuFirstNm) % stepNm != 0)
        throw InputError("spectral step must divide 400 nm (got " + std::to_string(stepNm) + ")");
    const CsvTable table = readCsv(dataDir + "/" + fileOf(metal), 3);
    auto s = std::make_shared<Spectrum>();
    s->name = metal;
    s->tableLambdaNm = table.columns[0];
    s->tableEta = table.columns[1];
    s->tableK = table.columns[2];
    const int first = stepNm == 1 ? kCmfFirstNm : kGpuFirstNm, last = stepNm == 1 ? kCmfLastNm : kGpuLastNm;
    for (int nm = first; nm <= last; nm += stepNm) {
        s->lambdaNm.push_back(nm);
        const dvec2 ek = s->etaK(nm);
        s->eta.push_back(ek.x);
        s->k.push_back(ek.y);
    }
    // Each 1 nm row adds its weight to the nearest sample (ties, possible for even steps, go up), so
    // the bins partition 360..830 nm and the weights keep their sum.
    const Observer o = observer(dataDir);
    s->weight.assign(s->size(), dvec3(0.0));
    s->xyzWeight.assign(s->size(), dvec3(0.0));
    dvec3 sum(0.0);
    for (size_t r = 0; r < o.rgb.size(); ++r) {
        const double nm = kCmfFirstNm + double(r);
        const double i = std::clamp(std::round((nm - first) / stepNm), 0.0, double(s->size() - 1));
        s->weight[size_t(i)] += o.rgb[r];
        s->xyzWeight[size_t(i)] += o.xyz[r] / o.ySum;
        sum += o.rgb[r];
    }
    s->whiteBeforeNormalization = sum / o.ySum;
    for (dvec3& w : s->weight) w /= sum;
    return s;
}

}  // namespace

CsvTable readCsv(const std::string& path, size_t columns) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read data file " + path);
    std::ostringstream text;
    text << in.rdbuf();
    const CsvNumbers csv = parseCsvNumbers(text.str(), path, columns);
    CsvTable t;
    t.source = csv.source;
    t.columns.assign(columns, {});
    for (const auto& row : csv.rows)
        for (size_t c = 0; c < columns; ++c) t.columns[c].push_back(row[c]);
    if (t.columns[0].size() < 2) throw InputError(path + ": fewer than two rows of data");
    for (size_t r = 1; r < t.columns[0].size(); ++r)
        if (!(t.columns[0][r] > t.columns[0][r - 1]))
            throw InputError(path + ": wavelengths must increase (row " + std::to_string(r + 1) + ")");
    return t;
}

dvec2 Spectrum::etaK(double nm) const {
    return {interpolate(tableLambdaNm, tableEta, nm), interpolate(tableLambdaNm, tableK, nm)};
}

std::vector<std::string> spectralMetals() { return {"copper", "gold"}; }
bool hasSpectralData(const std::string& material) { return material == "copper" || material == "gold"; }

std::shared_ptr<const Spectrum> loadSpectrum(const std::string& dataDir, const std::string& metal, int stepNm) {
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const Spectrum>> cache;
    const std::string key = dataDir + "|" + metal + "|" + std::to_string(stepNm);
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    return cache[key] = buildSpectrum(dataDir, metal, stepNm);
}

dvec3 F_Spectral(double cosTheta_i, const Spectrum& s) {
    dvec3 f(0.0);
    for (size_t i = 0; i < s.size(); ++i) f += s.weight[i] * F_Conductor(cosTheta_i, s.eta[i], s.k[i]);
    return f;
}

const std::vector<dvec3>& Spectrum::fresnelTable() const {
    std::call_once(m_tableOnce, [this] {
        m_table.resize(size_t(kFresnelTableSize));
        for (int i = 0; i < kFresnelTableSize; ++i) {
            const double t = double(i) / (kFresnelTableSize - 1);  // sqrt(cos theta)
            m_table[size_t(i)] = F_Spectral(t * t, *this);
        }
    });
    return m_table;
}

dvec3 F_SpectralTable(double cosTheta_i, const Spectrum& s) {
    // The same steps as the GLSL (shaders/brdf_gl.glsl, F_SpectralTable), in double.
    const std::vector<dvec3>& t = s.fresnelTable();
    // Not a number (a direction that is not one) reads as grazing: no float-to-int conversion of a NaN.
    const double c = cosTheta_i > 0.0 ? std::min(cosTheta_i, 1.0) : 0.0;
    const double x = std::sqrt(c) * (kFresnelTableSize - 1);
    const int i = std::min(int(x), kFresnelTableSize - 2);
    const double f = x - double(i);
    return t[size_t(i)] * (1.0 - f) + t[size_t(i) + 1] * f;
}

}  // namespace hilite::brdf
