// The spectral Fresnel of measured metals: the data files, the colour weights (a perfect reflector is
// white), and the seed's copper strip: reddish at normal incidence, a dip in red before grazing, white.

#include "brdf/spectral.hpp"

#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <algorithm>

using namespace hilite;

namespace {

double cosDeg(double deg) {
    double c, s;
    cosSinDeg(deg, c, s);
    return c;
}

}  // namespace

TEST_CASE("brdf::readCsv the data files, their sources kept") {
    const std::string dir = HILITE_DATA_DIR;
    const brdf::CsvTable cmf = brdf::readCsv(dir + "/colorimetry/cie1931_2deg_cmf.csv", 4);
    CHECK(cmf.columns[0].size() == 471);
    CHECK(cmf.source.find("CIE 1931") != std::string::npos);
    const brdf::CsvTable d65 = brdf::readCsv(dir + "/colorimetry/cie_d65.csv", 2);
    CHECK(d65.columns[0].size() == 531);
    CHECK(d65.source.find("D65") != std::string::npos);
    for (const char* metal : {"Cu", "Au"}) {
        const brdf::CsvTable t = brdf::readCsv(dir + "/metals/" + metal + "_eta_k.csv", 3);
        CHECK(t.columns[0].size() == 56);
        CHECK(t.source.find("pbrt-v4") != std::string::npos);
    }
    CHECK_THROWS_AS(brdf::readCsv(dir + "/no-such-file.csv", 2),
                    InputError);  // a missing data file is the scene's error: exit 2
    CHECK_THROWS_AS(brdf::readCsv(dir + "/metals/Cu_eta_k.csv", 2), InputError);  // 3 numbers a row
}

TEST_CASE("brdf::loadSpectrum weights: F = 1 gives white (1, 1, 1)") {
    for (int step : {brdf::kFullStepNm, brdf::kGpuStepNm}) {
        const auto s = brdf::loadSpectrum(HILITE_DATA_DIR, "copper", step);
        dvec3 sum(0.0);
        for (const dvec3& w : s->weight) sum += w;
        CAPTURE(step);
        CHECK(glm::length(sum - dvec3(1.0)) < 1e-12);
        // Before the per-channel division the white is M XYZ(D65) / Y: (1, 1, 1) to the matrix's 4 digits.
        MESSAGE("white before normalization: " << s->whiteBeforeNormalization.x << ", " << s->whiteBeforeNormalization.y
                                               << ", " << s->whiteBeforeNormalization.z);
        CHECK(glm::length(s->whiteBeforeNormalization - dvec3(1.0)) < 2e-3);
    }
    CHECK(brdf::loadSpectrum(HILITE_DATA_DIR, "copper", brdf::kFullStepNm)->size() == 471);
    CHECK(brdf::loadSpectrum(HILITE_DATA_DIR, "gold", brdf::kGpuStepNm)->size() == size_t(brdf::kMaxGpuSamples));
    CHECK_THROWS_AS(brdf::loadSpectrum("/nonexistent", "copper", 1), InputError);
    CHECK_THROWS_AS(brdf::loadSpectrum(HILITE_DATA_DIR, "silver", 1), InputError);
}

TEST_CASE("brdf::F_Spectral copper: reddish, a dip in red before grazing, white at grazing") {
    const auto cu = brdf::loadSpectrum(HILITE_DATA_DIR, "copper", brdf::kFullStepNm);
    const dvec3 normal = brdf::F_Spectral(1.0, *cu);
    MESSAGE("copper at 0 degrees: " << normal.x << ", " << normal.y << ", " << normal.z);
    CHECK(normal.x > normal.y);
    CHECK(normal.y > normal.z);
    const dvec3 at89 = brdf::F_Spectral(cosDeg(89.0), *cu);
    MESSAGE("copper at 89 degrees: " << at89.x << ", " << at89.y << ", " << at89.z);
    for (int c = 0; c < 3; ++c) CHECK(at89[c] >= 0.95);
    double minRed = normal.x, minAt = 0.0;
    for (int i = 0; i <= 9000; ++i) {
        const double r = brdf::F_Spectral(cosDeg(0.01 * i), *cu).x;
        if (r < minRed) minRed = r, minAt = 0.01 * i;
    }
    MESSAGE("copper red minimum " << minRed << " at " << minAt << " degrees (normal incidence " << normal.x << ")");
    CHECK(minRed < normal.x - 1e-3);
    CHECK(minAt > 45.0);
    CHECK(minAt < 89.0);
    CHECK(brdf::F_Spectral(0.0, *cu).x == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("brdf::F_Spectral the GPU's 81 samples against the full 1 nm tables") {
    for (const char* metal : {"copper", "gold"}) {
        const auto full = brdf::loadSpectrum(HILITE_DATA_DIR, metal, brdf::kFullStepNm);
        const auto gpu = brdf::loadSpectrum(HILITE_DATA_DIR, metal, brdf::kGpuStepNm);
        double worst = 0.0;
        for (double t = 0.0; t <= 90.0; t += 0.5) {
            const dvec3 d = brdf::F_Spectral(cosDeg(t), *full) - brdf::F_Spectral(cosDeg(t), *gpu);
            worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        }
        MESSAGE(std::string(metal) << ": max |F(81 samples) - F(471 samples)| = " << worst);
        CAPTURE(metal);
        CHECK(worst < 3e-3);
    }
}

TEST_CASE("brdf::F_Spectral gold: yellow at normal incidence") {
    const dvec3 au = brdf::F_Spectral(1.0, *brdf::loadSpectrum(HILITE_DATA_DIR, "gold", brdf::kFullStepNm));
    MESSAGE("gold at 0 degrees: " << au.x << ", " << au.y << ", " << au.z << " (red > 1: outside the sRGB gamut)");
    CHECK(au.x > au.y);
    CHECK(au.y > au.z);
}

TEST_CASE("brdf::F_Spectral F0 agrees with the published linear F0 of copper and gold") {
    // Real-Time Rendering 4th ed. (2018), table 9.2 (Hoffman): copper (0.955, 0.638, 0.538), gold
    // (1.000, 0.782, 0.344), linear sRGB, gold's red clipped at 1 there.
    const dvec3 cu = brdf::F_Spectral(1.0, *brdf::loadSpectrum(HILITE_DATA_DIR, "copper", brdf::kFullStepNm));
    const dvec3 au = brdf::F_Spectral(1.0, *brdf::loadSpectrum(HILITE_DATA_DIR, "gold", brdf::kFullStepNm));
    CHECK_NEAR(cu.x, 0.955, 2e-3);
    CHECK_NEAR(cu.y, 0.638, 2e-3);
    CHECK_NEAR(cu.z, 0.538, 2e-3);
    CHECK(std::min(au.x, 1.0) == 1.0);
    CHECK_NEAR(au.y, 0.782, 2e-3);
    CHECK_NEAR(au.z, 0.344, 2e-3);
}

TEST_CASE("brdf::F_SpectralTable within 1e-5 of F_Spectral over cos theta_d in [0, 1]") {
    for (const std::string& metal : brdf::spectralMetals())
        for (int step : {brdf::kGpuStepNm, brdf::kFullStepNm}) {
            const auto s = brdf::loadSpectrum(HILITE_DATA_DIR, metal, step);
            CHECK(s->fresnelTable().size() == size_t(brdf::kFresnelTableSize));
            // 16 points per table interval (spaced in sqrt(cos), as the entries are; their ends, where the table
            // is exact, included: the error peaks mid-interval), and as many spaced evenly in cos.
            const int n = 16 * (brdf::kFresnelTableSize - 1);
            double worst = 0.0, worstAt = 0.0;
            for (int i = 0; i <= n; ++i)
                for (double c : {double(i) / n * (double(i) / n), double(i) / n}) {
                    const dvec3 d = glm::abs(brdf::F_SpectralTable(c, *s) - brdf::F_Spectral(c, *s));
                    const double e = std::max({d.x, d.y, d.z});
                    if (e > worst) worst = e, worstAt = c;
                }
            CAPTURE(metal);
            CAPTURE(step);
            MESSAGE(metal << " (" << s->size() << " wavelengths): table worst error " << worst << " at cos "
                          << worstAt);
            CHECK(worst <= 1e-5);
            CHECK(worst > 0.0);  // the table is an approximation: a 0 would mean the exact sum was compared with itself
            CHECK(brdf::F_SpectralTable(1.0, *s) == brdf::F_Spectral(1.0, *s));  // the ends are entries
            CHECK(brdf::F_SpectralTable(0.0, *s) == brdf::F_Spectral(0.0, *s));
            CHECK(brdf::F_SpectralTable(-0.5, *s) == brdf::F_SpectralTable(0.0, *s));  // clamped as F_Conductor is
            CHECK(brdf::F_SpectralTable(1.5, *s) == brdf::F_SpectralTable(1.0, *s));
        }
}
