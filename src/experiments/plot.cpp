#include "experiments/plot.hpp"

#include "io/image_io.hpp"

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <map>
#include <sstream>

namespace hilite::experiments {

std::string quoteShell(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string quoteGnuplot(const std::string& s) {
    std::string q = "'";
    for (char c : s) {
        if (c == '\'') q += "''";
        else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) q += ' ';
        else q += c;
    }
    return q + "'";
}

const std::vector<std::string>& plotKeys() {
    static const std::vector<std::string> keys = {"top left",
                                                  "top center",
                                                  "top right",
                                                  "center left",
                                                  "center",
                                                  "center right",
                                                  "bottom left",
                                                  "bottom center",
                                                  "bottom right",
                                                  "outside right top",
                                                  "outside right center",
                                                  "outside right bottom",
                                                  "below",
                                                  "above",
                                                  "off"};
    return keys;
}

namespace {

/// A parser for `expr` reading the variable at `x`.
void setUp(mu::Parser& p, const std::string& expr, double* x) {
    p.DefineVar("x", x);
    p.DefineConst("pi", M_PI);
    p.SetExpr(expr);
}

}  // namespace

std::string theoryError(const std::string& expr) {
    // muparser's `=` assigns to a variable and `,` gives several results: neither is a curve.
    for (size_t i = 0; i < expr.size(); ++i)
        if (expr[i] == '=' && !(i > 0 && std::string("=<>!").find(expr[i - 1]) != std::string::npos) &&
            !(i + 1 < expr.size() && expr[i + 1] == '='))
            return "an assignment is not a curve (write an expression of x, e.g. cos(x*pi/180))";
    try {
        mu::Parser p;
        double x = 1;
        setUp(p, expr, &x);
        p.Eval();  // parses, and finds unknown names
        if (p.GetNumResults() != 1) return "one expression, not a list";
    } catch (const mu::Parser::exception_type& e) {
        return e.GetMsg();
    }
    return "";
}

std::vector<double> theoryValues(const std::string& expr, const std::vector<double>& xs) {
    std::vector<double> out;
    mu::Parser p;
    double x = 0;
    setUp(p, expr, &x);
    for (double v : xs) {
        x = v;
        double y = NAN;
        try {
            y = p.Eval();
        } catch (const mu::Parser::exception_type&) {
        }
        out.push_back(std::isfinite(y) ? y : NAN);
    }
    return out;
}

std::string outputNameError(const std::string& name, const std::string& extension) {
    if (name.empty()) return "empty";
    if (name.size() > 200) return "longer than 200 bytes";
    if (name.find('/') != std::string::npos) return "a name in the output folder, not a path (no '/')";
    if (name.front() == '.') return "starts with '.' (no hidden files, no '..')";
    if (name.front() == '-') return "starts with '-'";
    for (char c : name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control character";
    if (!extension.empty() && (name.size() <= extension.size() ||
                               name.compare(name.size() - extension.size(), extension.size(), extension) != 0))
        return "must end in " + extension;
    return "";
}

namespace {

std::string label(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

/// An axis label for a row field: words and a unit, not the column's name (a plot read "incidence_deg").
std::string fieldLabel(const std::string& field) {
    static const std::map<std::string, std::string> known = {
        {"incidence_deg", "angle of incidence θi (deg)"},
        {"aspect", "aspect (minor / major)"},
        {"eccentricity", "eccentricity"},
        {"major_deg", "semi-major axis (deg)"},
        {"minor_deg", "semi-minor axis (deg)"},
        {"orientation_deg", "orientation of the major axis (deg)"},
        {"centroid_u_deg", "centroid u, + towards the normal (deg)"},
        {"centroid_v_deg", "centroid v (deg)"},
        {"fwhm_u_deg", "width along u through the peak (deg)"},
        {"fwhm_v_deg", "width along v through the peak (deg)"},
        {"roughness", "roughness (α for GGX, m for Beckmann)"},
        {"exponent", "exponent n"},
        {"peak", "peak radiance"},
        {"area_deg2", "area (deg²)"},
        {"cos_incidence", "cos θi"}};
    if (const auto it = known.find(field); it != known.end()) return it->second;
    std::string out = field;
    for (const char* unit : {"_deg2", "_deg", "_ms"})
        if (out.size() > std::strlen(unit) &&
            out.compare(out.size() - std::strlen(unit), std::strlen(unit), unit) == 0) {
            out = out.substr(0, out.size() - std::strlen(unit)) + " (" + std::string(unit + 1) + ")";
            break;
        }
    std::replace(out.begin(), out.end(), '_', ' ');
    return out;
}

/// A series' title: its value, named when it is a number ("roughness = 0.02", not a bare "0.02").
std::string seriesTitle(const std::string& field, const nlohmann::json& v) {
    return v.is_number() ? field + " = " + v.dump() : label(v);
}

/// A data file's comment line: one line whatever the text holds.
std::string comment(const std::string& s) {
    std::string c = "# ";
    for (char ch : s) c += static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f ? ' ' : ch;
    return c + "\n";
}

/// Where the theory curves are evaluated: the rows' x values and 200 steps between their extremes (evenly
/// spaced, or geometrically on a log axis), so a curve is as smooth as gnuplot's own sampling made it.
std::vector<double> theorySamples(const std::vector<double>& data, bool logx) {
    std::vector<double> xs;
    for (double v : data)
        if (std::isfinite(v) && (!logx || v > 0)) xs.push_back(v);
    if (xs.empty()) return xs;
    const auto [lo, hi] = std::minmax_element(xs.begin(), xs.end());
    const double a = *lo, b = *hi;
    const int steps = 200;
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        xs.push_back(logx ? a * std::pow(b / a, t) : a + (b - a) * t);
    }
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    return xs;
}

}  // namespace

bool plot(const std::string& dir, const PlotSpec& spec, const Rows& rows, std::string& why) {
    // One data block per series, in first-seen order, for gnuplot's "index"; then one per theory curve.
    // A row with flags is not drawn on its series' line (a zig-zag of horizon strips read as data): it goes to a
    // block of its own, drawn as open circles titled with the flags it carries.
    std::vector<std::string> order;
    std::map<std::string, std::ostringstream> blocks;
    std::map<std::string, bool> drawn;   // the series has a point without flags
    std::map<std::string, bool> gapped;  // the series' last line is a gap: one blank line, never two (gnuplot's
                                         // block separator)
    std::map<std::string, std::map<double, double>> points;  // drawn (x, y) per series, to find coinciding lines
    std::ostringstream flaggedBlock;
    std::map<std::string, int> flagCounts;
    int flagged = 0;
    std::vector<double> xs;
    for (const auto& r : rows) {
        if (!r.contains(spec.x) || !r.contains(spec.y)) continue;
        const std::string key = spec.series.empty() ? spec.y : seriesTitle(spec.series, r[spec.series]);
        if (r[spec.y].is_null()) {  // not measured (no_mirror_lobe, float_overflow): a gap, not a line across it
            if (blocks.count(key) && !gapped[key]) blocks[key] << "\n", gapped[key] = true;
            continue;
        }
        if (!blocks.count(key)) order.push_back(key);
        if (r[spec.x].is_number()) xs.push_back(r[spec.x].get<double>());
        const bool hasFlags = r.contains("flags") && r["flags"].is_array() && !r["flags"].empty();
        if (hasFlags) {
            ++flagged;
            for (const auto& f : r["flags"]) ++flagCounts[label(f)];
            flaggedBlock << r[spec.x].dump() << " " << r[spec.y].dump() << "\n";
            if (!gapped[key]) blocks[key] << "\n";  // a gap in the series' line
            gapped[key] = true;
            continue;
        }
        blocks[key] << r[spec.x].dump() << " " << r[spec.y].dump() << "\n";
        gapped[key] = false;
        drawn[key] = true;
        if (r[spec.x].is_number() && r[spec.y].is_number())
            points[key][r[spec.x].get<double>()] = r[spec.y].get<double>();
    }
    // A line drawn over another (the same x, y within 0.5% of the plot's height: under 3 of its 600 pixels) hides
    // it: its title says so, rather than leave the reader to count the colours.
    std::map<std::string, std::string> coincides;
    {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (const auto& [k, ps] : points)
            for (const auto& [x, y] : ps) lo = std::min(lo, y), hi = std::max(hi, y);
        const double tol = 0.005 * (hi > lo ? hi - lo : std::max(1.0, std::abs(hi)));
        for (size_t i = 1; i < order.size(); ++i)
            for (size_t j = 0; j < i && !coincides.count(order[i]); ++j) {
                const auto &a = points[order[i]], &b = points[order[j]];
                if (a.size() < 2 || a.size() != b.size()) continue;
                bool same = true;
                for (auto ia = a.begin(), ib = b.begin(); same && ia != a.end(); ++ia, ++ib)
                    same = ia->first == ib->first && std::abs(ia->second - ib->second) <= tol;
                if (same) coincides[order[i]] = order[j];
            }
    }
    std::string data;
    // A series with every row flagged has no point of its own: "NaN NaN" keeps its block (a block of blank lines
    // alone is no block to gnuplot's index, and every later index, the flagged circles' included, would shift).
    for (const auto& k : order)
        data += comment(k) + (drawn[k] ? blocks[k].str() : "NaN NaN\n") + (drawn[k] && gapped[k] ? "\n" : "\n\n");
    std::string flaggedTitle;
    if (flagged) {
        for (const auto& [f, n] : flagCounts) flaggedTitle += (flaggedTitle.empty() ? "" : ", ") + f;
        flaggedTitle = "flagged (" + std::to_string(flagged) + "): " + flaggedTitle;
        data += comment(flaggedTitle) + flaggedBlock.str() + "\n\n";
    }
    const std::vector<double> samples = theorySamples(xs, spec.logx);
    // Rows without a numeric x give no samples: no curve (gnuplot would fail on an empty block).
    const size_t curves = samples.empty() ? 0 : spec.theory.size();
    for (size_t c = 0; c < curves; ++c) {
        const auto& [title, expr] = spec.theory[c];
        std::ostringstream block;
        block << std::setprecision(17);
        const auto ys = theoryValues(expr, samples);
        for (size_t i = 0; i < samples.size(); ++i)
            if (std::isfinite(ys[i])) block << samples[i] << " " << ys[i] << "\n";
            else block << "\n";  // undefined there: a gap in the line, never a NaN in the file
        data += comment("theory: " + title) + block.str() + "\n\n";
    }
    const std::string base = spec.file.substr(0, spec.file.rfind('.'));
    const std::string dat = dir + "/" + base + ".dat";
    io::writeFileAtomic(dat, data);

    std::ostringstream gp;
    // Many series under the plot: a taller canvas (20 px a line past 8), so that the plot keeps its height.
    const size_t entries = order.size() + (flagged ? 1 : 0) + curves;
    const bool wideKey = entries > 8 && (spec.key.empty() || spec.key == "below");
    gp << "set terminal pngcairo size 900," << (wideKey ? 600 + 20 * (entries - 8) : 600)
       << " noenhanced font 'DejaVu Sans,11'\n"
       << "set output " << quoteGnuplot(dir + "/" + spec.file + ".tmp") << "\n"
       << "set title " << quoteGnuplot(spec.title) << "\n"
       << "set xlabel " << quoteGnuplot(spec.xlabel.empty() ? fieldLabel(spec.x) : spec.xlabel) << "\n"
       << "set ylabel " << quoteGnuplot(spec.ylabel.empty() ? fieldLabel(spec.y) : spec.ylabel) << "\n";
    // The key is one of a fixed set (checked when the file is read); anything else keeps the default.
    const auto& keys = plotKeys();
    const std::string key = std::find(keys.begin(), keys.end(), spec.key) != keys.end() ? spec.key : "below";
    // Below the plot: no box, which gnuplot draws over the x label there.
    gp << (key == "off"     ? std::string("set key off\n")
           : key == "below" ? std::string("set key below\n")
                            : "set key " + key + " box opaque\n")
       << "set grid\n"
       << (spec.logx ? "set logscale x\n" : "") << (spec.logy ? "set logscale y\n" : "");
    if (spec.polar)
        gp << "set polar\nset angles degrees\nset theta top clockwise\nset size square\nunset border\n"
              "unset xtics\nunset ytics\nset grid polar 15\nset rrange [0:*]\nset ttics 0,15\n";
    gp << "plot ";
    bool first = true;
    // Twelve colours told apart (Paul Tol's "muted" and "bright" schemes), then the same colours dashed: gnuplot's
    // own eight repeat from the ninth series on.
    static const char* const colours[] = {"#332288", "#88CCEE", "#44AA99", "#117733", "#999933", "#DDCC77",
                                          "#CC6677", "#882255", "#AA4499", "#EE6677", "#4477AA", "#BBBBBB"};
    constexpr size_t nColours = sizeof colours / sizeof colours[0];
    size_t unlisted = spec.colourOrder.size();
    for (size_t i = 0; i < order.size(); ++i) {
        const auto listed = std::find(spec.colourOrder.begin(), spec.colourOrder.end(), order[i]);
        const size_t c = listed != spec.colourOrder.end() ? size_t(listed - spec.colourOrder.begin()) : unlisted++;
        gp << (first ? "" : ", ") << quoteGnuplot(dat) << " index " << i
           << " using 1:2 with linespoints pt 7 ps 0.5 lc rgb '" << colours[c % nColours] << "' dt " << 1 + c / nColours
           << " title "
           << quoteGnuplot(coincides.count(order[i]) ? order[i] + " (on " + coincides[order[i]] + ")" : order[i]);
        first = false;
    }
    const size_t theory0 = order.size() + (flagged ? 1 : 0);
    if (flagged) {
        gp << (first ? "" : ", ") << quoteGnuplot(dat) << " index " << order.size()
           << " using 1:2 with points pt 6 ps 1.6 lc rgb 'black' title " << quoteGnuplot(flaggedTitle);
        first = false;
    }
    for (size_t i = 0; i < curves; ++i) {
        gp << (first ? "" : ", ") << quoteGnuplot(dat) << " index " << theory0 + i << " using 1:2 with lines dt "
           << 2 + i << " lw 2.5 lc rgb '#303030' title " << quoteGnuplot(spec.theory[i].first);
        first = false;
    }
    if (first) gp << "NaN notitle";  // no rows with the fields: an empty frame, not a gnuplot syntax error
    gp << "\n";
    return runGnuplot(dir, spec.file, gp.str(), why);
}

bool runGnuplot(const std::string& dir, const std::string& file, const std::string& commands, std::string& why) {
    const std::string base = file.substr(0, file.rfind('.'));
    // "./" before a relative folder: a path starting with '-' is never read as a gnuplot option.
    const std::string script = (dir.empty() || dir.front() != '/' ? "./" : "") + dir + "/" + base + ".gp";
    io::writeFileAtomic(script, commands);
    const std::string cmd = "gnuplot " + quoteShell(script) + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return why = "cannot start gnuplot", false;
    char buf[512];
    std::string out;
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    if (pclose(p) != 0) return why = "gnuplot failed (install gnuplot-nox): " + out, false;
    const std::string png = dir + "/" + file;
    if (std::rename((png + ".tmp").c_str(), png.c_str()) != 0) return why = "cannot write " + png, false;
    return true;
}

}  // namespace hilite::experiments
