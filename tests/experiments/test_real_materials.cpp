// The shipped real_materials experiment on the RGL files of ../shared (skipped, naming them, where a clone has
// none): every .bsdf beside its own-NDF microfacet model, lobe = mirror, the plots, the contact sheet and the summary's
// verdict per material.

#include "hilite/experiments/run.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace hilite;

TEST_CASE("real_materials: each RGL file beside its own microfacet model, the lobe around the mirror direction") {
    const fs::path shared = fs::path(HILITE_SOURCE_DIR_STR) / ".." / "shared" / "data" / "measured";
    if (!fs::exists(shared / "cc_ibiza_sunset_rgb.bsdf")) {
        MESSAGE("skipped: " << shared.string() << " holds no RGL files (they are not part of the project; see README)");
        return;
    }
    const hilite_test::TempDir dir("hilite-real-materials");
    // The shipped file at every 10 deg (the shipped range is every 5), beside a link to the folder.
    std::ifstream in(fs::path(HILITE_SOURCE_DIR_STR) / "experiments" / "real_materials.toml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string range = "range = [0, 80, 5]";
    REQUIRE(text.find(range) != std::string::npos);
    text.replace(text.find(range), range.size(), "range = [0, 80, 10]");
    const std::string file = dir.write("real_materials.toml", text);
    fs::create_directory_symlink(fs::absolute(shared), dir.path / "measured");
    experiments::RunOptions o;
    o.experiment = file;
    o.out = dir / "out";
    const experiments::RunSummary s = experiments::runExperiment(o);
    CHECK(s.configurations == 14 * 9);  // 7 files and their 7 own-NDF models x 9 incidences
    for (const char* f : {"aspect.png", "major.png", "minor.png", "contact_sheet.png", "summary.md", "results.csv"})
        CHECK_MESSAGE(fs::file_size(dir.path / "out" / f) > 0, f);

    std::ifstream rows(dir.path / "out" / "results.jsonl");
    std::map<std::string, int> measured, flaggedUnbounded;
    for (std::string line; std::getline(rows, line);) {
        const auto r = nlohmann::json::parse(line);
        CHECK(r["lobe"] == "mirror");
        const std::string source = r["source"];
        if (r["variant"] == "own NDF") CHECK(r["model"] == "tabulated");
        if (!r["aspect"].is_null()) ++measured[source];
        for (const auto& f : r["flags"]) flaggedUnbounded[source] += f == "unbounded_at_horizon";
    }
    // The glossy films have a lobe at every incidence, and none of their rows reports the horizon's growth
    // (lobe = all flags every one of them unbounded_at_horizon).
    for (const std::string film : {"cc_ibiza_sunset_rgb", "cc_iris_purple_gem_rgb", "vch_golden_yellow_rgb"}) {
        CAPTURE(film);
        CHECK(measured[film] >= 8);
        CHECK(flaggedUnbounded[film] == 0);
    }
    CHECK(measured["paper_white_rgb"] == 0);  // matte: no lobe around the mirror direction at any incidence

    std::ifstream md(dir.path / "out" / "summary.md");
    const std::string summary((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    // The microfacet model of a film's own NDF narrows as cos theta_i; the films themselves follow neither
    // prediction (not round at normal incidence, rounder than cos theta_i at grazing light).
    for (const std::string film : {"cc_ibiza_sunset_rgb", "cc_iris_purple_gem_rgb", "vch_golden_yellow_rgb"}) {
        CAPTURE(film);
        const auto verdicts = summary.find("| source | rows |");
        REQUIRE(verdicts != std::string::npos);
        const auto own = summary.find(std::string("| ") + film + " own NDF | ", verdicts);
        REQUIRE(own != std::string::npos);
        CHECK(summary.substr(own, summary.find('\n', own) - own).find("cos theta_i (microfacet)") != std::string::npos);
        const auto real = summary.find(std::string("| ") + film + " | ", verdicts);
        REQUIRE(real != std::string::npos);
        MESSAGE(summary.substr(real, summary.find('\n', real) - real));
        MESSAGE(summary.substr(own, summary.find('\n', own) - own));
    }
    CHECK(summary.find("| paper_white_rgb | 0 | - | - | - (no row without flags) |") != std::string::npos);
}
