#include "hilite/measurement/measure_scene.hpp"
#include "render/area_bounds.hpp"
#include "render/renderer.hpp"

#include "measurement/measure_bumps.hpp"

#include "analysis/lobe_bounds.hpp"
#include "analysis/supersample.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "hilite/render/area_light.hpp"
#include "measurement/blind_framing.hpp"
#include "measurement/diagnose.hpp"
#include "measurement/framing.hpp"
#include "measurement/lobe_survey.hpp"
#include "measurement/mirror_lobe.hpp"
#include "measurement/peak_frame.hpp"
#include "render/cpu_view.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hilite::measurement {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

PinholeCamera measurementCamera(const render::Scene& scene, const dvec3& center, double fovDeg, int w, int h) {
    return PinholeCamera::measurementFrom(scene.light.chart(), render::eyePosition(scene), liftAboveHorizon(center),
                                          fovDeg, w, h);
}

TwinSampler::TwinSampler(const render::Scene& scene)
    : m_scene(scene), m_chart(scene.light.chart()), m_eye(render::eyePosition(scene)), m_wi(scene.light.direction()) {
    render::requireTwin(scene, "the CPU lobe");
}

bool TwinSampler::at(double u, double v, double& L) const {
    const dvec3 we = m_chart.direction(u, v);
    if (we.z <= 0.0) return false;
    L = brdf::luminance(render::surfaceRadiance(m_scene, m_wi, m_eye, we));
    return true;
}

analysis::LobeFunction twinLobe(const render::Scene& scene) {
    render::requireTwin(scene, "the CPU lobe");
    const auto copy = std::make_shared<const render::Scene>(scene);  // the functions may outlive `scene`
    const auto sampler = std::make_shared<const TwinSampler>(*copy);
    const MirrorChart chart = scene.light.chart();
    analysis::LobeFunction f;
    f.lobe = [copy, sampler](double u, double v) { return sampler->lobe(u, v); };
    f.visible = [chart](double u, double v) { return chart.direction(u, v).z > 0.0; };
    return f;
}

std::array<double, 4> twinRadii(const render::Scene& scene, double threshold) {
    render::requireTwin(scene, "the lobe width seed");
    const TwinSampler f(scene);
    const double l0 = f.lobe(0, 0);
    if (!(l0 > 0)) return {deg2rad(30.0), deg2rad(30.0), deg2rad(30.0), deg2rad(30.0)};
    std::array<double, 4> radii{};
    const double du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
        double lo = 0, hi = 1e-9;
        while (hi < kPi / 2 && f.lobe(hi * du[k], hi * dv[k]) >= threshold * l0) lo = hi, hi *= 2;
        for (int i = 0; i < 30; ++i) {  // to 1e-9 of the bracket: a seed, which the aiming renders correct
            const double mid = 0.5 * (lo + hi);
            (f.lobe(mid * du[k], mid * dv[k]) >= threshold * l0 ? lo : hi) = mid;
        }
        radii[size_t(k)] = hi;
    }
    return radii;
}

double twinHalfWidth(const render::Scene& scene, double threshold) {
    const auto r = twinRadii(scene, threshold);
    return *std::max_element(r.begin(), r.end());
}

namespace {

/// Draws one render of the measurement view: camera, sub-pixel jitter, crop (empty: the whole frame), and
/// CPU work to do while it is drawn (may be empty; GL runs it between the draw and the readback).
using ViewFn =
    std::function<void(const PinholeCamera&, dvec2, const PixelRect&, ImageF&, const std::function<void()>&)>;

/// The last aiming render and its region's box, from which the final frame was set.
struct Aim {
    PinholeCamera camera;
    RegionBox box;
    bool good = false;  ///< the loop ended on a frame it accepted (else: no box to crop to)
};

/// Automatic framing: seed the frame from the twin's half-width, then let coarse renders correct the
/// aim (off-specular shift, anisotropy, horizon) until the region sits inside the frame and fills most of it.
/// Aiming at one part of a region in several parts: its views keep only its pixels (keepPart), and the
/// region is L >= level, the global peak's.
/// A part's measured view (its camera and luminance), kept so that a later part's view does not count a
/// piece of the same region again.
struct CountedView {
    PinholeCamera camera;
    std::vector<float> L;  ///< row-major, camera.width x camera.height
    double level = 0;      ///< the region there: L >= level
    bool holds(const dvec3& ray) const;
};

struct PartAim {
    const render::Scene* scene = nullptr;
    const LobeSurvey* survey = nullptr;
    int part = 0;
    double level = 0;
    const std::vector<CountedView>* counted = nullptr;  ///< the views of the parts measured before this one
    const MirrorLobe* mirror = nullptr;                 ///< lobe = mirror: keep that lobe's pixels instead
};

void keepPart(ImageF& img, const PinholeCamera& cam, const PartAim& part);  // below

Aim aimFrame(const ViewFn& view, const render::Scene& scene, const MeasureSetup& setup, Frame& frame, Measurement& m,
             const PartAim* part = nullptr, const std::function<void()>& whileFirstDrawn = {}) {
    thread_local ImageF coarse;  // reused across calls: no allocation per measurement
    if (!part) {                 // a part's frame is seeded from its survey box by the caller
        const double r = twinHalfWidth(scene, setup.options.threshold);
        frame.fovDeg =
            std::clamp(2.0 * rad2deg(std::atan(std::tan(std::min(r, 1.3)) / setup.fill)), kMinFovDeg, kMaxFovDeg);
    }
    Aim aim;
    bool first = true;
    while (m.renders < setup.maxRenders - 1) {
        // The aiming renders keep the final frame's shape, so what fits them fits the final render.
        const double longest = std::max(setup.width, setup.height);
        const int cw = std::max(8, int(std::lround(setup.coarseSize * setup.width / longest)));
        const int ch = std::max(8, int(std::lround(setup.coarseSize * setup.height / longest)));
        aim.camera = measurementCamera(scene, frame.center, frame.fovDeg, cw, ch);
        auto t0 = Clock::now();
        view(aim.camera, dvec2(0.0), PixelRect{}, coarse, first ? whileFirstDrawn : std::function<void()>{});
        first = false;
        m.render_ms += msSince(t0);
        ++m.renders;
        t0 = Clock::now();
        if (part) keepPart(coarse, aim.camera, *part);
        aim.box = part ? regionBoxAbove(coarse, part->level) : regionBox(coarse, setup.options.threshold);
        aim.good = !aim.box.empty() && reframe(aim.camera, aim.box, setup.fill, frame);
        m.measure_ms += msSince(t0);
        if (aim.good || aim.box.empty()) break;
    }
    return aim;
}

/// The pixels of the final frame that can hold the region: the aiming render's box grown by 1.5 of its
/// pixels (a pixel is in by its centre, so the region may reach almost a pixel past the box, and the
/// aim moved by up to half a pixel) plus 2 final pixels (the contour's outer ring and one more), mapped
/// into the final camera (same eye: a homography, so the box's corners bound it). Empty: the whole frame.
PixelRect cropOf(const Aim& aim, const PinholeCamera& fine) {
    const double m = 1.5;
    double x0 = fine.width, y0 = fine.height, x1 = 0, y1 = 0;
    for (double cx : {aim.box.x0 - m, aim.box.x1 + 1 + m})
        for (double cy : {aim.box.y0 - m, aim.box.y1 + 1 + m}) {
            double nx = 0, ny = 0;
            if (!fine.project(aim.camera.ray(cx, cy), nx, ny)) return {};  // behind the final camera: no crop
            const double px = 0.5 * (nx + 1.0) * fine.width, py = 0.5 * (ny + 1.0) * fine.height;
            x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
        }
    const int ix0 = std::max(0, int(std::floor(x0)) - 2), iy0 = std::max(0, int(std::floor(y0)) - 2);
    const int ix1 = std::min(fine.width, int(std::ceil(x1)) + 2), iy1 = std::min(fine.height, int(std::ceil(y1)) + 2);
    if (ix1 - ix0 < 3 || iy1 - iy0 < 3) return {};  // too small to trust: the whole frame
    if (ix0 == 0 && iy0 == 0 && ix1 == fine.width && iy1 == fine.height) return {};
    return {ix0, iy0, ix1 - ix0, iy1 - iy0};
}

void keepLuminance(const ImageF& img, std::vector<float>& L) {
    L.resize(size_t(img.width) * size_t(img.height));
    for (size_t i = 0; i < L.size(); ++i) L[i] = img.data[4 * i];
}

bool CountedView::holds(const dvec3& ray) const {
    double nx = 0, ny = 0;
    if (!camera.project(ray, nx, ny)) return false;
    const double px = 0.5 * (nx + 1.0) * camera.width, py = 0.5 * (ny + 1.0) * camera.height;
    if (!(px >= -1 && px < camera.width + 1 && py >= -1 && py < camera.height + 1)) return false;
    // The pixel and its 8 neighbours: a brightest pixel on the horizon (or another edge of the region) may
    // fall just outside the earlier view's region (measured: 1.5e-5 above the horizon, in the pixel below it).
    const int ix = int(std::floor(px)), iy = int(std::floor(py));
    for (int y = std::max(0, iy - 1); y <= std::min(camera.height - 1, iy + 1); ++y)
        for (int x = std::max(0, ix - 1); x <= std::min(camera.width - 1, ix + 1); ++x)
            if (double(L[size_t(y) * size_t(camera.width) + size_t(x)]) >= level) return true;
    return false;
}

/// The final render(s) of the frame and their analysis: one render and measureImage, or n x n jittered
/// renders combined by the Supersampler.
analysis::Shape analyse(const ViewFn& view, const PinholeCamera& cam, const PixelRect& crop, const MeasureSetup& setup,
                        Measurement& m, const PartAim* part = nullptr, double level = 0,
                        std::vector<float>* luminance = nullptr) {
    thread_local ImageF img;  // reused: the readback never reallocates (4 MB at 512x512)
    const int n = setup.supersample;
    analysis::Options options = setup.options;
    options.level = level;
    m.shadedPixels = crop.empty() ? long(cam.width) * cam.height : long(crop.width) * crop.height;
    if (n <= 1) {
        auto t0 = Clock::now();
        view(cam, dvec2(0.0), crop, img, {});
        m.render_ms += msSince(t0);
        ++m.renders;
        t0 = Clock::now();
        if (part) keepPart(img, cam, *part);
        if (setup.keepImage) m.image = img;
        analysis::Shape shape = analysis::measureImage(img.data.data(), img.width, img.height, options);
        if (luminance) keepLuminance(img, *luminance);
        m.measure_ms += msSince(t0);
        return shape;
    }
    const int w = crop.empty() ? cam.width : crop.width, h = crop.empty() ? cam.height : crop.height;
    analysis::Supersampler ss(w, h, n * n);
    for (const dvec2 jitter : analysis::jitterGrid(n)) {
        auto t0 = Clock::now();
        view(cam, jitter, crop, img, {});
        m.render_ms += msSince(t0);
        ++m.renders;
        t0 = Clock::now();
        if (part) keepPart(img, cam, *part);
        ss.add(img.data.data());
        if (luminance) keepLuminance(img, *luminance);  // the last jitter's: enough to tell which region it is
        m.measure_ms += msSince(t0);
    }
    const auto t0 = Clock::now();
    analysis::Shape shape = ss.measure(options);
    m.measure_ms += msSince(t0);
    return shape;
}

/// Whether the aiming render resolved the lobe well enough to crop to it: at least 2 of its pixels across
/// the twin's minor axis. A thinner lobe falls between the aiming render's pixel centres in places, so its
/// box can miss whole stretches of the region (measured: anisotropic Beckmann 1e-4 x 1 at 45 deg, 256^2,
/// 1.4 aiming pixels across: the crop kept a 5.0 deg piece of a region that runs past the frame's edge, and
/// hid the `clipped` flag).
bool aimResolves(const LobeWidths& widths, const MeasureSetup& setup, const Frame& frame) {
    const double minor = widths.minor;
    const double pitch = 2.0 * std::tan(deg2rad(frame.fovDeg) / 2) / setup.coarseSize;  // rad per aiming pixel
    return !(minor > 0) || 2.0 * minor >= 2.0 * pitch;
}

/// lobe = mirror: the pixels outside the lobe's mask (MirrorLobe::holds) set to 0, then every component of
/// {L >= level} (4-connected; the level 0.1% lower, as keepPart's) but the one nearest the lobe's peak.
void keepMirror(ImageF& img, const PartAim& part) {
    const int W = img.width, H = img.height;
    const size_t n = size_t(W) * size_t(H);
    const double level = part.level * (1.0 - 1e-3);
    const dvec2 peak = part.mirror->peakUV;
    size_t nearest = n;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i) {
        float* q = &img.data[4 * i];
        if (!part.mirror->holds(q[1], q[2], q[0])) q[0] = 0.f;
        if (!(double(q[0]) >= level)) continue;
        const double d = glm::length(dvec2(q[1], q[2]) - peak);
        if (d < best) best = d, nearest = i;
    }
    if (nearest == n) return;
    const size_t brightest = nearest;
    thread_local std::vector<char> seen;
    thread_local std::vector<size_t> stack;
    seen.assign(n, 0);
    stack.assign(1, brightest);
    seen[brightest] = 1;
    while (!stack.empty()) {
        const size_t i = stack.back();
        stack.pop_back();
        const int x = int(i % size_t(W)), y = int(i / size_t(W));
        const auto visit = [&](int nx, int ny) {
            if (nx < 0 || ny < 0 || nx >= W || ny >= H) return;
            const size_t j = size_t(ny) * size_t(W) + size_t(nx);
            if (!seen[j] && double(img.data[4 * j]) >= level) seen[j] = 1, stack.push_back(j);
        };
        visit(x - 1, y), visit(x + 1, y), visit(x, y - 1), visit(x, y + 1);
    }
    for (size_t i = 0; i < n; ++i)
        if (!seen[i] && double(img.data[4 * i]) >= level) img.data[4 * i] = 0.f;
}

void keepPart(ImageF& img, const PinholeCamera& cam, const PartAim& part) {
    if (part.mirror) return keepMirror(img, part);
    // Image components of {L >= level} (4-connected; the level 0.1% lower so that each component holds all of
    // its part's pixels however the float peak differs from the twin's), each owned by the survey part its
    // brightest pixel lies in (the first in row order where several tie); the pixels of components owned by
    // another part are set to 0. Components are found as runs of a row joined to the runs they touch in the
    // row below (union-find): a pixel costs one comparison, where a flood fill pushed and popped each one.
    // A component this part owns whose brightest pixel lies in a region an earlier part's view measured is
    // a piece of that region, cut by this view's edge so that its brightest pixel is not the region's (a GGX
    // 0.05 x 0.2 lobe at 60 deg, split in 3 by the survey: the second view counted 76 deg^2 of the first's).
    const MirrorChart chart = part.scene->light.chart();
    const int W = img.width, H = img.height;
    const double level = part.level * (1.0 - 1e-3);
    struct Run {
        int y, x0, x1;  ///< pixels [x0, x1) of row y
    };
    thread_local std::vector<Run> runs;
    thread_local std::vector<int> up, rowStart, brightest;
    thread_local std::vector<char> another;  // per component (at its root): another part owns it
    runs.clear();
    rowStart.assign(size_t(H) + 1, 0);
    auto L = [&](int x, int y) { return double(img.data[4 * (size_t(y) * size_t(W) + size_t(x))]); };
    for (int y = 0; y < H; ++y) {
        rowStart[size_t(y)] = int(runs.size());
        for (int x = 0; x < W;) {
            if (!(L(x, y) >= level)) {
                ++x;
                continue;
            }
            const int x0 = x;
            while (x < W && L(x, y) >= level) ++x;
            runs.push_back({y, x0, x});
        }
    }
    rowStart[size_t(H)] = int(runs.size());
    up.resize(runs.size());
    for (size_t r = 0; r < runs.size(); ++r) up[r] = int(r);
    const auto find = [&](int r) {
        while (up[size_t(r)] != r) r = up[size_t(r)] = up[size_t(up[size_t(r)])];
        return r;
    };
    for (int y = 1; y < H; ++y) {  // join each run to the runs of the row below that share a column with it
        int b = rowStart[size_t(y) - 1];
        for (int a = rowStart[size_t(y)]; a < rowStart[size_t(y) + 1]; ++a) {
            while (b < rowStart[size_t(y)] && runs[size_t(b)].x1 <= runs[size_t(a)].x0) ++b;
            for (int c = b; c < rowStart[size_t(y)] && runs[size_t(c)].x0 < runs[size_t(a)].x1; ++c) {
                const int ra = find(a), rc = find(c);
                if (ra != rc) up[size_t(std::max(ra, rc))] = std::min(ra, rc);
            }
        }
    }
    brightest.assign(runs.size(), -1);  // per component (at its root): the brightest pixel, as y * W + x
    for (size_t r = 0; r < runs.size(); ++r) {
        const Run& run = runs[r];
        int& best = brightest[size_t(find(int(r)))];
        for (int x = run.x0; x < run.x1; ++x)
            if (best < 0 || L(x, run.y) > L(best % W, best / W)) best = run.y * W + x;
    }
    another.assign(runs.size(), 0);
    for (size_t r = 0; r < runs.size(); ++r) {
        if (find(int(r)) != int(r)) continue;  // one decision per component, at its root
        const float* q = &img.data[4 * size_t(brightest[r])];
        int owner = part.survey->partAt(chart.direction(q[1], q[2]));
        if (owner < 0) {  // beyond the survey's samples: the part whose box holds it, else this view's
            owner = part.part;
            for (size_t k = 0; k < part.survey->parts.size(); ++k) {
                const SurveyPart& b = part.survey->parts[k];
                if (q[1] >= b.u0 && q[1] <= b.u1 && q[2] >= b.v0 && q[2] <= b.v1) {
                    owner = int(k);
                    break;
                }
            }
        }
        if (owner == part.part && part.counted) {
            const int b = brightest[r];
            const dvec3 ray = cam.ray(b % W + 0.5, b / W + 0.5);
            for (const CountedView& v : *part.counted)
                if (v.holds(ray)) owner = -1;
        }
        another[r] = owner != part.part;
    }
    for (size_t r = 0; r < runs.size(); ++r) {
        if (!another[size_t(find(int(r)))]) continue;
        const Run& run = runs[r];
        for (int x = run.x0; x < run.x1; ++x) img.data[4 * (size_t(run.y) * size_t(W) + size_t(x))] = 0.f;
    }
}

/// A region in several parts (the survey found them): each part framed and measured in a view of its own,
/// at the level of the global peak (frac x the twin's sup, which the survey climbed to: the brightest pixel of
/// the part said to hold it can miss it), and the parts' moments added (they are disjoint). `parts` says each
/// part's own ellipse; the peak, its place and the widths through it come from the view with the brightest pixel.
Measurement measureParts(const ViewFn& view, const render::Scene& scene, const MeasureSetup& setup,
                         const LobeSurvey& survey) {
    Measurement m;
    m.framing = "automatic (" + std::to_string(survey.parts.size()) + " parts, a view each)";
    const MirrorChart chart = scene.light.chart();
    analysis::Shape total;
    analysis::AreaMoments moments;
    // Measured: a ring NDF (10-11 deg) at 30 deg, split in 12 by the survey: the first part's view kept only a
    // 1 deg^2 sliver of the ring (its other pieces owned elsewhere), brightest pixel 5.0 where the ring reaches
    // 10.0; at half of 5.0 the region was 262 deg^2 instead of 251.
    const double level = survey.level;
    std::vector<CountedView> counted;
    size_t peakPart = 0;
    for (size_t k = 0; k < survey.parts.size(); ++k) {
        const SurveyPart& p = survey.parts[k];
        PartAim part{&scene, &survey, int(k), level, &counted};
        const double half = 0.5 * std::max(p.u1 - p.u0, p.v1 - p.v0);
        Frame frame{liftAboveHorizon(chart.direction(0.5 * (p.u0 + p.u1), 0.5 * (p.v0 + p.v1))),
                    std::clamp(2.0 * rad2deg(std::atan(std::tan(std::min(half, 1.3)))), kMinFovDeg, kMaxFovDeg)};
        aimFrame(view, scene, setup, frame, m, &part);
        const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, setup.width, setup.height);
        CountedView seen{cam, {}, level};
        const analysis::Shape s = analyse(view, cam, PixelRect{}, setup, m, &part, level, &seen.L);
        const bool measured = !s.has(analysis::Flag::NoHighlight);
        if (k == 0) {
            total = s;  // the peak, its place and the widths through it (unless a later view sees a brighter pixel)
            total.flags.erase(analysis::Flag::NoHighlight);  // said below if no part has a region
            if (!measured) total.region_pixels = 0, total.minor_pixels = std::numeric_limits<double>::infinity();
            m.fovDeg = frame.fovDeg;
            m.center = frame.center;
        } else {
            if (s.peak > total.peak) {
                total.peak = s.peak, total.peak_u_deg = s.peak_u_deg, total.peak_v_deg = s.peak_v_deg;
                total.fwhm_u_deg = s.fwhm_u_deg, total.fwhm_v_deg = s.fwhm_v_deg;
                peakPart = k;
            }
            if (measured) {
                total.region_pixels += s.region_pixels;
                total.minor_pixels = std::min(total.minor_pixels, s.minor_pixels);
            }
            for (analysis::Flag f : s.flags)
                if (f != analysis::Flag::NoHighlight) total.flags.insert(f);
            // A view that found nothing of its part: the survey's part is another's (joined to it below the
            // survey's resolution, so measured in that one's view) or lies below the level: nothing is missing.
            // A part that runs out of its view is `clipped` (the flags above), not lost.
        }
        analysis::PartShape ps;
        setEllipse(ps, s.moments);
        ps.horizon_cut = s.has(analysis::Flag::HorizonCut);
        ps.measured = measured;
        if (ps.measured) moments = analysis::combine(moments, s.moments);
        counted.push_back(std::move(seen));
        total.parts.push_back(ps);
    }
    total.parts[peakPart].holds_peak = true;
    setEllipse(total, moments);
    total.components = 0;
    for (const auto& ps : total.parts) total.components += ps.measured;
    if (total.components == 0) total.flags.insert(analysis::Flag::NoHighlight), total.minor_pixels = 0;
    if (total.components < 2) total.parts.clear();
    m.shape = total;
    return m;
}

/// With a fixed frame the parts outside it are not measured: say so.
void flagPartsOutside(const render::Scene& scene, const LobeSurvey& survey, const PinholeCamera& cam,
                      analysis::Shape& shape) {
    const MirrorChart chart = scene.light.chart();
    for (const SurveyPart& p : survey.parts) {
        double nx = 0, ny = 0;
        const dvec3 we = chart.direction(p.seed.x, p.seed.y);
        if (!cam.project(-we, nx, ny) || std::abs(nx) > 1 || std::abs(ny) > 1) {
            shape.flags.insert(analysis::Flag::PartsNotMeasured);
            return;
        }
    }
}

/// The survey, where the scene has what it needs: a CPU twin, a flat surface (bumps are framed by their
/// analytic twin), a lobe with a peak.
std::optional<LobeSurvey> surveyFor(const render::Scene& scene, double threshold) {
    if (!render::hasTwin(scene) || scene.surface.bumps) return std::nullopt;
    LobeSurvey s = surveyLobe(scene, threshold);
    if (!(s.peak > 0)) return std::nullopt;
    return s;
}

/// A peak on the horizon: the widths along the chart lines through it that leave the visible hemisphere on
/// both sides there are not the lobe's (0 in the limit; a pixel centre 0.01 deg above the horizon gave 33.7 deg
/// along an image column): null, flagged peak_on_horizon. The line that climbs into the region keeps its width.
void flagPeakOnHorizonAt(const render::Scene& scene, dvec2 p, analysis::Shape& shape) {
    if (analysis::unmeasured(shape) || shape.has(analysis::Flag::NoHighlight)) return;
    const MirrorChart chart = scene.light.chart();
    // 1e-3 rad along the line: far past the peak's height above the horizon (the climb ends within ~1e-10 rad
    // of it), near enough that the line has not curved back up.
    const double e = 1e-3;
    const auto leaves = [&](dvec2 d) {
        return chart.direction(p.x + e * d.x, p.y + e * d.y).z <= 0 &&
               chart.direction(p.x - e * d.x, p.y - e * d.y).z <= 0;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (leaves({1, 0})) shape.fwhm_u_deg = nan, shape.flags.insert(analysis::Flag::PeakOnHorizon);
    if (leaves({0, 1})) shape.fwhm_v_deg = nan, shape.flags.insert(analysis::Flag::PeakOnHorizon);
}

void flagPeakOnHorizon(const render::Scene& scene, const std::optional<LobeSurvey>& survey, analysis::Shape& shape) {
    if (survey && survey->peakOnHorizon && !survey->unbounded) flagPeakOnHorizonAt(scene, survey->peakUV, shape);
}

/// The region's level where no pixel centre reaches the peak: a peak on the horizon is the lobe's limit there,
/// and the brightest pixel lies up to a pixel above it (measured: 1% below the sup at 512^2, GGX 0.2 + Smith +
/// Schlick at 45 deg, the aspect 1.1% off). Else 0: threshold x the image's own peak.
double horizonLevel(const std::optional<LobeSurvey>& survey, double threshold) {
    return survey && survey->peakOnHorizon && !survey->unbounded ? threshold * survey->peak : 0.0;
}

/// A lobe the survey found unbounded toward the horizon has no peak, however ordinary its pixels look.
void flagUnbounded(const std::optional<LobeSurvey>& survey, analysis::Shape& shape) {
    if (survey && survey->unbounded) shape.flags.insert(analysis::Flag::UnboundedAtHorizon);
}

/// The end of a measurement through one frame: a float diagnosis leaves no numbers (the flags raised before described
/// numbers that are not there), no highlight no parts, and the frame the final render used.
Measurement finish(Measurement& m, const Frame& frame) {
    if (analysis::unmeasured(m.shape))
        analysis::setUnmeasured(m.shape, m.shape.has(analysis::Flag::FloatOverflow) ? analysis::Flag::FloatOverflow
                                                                                    : analysis::Flag::FloatUnderflow);
    if (m.shape.has(analysis::Flag::NoHighlight)) m.shape.components = 0;
    m.fovDeg = frame.fovDeg;
    m.center = frame.center;
    return m;
}

/// lobe = mirror and no lobe holds the mirror direction: a named diagnosis, no numbers (or no_highlight where the
/// scene has no lobe anywhere).
analysis::Shape mirrorNotFound(const render::Scene& scene, const MeasureSetup& setup, Path path) {
    analysis::Shape shape;
    const MirrorLobe& lobe = findMirrorLobe(scene, setup.options.threshold);
    const bool elsewhere = lobe.peak > 0 || surveyLobe(scene, setup.options.threshold).peak > 0;
    if (elsewhere) {
        analysis::setUnmeasured(shape, analysis::Flag::NoMirrorLobe);
        return shape;
    }
    shape.flags.insert(analysis::Flag::NoHighlight);
    shape.components = 0;
    diagnose(scene, setup.options.threshold, path, shape);  // a delta lobe: mirror, not no_highlight
    return shape;
}

/// lobe = mirror (mirror_lobe.hpp): the lobe framed from its rays, every render masked to it (keepMirror).
Measurement measureMirror(const ViewFn& view, Path path, const render::Scene& scene, const MeasureSetup& setup) {
    const double frac = setup.options.threshold;
    const MirrorLobe& lobe = findMirrorLobe(scene, frac);
    const MirrorChart chart = scene.light.chart();
    Measurement m;
    m.framing = setup.fovDeg > 0 ? "fixed (mirror lobe)" : "automatic (mirror lobe)";
    Frame frame{liftAboveHorizon(chart.wr()), setup.fovDeg};
    m.fovDeg = frame.fovDeg;
    m.center = frame.center;
    if (!lobe.found) {
        m.shape = mirrorNotFound(scene, setup, path);
        return m;
    }
    PartAim part{&scene, nullptr, 0, lobe.level, nullptr, &lobe};
    Aim aim;
    if (setup.fovDeg <= 0) {
        double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
        lobe.box(u0, u1, v0, v1);
        const double half = 0.5 * std::max(u1 - u0, v1 - v0);
        frame = {
            liftAboveHorizon(chart.direction(0.5 * (u0 + u1), 0.5 * (v0 + v1))),
            std::clamp(2.0 * rad2deg(std::atan(std::tan(std::min(half, 1.3)) / setup.fill)), kMinFovDeg, kMaxFovDeg)};
        aim = aimFrame(view, scene, setup, frame, m, &part);
    }
    const LobeWidths widths = twinLobeWidths(scene, frac);
    const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, setup.width, setup.height);
    const PixelRect crop = setup.crop && aim.good && aimResolves(widths, setup, frame) ? cropOf(aim, cam) : PixelRect{};
    const double level = lobe.peakOnHorizon ? lobe.level : 0.0;  // no pixel centre reaches a horizon peak
    m.shape = analyse(view, cam, crop, setup, m, &part, level);
    if (!crop.empty() && m.shape.has(analysis::Flag::Clipped))
        m.shape = analyse(view, cam, PixelRect{}, setup, m, &part, level);
    diagnose(scene, frac, path, m.shape, &widths);
    if (lobe.saddleCut && !analysis::unmeasured(m.shape)) m.shape.flags.insert(analysis::Flag::SaddleCut);
    if (lobe.peakOnHorizon) flagPeakOnHorizonAt(scene, lobe.peakUV, m.shape);
    return finish(m, frame);
}

Measurement measureWith(const ViewFn& view, Path path, const render::Scene& scene, const MeasureSetup& setup) {
    if (setup.supersample < 1 || setup.supersample > kMaxSupersample)
        throw InputError("--supersample: must be a whole number in [1, " + std::to_string(kMaxSupersample) + "] (got " +
                         std::to_string(setup.supersample) + ")");
    if (setup.options.lobe == analysis::Lobe::Mirror) return measureMirror(view, path, scene, setup);
    const std::optional<LobeSurvey> survey = surveyFor(scene, setup.options.threshold);
    if (survey && !survey->unbounded && survey->parts.size() > 1 && setup.fovDeg <= 0) {
        Measurement m = measureParts(view, scene, setup, *survey);
        diagnose(scene, setup.options.threshold, path, m.shape);
        flagPeakOnHorizon(scene, survey, m.shape);
        return m;
    }
    Measurement m;
    m.framing = setup.fovDeg > 0 ? "fixed" : "automatic";
    Frame frame{liftAboveHorizon(scene.light.chart().wr()), setup.fovDeg};
    // The twin's widths: for the crop's decision and the diagnoses (computed once: ~1000 twin evaluations),
    // while the first aiming render is drawn: this core left idle there made the final render slower.
    LobeWidths widths;
    bool haveWidths = false;
    const std::function<void()> findWidths = [&] {
        widths = twinLobeWidths(scene, setup.options.threshold);
        haveWidths = true;
    };
    Aim aim;
    if (setup.fovDeg <= 0) aim = aimFrame(view, scene, setup, frame, m, nullptr, findWidths);
    if (!haveWidths) findWidths();
    const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, setup.width, setup.height);
    const PixelRect crop = setup.crop && aim.good && aimResolves(widths, setup, frame) ? cropOf(aim, cam) : PixelRect{};
    const double level = horizonLevel(survey, setup.options.threshold);
    m.shape = analyse(view, cam, crop, setup, m, nullptr, level);
    m.crop = crop, m.level = level, m.inFrame = true;
    // The region reached the crop's edge: the crop was too tight, not the frame. Measure the whole frame.
    if (!crop.empty() && m.shape.has(analysis::Flag::Clipped)) {
        m.shape = analyse(view, cam, PixelRect{}, setup, m, nullptr, level);
        m.crop = PixelRect{};
    }
    diagnose(scene, setup.options.threshold, path, m.shape, &widths);  // mirror, sub-pixel lobes, float limits
    if (survey && !survey->unbounded && survey->parts.size() > 1) flagPartsOutside(scene, *survey, cam, m.shape);
    flagUnbounded(survey, m.shape);
    flagPeakOnHorizon(scene, survey, m.shape);
    return finish(m, frame);
}

}  // namespace

Measurement measureGl(render::Renderer& renderer, const render::Scene& given, const MeasureSetup& setup) {
    const bool mirror = setup.options.lobe == analysis::Lobe::Mirror;
    if (mirror) render::requireTwin(given, "--lobe mirror");
    // No CPU twin (a .brdf file): framed from coarse renders alone, error from resolution convergence.
    if (!render::hasTwin(given)) return measureBlind(renderer, given, setup);
    // Framed by the twin of what is drawn: an area light's rule, not its exact integral (40 -> 4 ms for the sun).
    const render::Scene scene = given.light.twinRings != 0 ? given : render::withRuleTwin(given);
    // A peak far from the mirror direction (retroreflection): framed and measured about the peak.
    if (const auto framed = mirror ? std::nullopt : frameAboutPeak(scene, setup.options.threshold))
        return measureGl(renderer, *framed, setup);
    return measureWith(
        [&](const PinholeCamera& cam, dvec2 jitter, const PixelRect& crop, ImageF& img,
            const std::function<void()>& whileDrawing) {
            renderer.render(scene, cam, render::Output::Measure, img, jitter, crop, whileDrawing);
        },
        Path::Gl, scene, setup);
}

Measurement measureInFrame(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup,
                           const Measurement& like) {
    if (!like.inFrame) throw std::logic_error("measurement::measureInFrame: `like` was not measured in one frame");
    Measurement m;
    m.framing = "fixed";
    const PinholeCamera cam = measurementCamera(scene, like.center, like.fovDeg, setup.width, setup.height);
    const ViewFn view = [&](const PinholeCamera& c, dvec2 jitter, const PixelRect& crop, ImageF& img,
                            const std::function<void()>& whileDrawing) {
        renderer.render(scene, c, render::Output::Measure, img, jitter, crop, whileDrawing);
    };
    m.shape = analyse(view, cam, like.crop, setup, m, nullptr, like.level);
    if (!like.crop.empty() && m.shape.has(analysis::Flag::Clipped))
        m.shape = analyse(view, cam, PixelRect{}, setup, m, nullptr, like.level);
    return finish(m, Frame{like.center, like.fovDeg});
}

Measurement measureCpu(const render::Scene& given, const MeasureSetup& setup) {
    const render::Scene scene = given.light.twinRings != 0 ? given : render::withRuleTwin(given);
    const bool mirror = setup.options.lobe == analysis::Lobe::Mirror;
    if (const auto framed = mirror ? std::nullopt : frameAboutPeak(scene, setup.options.threshold))
        return measureCpu(*framed, setup);
    return measureWith(
        [&](const PinholeCamera& cam, dvec2 jitter, const PixelRect& crop, ImageF& img,
            const std::function<void()>& whileDrawing) {
            if (whileDrawing) whileDrawing();
            render::renderMeasureCpu(scene, cam, img, jitter, crop, setup.threads);
        },
        Path::Cpu, scene, setup);
}

Measurement measure(render::Renderer* renderer, const render::Scene& scene, const MeasureSetup& setup) {
    if (setup.cpu) return measureCpu(scene, setup);
    if (!renderer) throw std::logic_error("measurement::measure: the GL path needs a renderer");
    return measureAny(*renderer, scene, setup);  // bump fields go through measureBumps
}

namespace {

/// lobe = mirror: the polar contour about the lobe's peak, of the twin masked as the pixels are (mirror_lobe.hpp).
Measurement measureMirrorReference(const render::Scene& scene, const analysis::Options& options) {
    Measurement m;
    m.framing = "reference (mirror lobe)";
    const auto t0 = Clock::now();
    const MirrorLobe& lobe = findMirrorLobe(scene, options.threshold);
    if (!lobe.found) {
        MeasureSetup setup;
        setup.options = options;
        m.shape = mirrorNotFound(scene, setup, Path::Reference);
        m.measure_ms = msSince(t0);
        return m;
    }
    const analysis::LobeFunction f = twinLobe(scene);
    const auto mask = std::make_shared<const MirrorLobe>(lobe);
    analysis::LobeFunction masked;
    masked.lobe = [f, mask](double u, double v) {
        const double L = f.lobe(u, v);
        return mask->holds(u, v, L) ? L : 0.0;
    };
    masked.visible = f.visible;
    double radius = 0;
    for (int k = 0; k < kMirrorLobeRays; ++k)
        radius = std::max(radius, mask->maskRadius(2.0 * kPi * k / kMirrorLobeRays));
    m.shape = analysis::measureReference(masked, options, std::min(radius, kPi), lobe.peakUV.x, lobe.peakUV.y);
    diagnose(scene, options.threshold, Path::Reference, m.shape);
    if (lobe.saddleCut && !analysis::unmeasured(m.shape)) m.shape.flags.insert(analysis::Flag::SaddleCut);
    if (lobe.peakOnHorizon) flagPeakOnHorizonAt(scene, lobe.peakUV, m.shape);
    m.measure_ms = msSince(t0);
    return m;
}

}  // namespace

namespace {

/// The twin's cheap enclosure under a light with size integrated exactly (render/area_bounds.hpp); none otherwise.
analysis::LobeBounds twinBounds(const render::Scene& scene) {
    if (!scene.light.area() || scene.light.twinRings != 0) return {};
    const auto copy = std::make_shared<const render::Scene>(scene);
    const MirrorChart chart = scene.light.chart();
    const dvec3 eye = render::eyePosition(scene);
    return [copy, chart, eye](double u, double v, double& lo, double& hi) {
        const dvec3 we = chart.direction(u, v);
        if (we.z <= 0.0) return false;
        return render::areaLuminanceBounds(*copy, eye - (eye.z / we.z) * we, we, lo, hi);  // surfaceRadiance's point
    };
}

}  // namespace

Measurement measureReference(const render::Scene& scene, const analysis::Options& options) {
    render::requireTwin(scene, "--reference");
    if (options.lobe == analysis::Lobe::Mirror) return measureMirrorReference(scene, options);
    if (const auto framed = frameAboutPeak(scene, options.threshold)) return measureReference(*framed, options);
    Measurement m;
    m.framing = "reference";
    const auto t0 = Clock::now();
    const LobeSurvey survey = surveyLobe(scene, options.threshold);
    const analysis::LobeFunction f = twinLobe(scene);
    const double radius = std::min(4.0 * twinHalfWidth(scene, options.threshold), kPi / 2);
    if (survey.peak > 0 && !survey.unbounded) {
        // Fast path (~5 ms): the polar contour about the peak, where the region is one part, proven star-shaped
        // about the global peak, and the horizon does not cut it (a kink there: second order only).
        // Else the scan lines (~0.1-1 s), which assume nothing.
        bool polar = survey.parts.size() == 1 && !survey.parts[0].horizon && !survey.peakOnHorizon;
        if (polar) {
            m.shape =
                analysis::measureReference(f, twinBounds(scene), options, radius, survey.peakUV.x, survey.peakUV.y);
            polar = m.shape.peak >= survey.peak * (1.0 - 1e-9) && !m.shape.has(analysis::Flag::NotStarShaped) &&
                    !m.shape.has(analysis::Flag::HorizonCut);
        }
        if (!polar)
            m.shape = analysis::measureLines(f, options, survey.peak, survey.peakUV.x, survey.peakUV.y, survey.boxes());
    } else {  // no lobe, or one without a peak (G = 1 at the horizon): about the mirror direction, flagged
        m.shape = analysis::measureReference(f, options, radius);
        if (survey.unbounded) m.shape.flags.insert(analysis::Flag::UnboundedAtHorizon);
    }
    diagnose(scene, options.threshold, Path::Reference, m.shape);
    if (survey.peak > 0 && !survey.unbounded) flagPeakOnHorizon(scene, survey, m.shape);
    m.measure_ms = msSince(t0);
    return m;
}

}  // namespace hilite::measurement
