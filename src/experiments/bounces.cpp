#include "hilite/experiments/bounces.hpp"

#include "brdf/energy.hpp"
#include "brdf/integrate.hpp"
#include "core/text.hpp"
#include "hilite/brdf/colour.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/image.hpp"
#include "hilite/measurement/row.hpp"
#include "io/image_io.hpp"
#include "io/label.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace hilite::experiments {

std::ostream& operator<<(std::ostream& os, const BounceSettings& s) {
    return os << s.options << " texels=" << s.texels << " bumps_per_tile=" << s.bumpsPerTile;
}

void checkBounceSettings(const BounceSettings& s, bool asFlags) {
    const auto& o = s.options;
    const std::string where = asFlags ? "--" : "";
    const std::string bumps = asFlags ? "--bumps-per-tile" : "bumps_per_tile";
    // The seed as an experiment file takes it: a negative one given as a flag wraps to above 2^63.
    if (o.seed > 2147483647u)
        throw InputError(where + "seed: an integer in [0, 2147483647] (got " + std::to_string(o.seed) + ")");
    if (o.batches < 2 || o.batches > 1000)
        throw InputError(where + "batches: an integer in [2, 1000] (got " + std::to_string(o.batches) + ")");
    if (o.paths < o.batches || o.paths > 100000000)
        throw InputError(where + "paths: an integer in [batches, 1e8] (got " + std::to_string(o.paths) + ")");
    const bool pow2 = s.texels >= 64 && s.texels <= 4096 && (s.texels & (s.texels - 1)) == 0;
    if (!pow2) throw InputError(where + "texels: a power of two in [64, 4096] (got " + std::to_string(s.texels) + ")");
    // At least 8 texels a bump period: the field's own rule (micro/bump_field.hpp).
    if (s.bumpsPerTile < 1 || s.texels / s.bumpsPerTile < 8)
        throw InputError(bumps + ": an integer in [1, texels / 8] (got " + std::to_string(s.bumpsPerTile) + " for " +
                         std::to_string(s.texels) + " texels)");
}

scene::Resolved resolveBounceScene(scene::Values values) {
    // The study compares with Smith's masking and reflects on the surface alone: nothing else may be named.
    if (values.given("geometry") && values.text("geometry") != "smith")
        throw InputError(values.where("geometry") +
                         ": bounces are compared with Smith's G2: smith or leave it out (got '" +
                         values.text("geometry") + "')");
    for (const char* key : {"diffuse", "multiscatter"})
        if (values.given(key) && values.text(key) != "none")
            throw InputError(values.where(key) +
                             ": bounces trace the specular surface alone, and compute the "
                             "kulla-conty albedo themselves: none or leave it out (got '" +
                             values.text(key) + "')");
    values.set("geometry", "smith", "bounces");
    scene::Resolved r = scene::resolve(values, scene::Purpose::Brdf);
    const brdf::Params& p = r.scene.brdf;
    if (p.model != brdf::Model::Beckmann || p.isMeasured())
        throw InputError(values.where("model") +
                         ": bounces are traced on a Gaussian height field, whose slopes are "
                         "Beckmann's: beckmann (got '" +
                         values.text("model") + "')");
    if (p.anisotropic())
        throw InputError(values.where("roughness_y") + ": the height fields are isotropic (leave it out)");
    if (!(p.roughness >= kMinBounceRoughness && p.roughness <= kMaxBounceRoughness))
        throw InputError(values.where("roughness") + ": bounces are traced for m in [" + fmt(kMinBounceRoughness) +
                         ", " + fmt(kMaxBounceRoughness) + "] (got " + fmt(p.roughness) + ")");
    for (double a : r.angles)
        if (!(a >= 0 && a < 90))
            throw InputError(values.where("incidence") + ": a light below the horizon reflects nothing: [0, 90) (got " +
                             fmt(a) + ")");
    return r;
}

namespace {

/// The light of orders >= 2 together: its mean F product per channel.
brdf::Colour multipleColour(const micro::BounceTally& t, const brdf::ReflectanceChannels& ch) {
    std::vector<double> sum(ch.size(), 0.0);
    double energy = 0;
    for (size_t k = 1; k < t.reflected.size(); ++k) {
        energy += t.energy[k].value;
        for (size_t c = 0; c < ch.size(); ++c) sum[c] += t.reflected[k][c];
    }
    for (double& v : sum) v = energy > 0 ? v / energy : 0.0;
    return brdf::colourOf(sum, ch);
}

double luminance(const dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

}  // namespace

std::vector<BounceStudy> studyBounces(const scene::Values& values, const BounceSettings& s,
                                      const micro::BounceProgress& progress) {
    checkBounceSettings(s, false);  // the library's entry point checks as the CLI does (texels 1000 crashed the tile)
    const scene::Resolved r = resolveBounceScene(values);
    scene::Values kcValues = values;
    kcValues.set("geometry", "smith", "bounces");
    kcValues.set("multiscatter", "kulla-conty", "bounces");
    const brdf::Params kc = scene::resolve(kcValues, scene::Purpose::Brdf).scene.brdf;
    brdf::Params white = r.scene.brdf;
    white.fresnel = brdf::Fresnel::None;
    const brdf::ReflectanceChannels channels = brdf::reflectanceChannels(r.scene.brdf);
    micro::BumpSpec spec;
    spec.kind = micro::BumpKind::Beckmann;
    spec.roughness = r.scene.brdf.roughness;
    spec.seed = uint64_t(std::llround(std::stod(values.text("bump_seed"))));
    spec.texels = s.texels;
    spec.bumpsPerTile = s.bumpsPerTile;
    const std::string fieldStage = "field " + std::to_string(spec.texels) + "^2";
    if (progress) progress(fieldStage, 0, 1);
    const micro::BumpField& field = micro::cachedBumpField(spec);
    if (progress) progress(fieldStage, 1, 1);
    std::vector<BounceStudy> out;
    for (double theta : r.angles) {
        const auto t0 = std::chrono::steady_clock::now();
        BounceStudy st;
        st.thetaDeg = theta;
        st.params = r.scene.brdf;
        st.spec = spec;
        st.surface = s.options.surface;
        st.pathSeed = s.options.seed;
        st.hermiteRatio = s.options.surface == micro::TracedSurface::Hermite ? micro::hermiteSlopeRatio(field) : 1.0;
        std::ostringstream at;
        at << "theta " << theta << ": ";
        const auto told = [&](const std::string& stage, long done, long total) {
            if (progress) progress(at.str() + stage, done, total);
        };
        st.traced = micro::traceBounces(field, theta, channels, s.options, told);
        st.walk = micro::walkSmithBounces(spec.roughness, theta, channels, s.options, told);
        st.smithSingle = brdf::albedo(white, theta).x;
        st.singleAlbedo = brdf::albedo(r.scene.brdf, theta);
        st.kcAlbedo = brdf::albedo(kc, theta);
        st.tracedMultiple = multipleColour(st.traced, channels);
        st.walkMultiple = multipleColour(st.walk, channels);
        st.kcMultiple = brdf::colourOfRgb(kc.energy->Fms);
        st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        out.push_back(std::move(st));
    }
    return out;
}

namespace {

/// Order k's name in a column: 1 .. kMaxReportedOrder, then "5plus" for the rest.
std::string orderName(size_t k) {
    return k < size_t(micro::kMaxReportedOrder) ? std::to_string(k + 1) : std::to_string(k + 1) + "plus";
}
constexpr size_t kColourOrders = 3;  ///< orders whose colour a row carries one by one

/// Every column with its value: one list, so that the names and the values cannot part.
std::vector<std::pair<std::string, nlohmann::json>> fields(const BounceStudy* s) {
    std::vector<std::pair<std::string, nlohmann::json>> f;
    auto add = [&](const std::string& name, auto value) {
        if (s) f.emplace_back(name, nlohmann::json(value));
        else f.emplace_back(name, nullptr);
    };
    const micro::BounceTally empty;
    const micro::BounceTally& tr = s ? s->traced : empty;
    const micro::BounceTally& wk = s ? s->walk : empty;
    auto at = [](const std::vector<micro::Estimate>& v, size_t k) { return k < v.size() ? v[k] : micro::Estimate{}; };
    add("bounce_surface", s ? micro::toString(s->surface) : "");
    add("bounce_paths", tr.paths);
    add("bounce_seed", s ? s->pathSeed : uint64_t(0));
    add("bounce_texels", s ? s->spec.texels : 0);
    add("bounce_bumps_per_tile", s ? s->spec.bumpsPerTile : 0);
    add("hermite_ratio", s ? s->hermiteRatio : 0.0);
    add("bounce_time_ms", s ? 1000.0 * s->seconds : 0.0);
    add("smith_single", s ? s->smithSingle : 0.0);
    for (size_t k = 0; k <= size_t(micro::kMaxReportedOrder); ++k) {
        add("traced_e" + orderName(k), at(tr.energy, k).value);
        add("traced_e" + orderName(k) + "_err", at(tr.energy, k).error);
        add("smith_e" + orderName(k), at(wk.energy, k).value);
        add("smith_e" + orderName(k) + "_err", at(wk.energy, k).error);
    }
    add("traced_multiple", tr.multiple.value);
    add("traced_multiple_err", tr.multiple.error);
    add("smith_multiple", wk.multiple.value);
    add("smith_multiple_err", wk.multiple.error);
    add("kc_multiple", s ? 1.0 - s->smithSingle : 0.0);
    add("traced_stuck", tr.stuck.value);
    const dvec3 kcAlbedo = s ? s->kcAlbedo : dvec3(0.0), single = s ? s->singleAlbedo : dvec3(0.0);
    const char* rgb = "rgb";
    for (int c = 0; c < 3; ++c) add(std::string("traced_albedo_") + rgb[c], at(tr.reflectedRgb, size_t(c)).value);
    for (int c = 0; c < 3; ++c) add(std::string("kc_albedo_") + rgb[c], kcAlbedo[c]);
    add("traced_albedo_y", tr.reflectedY.value);
    add("traced_albedo_y_err", tr.reflectedY.error);
    add("smith_albedo_y", wk.reflectedY.value);
    add("smith_albedo_y_err", wk.reflectedY.error);
    add("single_albedo_y", luminance(single));
    add("kc_albedo_y", luminance(kcAlbedo));
    // What the surface does not reflect: a dielectric's body share (the coupled diffuse's rho = 1), a metal's absorption.
    add("traced_body", 1.0 - tr.reflectedY.value - tr.stuck.value);
    add("smith_body", 1.0 - wk.reflectedY.value - wk.stuck.value);
    add("kc_body", 1.0 - luminance(kcAlbedo));
    const brdf::Colour none;
    brdf::Colour noLight;  // an order no path reached has no colour
    noLight.chroma = noLight.x = noLight.y = noLight.rgb.x = noLight.rgb.y = noLight.rgb.z = NAN;
    for (size_t k = 0; k < kColourOrders; ++k) {
        const brdf::Colour& c = k < tr.colour.size() && at(tr.energy, k).value > 0 ? tr.colour[k] : noLight;
        add("traced_chroma" + orderName(k), at(tr.chroma, k).value);
        add("traced_chroma" + orderName(k) + "_err", at(tr.chroma, k).error);
        add("smith_chroma" + orderName(k), at(wk.chroma, k).value);
        add("smith_chroma" + orderName(k) + "_err", at(wk.chroma, k).error);
        add("traced_x" + orderName(k), c.x);
        add("traced_y" + orderName(k), c.y);
        for (int ch = 0; ch < 3; ++ch) add("traced_colour" + orderName(k) + "_" + rgb[ch], c.rgb[ch]);
    }
    const brdf::Colour trM = s && tr.multiple.value > 0 ? s->tracedMultiple : noLight,
                       wkM = s && wk.multiple.value > 0 ? s->walkMultiple : noLight, kcM = s ? s->kcMultiple : none;
    add("traced_chroma_ms", trM.chroma);
    add("smith_chroma_ms", wkM.chroma);
    add("kc_chroma_ms", kcM.chroma);
    for (int ch = 0; ch < 3; ++ch) add(std::string("traced_colour_ms_") + rgb[ch], trM.rgb[ch]);
    for (int ch = 0; ch < 3; ++ch) add(std::string("kc_colour_ms_") + rgb[ch], kcM.rgb[ch]);
    return f;
}

}  // namespace

std::vector<std::string> bounceColumns() {
    std::vector<std::string> out;
    for (const auto& [k, v] : fields(nullptr)) out.push_back(k);
    return out;
}

nlohmann::json bounceFields(const BounceStudy& s) {
    nlohmann::json row;
    for (auto& [k, v] : fields(&s)) row[k] = v;
    return row;
}

nlohmann::ordered_json bounceRow(const BounceStudy& s) {
    nlohmann::ordered_json j{{"theta_deg", s.thetaDeg}};
    const nlohmann::json f = bounceFields(s);
    for (const std::string& k : bounceColumns()) j[k] = f.at(k);
    return j;
}

}  // namespace hilite::experiments

namespace hilite::experiments {

namespace {

double num(const nlohmann::json& r, const std::string& k) { return measurement::rowNumber(r, k.c_str()); }

/// "0.859 +- 0.001" with the error's own leading digit deciding the decimals.
std::string pm(double v, double e) {
    std::ostringstream s;
    if (!std::isfinite(v)) return "-";
    const int digits = std::isfinite(e) && e > 0 ? std::clamp(1 - int(std::floor(std::log10(e))), 1, 6) : 4;
    s << std::fixed << std::setprecision(digits) << v;
    if (std::isfinite(e)) s << " +- " << e;
    return s.str();
}

std::string fixed(double v, int digits) {
    if (!std::isfinite(v)) return "-";
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

/// The scene of a row, as its columns say it.
std::string sceneOf(const nlohmann::json& r) {
    std::ostringstream s;
    const std::string material = r.value("material", std::string());
    s << (material.empty() ? r.value("fresnel", std::string("none")) : material) << " | " << num(r, "roughness")
      << " | " << num(r, "incidence_deg");
    return s.str();
}

void energyTable(const std::vector<nlohmann::json>& rows, std::ostringstream& md) {
    md << "### Energy per bounce order, F = 1\n\nThe share of the light that leaves after 1, 2, 3 and more bounces: "
          "`traced` on the explicit height field, `Smith` by the random walk on Smith's microsurface (Heitz et al. "
          "2016), each +- one standard error over the batches. `E(mu)` is the single scattering brdf::albedo "
          "integrates (Smith G2, the table of --multiscatter kulla-conty), `1 - E` what the compensation returns "
          "(its albedo is exactly 1). `traced - KC`: the traced multiple scattering less 1 - E, in standard "
          "errors.\n\n| material | m | theta_i | traced 1 | Smith 1 | E(mu) | traced 2 | Smith 2 | traced 3 | Smith 3 "
          "| "
          "traced >= 4 | Smith >= 4 | traced >= 2 | Smith >= 2 | KC 1 - E | traced - KC |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
        const double ms = num(r, "traced_multiple"), err = num(r, "traced_multiple_err"), kc = num(r, "kc_multiple");
        const double t4 = num(r, "traced_e4") + num(r, "traced_e5plus"),
                     w4 = num(r, "smith_e4") + num(r, "smith_e5plus");
        md << "| " << sceneOf(r) << " | " << pm(num(r, "traced_e1"), num(r, "traced_e1_err")) << " | "
           << pm(num(r, "smith_e1"), num(r, "smith_e1_err")) << " | " << fixed(num(r, "smith_single"), 4) << " | "
           << pm(num(r, "traced_e2"), num(r, "traced_e2_err")) << " | "
           << pm(num(r, "smith_e2"), num(r, "smith_e2_err")) << " | " << fixed(num(r, "traced_e3"), 4) << " | "
           << fixed(num(r, "smith_e3"), 4) << " | " << fixed(t4, 4) << " | " << fixed(w4, 4) << " | " << pm(ms, err)
           << " | " << pm(num(r, "smith_multiple"), num(r, "smith_multiple_err")) << " | " << fixed(kc, 4) << " | "
           << std::showpos << fixed(ms - kc, 4) << std::noshowpos << " (" << fixed((ms - kc) / err, 1) << " sigma) |\n";
    }
    md << "\n";
}

void colourTable(const std::vector<nlohmann::json>& rows, std::ostringstream& md) {
    md << "### Colour per bounce order\n\nThe light of each order has the colour of its mean Fresnel product, "
          "F multiplied per wavelength at each bounce and integrated under D65 (CIE 1931 2-degree): CIELAB C* "
          "against the white (D65), xy its chromaticity (white 0.3127, 0.3290). `>= 2` pools the orders from the "
          "second; Kulla-Conty's colour of those orders is F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) in linear "
          "sRGB. Errors: the spread of C* over the batches.\n\n| material | m | theta_i | C* 1 | C* 2 | C* 3 | C* 2 - "
          "C* 1 | "
          "xy 1 | xy 2 | C* >= 2 traced | Smith | KC F_ms | albedo Y traced | Smith | KC | single |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    int more = 0, counted = 0;
    double smallestSigma = INFINITY;
    for (const auto& r : rows) {
        const double c1 = num(r, "traced_chroma1"), c2 = num(r, "traced_chroma2"), e1 = num(r, "traced_chroma1_err"),
                     e2 = num(r, "traced_chroma2_err");
        const double sigma = (c2 - c1) / std::hypot(e1, e2);
        if (std::isfinite(sigma)) {
            ++counted;
            more += c2 > c1;
            smallestSigma = std::min(smallestSigma, sigma);
        }
        md << "| " << sceneOf(r) << " | " << pm(c1, e1) << " | " << pm(c2, e2) << " | "
           << pm(num(r, "traced_chroma3"), num(r, "traced_chroma3_err")) << " | " << std::showpos << fixed(c2 - c1, 2)
           << std::noshowpos << " (" << fixed(sigma, 1) << " sigma) | " << fixed(num(r, "traced_x1"), 4) << ", "
           << fixed(num(r, "traced_y1"), 4) << " | " << fixed(num(r, "traced_x2"), 4) << ", "
           << fixed(num(r, "traced_y2"), 4) << " | " << fixed(num(r, "traced_chroma_ms"), 2) << " | "
           << fixed(num(r, "smith_chroma_ms"), 2) << " | " << fixed(num(r, "kc_chroma_ms"), 2) << " | "
           << pm(num(r, "traced_albedo_y"), num(r, "traced_albedo_y_err")) << " | "
           << fixed(num(r, "smith_albedo_y"), 4) << " | " << fixed(num(r, "kc_albedo_y"), 4) << " | "
           << fixed(num(r, "single_albedo_y"), 4) << " |\n";
    }
    md << "\nSecond-bounce light is more saturated than first-bounce light (C* 2 > C* 1) in " << more << " of "
       << counted << " rows; the smallest margin is " << fixed(smallestSigma, 1) << " standard errors.\n\n";
}

void shareTable(const std::vector<nlohmann::json>& rows, std::ostringstream& md) {
    md << "### Surface and body\n\nWhat the surface reflects (luminance of the albedo, every order) and what it lets "
          "into the body (1 - that; with the coupled diffuse at rho = 1 the body returns all of it, rho (1 - E_s)). "
          "KC: E_s of the lobe with --multiscatter kulla-conty and the scene's Fresnel.\n\n| material | m | theta_i | "
          "surface traced | Smith | KC E_s | single | of it order 1 (traced) | orders >= 2 | body traced | Smith | "
          "KC |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
        const double surface = num(r, "traced_albedo_y");
        // Order 1's share of the reflected light: the luminance of order 1's reflectance times its energy.
        const double first =
            num(r, "traced_e1") * (0.2126 * num(r, "traced_colour1_r") + 0.7152 * num(r, "traced_colour1_g") +
                                   0.0722 * num(r, "traced_colour1_b"));
        md << "| " << sceneOf(r) << " | " << pm(surface, num(r, "traced_albedo_y_err")) << " | "
           << fixed(num(r, "smith_albedo_y"), 4) << " | " << fixed(num(r, "kc_albedo_y"), 4) << " | "
           << fixed(num(r, "single_albedo_y"), 4) << " | " << fixed(first, 4) << " | " << fixed(surface - first, 4)
           << " | " << fixed(num(r, "traced_body"), 4) << " | " << fixed(num(r, "smith_body"), 4) << " | "
           << fixed(num(r, "kc_body"), 4) << " |\n";
    }
    md << "\n";
}

}  // namespace

std::string bounceSection(const std::vector<nlohmann::json>& rows) {
    if (rows.empty()) return "";
    std::ostringstream md;
    const nlohmann::json& any = rows.front();
    md << "## Light that bounces more than once\n\nPaths traced on an explicit Beckmann height field ("
       << num(any, "bounce_texels") << "^2 texels, " << num(any, "bounce_bumps_per_tile") << " bumps a tile, surface `"
       << any.value("bounce_surface", std::string()) << "`, " << num(any, "bounce_paths")
       << " paths a row) and walked on Smith's microsurface; see docs/bounces.md for the method and what the "
          "differences mean.\n\n";
    energyTable(rows, md);
    std::vector<nlohmann::json> coloured, dielectric;
    for (const auto& r : rows) {
        const std::string f = r.value("fresnel", std::string("none"));
        if (f == "spectral" || f == "conductor" || f == "schlick") coloured.push_back(r);
        if (f == "dielectric") dielectric.push_back(r);
    }
    if (!coloured.empty()) colourTable(coloured, md);
    if (!dielectric.empty()) shareTable(dielectric, md);
    return md.str();
}

void writeBounceColours(const std::vector<nlohmann::json>& rows, const std::string& path) {
    // One row of patches per results row: orders 1, 2, 3, >= 2 traced, and Kulla-Conty's F_ms.
    const int patch = 48, gap = 4, scale = 1, th = io::textHeight(scale), label = 150, header = th + 6;
    const std::vector<std::pair<std::string, std::string>> columns = {{"1", "traced_colour1_"},
                                                                      {"2", "traced_colour2_"},
                                                                      {"3", "traced_colour3_"},
                                                                      {">=2", "traced_colour_ms_"},
                                                                      {"KC F_ms", "kc_colour_ms_"}};
    const int width = label + int(columns.size()) * (patch + gap), height = header + int(rows.size()) * (patch + gap);
    ImageF img(width, height, 3);
    auto top = [&](int yFromTop) { return height - 1 - yFromTop; };  // rows are stored bottom-up
    for (size_t c = 0; c < columns.size(); ++c)
        io::drawText(img, label + int(c) * (patch + gap), 2, columns[c].first, scale);
    for (size_t i = 0; i < rows.size(); ++i) {
        const auto& r = rows[i];
        const int y0 = header + int(i) * (patch + gap);
        std::ostringstream name;
        name << r.value("material", std::string("")) << " m " << num(r, "roughness") << ", " << num(r, "incidence_deg")
             << " deg";
        io::drawText(img, 2, y0 + patch / 2 - th / 2, name.str(), scale);
        for (size_t c = 0; c < columns.size(); ++c) {
            dvec3 rgb;
            for (int ch = 0; ch < 3; ++ch) rgb[ch] = num(r, columns[c].second + "rgb"[ch]);
            if (!std::isfinite(rgb.x + rgb.y + rgb.z)) continue;  // an order no path reached: left black
            for (int y = y0; y < y0 + patch; ++y)
                for (int x = label + int(c) * (patch + gap); x < label + int(c) * (patch + gap) + patch; ++x)
                    for (int ch = 0; ch < 3; ++ch) img.pixel(x, top(y))[ch] = float(std::clamp(rgb[ch], 0.0, 1.0));
        }
    }
    io::writePng(path, img, io::Exposure{});
}

}  // namespace hilite::experiments
