// The truth suite: GL and the double reference against an exhaustive truth that shares no code with either
// (scripts/highlight_truth.py, numpy; its output in tests/data/highlight_truth.csv; docs/truth.md).

#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/session.hpp"
#include "support/keys.hpp"

#include "core/csv.hpp"
#include "core/text.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

using namespace hilite;

namespace {

struct TruthRow {
    std::string keys;
    std::map<std::string, double> v;
    std::string note;
};

/// The CSV: a quoted case key, then numbers, then a note.
std::vector<TruthRow> readTruth() {
    std::ifstream in(std::string(HILITE_SOURCE_DIR_STR) + "/tests/data/highlight_truth.csv");
    REQUIRE(in.good());
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header = split(line, ',');
    std::vector<TruthRow> rows;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        TruthRow r;
        const size_t close = line.find('"', 1);
        r.keys = line.substr(1, close - 1);
        const std::vector<std::string> cells = split(line.substr(close + 2), ',');
        for (size_t i = 0; i + 1 < header.size() && i < cells.size(); ++i) {
            const std::optional<double> x = cells[i].empty() ? std::nullopt : parseNumber(cells[i]);
            if (x) r.v[header[i + 1]] = *x;
            else if (header[i + 1] == "note") r.note = cells[i];
        }
        if (cells.size() + 1 == header.size()) r.note = cells.back();
        rows.push_back(r);
    }
    return rows;
}

bool sweep(const std::string& keys) {
    return keys.rfind("model=ggx roughness=0.1 geometry=smith fresnel=schlick f0=0.04 incidence=", 0) == 0 &&
           keys.find("threshold=0.5") != std::string::npos && keys.find("azimuth") == std::string::npos;
}

/// Mirror-symmetric about the plane of incidence: isotropic (or anisotropic with an axis in the plane) and
/// lit at azimuth 0.
bool symmetric(const scene::Resolved& r) {
    const auto& b = r.scene.brdf;
    const bool iso = b.alphaY() == b.roughness || std::fmod(std::abs(b.tangentAngleDeg), 90.0) == 0.0;
    return iso && r.scene.light.azimuthDeg == 0.0;
}

}  // namespace

TEST_CASE("truth suite: GL and the reference against the exhaustive scan-line truth") {
    const std::vector<TruthRow> truth = readTruth();
    REQUIRE(truth.size() >= 60);
    measurement::Session session;
    int compared = 0;
    std::printf("%-100s %9s %9s %9s %3s %3s %3s  %s\n", "case", "truth", "ref-t", "gl-t", "tc", "rc", "gc",
                "flags ref | gl");
    for (const TruthRow& t : truth) {
        CAPTURE(t.keys);
        const scene::Resolved r = test::resolveKeys(t.keys);
        const auto ref = measurement::measureReference(r.scene, r.setup.options).shape;
        const nlohmann::json gl = measurement::toJson(session.measureOne(r));
        std::string rf, gf;
        for (auto f : ref.flags) rf += std::string(analysis::toString(f)) + ",";
        for (const auto& f : gl["flags"]) gf += f.get<std::string>() + ",";
        if (t.note == "unbounded") {  // no peak: both must say so
            CHECK(ref.has(analysis::Flag::UnboundedAtHorizon));
            CHECK(gf.find("unbounded_at_horizon") != std::string::npos);
            continue;
        }
        const double ta = t.v.at("aspect"), ra = ref.aspect, ga = gl["aspect"].get<double>();
        const int tc = int(t.v.at("components")), rc = ref.components, gc = gl["components"].get<int>();
        std::printf("%-100s %9.6f %+9.2e %+9.2e %3d %3d %3d  %s | %s\n", t.keys.c_str(), ta, ra - ta, ga - ta, tc, rc,
                    gc, rf.c_str(), gf.c_str());
        ++compared;
        // The reference: converged, whatever the topology.
        CHECK_NEAR(ra, ta, 5e-4);
        CHECK(rc == tc);
        if (sweep(t.keys)) {
            CHECK_NEAR(ga, ta, 0.005);
            CHECK(gc == tc);
        }
        // GL and the reference never differ by more than 0.005 without a flag on one of them.
        if (std::abs(ga - ra) > 0.005) CHECK_MESSAGE(!(rf.empty() && gf.empty()), "GL " << ga << " ref " << ra);
        // A mirror-symmetric lobe has its axes along u and v.
        if (symmetric(r) && ta < 0.999) {
            auto folded = [](double o) { return std::min(std::abs(o), std::abs(std::abs(o) - 90.0)); };
            CHECK(folded(ref.orientation_deg) <= 0.01);
            CHECK(folded(gl["orientation_deg"].get<double>()) <= 0.01);
        }
    }
    CHECK(compared >= 60);
}
