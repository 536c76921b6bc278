#pragma once
// Spectral Fresnel of measured metals: the exact conductor Fresnel evaluated per wavelength with the
// metal's measured eta(lambda), k(lambda), and integrated against the CIE 1931 2-degree observer under
// D65 into linear sRGB. The data are CSV files of data/ (each names its source on its first line):
// metals/{Cu,Au}_eta_k.csv, colorimetry/cie1931_2deg_cmf.csv, colorimetry/cie_d65.csv.
//
//   F_rgb(theta) = sum_i w_i F_Conductor(cos theta, eta(lambda_i), k(lambda_i)),
//   w_i = M (xbar, ybar, zbar)(lambda_i) D65(lambda_i), each channel divided by its sum over i,
//
// M the XYZ -> linear sRGB matrix of IEC 61966-2-1. Dividing each channel by its sum makes a perfect
// reflector (F = 1) exactly white (1, 1, 1); before it the white is M XYZ(D65) / Y(D65), off (1, 1, 1) by
// < 1e-3 from the 4-digit matrix (kept in Spectrum::whiteBeforeNormalization).

#include "hilite/brdf/terms.hpp"
#include "hilite/core/math.hpp"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace hilite::brdf {

/// A numeric CSV of data/: '#' lines are comments (the source), then one header line, then rows.
struct CsvTable {
    std::string source;                        ///< the comment lines
    std::vector<std::vector<double>> columns;  ///< columns[c][row]
};
/// Reads `path`; every row must have `columns` numbers. Throws SystemError naming path:line.
CsvTable readCsv(const std::string& path, size_t columns);

/// A metal sampled for the spectral Fresnel.
struct Spectrum {
    std::string name;                                     ///< "copper" or "gold"
    std::vector<double> lambdaNm, eta, k;                 ///< per sample
    std::vector<dvec3> weight;                            ///< linear sRGB weight per sample; each channel sums to 1
    std::vector<dvec3> xyzWeight;                         ///< CIE XYZ weight per sample under D65; Y sums to 1
    dvec3 whiteBeforeNormalization{1.0};                  ///< sum of the weights before the per-channel division
    std::vector<double> tableLambdaNm, tableEta, tableK;  ///< the measured table itself

    size_t size() const { return lambdaNm.size(); }
    /// eta and k at one wavelength, linear in lambda between the table's rows (as pbrt-v4 does).
    dvec2 etaK(double lambdaNm) const;
    /// F_Spectral at cos theta = (i / (kFresnelTableSize - 1))^2, i = 0 .. kFresnelTableSize - 1, in double:
    /// built on first use (once per spectrum, which loadSpectrum caches), shared by GL and the twin.
    const std::vector<dvec3>& fresnelTable() const;

private:
    mutable std::once_flag m_tableOnce;
    mutable std::vector<dvec3> m_table;
};

/// The metals with spectral data, by material name: copper (metals/Cu_eta_k.csv), gold (Au).
std::vector<std::string> spectralMetals();
bool hasSpectralData(const std::string& material);

/// The wavelength step of the full tables (1 nm over 360..830 nm: 471 samples, the CPU default) and of
/// the GPU's sample set (5 nm over 380..780 nm: 81 uniforms; each sample carries the weight of the 1 nm
/// rows nearest to it, the end samples also those of 360..377 and 783..830 nm).
constexpr int kFullStepNm = 1, kGpuStepNm = 5;
constexpr int kMaxGpuSamples = 81;

/// Loads `metal` and the colorimetry from `dataDir` and samples every `stepNm` (kFullStepNm or
/// kGpuStepNm, any divisor of 400 works). Cached per (dataDir, metal, step). Throws SystemError when a
/// file is missing or malformed, InputError for a metal without data.
std::shared_ptr<const Spectrum> loadSpectrum(const std::string& dataDir, const std::string& metal, int stepNm);

/// Linear sRGB weights of a spectrum sampled at `lambdaNm` (increasing, nm) and linear between the samples
/// (constant beyond the ends), under D65 with the CIE 1931 observer at 1 nm over 360..830 nm, as the metals':
/// rgb = sum_k w_k S_k, each channel's weights summing to 1 (a flat S = 1 is (1, 1, 1)). Throws SystemError when
/// the colorimetry files are missing.
std::vector<dvec3> rgbWeights(const std::string& dataDir, const std::vector<double>& lambdaNm);

/// Spectral Fresnel: F = sum_i w_i F_Conductor(cosTheta_i, eta_i, k_i), linear sRGB.
dvec3 F_Spectral(double cosTheta_i, const Spectrum& s);

/// Entries of the spectral Fresnel table over cos theta_d in [0, 1], read by linear interpolation
/// (--spectral-fresnel table). Entry i holds F at cos = (i / (N - 1))^2, spaced evenly in sqrt(cos): linear
/// interpolation errs by h^2/8 max|F''|, and F bends most near grazing (the worst error of an even spacing
/// in cos sits in its first interval). Worst over cos in [0, 1] against F_Spectral: see
/// tests/brdf/test_spectral.cpp (the table promises 1e-5). On the GPU it is a uniform vec3 array of 512
/// (the NDF table's budget, 512 vec4): an even spacing in cos needed 1024 entries for gold.
constexpr int kFresnelTableSize = 512;

/// The table's F: F_Spectral's table (Spectrum::fresnelTable) interpolated linearly in sqrt(cosTheta_i),
/// cosTheta_i clamped to [0, 1]; the GLSL twin is F_SpectralTable in shaders/brdf_gl.glsl.
dvec3 F_SpectralTable(double cosTheta_i, const Spectrum& s);

}  // namespace hilite::brdf
