// MERL .binary tables (brdf/merl.hpp): the index maths against hand-computed values and against a literal
// transcription of MERL's BRDFRead.cpp, the round trip tabulate -> encode -> parse -> evaluate against
// brdf::evaluate, the interpolation error off the bin centres, reciprocity, and every bad file refused in one
// line. One GGX table is shared by the cases (tabulating it is the slow part).

#include "brdf/integrate.hpp"
#include "brdf/merl.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <vector>

using namespace hilite;
namespace merl = hilite::brdf::merl;

namespace {

brdf::Params ggxParams() {
    brdf::Params p;
    p.model = brdf::Model::GGX;
    p.roughness = 0.1;
    p.geometry = brdf::Geometry::Smith;
    p.fresnel = brdf::Fresnel::Schlick;
    p.f0 = dvec3(0.04);
    return p;
}

/// GGX 0.1, Smith, Schlick 0.04, tabulated once for every case.
const merl::MeasuredBrdf& ggxTable() {
    static const merl::MeasuredBrdf t = [] {
        const auto t0 = std::chrono::steady_clock::now();
        merl::MeasuredBrdf m = merl::tabulate(ggxParams());
        MESSAGE("tabulating GGX 0.1 took "
                << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s");
        return m;
    }();
    return t;
}

/// BRDFRead.cpp's std_coords_to_half_diff_coords, transcribed (rotate_vector by Rodrigues, acos), as the
/// independent reference of toHalfDiff.
void brdfReadHalfDiff(const dvec3& in, const dvec3& out, double& thetaH, double& phiH, double& thetaD, double& phiD) {
    auto rotate = [](const dvec3& v, const dvec3& axis, double angle) {
        return v * std::cos(angle) + axis * glm::dot(axis, v) * (1.0 - std::cos(angle)) +
               glm::cross(axis, v) * std::sin(angle);
    };
    const dvec3 half = glm::normalize((in + out) / 2.0);
    thetaH = std::acos(half.z);
    phiH = std::atan2(half.y, half.x);
    const dvec3 d = rotate(rotate(in, {0, 0, 1}, -phiH), {0, 1, 0}, -thetaH);
    thetaD = std::acos(d.z);
    phiD = std::atan2(d.y, d.x);
}

dvec3 randomUpper(std::mt19937& g, double maxThetaDeg) {
    std::uniform_real_distribution<double> u(0, 1);
    const double t = deg2rad(maxThetaDeg) * std::sqrt(u(g)), p = 2 * kPi * u(g);
    return sphericalDirection(t, p);
}

std::string scratch(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("hilite-merl-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string header(int a, int b, int c) {
    std::string s(12, '\0');
    const std::int32_t d[3] = {a, b, c};
    std::memcpy(&s[0], d, 12);  // the test host is little-endian, as the files
    return s;
}

/// The message of the InputError that reading `path` throws ("" when none is thrown).
std::string refusal(const std::string& path) {
    try {
        merl::read(path, "--measured");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("merl: bin coordinates and indices against hand-computed values") {
    // theta_h: sqrt(theta_h / 90 deg) * 90. 1 deg -> sqrt(1/90) * 90 = 9.4868; 22.5 deg -> 45; 10 deg -> 30.
    CHECK(merl::thetaHalfCoord(deg2rad(1.0)) == doctest::Approx(9.486832980505138).epsilon(1e-14));
    CHECK(merl::thetaHalfCoord(deg2rad(22.5)) == doctest::Approx(45.0).epsilon(1e-14));
    CHECK(merl::nearestBin(merl::thetaHalfCoord(deg2rad(1.0)), 90) == 9);
    CHECK(merl::thetaHalfCoord(-0.1) == 0.0);
    CHECK(merl::thetaHalfAt(45.0) == doctest::Approx(deg2rad(22.5)).epsilon(1e-14));
    CHECK(merl::thetaHalfAt(30.0) == doctest::Approx(deg2rad(10.0)).epsilon(1e-14));
    // theta_d: one bin per degree; phi_d: one per degree of [0, 180) after the fold (-30 deg -> 150 deg).
    CHECK(merl::nearestBin(merl::thetaDiffCoord(deg2rad(45.3)), 90) == 45);
    CHECK(merl::phiDiffCoord(deg2rad(-30.0)) == doctest::Approx(150.0).epsilon(1e-14));
    CHECK(merl::nearestBin(merl::phiDiffCoord(deg2rad(179.9)), 180) == 179);
    CHECK(merl::nearestBin(merl::phiDiffCoord(kPi), 180) == 179);  // BRDFRead clamps pi into the last bin
    CHECK(merl::phiDiffAt(150.0) == doctest::Approx(deg2rad(150.0)).epsilon(1e-14));
    // Clamping: BRDFRead's (int) then [0, bins - 1].
    CHECK(merl::nearestBin(90.2, 90) == 89);
    CHECK(merl::nearestBin(-1.0, 90) == 0);
    CHECK(merl::nearestBin(std::nan(""), 90) == 0);
    // phi_d + 180 (theta_d + 90 theta_h).
    CHECK(merl::flatIndex(1, 2, 3) == 3 + 180 * (2 + 90 * 1));
    CHECK(merl::flatIndex(89, 89, 179) == merl::kEntries - 1);
    // Multilinear weights between bin centres i + 0.5: theta clamped to the edge, phi_d wrapped.
    auto w = merl::axisWeights(10.75, 90, false);
    CHECK(w.lo == 10);
    CHECK(w.hi == 11);
    CHECK(w.t == doctest::Approx(0.25));
    w = merl::axisWeights(0.3, 90, false);
    CHECK((w.lo == 0 && w.hi == 0 && w.t == 0.0));
    w = merl::axisWeights(89.9, 90, false);
    CHECK((w.lo == 89 && w.hi == 89));
    w = merl::axisWeights(0.25, 180, true);
    CHECK((w.lo == 179 && w.hi == 0));
    CHECK(w.t == doctest::Approx(0.75));
    w = merl::axisWeights(179.75, 180, true);
    CHECK((w.lo == 179 && w.hi == 0));
    CHECK(w.t == doctest::Approx(0.25));
}

TEST_CASE("merl: half/difference angles as BRDFRead computes them, and their inverse") {
    // Mirror configuration at 30 deg: h = n, theta_d = 30 deg.
    const dvec3 wi = sphericalDirectionDeg(30, 0), wo = sphericalDirectionDeg(30, 180);
    const merl::HalfDiff a = merl::toHalfDiff(wi, wo);
    CHECK(a.thetaH == doctest::Approx(0.0));
    CHECK(a.thetaD == doctest::Approx(deg2rad(30.0)));
    std::mt19937 g(7);
    double worst = 0;
    for (int n = 0; n < 20000; ++n) {
        const dvec3 i = randomUpper(g, 89), o = randomUpper(g, 89);
        double th, ph, td, pd;
        brdfReadHalfDiff(i, o, th, ph, td, pd);
        const merl::HalfDiff m = merl::toHalfDiff(i, o);
        // Same angles; phi_d compared after the fold (toHalfDiff may take d from wo: phi_d + 180 deg).
        const double dp = std::abs(merl::phiDiffCoord(m.phiD) - merl::phiDiffCoord(pd));  // bins, period 180
        worst = std::max({worst, std::abs(m.thetaH - th), std::abs(m.thetaD - td), deg2rad(std::min(dp, 180.0 - dp))});
        dvec3 bi, bo;
        merl::fromHalfDiff(m.thetaH, m.thetaD, m.phiD, bi, bo);
        const merl::HalfDiff back = merl::toHalfDiff(bi, bo);
        CHECK(back.thetaH == doctest::Approx(m.thetaH).epsilon(1e-9));
        CHECK(back.thetaD == doctest::Approx(m.thetaD).epsilon(1e-9));
    }
    // acos near 1 keeps ~1e-8 rad (BRDFRead); atan2 keeps all digits: they agree to acos's precision.
    CHECK(worst < 1e-7);
}

TEST_CASE("merl: tabulate -> encode -> parse round trip returns brdf::evaluate at every bin centre") {
    CHECK(merl::kFileBytes == 12 + 3 * 90 * 90 * 180 * 8);  // 34,992,012
    const merl::MeasuredBrdf& t = ggxTable();
    const std::string bytes = merl::encode(t);
    REQUIRE(bytes.size() == merl::kFileBytes);
    const auto t0 = std::chrono::steady_clock::now();
    const merl::MeasuredBrdf back = merl::parse(bytes, "ggx.binary");
    MESSAGE("parsing a MERL file took " << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
                                        << " s");
    CHECK(back.raw == t.raw);
    CHECK(back.noData == t.noData);
    CHECK(t.noData > 0);  // bins whose centre puts a direction below the horizon
    CHECK(t.noData < merl::kEntries / 2);
    const brdf::Params p = ggxParams();
    std::size_t bins = 0, exact = 0, oneUlp = 0, mismatched = 0;
    double worstNearest = 0, worstLinear = 0;
    for (int ih = 0; ih < merl::kThetaHBins; ++ih)
        for (int id = 0; id < merl::kThetaDBins; id += 3)
            for (int ip = 0; ip < merl::kPhiDBins; ip += 5) {
                dvec3 wi, wo;
                merl::fromHalfDiff(merl::thetaHalfAt(ih + 0.5), merl::thetaDiffAt(id + 0.5), merl::phiDiffAt(ip + 0.5),
                                   wi, wo);
                if (wi.z <= 0 || wo.z <= 0) {
                    mismatched += back.hasData(merl::flatIndex(ih, id, ip));
                    continue;
                }
                ++bins;
                const dvec3 want = brdf::evaluate(p, wi, wo);
                const dvec3 nearest = back.evaluate(wi, wo, merl::Interpolation::Nearest);
                const dvec3 linear = back.evaluate(wi, wo, merl::Interpolation::Multilinear);
                exact += nearest == want;
                bool withinUlp = true;
                for (int c = 0; c < 3; ++c)
                    withinUlp = withinUlp && (nearest[c] == want[c] || nearest[c] == std::nextafter(want[c], 0.0) ||
                                              nearest[c] == std::nextafter(want[c], HUGE_VAL));
                oneUlp += withinUlp;
                for (int c = 0; c < 3; ++c) {
                    worstNearest = std::max(worstNearest, std::abs(nearest[c] - want[c]) / want[c]);
                    worstLinear = std::max(worstLinear, std::abs(linear[c] - want[c]) / want[c]);
                }
            }
    MESSAGE(bins << " bin centres: " << exact << " bit-exact, " << oneUlp
                 << " within one ulp (nearest), worst relative error nearest " << worstNearest << ", multilinear "
                 << worstLinear);
    CHECK(mismatched == 0);
    // rawFor picks the entry whose scaled value is closest; where no double entry x scale rounds to f (the
    // products skip doubles where the entry's ulp is relatively coarser than f's), the last bit differs.
    CHECK(oneUlp == bins);
    CHECK(exact > bins / 2);
    // At a centre the multilinear weights are 1 on the bin up to the centre's rounding (u = i + 0.5 + ~1e-13).
    CHECK(worstLinear < 1e-9);
}

TEST_CASE("merl: off the bin centres, cubic beats multilinear beats nearest against the analytic GGX 0.1") {
    const merl::MeasuredBrdf& t = ggxTable();
    const brdf::Params p = ggxParams();
    const merl::Interpolation modes[3] = {merl::Interpolation::Nearest, merl::Interpolation::Multilinear,
                                          merl::Interpolation::Cubic};
    // Light at theta_i, viewer a few degrees off the mirror direction, in and across the plane of incidence:
    // where the lobe is, and where a MERL table's bins are the finest (theta_h's sqrt mapping).
    double lumErr[3] = {0, 0, 0};
    for (double ti : {0.0, 20.0, 40.0, 60.0, 80.0}) {
        double worst[3] = {0, 0, 0};
        for (double dTheta : {-7.3, -3.1, -1.2, -0.37, 0.0, 0.41, 1.3, 2.9, 6.7})
            for (double dPhi : {0.0, 1.7, 4.1}) {
                const double to = std::clamp(ti + dTheta, 0.2, 85.0);
                const dvec3 wi = sphericalDirectionDeg(ti, 0.0), wo = sphericalDirectionDeg(to, 180.0 + dPhi);
                const double want = brdf::luminance(brdf::evaluate(p, wi, wo));
                for (int k = 0; k < 3; ++k) {
                    const double got = brdf::luminance(t.evaluate(wi, wo, modes[k]));
                    worst[k] = std::max(worst[k], std::abs(got - want) / want);
                }
            }
        MESSAGE("theta_i " << ti << ": worst relative luminance error nearest " << worst[0] << ", multilinear "
                           << worst[1] << ", cubic " << worst[2]);
        for (int k = 0; k < 3; ++k) lumErr[k] = std::max(lumErr[k], worst[k]);
    }
    CHECK(lumErr[1] < lumErr[0]);
    CHECK(lumErr[2] < lumErr[1]);
    // Over the whole upper hemisphere (both directions within 80 deg), relative to the value and to the peak.
    std::mt19937 g(11);
    double rel[3] = {0, 0, 0};
    for (int n = 0; n < 20000; ++n) {
        const dvec3 wi = randomUpper(g, 80), wo = randomUpper(g, 80);
        const double want = brdf::luminance(brdf::evaluate(p, wi, wo));
        for (int k = 0; k < 3; ++k)
            rel[k] = std::max(rel[k], std::abs(brdf::luminance(t.evaluate(wi, wo, modes[k])) - want) / want);
    }
    MESSAGE("random pairs within 80 deg: worst relative luminance error nearest " << rel[0] << ", multilinear "
                                                                                  << rel[1] << ", cubic " << rel[2]);
    CHECK(rel[1] < rel[0]);
}

TEST_CASE("merl: the lookup is reciprocal bit for bit, and 0 below the horizon") {
    const merl::MeasuredBrdf& t = ggxTable();
    std::mt19937 g(3);
    int differ = 0;
    for (int n = 0; n < 20000; ++n) {
        const dvec3 wi = randomUpper(g, 89.9), wo = randomUpper(g, 89.9);
        for (auto how : {merl::Interpolation::Nearest, merl::Interpolation::Multilinear, merl::Interpolation::Cubic})
            differ += t.evaluate(wi, wo, how) != t.evaluate(wo, wi, how);
    }
    CHECK(differ == 0);
    CHECK(t.evaluate({0, 0, 1}, glm::normalize(dvec3(1, 0, -0.01))) == dvec3(0.0));
    CHECK(t.evaluate({0, 0, 1}, {0, 0, 1}) != dvec3(0.0));
    // Coverage: a point whose bins all hold data, and one at grazing theta_d where some hold none.
    CHECK(t.coverage(0.0, deg2rad(10.0), 0.3) == 1.0);
    CHECK(t.coverage(deg2rad(60.0), deg2rad(89.9), 0.0) < 1.0);
}

TEST_CASE("merl: bad files are refused in one line naming the file, the problem and what was expected") {
    const std::string dir = scratch("");
    auto oneLine = [](const std::string& m) { return !m.empty() && m.find('\n') == std::string::npos; };

    const std::string empty = scratch("empty.binary");
    writeBytes(empty, "");
    std::string m = refusal(empty);
    CHECK(oneLine(m));
    CHECK(m.find("--measured: '" + empty + "' is 0 bytes, too short for a MERL header") == 0);

    const std::string dims = scratch("dims.binary");
    writeBytes(dims, header(90, 90, 90) + std::string(100, '\0'));
    m = refusal(dims);
    CHECK(oneLine(m));
    CHECK(m.find("has dimensions 90 x 90 x 90; a MERL file has 90 x 90 x 180") != std::string::npos);
    writeBytes(dims, header(180, 90, 90));  // BRDFRead's product check passes this; the order matters
    CHECK(refusal(dims).find("has dimensions 180 x 90 x 90") != std::string::npos);

    const std::string truncated = scratch("truncated.binary");
    writeBytes(truncated, header(90, 90, 180) + std::string(8000, '\0'));
    m = refusal(truncated);
    CHECK(oneLine(m));
    CHECK(m.find("'" + truncated +
                 "' is 8012 bytes, expected 34992012 (a 12-byte header and 3 x 1458000 doubles): "
                 "truncated") != std::string::npos);

    const std::string folder = scratch("folder.binary");
    std::filesystem::create_directories(folder);
    m = refusal(folder);
    CHECK(oneLine(m));
    CHECK(m.find("is a directory, not a regular file") != std::string::npos);
    CHECK(refusal(scratch("missing.binary")).find("cannot read") != std::string::npos);

    // Full-size files: a NaN and an infinity among valid entries, every entry negative, trailing bytes.
    merl::MeasuredBrdf constant;  // not the GGX table: this case needs valid bytes, not a model (no tabulation)
    constant.raw.assign(3 * merl::kEntries, 1500.0);
    const std::string good = merl::encode(constant);
    const std::size_t at = merl::kHeaderBytes + 8 * (merl::kEntries + merl::flatIndex(3, 4, 5));  // green plane
    const std::string nan = scratch("nan.binary");
    const double q = std::numeric_limits<double>::quiet_NaN();
    std::string bad = good;
    std::memcpy(&bad[at], &q, 8);
    writeBytes(nan, bad);
    m = refusal(nan);
    CHECK(oneLine(m));
    CHECK(m.find("'" + nan + "' has a NaN entry in the green plane (theta_h bin 3, theta_d bin 4, phi_d bin 5)") !=
          std::string::npos);
    const double inf = -std::numeric_limits<double>::infinity();
    std::memcpy(&bad[at], &inf, 8);
    writeBytes(nan, bad);
    CHECK(refusal(nan).find("has an infinite entry in the green plane") != std::string::npos);

    std::string negative = header(90, 90, 180);
    for (std::size_t i = 0; i < 3 * merl::kEntries; ++i)
        negative.append(reinterpret_cast<const char*>(&merl::kNoData), 8);
    const std::string none = scratch("none.binary");
    writeBytes(none, negative);
    m = refusal(none);
    CHECK(oneLine(m));
    CHECK(m.find("has no data: every one of its 1458000 bins is negative") != std::string::npos);

    const std::string trailing = scratch("trailing.binary");
    writeBytes(trailing, good + "x");
    CHECK(refusal(trailing).find("is 34992013 bytes, expected 34992012") != std::string::npos);
    CHECK(refusal(trailing).find("trailing bytes") != std::string::npos);

    // The good file reads back as written.
    const std::string ok = scratch("ok.binary");
    writeBytes(ok, good);
    const merl::MeasuredBrdf back = merl::read(ok);
    CHECK(back.raw == constant.raw);
    CHECK(back.noData == 0);
    const dvec3 f = back.evaluate({0, 0, 1}, sphericalDirectionDeg(40, 120));  // 1500 x the channel scales
    CHECK(f.x == doctest::Approx(1.0));
    CHECK(f.y == doctest::Approx(1.15));
    CHECK(f.z == doctest::Approx(1.66));
    std::filesystem::remove_all(dir);
}

TEST_CASE("merl: tabulate refuses what a MERL table cannot hold") {
    brdf::Params p = ggxParams();
    p.roughnessY = 0.2;
    CHECK_THROWS_AS(merl::tabulate(p), std::invalid_argument);
}

TEST_CASE("merl: load reads a file once while it is unchanged, and brdf::evaluate looks the table up") {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("hilite-merl-load-" + std::to_string(getpid()) + ".binary"))
            .string();
    merl::MeasuredBrdf constant;
    constant.raw.assign(3 * merl::kEntries, 1500.0);
    { std::ofstream(path, std::ios::binary) << merl::encode(constant); }
    const auto a = merl::load(path, "--measured"), b = merl::load(path, "--measured");
    CHECK(a.get() == b.get());  // cached: the same table
    constant.raw.assign(3 * merl::kEntries, 3000.0);
    { std::ofstream(path, std::ios::binary) << merl::encode(constant); }
    std::filesystem::last_write_time(path, std::filesystem::last_write_time(path) + std::chrono::seconds(2));
    const auto c = merl::load(path, "--measured");
    CHECK(c.get() != a.get());  // the file changed: read again
    CHECK(c->raw.front() == 3000.0);
    hilite::brdf::Params p;
    p.model = hilite::brdf::Model::None;
    p.measured = c;
    const hilite::dvec3 wi = hilite::sphericalDirectionDeg(30, 0), wo = hilite::sphericalDirectionDeg(35, 180);
    const hilite::dvec3 f = hilite::brdf::evaluate(p, wi, wo);
    for (int ch = 0; ch < 3; ++ch) CHECK(f[ch] == doctest::Approx(2.0 * merl::kScale[ch] * 1500.0).epsilon(1e-12));
    CHECK(hilite::brdf::evaluate(p, wi, hilite::dvec3(0, 0.6, -0.8)) == hilite::dvec3(0.0));
    std::filesystem::remove(path);
}

TEST_CASE("merl: tables are held once and released: load keeps the 2 most recent, halves only the current one's") {
    std::vector<std::string> paths;
    for (int i = 0; i < 4; ++i) {
        paths.push_back((std::filesystem::temp_directory_path() /
                         ("hilite-merl-lru-" + std::to_string(getpid()) + "-" + std::to_string(i) + ".binary"))
                            .string());
        merl::MeasuredBrdf constant;
        constant.raw.assign(3 * merl::kEntries, 100.0 * (i + 1));
        std::ofstream(paths.back(), std::ios::binary) << merl::encode(constant);
    }
    std::weak_ptr<const merl::MeasuredBrdf> first, firstHalf;
    {
        const auto a = merl::load(paths[0], "--measured");
        first = a;
        firstHalf = merl::halfResolution(a, 0, 0);
        CHECK(merl::halfResolution(a, 0, 0) == firstHalf.lock());  // asked again for the same table: the same half
    }
    const auto b = merl::load(paths[1], "--measured");
    CHECK(!first.expired());  // one of the 2 most recent: a sweep coming back to it does not read it again
    CHECK(merl::load(paths[0], "--measured") == first.lock());
    CHECK(!merl::halfResolution(b, 0, 0)->raw.empty());
    CHECK(firstHalf.expired());  // another table's halves asked for: the first's are freed
    merl::load(paths[2], "--measured");
    merl::load(paths[3], "--measured");
    CHECK(first.expired());                                           // read 3 tables since and held by nobody: freed
    CHECK(merl::load(paths[0], "--measured")->raw.front() == 100.0);  // and read again when asked for
    for (const auto& p : paths) std::filesystem::remove(p);
}

TEST_CASE("merl: the albedo of a table: pi f for a constant one, the analytic GGX's within its resolution") {
    // A constant f = c above the horizon reflects pi c at every incidence (the Lambertian closed form).
    merl::MeasuredBrdf constant;
    constant.raw.assign(3 * merl::kEntries, 1500.0);
    brdf::Params p;
    p.model = brdf::Model::None;
    p.measured = std::make_shared<const merl::MeasuredBrdf>(constant);
    for (double theta : {0.0, 45.0, 80.0}) {
        CAPTURE(theta);
        const dvec3 a = brdf::albedo(p, theta, 0.0);
        for (int ch = 0; ch < 3; ++ch) CHECK(a[ch] == doctest::Approx(kPi * merl::kScale[ch] * 1500.0).epsilon(1e-9));
    }
    // GGX 0.1 through its table against the model's own albedo: the table's resolution, not the quadrature's
    // (measured 0.15% at 0 deg, 0.34% at 60, 0.76% at 80).
    p.measured = std::make_shared<const merl::MeasuredBrdf>(ggxTable());
    for (double theta : {0.0, 60.0, 80.0}) {
        CAPTURE(theta);
        const double table = brdf::albedo(p, theta, 0.0).x, model = brdf::albedo(ggxParams(), theta, 0.0).x;
        MESSAGE("albedo at " << theta << " deg: table " << table << ", GGX " << model);
        CHECK(table == doctest::Approx(model).epsilon(0.01));
    }
}

TEST_CASE("merl: HalvesLuminance gives the luminance of the table's and its six halves' lookups") {
    // The seven luminances side by side against each table's own lookup, at directions over the whole hemisphere
    // and near the horizon, where GGX's table has bins without data (the multilinear fallback runs there). The
    // table is grey (Schlick's F0 the same in every channel): no channel's cubic sum is negative where the
    // luminance's is not, so the two differ by the floats' rounding of the bins alone.
    auto table = std::make_shared<const merl::MeasuredBrdf>(ggxTable());
    REQUIRE(table->noData > 0);
    std::vector<std::shared_ptr<const merl::MeasuredBrdf>> tables{table};
    for (int axis = 0; axis < 3; ++axis)
        for (int parity = 0; parity < 2; ++parity) tables.push_back(merl::halfResolution(table, axis, parity));
    const auto stack = merl::halvesLuminance(table);
    CHECK(merl::halvesLuminance(table) == stack);  // made once per table
    auto dir = [](double thetaDeg, double phiDeg) {
        const double t = deg2rad(thetaDeg), p = deg2rad(phiDeg);
        return dvec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
    };
    int compared = 0, differ = 0;
    double worst = 0;
    for (double ti : {0.0, 7.0, 33.0, 61.0, 84.0, 89.5})
        for (double to = 0.0; to < 90.0; to += 2.9)
            for (double po = 0.0; po < 360.0; po += 23.7) {
                const dvec3 wi = dir(ti, 0.0), wo = dir(to, po);
                double all[merl::HalvesLuminance::kTables];
                stack->evaluate(wi, wo, all);
                for (size_t k = 0; k < tables.size(); ++k) {
                    const double f = brdf::luminance(tables[k]->evaluate(wi, wo));
                    worst = std::max(worst, std::abs(all[k] - f) / std::max(f, 1e-300));
                    CHECK(all[k] == doctest::Approx(f).epsilon(3e-7));
                    differ += k > 0 && f != brdf::luminance(tables[0]->evaluate(wi, wo));
                    compared += k > 0;
                }
            }
    MESSAGE("HalvesLuminance against the tables' lookups: at most " << worst << " relative");
    CHECK(differ > compared / 2);  // the halves do differ from the table: the comparison has teeth
    double below[merl::HalvesLuminance::kTables];
    stack->evaluate(dir(30, 0), dvec3(0, 0, -1), below);
    for (const double f : below) CHECK(f == 0.0);
}
