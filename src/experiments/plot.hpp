#pragma once
// Plots as PNG through gnuplot (Debian's gnuplot-nox): one line per series, optional theory curves.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::experiments {

struct PlotSpec {
    std::string file;               ///< PNG name inside the output folder
    std::string title;
    std::string x, y;               ///< row fields
    std::string series;             ///< row field whose values make separate lines ("" = one line)
    std::vector<std::pair<std::string, std::string>> theory;  ///< (title, gnuplot expression of x)
    std::string xlabel, ylabel;
    std::string key = "bottom left";  ///< gnuplot key position
    bool logx = false, logy = false;  ///< logarithmic axes
};

/// Writes dir/<spec.file> from the rows (skipping rows whose y is null). Returns false (and says why in
/// `why`) when gnuplot is missing or fails; the data file beside it is kept either way.
bool plot(const std::string& dir, const PlotSpec& spec, const std::vector<nlohmann::json>& rows, std::string& why);

/// Runs gnuplot on `commands` (written to dir/<file stem>.gp); the commands write dir/<file>.tmp, which
/// is renamed to dir/<file> on success. False (and why) when gnuplot is missing or fails.
bool runGnuplot(const std::string& dir, const std::string& file, const std::string& commands, std::string& why);
/// `s` quoted for a POSIX shell (and for gnuplot's strings).
std::string quoteShell(const std::string& s);

}  // namespace hilite::experiments
