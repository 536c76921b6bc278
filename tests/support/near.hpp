#pragma once
// CHECK_NEAR(a, b, tol) / REQUIRE_NEAR: |a - b| <= tol, and on failure both values, their difference and the
// tolerance (CHECK(std::abs(a - b) < tol) prints only "x < y" of the difference). A NaN on either side fails.

#include <doctest/doctest.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace hilite_test {

/// "a = 0.50170000001, b = 0.5017, |a - b| = 1e-11 > tol 1e-12", the expressions as written.
inline std::string nearMessage(const char* ea, const char* eb, double a, double b, double tol) {
    std::ostringstream s;
    s << std::setprecision(17) << ea << " = " << a << ", " << eb << " = " << b << ", |a - b| = " << std::abs(a - b)
      << " (tolerance " << tol << ")";
    return s.str();
}

}  // namespace hilite_test

#define HILITE_NEAR_IMPL(macro, a, b, tol)                                                              \
    do {                                                                                                \
        const double hilite_near_a = double(a), hilite_near_b = double(b), hilite_near_t = double(tol); \
        macro(std::abs(hilite_near_a - hilite_near_b) <= hilite_near_t,                                 \
              hilite_test::nearMessage(#a, #b, hilite_near_a, hilite_near_b, hilite_near_t));           \
    } while (false)

#define CHECK_NEAR(a, b, tol) HILITE_NEAR_IMPL(CHECK_MESSAGE, a, b, tol)
#define REQUIRE_NEAR(a, b, tol) HILITE_NEAR_IMPL(REQUIRE_MESSAGE, a, b, tol)
