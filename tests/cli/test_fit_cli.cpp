// `hilite fit` as a user meets it: bad flags and output folders are refused in one line, exit 2, nothing
// written. The fits themselves (each model fitted back, Phong against GGX, the fit_models experiment), in-process:
// tests/experiments/test_fit.cpp.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

TEST_CASE("cli::fit: bad input is refused in one line naming the flag, exit 2, nothing written") {
    hilite_test::TempDir dir("hilite-fit-bad");
    const std::string out = dir / "out";
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"--model ggx --models phong,foo", "--models: 'foo' is not a model"},
        {"--model ggx --models none", "--models: 'none' is not a model"},
        {"--model ggx --models ggx,beckmann,ggx", "--models: 'ggx' is given twice"},
        {"--model ggx --thresholds 0.1,1.5", "--thresholds: each must be in (0, 1)"},
        {"--model ggx --thresholds 0.1,x", "--thresholds: 'x' is not a number"},
        {"--model ggx --weights 1,2", "--weights: one per threshold (5), got 2"},
        {"--model ggx --weights 0,0,0,0,0", "--weights: at least one must be > 0"},
        {"--model ggx --weights 1e308,1e308,0,0,0", "--weights: their sum must be finite"},
        {"--target " + (dir / "x.txt"), "--target: '"},
        {"--target " + (dir / "missing.binary"), "--target: cannot read"},
        {"--model ggx --models phong --fit-anisotropy", "--fit-anisotropy: needs beckmann or ggx"},
        {"--model ggx --roughness -1", "--roughness"},
        {"--model ggx --rank-by both", "--rank-by: both not in {shape,values}"},
        {"--model ggx --fit-diffuse yes", "--fit-diffuse: yes not in {auto,on,off}"},
        {"--brdf " + std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/ggx.brdf --rank-by values",
         "--rank-by values: the target has no double evaluation"},
    };
    // An output folder that cannot be made, or a file in its place: refused before anything is fitted. Under a
    // regular file nothing can be made, even as root (/proc/... could be, in a chroot without /proc mounted).
    { std::ofstream(dir / "a_file") << "x"; }
    for (const std::string& o :
         {(std::filesystem::path(dir / "a_file") / "no-such" / "out").string(), dir / "a_file"}) {
        CAPTURE(o);
        const auto r = hilite_test::hilite("fit --model ggx --models ggx -o " + o);
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        CHECK(r.out.find("-o: ") != std::string::npos);
    }
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const auto r = hilite_test::hilite("fit " + c.args + " -o " + out);
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        CHECK(r.out.find(c.message) != std::string::npos);
        CHECK(!std::filesystem::exists(out));
    }
}
