// One doctest case per row of each hard-case table and per path (tests/hard/hard_cases.hpp): add a row to
// scene_cases.cpp or term_cases.cpp and two cases appear, "hard scene gl: NAME" and "hard scene double: NAME"
// (or "hard term ..."). Every case asserts numbers, never times.

#include "hard/hard_cases.hpp"

#include "brdf/merl.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/scene/resolve.hpp"
#include "support/gl_fixture.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <deque>
#include <fstream>
#include <string>
#include <utility>

using namespace hilite;
using namespace hilite::hard;

namespace {

/// Chart coordinates, absolute (rad): float rho = atan(s, c) up to pi/2 from the mirror direction, and
/// llvmpipe's atan good to ~1e-6 rad (see D_Gaussian in brdf.glsl): measured 3e-6 in 160-degree frames.
constexpr double kUvTolerance = 1e-5;
/// Pixel (u, v) area: the shader's float arithmetic on the camera basis and rho / sin(rho).
constexpr double kWeightTolerance = 1e-4;
/// GL measurement vs the double reference, where neither is diagnosed (as tests/experiments/). A horizon cut
/// takes the pixel edge as the horizon (measure_image.cpp), a first-order error: 2% on the semi-major axis.
constexpr double kAspectTolerance = 0.005, kMajorTolerance = 0.01, kMajorToleranceCut = 0.02;

void checkMeasurement(const analysis::Shape& s, const analysis::FlagSet& expected) {
    INFO("shape: " << s);
    CHECK(shapeFinite(s));
    CHECK(numbersOrDiagnosis(s));
    CHECK(flagList(s.flags) == flagList(expected));
}

/// Diagnoses after which the GL and reference numbers describe different things (or none).
bool comparable(const analysis::Shape& s) {
    using analysis::Flag;
    for (Flag f : {Flag::Clipped, Flag::UnderResolved, Flag::NoHighlight, Flag::CoversFrame, Flag::Mirror,
                   Flag::EffectivelyMirror, Flag::UnboundedAtHorizon, Flag::NotStarShaped, Flag::NotConverged,
                   Flag::LightUndersampled, Flag::FloatOverflow, Flag::FloatUnderflow})
        if (s.has(f)) return false;
    return true;
}

void sceneGl(size_t i) {
    const SceneCase& c = sceneCases().at(i);
    INFO("scene: " << c.scene);
    const SceneOutcome o = runSceneGl(*test::glEnv().renderer, c);
    INFO("pixels: " << o.pixels.values << " values, " << o.pixels.compared << " compared, max relative error "
                    << o.pixels.maxRelError << " (tolerance " << o.tolerance << "), uv error " << o.pixels.maxUvError
                    << " rad, weight error " << o.pixels.maxWeightError);
    CHECK(o.pixels.nonFinite == 0);
    CHECK(o.pixels.negative == 0);
    CHECK(o.pixels.maxRelError <= o.tolerance);
    CHECK(o.pixels.maxUvError <= kUvTolerance);
    CHECK(o.pixels.maxWeightError <= kWeightTolerance);
    checkMeasurement(o.measurement.shape, c.glFlags);
    const analysis::Shape ref = measurement::measureReference(c.scene, c.setup.options).shape;
    if (comparable(o.measurement.shape) && comparable(ref)) {
        INFO("reference: " << ref);
        CHECK_NEAR(o.measurement.shape.aspect, ref.aspect,
                   (c.aspectTolerance > 0 ? c.aspectTolerance : kAspectTolerance));
        const bool cut = o.measurement.shape.has(analysis::Flag::HorizonCut);
        CHECK_NEAR(o.measurement.shape.major_deg / ref.major_deg, 1.0, (cut ? kMajorToleranceCut : kMajorTolerance));
        // A width is measured on both paths or on neither (peak_on_horizon: null on both).
        CHECK(std::isnan(o.measurement.shape.fwhm_u_deg) == std::isnan(ref.fwhm_u_deg));
        CHECK(std::isnan(o.measurement.shape.fwhm_v_deg) == std::isnan(ref.fwhm_v_deg));
        // One region is one region: each counted once (a part seen in two views was counted twice).
        CHECK(o.measurement.shape.components == ref.components);
        CHECK(std::abs(o.measurement.shape.centroid_u_deg - ref.centroid_u_deg) <= kMajorToleranceCut * ref.major_deg);
        CHECK(std::abs(o.measurement.shape.centroid_v_deg - ref.centroid_v_deg) <= kMajorToleranceCut * ref.major_deg);
    }
}

void sceneDouble(size_t i) {
    const SceneCase& c = sceneCases().at(i);
    INFO("scene: " << c.scene);
    const SceneOutcome o = runSceneDouble(c);
    CHECK(o.pixels.values > 0);
    CHECK(o.pixels.nonFinite == 0);
    CHECK(o.pixels.negative == 0);
    checkMeasurement(o.measurement.shape, c.refFlags);
}

void checkTermValue(const TermCase& c, const TermOutcome& o) {
    for (int j = 0; j < c.components; ++j) {
        INFO("component " << j << ": " << o.value[j] << " (twin " << o.twin[j] << ")");
        CHECK(std::isfinite(o.value[j]));
        CHECK(o.value[j] >= 0.0);
    }
}

void termGl(size_t i) {
    const TermCase& c = termCases().at(i);
    test::glEnv();  // makes the context current
    const TermOutcome o = runTermGl(c);
    checkTermValue(c, o);
    INFO("relative error against the twin: " << o.error);
    CHECK(o.error <= c.tolerance);
}

void termDouble(size_t i) {
    const TermCase& c = termCases().at(i);
    const TermOutcome o = runTermDouble(c);
    checkTermValue(c, o);
    INFO("relative error against the exact answer: " << o.error);
    CHECK(o.error <= 1e-9);
}

// ---- Registration: one case per row and path ----

constexpr size_t kMaxRows = 96;  ///< raise it when a table outgrows it (a check below says so)
std::deque<std::string>& names() {
    static std::deque<std::string> n;  // doctest keeps the name pointers: stable storage
    return n;
}

template <size_t I>
void sceneGlCase() {
    sceneGl(I);
}
template <size_t I>
void sceneDoubleCase() {
    sceneDouble(I);
}
template <size_t I>
void termGlCase() {
    termGl(I);
}
template <size_t I>
void termDoubleCase() {
    termDouble(I);
}

void add(void (*f)(), const std::string& name) {
    names().push_back(name);
    doctest::detail::regTest(doctest::detail::TestCase(f, __FILE__, unsigned(names().size()),
                                                       doctest_detail_test_suite_ns::getCurrentTestSuite()) *
                             names().back().c_str());
}

template <size_t... I>
int registerAll(std::index_sequence<I...>) {
    const size_t scenes = sceneCases().size(), terms = termCases().size();
    ((I < scenes ? add(sceneGlCase<I>, "hard scene gl: " + sceneCases()[I].name) : void()), ...);
    ((I < scenes ? add(sceneDoubleCase<I>, "hard scene double: " + sceneCases()[I].name) : void()), ...);
    ((I < terms ? add(termGlCase<I>, "hard term gl: " + termCases()[I].name) : void()), ...);
    ((I < terms ? add(termDoubleCase<I>, "hard term double: " + termCases()[I].name) : void()), ...);
    return 0;
}

const int registered = registerAll(std::make_index_sequence<kMaxRows>());

}  // namespace

TEST_CASE("hard tables fit the registration") {
    CHECK(registered == 0);
    CHECK(sceneCases().size() <= kMaxRows);
    CHECK(termCases().size() <= kMaxRows);
}

// ---- table_error: the bounds of a measured table's error fields ----

TEST_CASE("hard table_error: eccentricityChange in closed form, within [0, 1]") {
    // a 0.6 +- 0.2: e(0.6) = 0.8, e(0.4) = sqrt(0.84), e(0.8) = 0.6; the larger change is 0.2.
    CHECK_NEAR(measurement::eccentricityChange(0.6, 0.2), 0.2, 1e-15);
    // Round: e(1) = 0, e(1 - d) = sqrt(2 d - d^2).
    CHECK_NEAR(measurement::eccentricityChange(1.0, 0.19), std::sqrt(1.0 - 0.81 * 0.81), 1e-15);
    CHECK(measurement::eccentricityChange(1.0, 0.0) == 0.0);
    // An interval past [0, 1] is cut there: 0.5 +- 2 spans a in [0, 1], e from 0 to 1 about e(0.5) = sqrt(0.75).
    CHECK_NEAR(measurement::eccentricityChange(0.5, 2.0), std::sqrt(0.75), 1e-15);
    for (double a = 0; a <= 1.0; a += 0.125)
        for (double d : {0.0, 1e-12, 1e-3, 0.1, 1.0, 10.0, 1e300}) {
            const double c = measurement::eccentricityChange(a, d);
            CHECK(c >= 0.0);
            CHECK(c <= 1.0);
        }
}

TEST_CASE("hard table_error: a round highlight (retro n 100 tabulated, theta_i 0) has an eccentricity error <= 1") {
    // Its eccentricity is ~2e-7 (aspect 1 - 2e-14): the slope a / e of the old first-order propagation gave an
    // eccentricity error of 9.5e5 here. The error now is the change of sqrt(1 - a^2) over the aspect's error.
    hilite_test::TempDir dir("hilite-hard-table-error");
    const std::string file = dir / "retro.binary";
    {
        scene::Values v;
        v.set("model", "retro");
        v.set("exponent", "100");
        const brdf::Params p = scene::resolve(v, scene::Purpose::Brdf).scene.brdf;
        std::ofstream(file, std::ios::binary) << brdf::merl::encode(brdf::merl::tabulate(p));
    }
    scene::Values v;
    v.set("measured", file);
    v.set("incidence", "0");
    v.set("reference", "true");
    const measurement::Result r = measurement::measureRow(nullptr, scene::resolve(v));
    REQUIRE(r.tableError);
    const measurement::TableError& e = *r.tableError;
    INFO("aspect " << r.shape().aspect << " +- " << e.aspect << ", eccentricity " << r.shape().eccentricity << " +- "
                   << e.eccentricity);
    CHECK(r.shape().aspect > 1.0 - 1e-9);
    CHECK(e.aspect > 0.0);
    CHECK(e.eccentricity >= 0.0);
    CHECK(e.eccentricity <= 1.0);
    // Round, so the aspect's interval reaches down to 1 - e.aspect alone: e = sqrt(1 - (1 - d)^2) there.
    const double d = e.aspect, atEnd = std::sqrt(1.0 - (1.0 - d) * (1.0 - d));
    CHECK_NEAR(e.eccentricity, atEnd - r.shape().eccentricity, 1e-9);
}
