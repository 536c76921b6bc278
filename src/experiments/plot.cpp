#include "experiments/plot.hpp"

#include "io/image_io.hpp"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

namespace hilite::experiments {

std::string quoteShell(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

namespace {

std::string label(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

}  // namespace

bool plot(const std::string& dir, const PlotSpec& spec, const std::vector<nlohmann::json>& rows, std::string& why) {
    // One data block per series, in first-seen order, for gnuplot's "index".
    std::vector<std::string> order;
    std::map<std::string, std::ostringstream> blocks;
    for (const auto& r : rows) {
        if (!r.contains(spec.x) || !r.contains(spec.y) || r[spec.y].is_null()) continue;
        const std::string key = spec.series.empty() ? spec.y : label(r[spec.series]);
        if (!blocks.count(key)) order.push_back(key);
        blocks[key] << r[spec.x].dump() << " " << r[spec.y].dump() << "\n";
    }
    std::string data;
    for (const auto& k : order) data += "# " + k + "\n" + blocks[k].str() + "\n\n";
    const std::string base = spec.file.substr(0, spec.file.rfind('.'));
    io::writeFileAtomic(dir + "/" + base + ".dat", data);

    std::ostringstream gp;
    gp << "set terminal pngcairo size 900,600 noenhanced font 'DejaVu Sans,11'\n"
       << "set output " << quoteShell(dir + "/" + spec.file + ".tmp") << "\n"
       << "set title " << nlohmann::json(spec.title).dump() << "\n"
       << "set xlabel " << nlohmann::json(spec.xlabel.empty() ? spec.x : spec.xlabel).dump() << "\n"
       << "set ylabel " << nlohmann::json(spec.ylabel.empty() ? spec.y : spec.ylabel).dump() << "\n"
       << "set key " << spec.key << " box opaque\nset grid\n"
       << (spec.logx ? "set logscale x\n" : "") << (spec.logy ? "set logscale y\n" : "");
    gp << "plot ";
    bool first = true;
    for (size_t i = 0; i < order.size(); ++i) {
        gp << (first ? "" : ", ") << quoteShell(dir + "/" + base + ".dat") << " index " << i
           << " using 1:2 with linespoints pt 7 ps 0.5 title " << nlohmann::json(order[i]).dump();
        first = false;
    }
    for (const auto& [title, expr] : spec.theory) {
        gp << (first ? "" : ", ") << expr << " with lines dt 2 lw 2 title " << nlohmann::json(title).dump();
        first = false;
    }
    gp << "\n";
    return runGnuplot(dir, spec.file, gp.str(), why);
}

bool runGnuplot(const std::string& dir, const std::string& file, const std::string& commands, std::string& why) {
    const std::string base = file.substr(0, file.rfind('.'));
    const std::string script = dir + "/" + base + ".gp";
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
