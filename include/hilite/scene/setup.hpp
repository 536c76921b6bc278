#pragma once
// How a scene is measured: image size, framing, the analysis options and the accuracy knobs. Plain data,
// filled by scene::resolve() from the registry's [camera] and [measurement] parameters.

#include "hilite/analysis/highlight.hpp"

#include <iosfwd>

namespace hilite::scene {

/// Largest supersampling grid side n (n^2 renders): beyond 8 the coverage steps (1/64) are far below
/// every other error and the time is 64 renders.
constexpr int kMaxSupersample = 8;

struct MeasureSetup {
    int width = 512, height = 512;
    double fovDeg = 0.0;  ///< > 0: fixed framing (camera on the mirror direction); 0: automatic framing
    analysis::Options options;
    int coarseSize = 64;       ///< automatic framing: size of the aiming renders
    int maxRenders = 5;        ///< automatic framing: at most this many renders in all (aiming + final)
    int maxBlindRenders = 16;  ///< blind framing (no CPU twin, .brdf files): at most this many aiming renders
    double fill = 0.8;         ///< automatic framing: the region's half-extent as a fraction of the half-frame
    /// Automatic framing: the final frame is drawn, read and analysed only over the region's box seen in
    /// the last aiming render, plus a margin (the frame, its pixels and the numbers stay those of the
    /// whole frame). If the region reaches the crop's edge the whole frame is rendered again.
    bool crop = true;
    int supersample = 1;  ///< n: the final frame is rendered n x n times, jittered (analysis/supersample.hpp)
    bool cpu = false;     ///< measure(): the double twin renders the view on the CPU instead of GL
    int threads = 0;      ///< CPU path: threads (0: every core)
    /// measure(): Measurement::image keeps the final render (one sample per pixel, GL or CPU), so a caller can
    /// measure it again at other levels without rendering it again (experiments/fit.cpp's thresholds)
    bool keepImage = false;
};
std::ostream& operator<<(std::ostream&, const MeasureSetup&);

}  // namespace hilite::scene
