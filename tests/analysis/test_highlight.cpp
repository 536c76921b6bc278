// The shared parts of the measurement: flag names, option checks, and the ellipse of given moments.

#include "hilite/analysis/highlight.hpp"

#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

using namespace hilite;
using namespace hilite::analysis;

namespace {

/// Central second moments of a uniform ellipse with semi-axes a, b (rad), major axis at angle phi from +u.
AreaMoments ellipseMoments(double a, double b, double phi) {
    const double c = std::cos(phi), s = std::sin(phi), la = a * a / 4, lb = b * b / 4;
    AreaMoments m;
    m.area = kPi * a * b;
    m.cuu = la * c * c + lb * s * s;
    m.cvv = la * s * s + lb * c * c;
    m.cuv = (la - lb) * c * s;
    return m;
}

}  // namespace

TEST_CASE("analysis::toString") {
    CHECK(std::string(toString(Flag::Clipped)) == "clipped");
    CHECK(std::string(toString(Flag::HorizonCut)) == "horizon_cut");
    CHECK(std::string(toString(Flag::UnderResolved)) == "under_resolved");
    CHECK(std::string(toString(Flag::NoHighlight)) == "no_highlight");
    CHECK(std::string(toString(Flag::CoversFrame)) == "covers_frame");
    std::ostringstream os;
    Shape s;
    s.flags = {Flag::Clipped, Flag::HorizonCut};
    os << s << " " << Options{};
    CHECK(os.str().find("flags=[clipped,horizon_cut]") != std::string::npos);
    CHECK(os.str().find("threshold=0.5") != std::string::npos);
}

TEST_CASE("analysis::validate") {
    Options opt;
    SUBCASE("defaults are valid") { CHECK_NOTHROW(validate(opt)); }
    SUBCASE("threshold outside (0, 1)") {
        for (double t : {0.0, 1.0, -0.5, 2.0, std::numeric_limits<double>::quiet_NaN()}) {
            opt.threshold = t;
            CHECK_THROWS_AS(validate(opt), InputError);
        }
    }
    SUBCASE("minPixelsAcross below 1") {
        opt.minPixelsAcross = 0;
        CHECK_THROWS_AS(validate(opt), InputError);
    }
}

TEST_CASE("analysis::Shape::has") {
    Shape s;
    s.flags = {Flag::UnderResolved};
    CHECK(s.has(Flag::UnderResolved));
    CHECK_FALSE(s.has(Flag::Clipped));
}

TEST_CASE("analysis::FlagSet: each flag once, in the order raised") {
    FlagSet f{Flag::HorizonCut, Flag::Clipped, Flag::HorizonCut};
    CHECK(f.size() == 2);
    f.insert(Flag::UnderResolved);
    f.insert(Flag::Clipped);  // there already: stays where it was
    CHECK(std::vector<Flag>(f.begin(), f.end()) ==
          std::vector<Flag>{Flag::HorizonCut, Flag::Clipped, Flag::UnderResolved});
    f.erase(Flag::Clipped);
    CHECK_FALSE(f.has(Flag::Clipped));
    CHECK(f == FlagSet{Flag::HorizonCut, Flag::UnderResolved});
    CHECK(f != FlagSet{Flag::UnderResolved, Flag::HorizonCut});  // the order is part of the value (the row's)
    f.erase(Flag::Mirror);                                       // absent: nothing
    CHECK(f.size() == 2);
}

TEST_CASE("analysis::setEllipse") {
    Shape s;
    SUBCASE("an ellipse's moments give back its semi-axes") {
        setEllipse(s, ellipseMoments(0.2, 0.05, 0.0));
        CHECK(s.major_deg == doctest::Approx(rad2deg(0.2)).epsilon(1e-14));
        CHECK(s.minor_deg == doctest::Approx(rad2deg(0.05)).epsilon(1e-14));
        CHECK(s.aspect == doctest::Approx(0.25).epsilon(1e-14));
        CHECK(s.eccentricity == doctest::Approx(std::sqrt(1 - 0.0625)).epsilon(1e-14));
        CHECK(s.orientation_deg == 0.0);
        CHECK(s.area_deg2 == doctest::Approx(kPi * rad2deg(0.2) * rad2deg(0.05)).epsilon(1e-14));
    }
    SUBCASE("orientation in (-90, 90]") {
        for (double phiDeg : {30.0, -60.0, 89.0, 90.0, -89.0}) {
            CAPTURE(phiDeg);
            setEllipse(s, ellipseMoments(0.1, 0.07, deg2rad(phiDeg)));
            CHECK(s.orientation_deg == doctest::Approx(phiDeg).epsilon(1e-12));
            CHECK(s.aspect == doctest::Approx(0.7).epsilon(1e-12));
        }
        // Major axis along v, with cuv = -0 from rounding: +90, never -90.
        AreaMoments m = ellipseMoments(0.1, 0.07, 0.0);
        std::swap(m.cuu, m.cvv);
        m.cuv = -0.0;
        setEllipse(s, m);
        CHECK(s.orientation_deg == 90.0);
    }
    SUBCASE("thin ellipse: lmin = det / lmax keeps the relative precision mean - hypot would lose") {
        setEllipse(s, ellipseMoments(1.0, 1e-7, 0.0));
        CHECK(s.minor_deg == doctest::Approx(rad2deg(1e-7)).epsilon(1e-6));
        CHECK(s.aspect == doctest::Approx(1e-7).epsilon(1e-6));
    }
    SUBCASE("circle and point") {
        setEllipse(s, ellipseMoments(0.1, 0.1, 0.0));
        CHECK(s.aspect == 1.0);
        CHECK(s.eccentricity == 0.0);
        setEllipse(s, AreaMoments{});
        CHECK(s.aspect == 1.0);  // a point counts as round
        CHECK(s.major_deg == 0.0);
    }
    SUBCASE("centroid in degrees") {
        AreaMoments m = ellipseMoments(0.1, 0.1, 0.0);
        m.mean_u = -0.01;
        m.mean_v = 0.02;
        setEllipse(s, m);
        CHECK(s.centroid_u_deg == doctest::Approx(rad2deg(-0.01)));
        CHECK(s.centroid_v_deg == doctest::Approx(rad2deg(0.02)));
    }
}
