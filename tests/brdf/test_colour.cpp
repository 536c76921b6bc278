// The colour of a reflectance: the channels of a Fresnel term, their XYZ weights and CIELAB.

#include "brdf/spectral.hpp"
#include "hilite/brdf/colour.hpp"
#include "hilite/brdf/terms.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <random>

using namespace hilite;

TEST_CASE("brdf::labFromXyz") {
    // sRGB red (XYZ the first column of IEC 61966-2-1's matrix) against D65: L* 53.24, a* 80.09, b* 67.20
    // (CIE 15:2004 formulas; the values of Lindbloom's calculator, brucelindbloom.com).
    const dvec3 lab = brdf::labFromXyz({0.4124, 0.2126, 0.0193}, {0.9505, 1.0, 1.089});
    CHECK(lab.x == doctest::Approx(53.24).epsilon(1e-3));
    CHECK(lab.y == doctest::Approx(80.09).epsilon(1e-3));
    CHECK(lab.z == doctest::Approx(67.20).epsilon(1e-3));
    SUBCASE("the white is L* 100, a* = b* = 0; black L* 0") {
        const dvec3 w = brdf::labFromXyz({0.9505, 1.0, 1.089}, {0.9505, 1.0, 1.089});
        CHECK(w.x == doctest::Approx(100.0));
        CHECK_NEAR(w.y, 0.0, 1e-12);
        CHECK_NEAR(w.z, 0.0, 1e-12);
        CHECK(brdf::labFromXyz(dvec3(0.0), {0.9505, 1.0, 1.089}).x == doctest::Approx(0.0));
    }
}

TEST_CASE("brdf::reflectanceChannels") {
    brdf::Params p;
    SUBCASE("sRGB channels: a reflectance of 1 is the D65 white") {
        const auto ch = brdf::reflectanceChannels(p);
        REQUIRE(ch.size() == 3);
        const brdf::Colour c = brdf::colourOf({1.0, 1.0, 1.0}, ch);
        CHECK(c.xyz.y == doctest::Approx(1.0).epsilon(1e-4));
        CHECK(c.chroma < 1e-9);
        CHECK(c.x == doctest::Approx(0.3127).epsilon(1e-3));
        CHECK(c.y == doctest::Approx(0.3290).epsilon(1e-3));
    }
    SUBCASE("gold: one channel a wavelength, Y of the white 1, its white's chroma 0, the table within 1e-5") {
        p.fresnel = brdf::Fresnel::Spectral;
        p.spectrum = brdf::loadSpectrum(HILITE_DATA_DIR, "gold", brdf::kFullStepNm);
        const auto ch = brdf::reflectanceChannels(p);
        REQUIRE(ch.size() == p.spectrum->size());
        const brdf::Colour white = brdf::colourOf(std::vector<double>(ch.size(), 1.0), ch);
        CHECK(white.xyz.y == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(white.chroma < 1e-9);
        std::mt19937_64 rng(3);
        std::vector<double> F(ch.size());
        double worst = 0;
        for (int i = 0; i < 200; ++i) {
            const double c = double(rng() >> 11) * 0x1.0p-53;
            ch.fresnel(c, F.data());
            for (size_t k = 0; k < F.size(); ++k)
                worst = std::max(worst, std::abs(F[k] - brdf::F_Conductor(c, p.spectrum->eta[k], p.spectrum->k[k])));
        }
        CHECK(worst < 1e-5);
        // Gold at normal incidence is yellow: its chroma is far from 0, its xy far from the white.
        std::vector<double> F0(ch.size());
        ch.fresnel(1.0, F0.data());
        const brdf::Colour gold = brdf::colourOf(F0, ch);
        CHECK(gold.chroma > 20.0);
        CHECK(gold.xyFromWhite > 0.05);
        // The sRGB weights of the channels give what F_Spectral gives.
        CHECK(gold.rgb.x == doctest::Approx(brdf::F_Spectral(1.0, *p.spectrum).x).epsilon(1e-12));
    }
}
