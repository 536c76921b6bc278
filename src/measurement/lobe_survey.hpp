#pragma once
// The whole highlight before any framing (../shared/notes/measurement.md, rule 3): the global peak of the
// twin's lobe over the visible hemisphere, and every part of the region {L >= frac * peak}. A coarse scan of
// the hemisphere (rings of elevation, dense toward the horizon, where thin parts live), then each part's
// box in the scene's chart: what the GL path frames one view each, and the reference scans line by line.
// Example it exists for: GGX alpha 0.1 + height-correlated Smith + Schlick F0 0.04 at theta_i 60 deg has the
// main lobe and a strip just above the horizon where the lobe rises back above half its peak.

#include "hilite/analysis/highlight.hpp"
#include "hilite/render/scene.hpp"

#include <vector>

namespace hilite::measurement {

/// One part of the region as the survey's samples see it.
struct SurveyPart {
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;  ///< chart box (rad) of its samples, grown by a grid step
    double maxValue = 0;                    ///< largest sampled lobe value in it
    dvec2 seed{0.0};                        ///< chart point of that sample
    bool horizon = false;                   ///< it has samples on the lowest ring: the horizon bounds it
    bool holdsPeak = false;                 ///< the global peak lies in it
    int samples = 0;                        ///< survey samples in it
};

struct LobeSurvey {
    double peak = 0;  ///< largest lobe value over the visible hemisphere (0: no highlight)
    dvec3 peakDirection{0, 0, 1};
    dvec2 peakUV{0.0};           ///< the peak in the scene's chart
    bool peakOnHorizon = false;  ///< the lobe still rises toward the horizon there: the peak is its limit
    /// the lobe grows without bound toward the horizon there (G = 1: f ~ 1 / cos theta_o): no peak, no region
    bool unbounded = false;
    double level = 0;               ///< frac * peak: the region's threshold
    std::vector<SurveyPart> parts;  ///< the part holding the peak first, then by decreasing maxValue

    /// The part whose survey samples lie nearest `we` (within two grid steps), or -1.
    int partAt(const dvec3& we) const;
    /// The parts' boxes in the chart (radians).
    std::vector<analysis::ChartBox> boxes() const;

    // The grid: rings of elevation (deg, decreasing) x azimuths (relative to the light's, from the
    // forward direction), each sample's part label (-1: outside the region).
    std::vector<double> ringsDeg;
    int azimuths = 0;
    double azimuth0Deg = 0;
    std::vector<int> labels;
    std::vector<double> values;     ///< the samples' lobe values
    std::vector<dvec3> directions;  ///< and directions
};

/// Azimuths of the survey grid (29 rings x 72: about 2100 twin evaluations, plus the peak's climbs).
constexpr int kSurveyAzimuths = 72;

/// The survey of a scene with a CPU twin (InputError otherwise), for the region at `frac` of the peak. The
/// peak: the best of the grid and of the mirror, light and normal directions, refined by a pattern search
/// from the best sample of every part (so a narrow lobe between samples is still found). Kept per thread
/// for the last scene (GL measurement, reference and row ask for the same one).
LobeSurvey surveyLobe(const render::Scene& scene, double frac);

}  // namespace hilite::measurement
