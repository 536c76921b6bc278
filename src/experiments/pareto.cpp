#include "experiments/pareto.hpp"

#include "experiments/plot.hpp"
#include "io/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

namespace hilite::experiments {

namespace {

std::string text(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

/// A data file's comment: control characters (a newline would start a data line) become spaces.
std::string oneLine(std::string s) {
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    return s;
}

double number(const nlohmann::json& row, const std::string& key) {
    return row.contains(key) && row[key].is_number() ? row[key].get<double>() : NAN;
}

/// Marks the points no other point beats in both time and error (ties in both: the first stays).
void markFront(std::vector<ParetoPoint>& points) {
    for (auto& p : points) {
        p.front = std::none_of(points.begin(), points.end(), [&](const ParetoPoint& q) {
            return &q != &p && q.time <= p.time && q.error <= p.error && (q.time < p.time || q.error < p.error);
        });
    }
}

}  // namespace

std::vector<ParetoPoint> paretoPoints(const ParetoSpec& spec, const Rows& rows) {
    std::vector<ParetoPoint> points;
    std::map<std::string, size_t> index;
    for (const auto& r : rows) {
        const double err = number(r, spec.error), t = number(r, spec.time);
        if (!r.contains(spec.setting) || !std::isfinite(err) || !std::isfinite(t)) continue;
        const std::string name = text(r[spec.setting]);
        auto it = index.find(name);
        if (it == index.end()) {
            it = index.emplace(name, points.size()).first;
            points.push_back({name, r.contains(spec.series) ? text(r[spec.series]) : std::string()});
        }
        ParetoPoint& p = points[it->second];
        p.error = std::max(p.error, err);
        p.time += t;
        for (auto [key, worst] : {std::pair{"major_error", &p.majorError}, {"minor_error", &p.minorError}})
            if (std::isfinite(number(r, key))) *worst = std::max(*worst, number(r, key));
        ++p.rows;
    }
    for (auto& p : points) p.time /= p.rows;
    markFront(points);
    return points;
}

const ParetoPoint* cheapestReaching(const std::vector<ParetoPoint>& points, double target) {
    const ParetoPoint* best = nullptr;
    for (const auto& p : points)
        if (p.error <= target && (!best || p.time < best->time)) best = &p;
    return best;
}

bool plotPareto(const std::string& dir, const ParetoSpec& spec, const std::vector<ParetoPoint>& points,
                std::string& why) {
    // One data block per series, then the front sorted by time; errors of exactly 0 cannot go on a log axis.
    std::vector<std::string> order;
    std::map<std::string, std::ostringstream> blocks;
    std::ostringstream front;
    std::vector<const ParetoPoint*> onFront;
    const double floor = 1e-9;
    for (const auto& p : points) {
        if (!blocks.count(p.series)) order.push_back(p.series);
        blocks[p.series] << std::setprecision(10) << p.time << " " << std::max(p.error, floor) << " "
                         << nlohmann::json(p.setting).dump() << "\n";
        if (p.front) onFront.push_back(&p);
    }
    std::sort(onFront.begin(), onFront.end(),
              [](const ParetoPoint* a, const ParetoPoint* b) { return a->time < b->time; });
    for (const auto* p : onFront)
        front << std::setprecision(10) << p->time << " " << std::max(p->error, floor) << " "
              << nlohmann::json(p->setting).dump() << "\n";
    std::string data;
    for (const auto& k : order) data += "# " + oneLine(k) + "\n" + blocks[k].str() + "\n\n";
    data += "# Pareto front\n" + front.str() + "\n\n";
    const std::string base = spec.file.substr(0, spec.file.rfind('.'));
    const std::string dat = dir + "/" + base + ".dat";
    io::writeFileAtomic(dat, data);

    std::ostringstream gp;
    gp << "set terminal pngcairo size 1000,700 font 'DejaVu Sans,10'\n"
       << "set output " << quoteGnuplot(dir + "/" + spec.file + ".tmp") << "\n"
       << "set title " << quoteGnuplot(spec.title) << "\n"
       << "set xlabel " << quoteGnuplot(spec.time + " (mean over the scenes; log)") << "\n"
       << "set ylabel " << quoteGnuplot(spec.error + " (worst over the scenes; log)") << "\n"
       << "set termoption noenhanced\n"  // keeps the underscores of column names
       << "set logscale xy\nset format y '1e%L'\nset grid\nset key outside right top box opaque\n";
    for (double t : spec.targets)
        gp << "set arrow from graph 0, first " << t << " to graph 1, first " << t << " nohead dt 3 lc rgb 'gray40'\n";
    gp << "plot " << quoteGnuplot(dat) << " index " << order.size()
       << " using 1:2 with steps lw 3 lc rgb '#80000000' title 'Pareto front'";
    for (size_t i = 0; i < order.size(); ++i)
        gp << ", " << quoteGnuplot(dat) << " index " << i << " using 1:2 with points pt " << (5 + 2 * int(i % 4))
           << " ps 1.4 title " << quoteGnuplot(order[i].empty() ? "settings" : order[i]);
    gp << ", " << quoteGnuplot(dat) << " index " << order.size()
       << " using 1:2 with points pt 6 ps 2.6 lw 2 lc rgb 'black' title 'on the front', " << quoteGnuplot(dat)
       << " index " << order.size() << " using 1:2:3 with labels left offset 1.2,0.6 font ',8' notitle\n";
    return runGnuplot(dir, spec.file, gp.str(), why);
}

std::string paretoMarkdown(const ParetoSpec& spec, const std::vector<ParetoPoint>& points) {
    std::ostringstream md;
    md << "## " << spec.title << "\n\n![" << spec.title << "](" << spec.file << ")\n\n"
       << "Per setting: the worst " << spec.error << " over its rows (scenes) and the mean " << spec.time
       << " over them; a setting is on the Pareto front when no other is both faster and more accurate.\n\n";
    if (!spec.targets.empty()) {
        md << "| target " << spec.error
           << " | cheapest setting reaching it | worst error | mean time |\n|---|---|---|---|\n";
        for (double t : spec.targets) {
            const ParetoPoint* p = cheapestReaching(points, t);
            md << std::setprecision(3) << "| " << t << " | ";
            if (p) md << p->setting << " | " << p->error << " | " << p->time << " |\n";
            else md << "none of the settings | | |\n";
        }
        md << "\n";
    }
    // The semi-axes' errors beside the plotted one (each only when it is not the plotted one).
    const bool major = spec.error != "major_error", minor = spec.error != "minor_error";
    md << "| setting | " << spec.series << " | worst " << spec.error << (major ? " | worst major_error" : "")
       << (minor ? " | worst minor_error" : "") << " | mean " << spec.time << " | rows | front |\n|---|---|---|"
       << (major ? "---|" : "") << (minor ? "---|" : "") << "---|---|---|\n";
    for (const auto& p : points) {
        md << std::setprecision(3) << "| " << p.setting << " | " << p.series << " | " << p.error << " | ";
        if (major) md << p.majorError << " | ";
        if (minor) md << p.minorError << " | ";
        md << p.time << " | " << p.rows << " | " << (p.front ? "yes" : "") << " |\n";
    }
    return md.str() + "\n";
}

}  // namespace hilite::experiments
