// The term rows: every term of shaders/brdf.glsl where its formula breaks (0/0, inf * 0, underflow,
// arguments just outside their range), against its C++ twin. `expected` is the exact answer where known.
// Add a row: name, blocks, GLSL setting r from a[], arguments, the twin, and optionally the answer.

#include "hard/hard_cases.hpp"

#include "hilite/brdf/terms.hpp"

#include <cmath>

namespace hilite::hard {

namespace {

using glm::dvec4;
using Args = std::vector<double>;

dvec4 one(double x) { return {x, 0.0, 0.0, 0.0}; }

TermCase scalar(std::string name, std::string block, std::string call, Args args,
                std::function<double(const Args&)> twin, std::optional<double> expected) {
    TermCase c;
    c.name = std::move(name);
    c.blocks = {std::move(block)};
    c.glsl = "r.x = " + std::move(call) + ";";
    c.args = std::move(args);
    c.twin = [twin](const Args& a) { return one(twin(a)); };
    if (expected) c.expected = one(*expected);
    return c;
}

TermCase phong(std::string name, double oneMinusCos, double n, std::optional<double> expected) {
    return scalar(
        std::move(name), "Phong_Normalized", "Phong_Normalized(a[0], a[1])", {oneMinusCos, n},
        [](const Args& a) { return brdf::Phong_Normalized(a[0], a[1]); }, expected);
}

TermCase ggx(std::string name, double NoH, double sin2h, double alpha, std::optional<double> expected) {
    return scalar(
        std::move(name), "D_GGX", "D_GGX(a[0], a[1], a[2])", {NoH, sin2h, alpha},
        [](const Args& a) { return brdf::D_GGX(a[0], a[1], a[2]); }, expected);
}

TermCase beckmann(std::string name, double NoH, double sin2h, double m, std::optional<double> expected) {
    return scalar(
        std::move(name), "D_Beckmann", "D_Beckmann(a[0], a[1], a[2])", {NoH, sin2h, m},
        [](const Args& a) { return brdf::D_Beckmann(a[0], a[1], a[2]); }, expected);
}

TermCase aniso(std::string name, const std::string& term, Args args, std::optional<double> expected) {
    const bool isGgx = term == "D_GGXAniso";
    return scalar(
        std::move(name), term, term + "(a[0], a[1], a[2], a[3], a[4])", std::move(args),
        [isGgx](const Args& a) {
            return isGgx ? brdf::D_GGXAniso(a[0], a[1], a[2], a[3], a[4])
                         : brdf::D_BeckmannAniso(a[0], a[1], a[2], a[3], a[4]);
        },
        expected);
}

/// G2 of two Lambdas of the same model: cos_i, cos_o, roughness.
TermCase smith(std::string name, const std::string& g2, const std::string& lambda, Args args,
               std::optional<double> expected) {
    TermCase c = scalar(
        std::move(name), g2, g2 + "(" + lambda + "(a[0], a[2]), " + lambda + "(a[1], a[2]))", std::move(args),
        [g2, lambda](const Args& a) {
            auto L = [&](double cosTheta) {
                return lambda == "Lambda_GGX" ? brdf::Lambda_GGX(cosTheta, a[2])
                                              : brdf::Lambda_Beckmann(cosTheta, a[2]);
            };
            return g2 == "G2_SmithCorrelated" ? brdf::G2_SmithCorrelated(L(a[0]), L(a[1]))
                                              : brdf::G2_SmithSeparable(L(a[0]), L(a[1]));
        },
        expected);
    c.blocks.push_back(lambda);
    return c;
}

TermCase schlick(std::string name, double f0, double cosTheta, double expected) {
    return scalar(
        std::move(name), "F_Schlick", "F_Schlick(vec3(a[0]), a[1]).x", {f0, cosTheta},
        [](const Args& a) { return brdf::F_Schlick(dvec3(a[0]), a[1]).x; }, expected);
}

/// (Rs, Rp, F) of the exact dielectric (k < 0) or conductor Fresnel.
TermCase exact(std::string name, double cosTheta, double eta, double k, std::optional<dvec4> expected) {
    TermCase c;
    c.name = std::move(name);
    const bool conductor = k >= 0;
    c.blocks = {conductor ? "F_Conductor" : "F_Dielectric"};
    c.glsl = conductor ? "r.xy = F_ConductorSP(a[0], a[1], a[2]); r.z = F_Conductor(a[0], a[1], a[2]);"
                       : "r.xy = F_DielectricSP(a[0], a[1]); r.z = F_Dielectric(a[0], a[1]);";
    c.args = {cosTheta, eta, std::max(k, 0.0)};
    c.twin = [conductor](const Args& a) {
        const dvec2 sp = conductor ? brdf::F_ConductorSP(a[0], a[1], a[2]) : brdf::F_DielectricSP(a[0], a[1]);
        return dvec4(sp, conductor ? brdf::F_Conductor(a[0], a[1], a[2]) : brdf::F_Dielectric(a[0], a[1]), 0.0);
    };
    c.components = 3;
    c.expected = expected;
    return c;
}

/// (valid, NoH, sin2h, VoH) of halfVector(wi, wo).
TermCase half(std::string name, dvec3 wi, dvec3 wo, dvec4 expected) {
    TermCase c;
    c.name = std::move(name);
    c.blocks = {"HalfVector"};
    c.glsl =
        "HalfVector hv = halfVector(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]));\n"
        "    r = vec4(hv.valid ? 1.0 : 0.0, hv.NoH, hv.sin2h, hv.VoH);";
    c.args = {wi.x, wi.y, wi.z, wo.x, wo.y, wo.z};
    c.twin = [](const Args& a) {
        const brdf::HalfVector hv = brdf::halfVector({a[0], a[1], a[2]}, {a[3], a[4], a[5]});
        return dvec4(hv.valid ? 1.0 : 0.0, hv.NoH, hv.sin2h, hv.VoH);
    };
    c.components = 4;
    c.expected = expected;
    c.tolerance = 1e-6;
    return c;
}

std::vector<TermCase> build() {
    const double pi = kPi, critical = std::sqrt(1.0 - 0.49);  // cos of eta = 0.7's critical angle
    const double glass = 0.04;                                // ((1.5 - 1) / (1.5 + 1))^2
    std::vector<TermCase> t = {
        // cos^n lobes: exp(n log(1 - x)) from a stable 1 - cos, exponents 0 to 1e8.
        phong("Phong_Normalized n 0 at 1-cos 0.5", 0.5, 0.0, 1.0 / pi),
        phong("Phong_Normalized n 0 past 90 deg from the mirror (cos^0 = 1)", 1.5, 0.0, 1.0 / pi),
        phong("Phong_Normalized n 1 at the mirror direction", 0.0, 1.0, 1.5 / pi),
        phong("Phong_Normalized n 1e4 at 1-cos 1e-5", 1e-5, 1e4,
              10002.0 / (2 * pi) * std::exp(1e4 * std::log1p(-1e-5))),
        phong("Phong_Normalized n 1e6 at 1-cos 1e-7", 1e-7, 1e6, std::nullopt),
        phong("Phong_Normalized n 1e8 at 1-cos 1e-9 (cos is 1 in float)", 1e-9, 1e8, std::nullopt),
        phong("Phong_Normalized n 1e8 at 1-cos 0.5 (exp underflows)", 0.5, 1e8, 0.0),
        scalar(
            "D_BlinnPhong n 1e8 at h = n", "D_BlinnPhong", "D_BlinnPhong(a[0], a[1])", {0.0, 1e8},
            [](const Args& a) { return brdf::D_BlinnPhong(a[0], a[1]); }, (1e8 + 2) / (2 * pi)),
        scalar(
            "D_BlinnPhong n 1e8 with h on the horizon", "D_BlinnPhong", "D_BlinnPhong(a[0], a[1])", {1.0, 1e8},
            [](const Args& a) { return brdf::D_BlinnPhong(a[0], a[1]); }, 0.0),
        // NDFs at roughness 0 (a delta), 1e-7, 10, and h at the horizon.
        ggx("D_GGX alpha 0 at h = n (0/0 unguarded)", 1.0, 0.0, 0.0, 0.0),
        ggx("D_GGX alpha 0 off the peak", 0.8, 0.36, 0.0, 0.0),
        ggx("D_GGX alpha 1e-7 at h = n", 1.0, 0.0, 1e-7, 1.0 / (pi * 1e-14)),
        ggx("D_GGX alpha 1e-7 at theta_h 1e-7", 1.0, 1e-14, 1e-7, std::nullopt),
        ggx("D_GGX alpha 10 at h = n", 1.0, 0.0, 10.0, 1.0 / (100 * pi)),
        ggx("D_GGX alpha 10 with h 1e-7 above the horizon", 1e-7, 1.0, 10.0, std::nullopt),
        beckmann("D_Beckmann m 0 at h = n (0/0 unguarded)", 1.0, 0.0, 0.0, 0.0),
        beckmann("D_Beckmann m 1e-7 at h = n", 1.0, 0.0, 1e-7, 1.0 / (pi * 1e-14)),
        beckmann("D_Beckmann m 10 with h 1e-10 above the horizon (NoH^4 underflows: 0/0 unguarded)", 1e-10, 1.0, 10.0,
                 0.0),
        beckmann("D_Beckmann m 1e-4 at theta_h 1e-3 (exp(-100) is subnormal in float)", std::cos(1e-3),
                 std::pow(std::sin(1e-3), 2), 1e-4, std::nullopt),
        scalar(
            "D_Gaussian m 0 at h = n (0/0 unguarded)", "D_Gaussian", "D_Gaussian(a[0], a[1], a[2], a[3])",
            {1.0, 0.0, 0.0, brdf::gaussianNormalization(0.0)},
            [](const Args& a) { return brdf::D_Gaussian(a[0], a[1], a[2], a[3]); }, 0.0),
        scalar(
            "D_Gaussian m 1e-7 at h = n", "D_Gaussian", "D_Gaussian(a[0], a[1], a[2], a[3])",
            {1.0, 0.0, 1e-7, brdf::gaussianNormalization(1e-7)},
            [](const Args& a) { return brdf::D_Gaussian(a[0], a[1], a[2], a[3]); }, std::nullopt),
        aniso("D_GGXAniso alpha_x 0 (smooth along x: HoX / 0 unguarded)", "D_GGXAniso", {0, 0, 1, 0, 0.1}, 0.0),
        aniso("D_GGXAniso alpha_x / alpha_y 1e-4 at h = n", "D_GGXAniso", {0, 0, 1, 1e-5, 0.1}, 1 / (pi * 1e-6)),
        aniso("D_GGXAniso alpha_x / alpha_y 1e-4 at h 1e-5 off n along x", "D_GGXAniso",
              {1e-5, 0, std::sqrt(1 - 1e-10), 1e-5, 0.1}, std::nullopt),
        aniso("D_BeckmannAniso alpha_x 0", "D_BeckmannAniso", {0, 0, 1, 0, 1}, 0.0),
        aniso("D_BeckmannAniso alpha_x / alpha_y 1e-4 at h = n", "D_BeckmannAniso", {0, 0, 1, 1e-4, 1},
              1 / (pi * 1e-4)),
        // Masking-shadowing at the horizon (Lambda = inf, G = 0) and for a smooth surface.
        smith("G2_SmithCorrelated GGX with wo on the horizon", "G2_SmithCorrelated", "Lambda_GGX", {0.7, 0.0, 0.3},
              0.0),
        smith("G2_SmithCorrelated GGX with wo 1e-7 above the horizon", "G2_SmithCorrelated", "Lambda_GGX",
              {0.7, 1e-7, 0.3}, std::nullopt),
        smith("G2_SmithCorrelated GGX alpha 0 on the horizon (0 * inf unguarded)", "G2_SmithCorrelated", "Lambda_GGX",
              {0.7, 0.0, 0.0}, 1.0),
        smith("G2_SmithSeparable Beckmann with wo on the horizon", "G2_SmithSeparable", "Lambda_Beckmann",
              {0.7, 0.0, 0.3}, 0.0),
        smith("G2_SmithCorrelated Beckmann m 0 on the horizon (0/0 unguarded)", "G2_SmithCorrelated", "Lambda_Beckmann",
              {0.7, 0.0, 0.0}, 1.0),
        scalar(
            "Lambda_GGXAniso of a smooth surface 1e-25 above the horizon (z^2 underflows: 0/0 unguarded)",
            "Lambda_GGXAniso", "Lambda_GGXAniso(vec3(a[0], a[1], a[2]), a[3], a[4])", {1.0, 0.0, 1e-25, 0.0, 0.0},
            [](const Args& a) {
                return brdf::Lambda_GGXAniso({a[0], a[1], a[2]}, a[3], a[4]);
            },
            0.0),
        scalar(
            "G_CookTorrance with wi = -wo (VoH = 0)", "G_CookTorrance", "G_CookTorrance(a[0], a[1], a[2], a[3])",
            {0.0, 0.5, 0.5, 0.0}, [](const Args& a) { return brdf::G_CookTorrance(a[0], a[1], a[2], a[3]); }, 0.0),
        scalar(
            "G_CookTorrance with wo on the horizon", "G_CookTorrance", "G_CookTorrance(a[0], a[1], a[2], a[3])",
            {1.0, 0.0, 0.5, 0.7}, [](const Args& a) { return brdf::G_CookTorrance(a[0], a[1], a[2], a[3]); }, 0.0),
        // The half vector: none for wi = -wo; exact for a mirror pair at grazing.
        half("halfVector of wi = -wo (none)", {0.6, 0.0, 0.8}, {-0.6, 0.0, -0.8}, dvec4(0.0)),
        half("halfVector of a mirror pair 1e-8 above the horizon (h = n)", {std::sqrt(1 - 1e-16), 0.0, 1e-8},
             {-std::sqrt(1 - 1e-16), 0.0, 1e-8}, {1.0, 1.0, 0.0, 1e-8}),
        // Fresnel at cos 0, 1 and just outside [0, 1]; eta = 1; k = 0; total internal reflection; F0 0 and 1.
        schlick("F_Schlick F0 0 at cos 0", 0.0, 0.0, 1.0),
        schlick("F_Schlick F0 0 at cos 1", 0.0, 1.0, 0.0),
        schlick("F_Schlick F0 0 at cos 1 + 1e-7", 0.0, 1.0 + 1e-7, 0.0),
        schlick("F_Schlick F0 0 at cos -1e-7", 0.0, -1e-7, 1.0),
        schlick("F_Schlick F0 1 at cos 0.3", 1.0, 0.3, 1.0),
        exact("F_Dielectric eta 1.5 at cos 0", 0.0, 1.5, -1, dvec4(1, 1, 1, 0)),
        exact("F_Dielectric eta 1.5 at cos 1", 1.0, 1.5, -1, dvec4(glass, glass, glass, 0)),
        exact("F_Dielectric eta 1.5 at cos 1 + 1e-7", 1.0 + 1e-7, 1.5, -1, dvec4(glass, glass, glass, 0)),
        exact("F_Dielectric eta 1.5 at cos -1e-7", -1e-7, 1.5, -1, dvec4(1, 1, 1, 0)),
        exact("F_Dielectric eta 1 at cos 0 (no interface: the TIR test said 1 unguarded)", 0.0, 1.0, -1, dvec4(0.0)),
        exact("F_Dielectric eta 1 at cos 0.5", 0.5, 1.0, -1, dvec4(0.0)),
        exact("F_Dielectric eta 0.7 beyond the critical angle (total internal reflection)", 0.2, 0.7, -1,
              dvec4(1, 1, 1, 0)),
        [&] {
            // F has an infinite slope here: float rounding of 1 - cos^2 (6e-8) moves cos(theta_t) by
            // sqrt(6e-8) and F by ~1e-3 (see F_Dielectric in shaders/brdf.glsl).
            TermCase c = exact("F_Dielectric eta 0.7 at the critical angle", critical, 0.7, -1, std::nullopt);
            c.tolerance = 2e-3;
            return c;
        }(),
        exact("F_Conductor eta 1 k 0 at cos 0 (no interface: 0/0 unguarded)", 0.0, 1.0, 0.0, dvec4(0.0)),
        [&] {
            // A near-matched interface: F = 2.6e-9, below float's rounding of the terms; the stable forms keep
            // 4 digits (the textbook differences gave 0).
            TermCase c = exact("F_Conductor k 0 eta 1.0001 at cos 0.9 (F = 2.6e-9)", 0.9, 1.0001, 0.0, std::nullopt);
            c.tolerance = 1e-3;
            return c;
        }(),
        exact("F_Conductor k 0 eta 1.5 at cos 1 (a dielectric)", 1.0, 1.5, 0.0, dvec4(glass, glass, glass, 0)),
        exact("F_Conductor k 0 eta 0.7 beyond the critical angle", 0.2, 0.7, 0.0, dvec4(1, 1, 1, 0)),
        exact("F_Conductor silver at cos 1 + 1e-7", 1.0 + 1e-7, 0.14, 4.15, std::nullopt),
        exact("F_Conductor silver at cos -1e-7", -1e-7, 0.14, 4.15, dvec4(1, 1, 1, 0)),
        // A diffuse term whose formula divides by max(cos_i, cos_o).
        scalar(
            "Fd_OrenNayar with both directions on the horizon (0/0 unguarded)", "Fd_OrenNayar",
            "Fd_OrenNayar(vec3(1.0), a[0], a[1], a[2], a[3]).x", {0.5, 0.0, 0.0, -1.0},
            [](const Args& a) { return brdf::Fd_OrenNayar(dvec3(1.0), a[0], a[1], a[2], a[3]).x; },
            (1.0 - 0.5 * 0.25 / (0.25 + 0.33)) / pi),
    };
    return t;
}

}  // namespace

const std::vector<TermCase>& termCases() {
    static const std::vector<TermCase> cases = build();
    return cases;
}

}  // namespace hilite::hard
