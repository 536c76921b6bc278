// One default per parameter (issue 31): the registry's default text is read from the default-constructed
// structs, and resolving no values gives those structs back field by field; every choice is its name table.

#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"

#include <doctest/doctest.h>

using namespace hilite;

TEST_CASE("scene::resolve of no values is the default-constructed structs, field by field") {
    const scene::Resolved r = scene::resolve(scene::Values{});
    const scene::Resolved fresh;

    const brdf::Params &p = r.scene.brdf, P;
    CHECK((p.model == P.model));
    CHECK(p.exponent == P.exponent);
    CHECK(p.roughness == P.roughness);
    CHECK(p.roughnessY == P.roughnessY);
    CHECK(p.tangentAngleDeg == P.tangentAngleDeg);
    CHECK((p.fresnel == P.fresnel));
    CHECK(p.f0 == P.f0);
    CHECK(p.eta == P.eta);
    CHECK(p.k == P.k);
    CHECK(p.spectrum == P.spectrum);
    CHECK(p.spectralTable == P.spectralTable);
    CHECK(p.ndfTable == P.ndfTable);
    CHECK(p.measured == P.measured);
    CHECK((p.geometry == P.geometry));
    CHECK((p.diffuse == P.diffuse));
    CHECK(p.albedo == P.albedo);
    CHECK(p.sigmaDeg == P.sigmaDeg);
    CHECK((p.multiscatter == P.multiscatter));
    CHECK(p.energy == P.energy);

    const render::Light &l = r.scene.light, L;
    CHECK((l.type == L.type));
    CHECK(l.incidenceDeg == L.incidenceDeg);
    CHECK(l.azimuthDeg == L.azimuthDeg);
    CHECK(l.irradiance == L.irradiance);
    CHECK(l.intensity == L.intensity);
    CHECK(l.distance == L.distance);
    CHECK(l.radius == L.radius);
    CHECK(l.angleDeg == L.angleDeg);
    CHECK(l.rings == L.rings);
    CHECK(l.ruleTarget == L.ruleTarget);
    CHECK(l.chartCenter == L.chartCenter);

    const render::Surface &s = r.scene.surface, S;
    CHECK(s.bumps == S.bumps);
    CHECK(s.bumpPeriodPx == S.bumpPeriodPx);
    CHECK(s.seed == S.seed);
    CHECK(s.samples == S.samples);
    CHECK(s.samplesPerPeriod == S.samplesPerPeriod);
    CHECK(s.sunDeg == S.sunDeg);
    CHECK(s.texels == S.texels);
    CHECK(s.bumpsPerTile == S.bumpsPerTile);
    CHECK((s.filter == S.filter));
    CHECK(s.prefilterCheck == S.prefilterCheck);

    CHECK(r.scene.brdfFile == fresh.scene.brdfFile);
    CHECK(r.scene.eyeDistance == fresh.scene.eyeDistance);

    const scene::MeasureSetup &m = r.setup, M;
    CHECK(m.width == M.width);
    CHECK(m.height == M.height);
    CHECK(m.fovDeg == M.fovDeg);
    CHECK(m.options.threshold == M.options.threshold);
    CHECK(m.options.minPixelsAcross == M.options.minPixelsAcross);
    CHECK(m.options.subpixel == M.options.subpixel);
    CHECK(m.options.level == M.options.level);
    CHECK(m.coarseSize == M.coarseSize);
    CHECK(m.maxRenders == M.maxRenders);
    CHECK(m.maxBlindRenders == M.maxBlindRenders);
    CHECK(m.fill == M.fill);
    CHECK(m.crop == M.crop);
    CHECK(m.supersample == M.supersample);
    CHECK(m.cpu == M.cpu);
    CHECK(m.threads == M.threads);

    CHECK(r.angles == std::vector<double>{L.incidenceDeg});
    CHECK(r.tolerance == fresh.tolerance);
    CHECK(r.reference == fresh.reference);
    CHECK((r.view == fresh.view));
    CHECK(r.fovDeg == fresh.fovDeg);
    CHECK(r.elevationDeg == fresh.elevationDeg);
    CHECK(r.backend == fresh.backend);
    CHECK(r.gpu == fresh.gpu);
    CHECK(r.shaderTimeoutS == fresh.shaderTimeoutS);
}

TEST_CASE("scene::registry defaults are the fields' defaults, written once") {
    const scene::Resolved r = scene::resolve(scene::Values{});
    const scene::Resolved fresh;
    for (const scene::Param& p : scene::registry()) {
        CAPTURE(p.name);
        if (p.write) CHECK(p.read);  // a written field reads back (help, keys)
        if (!p.read) continue;
        // What no values resolve to is the default-constructed field, in full precision.
        CHECK(p.read(r, true) == p.read(fresh, true));
        // The entry's default text is that field's, as printed for help and the README.
        if (!p.def.empty()) CHECK(p.def == p.read(fresh, false));
        // Its default reads back as itself through the entry's own write.
        if (p.write && !p.def.empty()) {
            scene::Resolved w;
            p.write(w, p.def);
            CHECK(p.read(w, true) == p.read(fresh, true));
        }
    }
}

TEST_CASE("scene::registry choices come from name tables: each name writes a value that reads back as it") {
    for (const scene::Param& p : scene::registry()) {
        if (p.kind != scene::Kind::Choice || !p.write) continue;
        CAPTURE(p.name);
        for (const std::string& c : p.choices) {
            if (c.empty()) continue;
            scene::Resolved r;
            p.write(r, c);
            CHECK(p.read(r, false) == c);
        }
    }
    // The enums the if-chains used to read (a last branch was a silent default): printed from their tables.
    CHECK(std::string(render::toString(render::LightType::Disk)) == "disk");
    CHECK(std::string(render::toString(render::BumpFilter::Moments)) == "moments");
    CHECK(std::string(scene::toString(scene::View::Photo)) == "photo");
    CHECK(scene::find("light")->choices == namesIn(render::kLightTypes));
    CHECK(scene::find("bump_filter")->choices == namesIn(render::kBumpFilters));
    CHECK(scene::find("view")->choices == namesIn(scene::kViews));
}

TEST_CASE("scene::kNames, the names the compiler checks (scene::Name), are the registry's, in order") {
    std::vector<std::string> names, listed(std::begin(scene::kNames), std::end(scene::kNames));
    for (const scene::Param& p : scene::registry()) names.push_back(p.name);
    CHECK(names == listed);
    static_assert(scene::Name("roughness_y").text[0] == 'r');
    // scene::Name("roughnes") in a constant expression does not compile: the check throws.
    CHECK_THROWS_AS(scene::Name(std::string("roughnes").c_str()), std::logic_error);
}
