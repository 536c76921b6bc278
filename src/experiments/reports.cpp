#include "experiments/reports.hpp"

#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "experiments/strip.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/measurement/row.hpp"
#include "io/image_io.hpp"
#include "io/label.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <map>
#include <sstream>
#include <utility>

namespace hilite::experiments {

namespace {

struct Report {
    std::ostringstream md;
    std::vector<std::string> notes;  ///< what could not be made, and why
};

void plots(const Experiment& e, const std::string& dir, const Rows& rows, Report& out) {
    for (const auto& p : e.plots) {
        std::string why;
        if (!plot(dir, p, rows, why)) out.notes.push_back("plot " + p.file + " not made: " + why);
    }
}

/// Photo views, one row per sheet row value, one column per column value, each tile exposed to its own
/// peak; the row values are written left of the tiles and the column values above them.
bool contactSheet(ExperimentRunner& runner, const std::string& dir) {
    const Experiment& e = runner.experiment();
    if (e.sheetRows.empty() || e.sheetColumns.empty()) return false;
    scene::Values sizeValue;
    sizeValue.set("size", e.sheetSize, e.path + ": contact_sheet.size");
    const scene::Resolved sized = scene::resolve(sizeValue, scene::Purpose::Render);
    const int tw = sized.setup.width, th = sized.setup.height;
    const int gap = 4, cols = int(e.sheetColumns.size()), nrows = int(e.sheetRows.size()), scale = 3;
    const std::string rowKey = e.sheetRowKey.substr(e.sheetRowKey.find('.') + 1);
    const std::string colKey = e.sheetColumnKey.substr(e.sheetColumnKey.find('.') + 1);
    int left = io::textWidth(rowKey, scale);
    for (const auto& r : e.sheetRows) left = std::max(left, io::textWidth(r, scale));
    left += 2 * gap;
    // A title band: the experiment's title, the parameters every tile shares, and the exposure rule (a tile
    // exposed to its own peak says nothing of brightness across tiles).
    const int small = 2, band = 2 * io::textHeight(small) + 2 * gap;
    const int top = band + 2 * io::textHeight(scale) + gap;
    ImageF sheet(left + cols * tw + (cols - 1) * gap, top + nrows * th + (nrows - 1) * gap, 4);
    std::string fixed;
    for (const auto& [name, value] : e.base.given()) fixed += (fixed.empty() ? "" : ", ") + name + " " + value.text;
    std::string line2 = (fixed.empty() ? std::string("defaults") : fixed) + "; each tile exposed to its own peak";
    while (line2.size() > 4 && io::textWidth(line2, small) > sheet.width - 4)
        line2 = line2.substr(0, line2.size() - 4) + "...";
    std::string line1 = e.title;
    while (line1.size() > 4 && io::textWidth(line1, small) > sheet.width - 4)
        line1 = line1.substr(0, line1.size() - 4) + "...";
    io::drawText(sheet, 2, 0, line1, small);
    io::drawText(sheet, 2, io::textHeight(small) + gap / 2, line2, small, 0.7f);
    io::drawText(sheet, left, band, colKey + " ->", scale);
    io::drawText(sheet, 2, band, rowKey, scale);
    for (int ri = 0; ri < nrows; ++ri)
        for (int ci = 0; ci < cols; ++ci) {
            scene::Values values = e.base;
            values.merge(e.sheetRowValues[size_t(ri)]);
            values.merge(e.sheetColumnValues[size_t(ci)]);
            if (!e.sheetFov.empty()) values.set("fov", e.sheetFov, e.path + ": contact_sheet.fov");
            nlohmann::json ignored;
            runner.applyMatch(values, ignored);
            const ImageF tile = runner.photo(values, tw, th);
            double peak = 0;
            for (size_t i = 0; i < tile.data.size(); i += 4) peak = std::max(peak, double(tile.data[i + 1]));
            const double s = peak > 0 ? 1.0 / peak : 1.0;  // each tile exposed to its own peak
            const int x0 = left + ci * (tw + gap), yTop = top + ri * (th + gap);
            for (int y = 0; y < th; ++y)
                for (int x = 0; x < tw; ++x)
                    for (int c = 0; c < 4; ++c)
                        sheet.pixel(x0 + x, sheet.height - yTop - th + y)[c] =
                            float(tile.pixel(x, y)[c] * (c < 3 ? s : 1.0));
            if (ri == 0) io::drawText(sheet, x0, band + io::textHeight(scale), e.sheetColumns[size_t(ci)], scale);
            if (ci == 0)
                io::drawText(sheet, 2, yTop + th / 2 - io::textHeight(scale) / 2, e.sheetRows[size_t(ri)], scale);
        }
    io::writePng(dir + "/" + e.sheetFile, sheet, {});
    return true;
}

/// Fresnel strips: the material's colour from normal incidence to grazing, and F against theta.
void strips(const Experiment& e, const std::string& dir, Report& out) {
    for (const auto& [material, file] : e.strips) {
        scene::Values v;
        v.set("material", material, e.path + ": strip.material");
        const brdf::Params p = scene::resolve(v, scene::Purpose::Brdf).scene.brdf;
        writeFresnelStrip(p, 512, 64, dir + "/" + file, material + " (" + brdf::toString(p.fresnel) + ")");
        std::vector<nlohmann::json> frows;
        for (int t = 0; t <= 90; ++t) {
            double c, s;
            cosSinDeg(t, c, s);
            const dvec3 F = brdf::fresnel(p, c);
            for (int ch = 0; ch < 3; ++ch)
                frows.push_back({{"theta_deg", t}, {"channel", std::string(1, "rgb"[ch])}, {"F", F[ch]}});
        }
        PlotSpec spec;
        spec.file = material + "_fresnel.png";
        spec.title = "Fresnel reflectance of " + material + " (" + brdf::toString(p.fresnel) + "), linear sRGB";
        spec.x = "theta_deg", spec.y = "F", spec.series = "channel", spec.key = "top left";
        std::string why;
        if (!plot(dir, spec, frows, why)) out.notes.push_back("plot " + spec.file + " not made: " + why);
        const auto st = fresnelStats(p);
        out.md << std::setprecision(4) << "![" << material << " strip](" << file << ")\n\n![" << material
               << " Fresnel](" << spec.file << ")\n\n"
               << material << " (" << brdf::toString(p.fresnel) << "): F(0) = (" << st.normal.x << ", " << st.normal.y
               << ", " << st.normal.z << "), red dips to " << st.redMin << " at " << st.redMinThetaDeg
               << " deg, F(89) = (" << st.grazing89.x << ", " << st.grazing89.y << ", " << st.grazing89.z << ").\n\n";
    }
}

/// The "shape" section: the headline table of the series at the chosen angles, and how far each series is
/// from a round highlight and from the microfacet prediction aspect = cos theta_i.
std::string shapeSection(const Experiment& e, const Rows& rows) {
    if (e.summarySeries.empty()) return "";
    std::ostringstream md;
    md << "## Headline numbers\n\n| " << e.summarySeries << " | " << e.summaryX
       << " | aspect | cos | eccentricity | semi-major (deg) | semi-minor (deg) | centroid u (deg) | flags |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    std::map<std::string, std::pair<double, double>> worst;  // series -> max |aspect-1|, max |aspect-cos|
    std::map<std::string, int> counted;                      // series -> rows without flags at x <= 80
    std::map<std::string, double> apart;                     // series -> max |1 - cos theta_i| over those rows
    std::vector<std::string> order;
    for (const auto& r : rows) {
        if (!r.contains(e.summarySeries)) continue;
        const std::string s =
            r[e.summarySeries].is_string() ? r[e.summarySeries].get<std::string>() : r[e.summarySeries].dump();
        if (!worst.count(s)) order.push_back(s), worst[s] = {0, 0};  // listed even with no aspect (no_mirror_lobe)
        if (r["aspect"].is_null()) continue;
        const double x = r.value(e.summaryX, 0.0), a = r["aspect"].get<double>();
        if (r["flags"].empty() && x <= 80) {
            worst[s].first = std::max(worst[s].first, std::abs(a - 1));
            worst[s].second = std::max(worst[s].second, std::abs(a - r.value("cos_incidence", 1.0)));
            ++counted[s];
            apart[s] = std::max(apart[s], std::abs(1.0 - r.value("cos_incidence", 1.0)));
        }
        if (std::find(e.summaryAt.begin(), e.summaryAt.end(), x) == e.summaryAt.end()) continue;
        std::string flags;
        for (const auto& fl : r["flags"]) flags += (flags.empty() ? "" : ", ") + fl.get<std::string>();
        md << std::setprecision(5) << "| " << s << " | " << x << " | " << a << " | " << r.value("cos_incidence", 0.0)
           << " | " << r.value("eccentricity", 0.0) << " | " << r.value("major_deg", 0.0) << " | "
           << r.value("minor_deg", 0.0) << " | " << r.value("centroid_u_deg", 0.0) << " | " << flags << " |\n";
    }
    // "follows": the prediction nearer over every row, if it is within 0.1 of it everywhere (else neither), where
    // some row tells the two apart (|1 - cos theta_i| > 0.1: theta_i > 25.8 deg).
    md << "\nOver the rows without flags at " << e.summaryX << " <= 80 (follows: the prediction within 0.1 of the "
       << "aspect on every such row, the nearer one if both are):\n\n| " << e.summarySeries
       << " | rows | max abs(aspect - 1) | max abs(aspect - cos theta_i) | follows |\n|---|---|---|---|---|\n";
    for (const auto& s : order) {
        const auto [one, cosine] = worst[s];
        const char* follows = !counted[s]                   ? "- (no row without flags)"
                              : apart[s] <= 0.1             ? "- (no row tells the two apart)"
                              : std::min(one, cosine) > 0.1 ? "neither"
                              : cosine < one                ? "cos theta_i (microfacet)"
                                                            : "1 (round: reflection lobe)";
        std::ostringstream a, b;
        a << std::setprecision(3) << one, b << std::setprecision(3) << cosine;
        md << "| " << s << " | " << counted[s] << " | " << (counted[s] ? a.str() : "-") << " | "
           << (counted[s] ? b.str() : "-") << " | " << follows << " |\n";
    }
    return md.str();
}

void header(ExperimentRunner& runner, const Rows& rows, double seconds, Report& out) {
    const Experiment& e = runner.experiment();
    out.md << "# " << e.title << "\n\n" << e.description << "\n\n" << rows.size() << " configurations";
    out.md << std::defaultfloat << ". Rows: [results.csv](results.csv), [results.jsonl](results.jsonl).\n\n";
    // The matched widths from the rows, not from this process's own matching: a merge, or a resume of a finished
    // folder, matched nothing itself and left out the models measured elsewhere (Beckmann and Blinn-Phong).
    std::map<std::string, double> matched;
    for (const auto& r : rows)
        if (r.contains("matched_parameter") && r["matched_parameter"].is_number() && r.contains("model") &&
            r["model"].is_string())
            matched.emplace(r["model"].get<std::string>(), r["matched_parameter"].get<double>());
    if (!matched.empty()) {
        out.md << "Lobe widths matched at normal incidence to a semi-major axis of " << std::setprecision(5)
               << runner.targetMajorDeg() << " deg:\n\n| model | parameter |\n|---|---|\n";
        for (const auto& [k, v] : matched) out.md << "| " << k << " | " << std::setprecision(6) << v << " |\n";
        out.md << "\n";
    }
    // Timing on a line of its own: the only line a merge or a resume writes differently from a single run.
    if (seconds >= 0)
        out.md << "Time: this run measured for " << std::fixed << std::setprecision(2) << seconds << " s.\n\n"
               << std::defaultfloat;
}

/// [fit]: the ranking, a line per target, and how often each model came first.
std::string fitSection(const Experiment& e, const Rows& rows) {
    std::ostringstream md;
    md << "## Which model fits\n\nEach row: the models fitted to the target's highlight over its incidences and the "
          "thresholds ";
    for (size_t j = 0; j < e.fit->thresholds.size(); ++j) md << (j ? ", " : "") << e.fit->thresholds[j];
    md << "; ranked by the " << e.fit->rankBy << " residual ("
       << (e.fit->rankBy == "shape" ? "the weighted RMS of ln(fit / target) of the semi-axes, 0.01: about 1% off"
                                    : "the RMS of ln(1 + f cos theta_i) between fit and target over the measured "
                                      "directions, Low et al. 2012")
       << "), the rank in brackets. Verdict: no_model_fits when the best residual exceeds max(10 x the target's "
          "resolution, 0.01); tie when the second is within max(resolution, 1e-4) of it; target_unresolved when the "
          "resolution itself exceeds 0.02.\n\n| target |";
    for (const auto& m : e.fit->models) md << " " << m << " |";
    md << " best | verdict |\n|---|";
    for (size_t k = 0; k < e.fit->models.size(); ++k) md << "---|";
    md << "---|---|\n";
    std::map<std::string, int> wins;
    for (const auto& r : rows) {
        md << "| " << r.value("target", std::string("?")) << " |";
        for (const auto& m : e.fit->models) {
            const auto res = r.find(m + "_residual");
            const auto rank = r.find(m + "_rank");
            char buf[64];
            if (res != r.end() && res->is_number() && rank != r.end() && rank->is_number())
                std::snprintf(buf, sizeof buf, " %.3e (%d) |", res->get<double>(), rank->get<int>());
            else std::snprintf(buf, sizeof buf, " - |");
            md << buf;
        }
        const std::string best = r.value("best_model", std::string("-"));
        const std::string atBound = r.value(best + "_at_bound", std::string(""));
        md << " " << best << " " << r.value("best_params", std::string(""))
           << (atBound.empty() ? "" : " (at its search bound: " + atBound + ")") << " | "
           << r.value("verdict", std::string("-")) << " |\n";
        ++wins[best];
    }
    md << "\nFirst place:";
    for (const auto& m : e.fit->models) md << " " << m << " " << wins[m] << ";";
    md << " of " << rows.size() << " targets.\n\n";
    return md.str();
}

}  // namespace

const std::vector<std::string>& reportSections() {
    static const std::vector<std::string> all = {"shape", "microgeometry"};
    return all;
}

bool isReportSection(const std::string& name) {
    const auto& all = reportSections();
    return std::find(all.begin(), all.end(), name) != all.end();
}

void writeReports(ExperimentRunner& runner, const std::string& dir, const Rows& rows, double seconds) {
    const Experiment& e = runner.experiment();
    Report out;
    plots(e, dir, rows, out);
    const bool sheet = contactSheet(runner, dir);
    header(runner, rows, seconds, out);
    for (const auto& p : e.plots) {
        out.md << "![" << p.title << "](" << p.file << ")\n\n";
        // The rows drawn as open circles (plot.cpp): listed, so that no flagged point reads as data.
        std::map<std::string, int> counts;
        int flagged = 0;
        for (const auto& r : rows)
            if (r.contains(p.x) && r.contains(p.y) && !r[p.y].is_null() && r.contains("flags") &&
                r["flags"].is_array() && !r["flags"].empty()) {
                ++flagged;
                for (const auto& f : r["flags"]) ++counts[f.is_string() ? f.get<std::string>() : f.dump()];
            }
        if (flagged) {
            out.md << "Open circles: " << flagged << " flagged row" << (flagged > 1 ? "s" : "")
                   << ", off the lines (the numbers do not describe the whole highlight):";
            const char* sep = " ";
            for (const auto& [f, n] : counts) out.md << std::exchange(sep, ", ") << "`" << f << "` " << n;
            out.md << ".\n\n";
        }
    }
    strips(e, dir, out);
    if (sheet)
        out.md << "![contact sheet](" << e.sheetFile << ")\n\nContact sheet: photo views, rows = " << e.sheetRowKey
               << " (top to bottom, values at the left), columns = " << e.sheetColumnKey
               << " (left to right, values above); each tile is exposed to its own peak.\n\n";
    for (const auto& s : e.sections) out.md << (s == "shape" ? shapeSection(e, rows) : microSummary(rows));
    if (e.fit) out.md << fitSection(e, rows);
    if (e.bounces) {
        const std::vector<nlohmann::json> all = rows.materialize();  // a bounce study's handful of rows
        if (!e.bounceColoursFile.empty()) {
            writeBounceColours(all, dir + "/" + e.bounceColoursFile);
            out.md
                << "![colour of each bounce order](" << e.bounceColoursFile
                << ")\n\nThe colour of each bounce "
                   "order's light (its mean Fresnel product, linear sRGB written sRGB-encoded), a row per result row: "
                   "orders 1, 2, 3 and >= 2 traced on the height field, and Kulla-Conty's F_ms.\n\n";
        }
        out.md << bounceSection(all);
    }
    for (const auto& spec : e.pareto) {
        const auto points = paretoPoints(spec, rows);
        std::string why;
        if (!plotPareto(dir, spec, points, why)) out.notes.push_back("plot " + spec.file + " not made: " + why);
        out.md << paretoMarkdown(spec, points);
    }
    if (e.timing)
        out.md << "Times: wall clock of one whole measurement (framing, renders, readback, analysis) in the running "
                  "process, the median of "
               << e.repeats << " repeats after " << e.warmup << " warm-up run(s) per row.\n";
    for (const auto& n : out.notes) out.md << "\nNote: " << n << "\n";
    io::writeFileAtomic(dir + "/summary.md", out.md.str());
}

}  // namespace hilite::experiments
