// `hilite brdf tabulate` as a user meets it: a MERL file that reads back as the model at its bin centres,
// and bad input refused in one line with exit code 2 and nothing written.

#include "support/run_hilite.hpp"

#include "brdf/merl.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

namespace merl = hilite::brdf::merl;

TEST_CASE("cli::brdf tabulate: GGX 0.1 smith schlick as a MERL file equal to brdf::evaluate at its bin centres") {
    hilite_test::TempDir dir("hilite-tabulate");
    const std::string out = dir / "ggx.binary";
    const auto r = hilite_test::hilite(
        "brdf tabulate --model ggx --roughness 0.1 --geometry smith --fresnel schlick "
        "--f0 0.04 -o " +
        out);
    REQUIRE(r.code == 0);
    CHECK(hilite_test::lines(r.out) == 1);
    CHECK(r.out.find("wrote " + out + ": MERL table 90 x 90 x 180") == 0);
    REQUIRE(std::filesystem::file_size(out) == merl::kFileBytes);
    const merl::MeasuredBrdf m = merl::read(out);
    hilite::brdf::Params p;
    p.model = hilite::brdf::Model::GGX;
    p.roughness = 0.1;
    p.geometry = hilite::brdf::Geometry::Smith;
    p.fresnel = hilite::brdf::Fresnel::Schlick;
    p.f0 = hilite::dvec3(0.04);
    CHECK(m.raw == merl::tabulate(p).raw);  // the CLI writes the library's table
    int checked = 0;
    for (int ih : {0, 3, 20, 45, 80})
        for (int id : {0, 30, 60})
            for (int ip : {0, 90, 179}) {
                hilite::dvec3 wi, wo;
                merl::fromHalfDiff(merl::thetaHalfAt(ih + 0.5), merl::thetaDiffAt(id + 0.5), merl::phiDiffAt(ip + 0.5),
                                   wi, wo);
                if (wi.z <= 0 || wo.z <= 0) continue;
                const hilite::dvec3 want = hilite::brdf::evaluate(p, wi, wo),
                                    got = m.evaluate(wi, wo, merl::Interpolation::Nearest);
                for (int c = 0; c < 3; ++c) CHECK(std::abs(got[c] - want[c]) <= 2.3e-16 * want[c]);
                ++checked;
            }
    CHECK(checked > 30);
}

TEST_CASE("cli::brdf tabulate: bad input is one line, exit 2, nothing written") {
    hilite_test::TempDir dir("hilite-tabulate-bad");
    const std::string out = dir / "bad.binary";
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"--model ggx --roughness 0.1 --roughness-y 0.3 -o " + out, "--roughness-y: a MERL table is isotropic"},
        {"--model ggx --roughness -1 -o " + out, "--roughness"},
        {"--model ggx --roughness 0.1", "-o: give the MERL .binary file to write"},
        {"--model ggx --roughness 0.1 -o " + dir.path.string(), "-o"},
        {"--model ggx --roughness 0.1 -o " + (dir / "no/such/dir/x.binary"), "-o"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.args);
        const auto r = hilite_test::hilite("brdf tabulate " + c.args);
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        CHECK(r.out.find(c.message) != std::string::npos);
        CHECK(!std::filesystem::exists(out));
    }
    // Only the named output was considered: nothing else appeared in the folder.
    CHECK(std::filesystem::is_empty(dir.path));
}
