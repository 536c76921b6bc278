// `hilite brdf`: the physics of the reflectance terms as numbers, computed in double on the CPU with the
// full spectral tables (1 nm): directional-hemispherical reflectance vs theta (albedo), Fresnel vs theta,
// the NDF's normalization, the Fresnel colour strip of a material (PNG), and a model tabulated as a MERL
// .binary file (brdf/merl.hpp). A table by default; with --json one JSON object per line.

#include "brdf/bihemispherical.hpp"
#include "brdf/integrate.hpp"
#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/spectral.hpp"
#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "core/text.hpp"
#include "experiments/strip.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "io/image_io.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

namespace hilite::cli {

namespace {

struct BrdfFlags {
    SceneOptions scene;
    bool json = false;
    bool spectral = false;                              ///< fresnel, strip: --spectral
    std::string roughness = "0.02,0.05,0.1,0.2,0.5,1";  ///< normalization: the sweep
    std::string exponent = "1,10,100,1000,10000";
    std::string png;  ///< strip (PNG), tabulate (MERL .binary): -o
};

/// "0.1", "0.1,0.2" or START:STOP:STEP (inclusive), each value finite in [lo, hi].
std::vector<double> parseList(const std::string& flag, const std::string& text, double lo, double hi) {
    auto number = [&](const std::string& t) {
        const auto v = parseNumber(t);
        if (!v) throw InputError(flag + ": '" + t + "' is not a number");
        return *v;
    };
    auto checkRange = [&](const std::string&, double v, double a, double b) {
        if (!std::isfinite(v) || v < a || v > b)
            throw InputError(flag + ": must be a finite number in [" + fmt(a) + ", " + fmt(b) + "] (got " + fmt(v) +
                             ")");
        return v;
    };
    std::vector<std::string> parts;
    std::stringstream in(text);
    const char sep = text.find(':') != std::string::npos ? ':' : ',';
    for (std::string p; std::getline(in, p, sep);) parts.push_back(p);
    if (!text.empty() && text.back() == sep) parts.push_back("");
    std::vector<double> out;
    if (sep == ':') {
        if (parts.size() != 3) throw InputError(flag + ": a range is START:STOP:STEP (got '" + text + "')");
        const double a = checkRange(flag, number(parts[0]), lo, hi), b = checkRange(flag, number(parts[1]), lo, hi);
        const double step = number(parts[2]);
        if (!(step > 0) || b < a || (b - a) / step > 1e5)
            throw InputError(flag + ": range needs START <= STOP, STEP > 0 and at most 1e5 values (got '" + text +
                             "')");
        const long n = std::lround(std::floor((b - a) / step + 1e-9));
        for (long i = 0; i <= n; ++i) out.push_back(a + double(i) * step);
    } else {
        for (const auto& p : parts) out.push_back(checkRange(flag, number(p), lo, hi));
    }
    if (out.empty()) throw InputError(flag + ": no value given");
    return out;
}

std::string rowFormat(double v) {
    // Never a printed nan/inf: the parameters took a term out of double range.
    if (!std::isfinite(v))
        throw InputError("brdf: the parameters give a non-finite value (" + std::string(std::isnan(v) ? "NaN" : "Inf") +
                         "): a term is out of double range; no number printed for it");
    std::ostringstream s;
    s << std::setw(12) << std::setprecision(7) << v;
    return s.str();
}

void printRgbRows(const BrdfFlags& f, const std::vector<double>& thetas, const char* key,
                  const std::function<dvec3(double)>& value) {
    for (double t : thetas) {
        const dvec3 v = value(t);
        if (f.json) {
            std::cout << nlohmann::ordered_json{{"theta_deg", t}, {key, {v.x, v.y, v.z}}}.dump() << "\n";
        } else {
            std::cout << rowFormat(t) << rowFormat(v.x) << rowFormat(v.y) << rowFormat(v.z) << "\n";
        }
    }
}

/// What a Fresnel term is, for the table's header and the strip's log line.
std::string describeFresnel(const brdf::Params& p) {
    std::ostringstream s;
    auto rgb = [&](const char* name, const dvec3& v) { s << " " << name << "=" << v.x << "," << v.y << "," << v.z; };
    s << "fresnel=" << p.fresnel;
    if (p.fresnel == brdf::Fresnel::Schlick) rgb("f0", p.f0);
    if (p.fresnel == brdf::Fresnel::Dielectric || p.fresnel == brdf::Fresnel::Conductor) rgb("eta", p.eta);
    if (p.fresnel == brdf::Fresnel::Conductor) rgb("k", p.k);
    if (p.fresnel == brdf::Fresnel::Spectral)
        s << " material=" << p.spectrum->name << " wavelengths=" << p.spectrum->size() << " ("
          << p.spectrum->lambdaNm.front() << ".." << p.spectrum->lambdaNm.back()
          << " nm, CIE 1931 2-degree, D65, linear sRGB)";
    return s.str();
}

/// The Fresnel of the flags: --spectral sets the mode; the mode must be one (not none).
scene::Resolved resolveBrdf(const BrdfFlags& f) { return scene::resolve(commandValues(f.scene), scene::Purpose::Brdf); }

brdf::Params fresnelParams(const BrdfFlags& f) { return scene::resolveFresnel(commandValues(f.scene), f.spectral); }

int runAlbedo(const BrdfFlags& f) {
    const scene::Resolved r = resolveBrdf(f);
    const brdf::Params& p = r.scene.brdf;
    const auto& thetas = r.angles;
    const double phi = r.scene.light.azimuthDeg;
    if (!f.json)
        std::cout << "# " << p << " azimuth=" << phi << "\n#    theta_deg    albedo_r    albedo_g    albedo_b\n";
    // The cosine-weighted average over every incidence (and azimuth): one number per channel, on every JSON
    // row (so each line stays one self-contained object) and as the table's last line.
    const dvec3 hh = brdf::bihemisphericalAlbedo(p);
    if (f.json) {
        for (double t : thetas) {
            const dvec3 v = brdf::albedo(p, t, phi);
            std::cout << nlohmann::ordered_json{{"theta_deg", t},
                                                {"albedo", {v.x, v.y, v.z}},
                                                {"bihemispherical_albedo", {hh.x, hh.y, hh.z}}}
                             .dump()
                      << "\n";
        }
        return 0;
    }
    printRgbRows(f, thetas, "albedo", [&](double t) { return brdf::albedo(p, t, phi); });
    std::cout << "# bihemispherical albedo (1/pi) int rho(wi) cos(theta_i) dwi:" << rowFormat(hh.x) << rowFormat(hh.y)
              << rowFormat(hh.z) << "\n";
    return 0;
}

int runFresnel(const BrdfFlags& f) {
    const brdf::Params p = fresnelParams(f);
    const auto thetas = resolveBrdf(f).angles;
    if (!f.json) std::cout << "# " << describeFresnel(p) << "\n#    theta_deg           r           g           b\n";
    double most = 0;
    printRgbRows(f, thetas, "rgb", [&](double t) {
        double c, s;
        cosSinDeg(t, c, s);
        const dvec3 F = brdf::fresnel(p, c);
        most = std::max({most, F.x, F.y, F.z});
        return F;
    });
    // A reflectance above 1 reads as a bug: it is the colour, not the energy (gold at 0 deg: r 1.022).
    if (!f.json && most > 1.0 + 1e-12)
        std::cout
            << "# a component above 1: the measured spectrum's colour lies outside the sRGB gamut, so a linear sRGB\n"
               "# component exceeds 1 while every wavelength's reflectance, and the luminance Y, stay at most 1\n";
    return 0;
}

int runNormalization(const BrdfFlags& f) {
    const scene::Values given = commandValues(f.scene);
    const std::string modelName = given.text("model");
    auto model = brdf::parseModel(modelName);
    if (!model || !brdf::isMicrofacet(*model))
        throw InputError(given.where("model") +
                         ": normalization needs an NDF: blinn, gaussian, beckmann, ggx, "
                         "tabulated (got '" +
                         modelName + "')");
    if (*model == brdf::Model::Tabulated) {  // the table, normalized when read, and the factor applied
        const brdf::Params p = resolveBrdf(f).scene.brdf;
        const double integral = brdf::ndfIntegral(p);
        nlohmann::ordered_json j{
            {"ndf_table", p.ndfTable->file}, {"normalization", p.ndfTable->normalization}, {"integral", integral}};
        if (f.json) std::cout << j.dump() << "\n";
        else
            std::cout << "# int D(h) (n.h) dw_h, model=tabulated " << p.ndfTable->file << ": the file's D x "
                      << std::setprecision(10) << p.ndfTable->normalization << "\n"
                      << std::setw(12) << integral << "\n";
        return 0;
    }
    const bool exponent = brdf::usesExponent(*model);
    const auto values = exponent
                            ? parseList("--exponent", f.exponent, brdf::kMinExponent, brdf::kMaxExponent)
                            : parseList("--roughness", f.roughness, brdf::kMinIntegrableRoughness, brdf::kMaxRoughness);
    if (!f.json)
        std::cout << "# int D(h) (n.h) dw_h, model=" << modelName << "\n#    roughness    exponent    integral\n";
    for (double v : values) {
        scene::Values s = given;
        s.set(exponent ? "exponent" : "roughness", exactText(v), exponent ? "--exponent" : "--roughness");
        const brdf::Params p = scene::resolve(s, scene::Purpose::Brdf).scene.brdf;
        const double integral = brdf::ndfIntegral(p);
        nlohmann::ordered_json j{{"roughness", nullptr}, {"exponent", nullptr}, {"integral", integral}};
        j[exponent ? "exponent" : "roughness"] = v;
        if (f.json) std::cout << j.dump() << "\n";
        else
            std::cout << (exponent ? std::string(12, ' ') + rowFormat(v) : rowFormat(v) + std::string(12, ' '))
                      << std::setw(12) << std::setprecision(10) << integral << "\n";
    }
    return 0;
}

int runStrip(const BrdfFlags& f) {
    const brdf::Params p = fresnelParams(f);
    const scene::Resolved r = resolveBrdf(f);
    const int width = r.setup.width, height = r.setup.height;
    if (f.png.empty()) throw InputError("-o: give the PNG to write");
    io::checkWritable(f.png, "-o");
    experiments::writeFresnelStrip(p, width, height, f.png);
    std::cout << "wrote " << f.png << ": " << width << "x" << height << " Fresnel strip, theta 0 (left) to 90 (right) "
              << "degrees, linear F sRGB-encoded: " << describeFresnel(p) << "\n";
    return 0;
}

/// tabulate: every check (the parameters, isotropy, -o) before the table is computed and written.
int runTabulate(const BrdfFlags& f) {
    const scene::Values given = commandValues(f.scene);
    const brdf::Params p = resolveBrdf(f).scene.brdf;
    if (p.anisotropic())
        throw InputError(given.where("roughness_y") +
                         ": a MERL table is isotropic (90 x 90 x 180 over theta_h, "
                         "theta_d, phi_d); brdf tabulate takes isotropic models only");
    if (f.png.empty()) throw InputError("-o: give the MERL .binary file to write");
    io::checkWritable(f.png, "-o");
    const brdf::merl::MeasuredBrdf table = brdf::merl::tabulate(p);
    io::writeFileAtomic(f.png, brdf::merl::encode(table));
    std::cout << "wrote " << f.png << ": MERL table " << brdf::merl::kThetaHBins << " x " << brdf::merl::kThetaDBins
              << " x " << brdf::merl::kPhiDBins << " (theta_h, theta_d, phi_d) at the bin centres, " << table.noData
              << " bins below the horizon stored as no data: " << p << "\n";
    return 0;
}

/// A subcommand's flags: the registry parameters it reads, defaults of its own; the CPU uses the full 1 nm
/// tables.
std::shared_ptr<BrdfFlags> subcommandFlags(CLI::App& sub, const std::string& incidence, const std::string& size,
                                           std::function<bool(const scene::Param&)> keep) {
    auto f = std::make_shared<BrdfFlags>();
    if (!incidence.empty()) f->scene.defaults["incidence"] = incidence;
    if (!size.empty()) f->scene.defaults["size"] = size;
    addParamFlags(sub, f->scene, keep);
    return f;
}

/// The parameters a Fresnel term reads, and those a whole BRDF does (its lobe, Fresnel and diffuse).
bool fresnelParam(const scene::Param& p) {
    return p.name == "material" || p.name == "fresnel" || p.name == "eta" || p.name == "k" || p.name == "f0";
}
bool brdfParam(const scene::Param& p) {
    return p.table == scene::Table::Material && p.name != "brdf" && p.name != "param";
}

const char* kSpectralHelp = "spectral Fresnel of the material's measured eta, k (implied for copper, gold)";
const char* kJsonHelp = "one JSON object per line instead of the table";

}  // namespace

Action addBrdf(CLI::App& app) {
    app.require_subcommand(1);
    CLI::App* albedo = app.add_subcommand("albedo", "directional-hemispherical reflectance vs theta_i (CPU, double)");
    auto fa = subcommandFlags(*albedo, "0:85:5", "", [](const scene::Param& p) {
        return brdfParam(p) || p.name == "incidence" || p.name == "azimuth";
    });
    albedo->add_flag("--json", fa->json, kJsonHelp);
    albedo->footer(
        "A light at 90 degrees delivers nothing: albedo 0 there by the horizon convention.\n"
        "Example: hilite brdf albedo --model ggx --roughness 0.3 --geometry smith --json");

    CLI::App* fresnel = app.add_subcommand("fresnel", "Fresnel reflectance F vs theta_i, RGB or spectral");
    auto ff = subcommandFlags(*fresnel, "0:90:5", "",
                              [](const scene::Param& p) { return fresnelParam(p) || p.name == "incidence"; });
    fresnel->add_flag("--spectral", ff->spectral, kSpectralHelp);
    fresnel->add_flag("--json", ff->json, kJsonHelp);
    fresnel->footer("Example: hilite brdf fresnel --material copper --incidence 0:90:5");

    CLI::App* normalization = app.add_subcommand("normalization", "int D(h) (n.h) dw_h of an NDF (1 if normalized)");
    auto fn = subcommandFlags(*normalization, "0", "", [](const scene::Param& p) {
        return p.name == "model" || p.name == "roughness_y" || p.name == "tangent_angle" || p.name == "ndf_table";
    });
    normalization->add_option("--roughness", fn->roughness, "roughness values: list or START:STOP:STEP, in [1e-4, 10]")
        ->capture_default_str();
    normalization->add_option("--exponent", fn->exponent, "exponents (blinn): list or START:STOP:STEP, in [0, 1e8]")
        ->capture_default_str();
    normalization->add_flag("--json", fn->json, kJsonHelp);
    normalization->footer("Example: hilite brdf normalization --model beckmann --roughness 0.02,0.1,1");

    CLI::App* strip = app.add_subcommand("strip", "PNG of a material's Fresnel colour, theta 0 (left) to 90 (right)");
    auto fs = subcommandFlags(*strip, "0", "512x64",
                              [](const scene::Param& p) { return fresnelParam(p) || p.name == "size"; });
    strip->add_flag("--spectral", fs->spectral, kSpectralHelp);
    strip->add_option("-o,--output", fs->png, "PNG output (sRGB-encoded linear F)");
    strip->footer("Example: hilite brdf strip --material gold -o gold.png");

    CLI::App* tabulate =
        app.add_subcommand("tabulate", "a built-in isotropic model as a MERL .binary table (CPU, double)");
    auto ft = subcommandFlags(*tabulate, "", "", brdfParam);
    tabulate->add_option("-o,--output", ft->png, "MERL .binary output (34,992,012 bytes)");
    tabulate->footer(
        "brdf::evaluate (lobe with F and G, diffuse) at every bin centre; bins whose centre puts a "
        "direction below the horizon hold -1 (no data).\n"
        "Example: hilite brdf tabulate --model ggx --roughness 0.1 --geometry smith --fresnel schlick -o ggx.binary");

    const auto [bounces, runBounces] = addBrdfBounces(app);
    const auto [slice, runSliceCmd] = addBrdfSlice(app);
    const auto [inspectCmd, runInspectCmd] = addBrdfInspect(app);

    app.footer(
        "Examples: hilite brdf fresnel --material copper --incidence 0:90:5\n"
        "          hilite brdf albedo --model ggx --roughness 0.3 --geometry smith --json\n"
        "          hilite brdf normalization --model beckmann --roughness 0.02,0.1,1\n"
        "          hilite brdf strip --material gold -o gold.png\n"
        "          hilite brdf tabulate --model ggx --roughness 0.1 --geometry smith --fresnel schlick -o ggx.binary\n"
        "          hilite brdf bounces --roughness 0.6 --material gold --incidence 0,60\n"
        "          hilite brdf slice --model ggx --roughness 0.1 --incidence 60 -o slices\n"
        "          hilite brdf inspect paper_white_rgb.bsdf --incidence 0,30,60");
    return [=, bounces = bounces, runBounces = runBounces, slice = slice, runSliceCmd = runSliceCmd,
            inspectCmd = inspectCmd, runInspectCmd = runInspectCmd] {
        if (inspectCmd->parsed()) return runInspectCmd();
        if (bounces->parsed()) return runBounces();
        if (slice->parsed()) return runSliceCmd();
        if (albedo->parsed()) return runAlbedo(*fa);
        if (fresnel->parsed()) return runFresnel(*ff);
        if (normalization->parsed()) return runNormalization(*fn);
        if (tabulate->parsed()) return runTabulate(*ft);
        return runStrip(*fs);
    };
}

}  // namespace hilite::cli
