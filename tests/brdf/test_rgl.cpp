// RGL `.bsdf` materials (brdf/rgl.hpp): the tensor_file reader, the lookup at the tables' nodes on a synthetic
// material whose every table is known, the seven real files of ../shared (skipped, naming what is missing,
// where a clone has none), and bad files refused in one line (a GL twin per pixel: tests/render/test_rgl_gl.cpp).

#include "brdf/inspect.hpp"
#include "brdf/integrate.hpp"
#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/rgl.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/brdf/terms.hpp"
#include "hilite/core/error.hpp"
#include "support/rgl_file.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace hilite;
using hilite_test::TensorField;

namespace {

brdf::rgl::Material synthetic(int n = 4) {
    return brdf::rgl::parse(hilite_test::tensorFile(hilite_test::syntheticRgl(n)), "synthetic.bsdf");
}

/// wo for the light wi and the half vector at polar angle thetaM, azimuth phiM (radians).
dvec3 reflectAbout(const dvec3& wi, double thetaM, double phiM) {
    const dvec3 m(std::sin(thetaM) * std::cos(phiM), std::sin(thetaM) * std::sin(phiM), std::cos(thetaM));
    return 2.0 * glm::dot(wi, m) * m - wi;
}

std::string refusal(const std::string& bytes) {
    try {
        (void)brdf::rgl::parse(bytes, "bad.bsdf", "--measured");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const char* const kRealFiles[] = {"cc_ibiza_sunset_rgb.bsdf",  "cc_iris_purple_gem_rgb.bsdf",
                                  "cg_sunflower_rgb.bsdf",     "colodur_napoli_4f_rgb.bsdf",
                                  "paper_white_rgb.bsdf",      "satin_rosaline_rgb.bsdf",
                                  "vch_golden_yellow_rgb.bsdf"};

}  // namespace

TEST_CASE("rgl: a synthetic material's lookup returns the stored rgb node where the half vector lands on one") {
    const brdf::rgl::Material m = synthetic(7);
    CHECK(m.description == "synthetic");
    CHECK(m.isotropic);
    CHECK(m.jacobian);
    CHECK(m.at.nTheta == 3);
    const int n = m.at.rgbX;
    int checked = 0;
    for (int k = 0; k < 2; ++k) {  // incidence nodes 0 and 0.6 rad (pi/2 lies on the horizon)
        const double thetaI = m.thetaI(k);
        const dvec3 wi(std::sin(thetaI), 0.0, std::cos(thetaI));
        for (int x = 1; x < 4; ++x)  // not 0: a half vector at the pole has no azimuth
            for (int y = 0; y + 1 < n; ++y) {
                // u(theta_m) = x / (n - 1), u(phi_m - phi_i) = y / (n - 1); the uniform VNDF's warp is the identity
                const double u = double(x) / (n - 1), v = double(y) / (n - 1);
                const double thetaM = u * u * kPi / 2, phiM = v * 2 * kPi - kPi;
                const dvec3 wo = reflectAbout(wi, thetaM, phiM);
                if (wo.z <= 0) continue;
                const dvec3 s = m.stored(wi, wo);
                for (int c = 0; c < 3; ++c) {
                    CAPTURE(k);
                    CAPTURE(x);
                    CAPTURE(y);
                    CAPTURE(c);
                    CHECK(std::abs(s[c] - double(hilite_test::syntheticRgb(k, c, x, y))) < 1e-9);
                }
                // f = stored / cos theta_o
                CHECK(std::abs(m.evaluate(wi, wo).x * wo.z - s.x) < 1e-12);
                ++checked;
            }
    }
    CHECK(checked >= 2 * 2 * (n - 1));
    // Between incidences the value is linear in theta_i: halfway between nodes 0 and 1, the mean of the two.
    const double mid = 0.5 * (m.thetaI(0) + m.thetaI(1));
    const dvec3 wi(std::sin(mid), 0.0, std::cos(mid));
    const double u = 1.0 / (n - 1);
    const dvec3 s = m.stored(wi, reflectAbout(wi, u * u * kPi / 2, -kPi));
    CHECK(std::abs(s.x - 0.5 * (hilite_test::syntheticRgb(0, 0, 1, 0) + hilite_test::syntheticRgb(1, 0, 1, 0))) < 1e-7);
    // Below the horizon: nothing.
    CHECK(m.evaluate(dvec3(0, 0, -1), dvec3(0, 0, 1)) == dvec3(0.0));
}

TEST_CASE("rgl: the warp's inverse maps the half vector's unit square onto itself, monotone in each coordinate") {
    const std::string dir = hilite_test::sharedMeasured();
    const std::string file = dir + "/cg_sunflower_rgb.bsdf";
    if (!std::filesystem::exists(file)) {
        MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
        return;
    }
    const brdf::rgl::Material m = brdf::rgl::read(file);
    for (int k = 0; k + 1 < m.at.nTheta; ++k) {  // not the last, at the horizon (rows of no visible normal)
        const brdf::rgl::ParamWeight pw = m.phiWeight(0), tw = m.thetaWeight(m.thetaI(k));
        CHECK(tw.index == k);
        CHECK(tw.t == 0.0);
        const dvec2 lo = m.invert({0, 0}, pw, tw), hi = m.invert({1, 1}, pw, tw);
        CHECK(std::abs(lo.x) < 1e-12);
        CHECK(std::abs(lo.y) < 1e-12);
        CHECK(std::abs(hi.x - 1) < 1e-9);
        CHECK(std::abs(hi.y - 1) < 1e-9);
        double previous = -1;
        for (int i = 0; i <= 64; ++i) {  // along theta at a fixed phi: the conditional CDF rises
            const dvec2 s = m.invert({i / 64.0, 0.3}, pw, tw);
            CHECK(s.x >= previous - 1e-12);
            previous = s.x;
        }
    }
}

TEST_CASE("rgl: the seven real files read, and their directional albedo is a reflectance") {
    const std::string dir = hilite_test::sharedMeasured();
    for (const char* name : kRealFiles) {
        const std::string file = dir + "/" + name;
        if (!std::filesystem::exists(file)) {
            MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
            continue;
        }
        CAPTURE(file);
        CHECK(brdf::rgl::fileIsTensorFile(file));
        const auto m = brdf::rgl::load(file);
        CHECK(brdf::rgl::load(file) == m);  // read once
        CHECK(!m->description.empty());
        CHECK(m->isotropic);
        CHECK(m->at.nTheta >= 2);
        CHECK(m->thetaI(0) == 0.0);
        CHECK(std::abs(m->thetaI(m->at.nTheta - 1) - kPi / 2) < 1e-6);
        CHECK(m->validNodes <= m->nodes);
        brdf::Params p;
        p.model = brdf::Model::None;
        p.rgl = m;
        for (double theta : {0.0, 40.0}) {  // energy: a passive surface reflects at most what it receives
            const dvec3 a = brdf::albedo(p, theta, 0.0);
            CAPTURE(theta);
            MESSAGE(std::string(name) << " albedo at " << theta << " deg: " << a.x << " " << a.y << " " << a.z);
            for (int c = 0; c < 3; ++c) {
                CHECK(a[c] > 0.0);
                CHECK(a[c] < 1.05);
            }
        }
    }
}

TEST_CASE("rgl: bad files are refused in one line naming the file and what is wrong") {
    using hilite_test::syntheticRgl;
    using hilite_test::tensorFile;
    CHECK(refusal(tensorFile(syntheticRgl())).empty());
    struct Case {
        const char* what;
        std::string bytes;
        const char* message;
    };
    std::vector<Case> cases;
    {
        std::string b = tensorFile(syntheticRgl());
        b[10] = 'X';
        cases.push_back({"wrong magic", b, "does not start with \"tensor_file\""});
    }
    cases.push_back({"wrong version", tensorFile(syntheticRgl(), 2, 0), "version 2.0"});
    {
        auto f = syntheticRgl();
        f.erase(f.begin() + 8);  // rgb
        cases.push_back({"missing field", tensorFile(f), "has no field 'rgb'"});
    }
    {
        auto f = syntheticRgl();
        hilite_test::field(f, "rgb").name = "spectra";
        cases.push_back({"spectral without wavelengths", tensorFile(f), "has no field 'wavelengths'"});
    }
    {
        auto f = syntheticRgl();
        auto& rgb = hilite_test::field(f, "rgb");
        rgb.shape = {1, 3, 12, 4};
        cases.push_back({"mis-shaped field", tensorFile(f), "field 'rgb' has shape [1, 3, 12, 4]"});
    }
    {
        auto f = syntheticRgl();
        auto& t = hilite_test::field(f, "theta_i");
        t.type = 11;
        t.bytes += t.bytes;
        cases.push_back({"wrong type", tensorFile(f), "field 'theta_i' is f64; expected f32"});
    }
    {
        const std::string b = tensorFile(syntheticRgl());
        cases.push_back({"truncated data", b.substr(0, b.size() - 5), "runs past the end of the file"});
        cases.push_back({"truncated header", b.substr(0, 40), "truncated"});
        cases.push_back({"empty", "", "does not start with"});
    }
    {
        auto f = syntheticRgl();
        std::vector<float> v(3 * 8 * 8, 1.0f);
        v[70] = std::numeric_limits<float>::quiet_NaN();
        hilite_test::field(f, "vndf").bytes = hilite_test::floatBytes(v);
        cases.push_back({"NaN", tensorFile(f), "field 'vndf' holds a NaN value at index 70"});
    }
    {
        auto f = syntheticRgl();
        std::vector<float> v(16, 0.5f);
        v[3] = std::numeric_limits<float>::infinity();
        hilite_test::field(f, "sigma").bytes = hilite_test::floatBytes(v);
        cases.push_back({"Inf", tensorFile(f), "field 'sigma' holds an infinite value at index 3"});
    }
    {
        auto f = syntheticRgl();
        hilite_test::field(f, "sigma").bytes = hilite_test::floatBytes(std::vector<float>(16, 0.0f));
        cases.push_back({"sigma 0", tensorFile(f), "expected > 0 (it divides)"});
    }
    {
        auto f = syntheticRgl();
        hilite_test::field(f, "vndf").bytes = hilite_test::floatBytes(std::vector<float>(3 * 8 * 8, 0.0f));
        cases.push_back({"empty VNDF", tensorFile(f), "integrates to 0"});
    }
    {
        auto f = syntheticRgl();
        hilite_test::field(f, "theta_i").bytes = hilite_test::floatBytes({0.0f, 0.6f, 0.3f});
        cases.push_back({"theta_i out of order", tensorFile(f), "field 'theta_i' is not increasing"});
    }
    {
        auto f = syntheticRgl();
        auto& v = hilite_test::field(f, "vndf");
        v.shape = {1, 3, 8, 0x2000000000000000ull};  // a size whose product overflows 64 bits
        cases.push_back({"huge shape", tensorFile(f), "runs past the end of the file"});
    }
    for (const Case& c : cases) {
        CAPTURE(c.what);
        const std::string why = refusal(c.bytes);
        CAPTURE(why);
        CHECK(why.find("--measured: 'bad.bsdf' ") == 0);
        CHECK(why.find('\n') == std::string::npos);
        CHECK(why.find(c.message) != std::string::npos);
    }
}

TEST_CASE("rgl: a directory, a FIFO and a 10 GB sparse file are refused before anything is read") {
    hilite_test::TempDir dir("hilite-rgl");
    const std::string fifo = dir / "fifo.bsdf", sparse = dir / "huge.bsdf";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    {
        std::ofstream out(sparse, std::ios::binary);
        out << std::string("tensor_file\0", 12);
    }
    REQUIRE(::truncate(sparse.c_str(), 10LL << 30) == 0);
    for (const std::string& path : {dir.path.string(), fifo, sparse}) {
        CAPTURE(path);
        std::string why;
        try {
            (void)brdf::rgl::read(path, "--measured");
        } catch (const InputError& e) {
            why = e.what();
        }
        CAPTURE(why);
        CHECK(why.find("--measured: '" + path + "'") == 0);
        CHECK(why.find('\n') == std::string::npos);
    }
}

TEST_CASE("rgl: brdf inspect reports the file, its albedo as brdf::albedo, and a table's off-specular peak") {
    brdf::Params p;
    p.model = brdf::Model::None;
    p.rgl = std::make_shared<const brdf::rgl::Material>(synthetic(7));
    const brdf::Inspection in = brdf::inspect(p, {0.0, 30.0}, 0.0);
    CHECK(in.format == "rgl");
    CHECK(in.description == "synthetic");
    REQUIRE(in.thetaINodesDeg.size() == 3);
    CHECK(in.thetaINodesDeg[2] == doctest::Approx(90.0));
    CHECK(in.reciprocity.pairs > 1000);
    REQUIRE(in.incidences.size() == 2);
    const dvec3 a = brdf::albedo(p, 30.0, 0.0);
    CHECK(in.incidences[1].albedo.x == a.x);

    // A GGX 0.2 Smith Schlick table: reciprocal by construction, and its peak of f cos theta_o where a scan of
    // the analytic model puts it (an independent evaluation: the model, not the table).
    brdf::Params ggx;
    ggx.model = brdf::Model::GGX;
    ggx.roughness = 0.2;
    ggx.geometry = brdf::Geometry::Smith;
    ggx.fresnel = brdf::Fresnel::Schlick;
    ggx.f0 = dvec3(0.04);
    brdf::Params table;
    table.model = brdf::Model::None;
    table.measured = std::make_shared<const brdf::merl::MeasuredBrdf>(brdf::merl::tabulate(ggx));
    const brdf::Inspection t = brdf::inspect(table, {60.0}, 0.0);
    CHECK(t.format == "merl");
    CHECK(t.reciprocity.max < 1e-12);
    double best = -1, bestTheta = 0;
    for (int i = 0; i < 360; ++i) {  // the analytic model in the plane of incidence
        const dvec3 wo = sphericalDirectionDeg(0.25 * i, 180.0);
        const double v = brdf::evaluate(ggx, sphericalDirectionDeg(60.0, 0.0), wo).y * wo.z;
        if (v > best) best = v, bestTheta = 0.25 * i;
    }
    MESSAGE("GGX 0.2 at 60 deg: the table's peak of f cos theta_o at " << t.incidences[0].peakThetaODeg
                                                                       << " deg, the model's at " << bestTheta);
    CHECK(bestTheta > 61.0);  // off-specular: beyond the mirror direction
    CHECK(std::abs(t.incidences[0].peakThetaODeg - bestTheta) <= 0.5);
    CHECK(t.incidences[0].peakOffsetDeg == doctest::Approx(t.incidences[0].peakThetaODeg - 60.0).epsilon(1e-6));
}

TEST_CASE("rgl: --ndf-table FILE.bsdf, a file's measured NDF as a table - GGX 0.2 sampled as the files are") {
    hilite_test::TempDir dir("hilite-rgl-ndf");
    const std::string file = dir / "ggx.bsdf";
    std::ofstream(file, std::ios::binary) << hilite_test::tensorFile(hilite_test::syntheticGgxNdf(0.2));
    REQUIRE(brdf::isRglNdfFile(file));
    const auto t = brdf::rglNdfTable(file);
    CHECK(t->fromRgl);
    // The nodes' GGX integrates to 1 up to the table's linear pieces: the factor says how far.
    CHECK(t->normalization == doctest::Approx(1.0).epsilon(2e-3));
    for (double deg : {0.0, 2.0, 5.0, 11.3, 20.0, 40.0}) {
        CAPTURE(deg);
        const double h = deg2rad(deg), c = std::cos(h), s2 = std::sin(h) * std::sin(h);
        CHECK(brdf::D_Tabulated(c, s2, *t) == doctest::Approx(brdf::D_GGX(c, s2, 0.2)).epsilon(5e-3));
    }
    // Smith's Lambda from the file's sigma is GGX's, and the integral of the table's D agrees with it.
    for (double deg : {0.0, 30.0, 60.0, 80.0}) {
        CAPTURE(deg);
        const double c = std::cos(deg2rad(deg)), t2 = std::pow(std::tan(deg2rad(deg)), 2);
        CHECK(brdf::Lambda_Tabulated(c, *t) ==
              doctest::Approx(0.5 * (-1.0 + std::sqrt(1.0 + 0.04 * t2))).epsilon(3e-3));
    }
    CHECK(t->projectedAreaMismatch < 3e-3);
}

TEST_CASE("rgl: the real files' NDFs integrate to 1 and their sigma tables are the integrals of their NDFs") {
    const std::string dir = hilite_test::sharedMeasured();
    for (const char* name : {"cc_ibiza_sunset_rgb.bsdf", "cg_sunflower_rgb.bsdf", "paper_white_rgb.bsdf"}) {
        const std::string file = dir + "/" + name;
        if (!std::filesystem::exists(file)) {
            MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
            continue;
        }
        CAPTURE(file);
        const auto t = brdf::rglNdfTable(file);
        MESSAGE(std::string(name) << ": NDF normalization " << t->normalization << ", half-width "
                                  << rad2deg(t->halfWidth)
                                  << " deg, sigma against the integral of D: " << t->projectedAreaMismatch);
        CHECK(t->normalization == doctest::Approx(1.0).epsilon(0.02));
        CHECK(t->projectedAreaMismatch < 0.015);
    }
}

TEST_CASE("rgl: a spectral file is reduced to linear sRGB at its nodes (CIE 1931 under D65, as the metals)") {
    // A flat spectrum is grey: every channel holds the spectrum's value (the weights of each channel sum to 1).
    const auto flat =
        brdf::rgl::parse(hilite_test::tensorFile(hilite_test::syntheticSpectral([](double) { return 1.0; })),
                         "flat.bsdf", "RGL file", HILITE_DATA_DIR);
    CHECK(flat.wavelengths == 48);
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x)
                    CHECK(flat.rgbNode(0, k, c, x, y) ==
                          doctest::Approx(double(hilite_test::syntheticRgb(k, 0, x, y))).epsilon(1e-6));
    // Long wavelengths only (a red dye): red, little green, no blue.
    const auto red = brdf::rgl::parse(
        hilite_test::tensorFile(hilite_test::syntheticSpectral([](double nm) { return nm >= 620 ? 1.0 : 0.0; })),
        "red.bsdf", "RGL file", HILITE_DATA_DIR);
    const double r = red.rgbNode(0, 0, 0, 0, 0), g = red.rgbNode(0, 0, 1, 0, 0), b = red.rgbNode(0, 0, 2, 0, 0);
    MESSAGE("a spectrum of 1 above 620 nm: linear sRGB " << r << ", " << g << ", " << b);
    CHECK(r > 0.3 * double(hilite_test::syntheticRgb(0, 0, 0, 0)));
    CHECK(g < 0.2 * r);
    CHECK(std::abs(b) < 0.02 * r);
    // The weights themselves: a flat spectrum sums to (1, 1, 1) over any sampling.
    dvec3 sum(0.0);
    for (const dvec3& w : brdf::rgbWeights(HILITE_DATA_DIR, {400.0, 550.0, 551.0, 700.0})) sum += w;
    CHECK(sum.x == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(sum.z == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("rgl: bad spectral files are refused in one line") {
    auto fields = hilite_test::syntheticSpectral([](double) { return 1.0; });
    auto& wl = hilite_test::field(fields, "wavelengths");
    std::vector<float> backwards;
    for (int i = 0; i < 48; ++i) backwards.push_back(float(830.0 - 10.0 * i));
    wl.bytes = hilite_test::floatBytes(backwards);
    const auto refused = [](const std::string& bytes, const std::string& dataDir) {
        try {
            brdf::rgl::parse(bytes, "bad.bsdf", "--measured", dataDir);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string order = refused(hilite_test::tensorFile(fields), HILITE_DATA_DIR);
    CHECK(order.find("'wavelengths' is not increasing") != std::string::npos);
    CHECK(order.find('\n') == std::string::npos);
    const std::string noData =
        refused(hilite_test::tensorFile(hilite_test::syntheticSpectral([](double) { return 1.0; })), "");
    CHECK(noData.find("colorimetry") != std::string::npos);
    auto noWl = hilite_test::syntheticSpectral([](double) { return 1.0; });
    noWl.pop_back();  // the wavelengths field
    CHECK(refused(hilite_test::tensorFile(noWl), HILITE_DATA_DIR).find("'wavelengths'") != std::string::npos);
}
