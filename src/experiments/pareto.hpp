#pragma once
// Error against time: the rows of an experiment grouped into settings, each setting's worst
// error over its rows against its mean time, the Pareto front (no other setting is both faster and more
// accurate), a log-log plot and the summary's table.

#include "experiments/rows.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::experiments {

/// [[pareto]] of an experiment file.
struct ParetoSpec {
    std::string file = "error_time.png", title = "Error against time";
    std::string setting = "setting";  ///< the row column naming a setting
    std::string series = "knob";      ///< the row column grouping settings in the plot
    std::string error = "aspect_error", time = "time_ms";
    std::vector<double> targets;  ///< summary: the cheapest setting reaching each
};

struct ParetoPoint {
    std::string setting, series;
    double error = 0;                       ///< worst (largest) error over the setting's rows
    double time = 0;                        ///< mean time over the setting's rows
    double majorError = 0, minorError = 0;  ///< worst major_error / minor_error, when the rows have them
    int rows = 0;
    bool front = false;  ///< on the Pareto front
};

/// One point per setting, in first-seen order (rows without the error or time columns are skipped).
std::vector<ParetoPoint> paretoPoints(const ParetoSpec& spec, const Rows& rows);
/// The cheapest setting whose error is at most `target`; nullptr if none.
const ParetoPoint* cheapestReaching(const std::vector<ParetoPoint>& points, double target);
/// dir/<spec.file>: log-log, one point type per series, the front as a line. False (and why) without gnuplot.
bool plotPareto(const std::string& dir, const ParetoSpec& spec, const std::vector<ParetoPoint>& points,
                std::string& why);
/// The summary's section: the cheapest setting per target, then every setting.
std::string paretoMarkdown(const ParetoSpec& spec, const std::vector<ParetoPoint>& points);

}  // namespace hilite::experiments
