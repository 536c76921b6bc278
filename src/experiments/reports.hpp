#pragma once
// What a finished experiment writes from its rows: plots, the contact sheet, Fresnel strips, summary.md
// and its sections. Study-specific sections are named by the experiment file ([summary] sections).

#include "experiments/rows.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::experiments {

class ExperimentRunner;

/// The report sections an experiment file can ask for ([summary] sections = [...]).
const std::vector<std::string>& reportSections();
bool isReportSection(const std::string& name);

/// Plots, contact sheet, strips and summary.md in `dir`. seconds < 0: unknown (merge).
void writeReports(ExperimentRunner& runner, const std::string& dir, const Rows& rows, double seconds);

/// The "microgeometry" section: convergence per incidence, the smallest period against the analytic BRDF, the
/// realised slopes, and masking traced against the height field beside Smith's G (empty without bump rows).
std::string microSummary(const Rows& rows);

}  // namespace hilite::experiments
