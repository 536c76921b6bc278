// A consumer built with `c++ pkgconfig_consumer.cpp $(pkg-config --cflags --libs hilite)` alone (no CMake
// package): measures the GGX highlight at 60 degrees; exit 0 when its aspect is the known 0.50166 +- 0.002.
#include <hilite/hilite.hpp>

#include <cmath>
#include <cstdio>

int main() {
    try {
        hilite::scene::Values values;  // GGX alpha 0.1, implicit geometry, no Fresnel, directional light
        values.set("incidence", "60");
        hilite::measurement::Session session;
        const double aspect = session.measureOne(hilite::scene::resolve(values)).shape().aspect;
        std::printf("hilite %s: GGX alpha 0.1 at 60 deg: aspect %.5f\n", HILITE_VERSION_STRING, aspect);
        return std::abs(aspect - 0.50166) < 0.002 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pkgconfig_consumer: %s\n", e.what());
        return 2;
    }
}
