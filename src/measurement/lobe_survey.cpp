#include "measurement/lobe_survey.hpp"

#include "core/text.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/scene/registry.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>
#include <tuple>

namespace hilite::measurement {

namespace {

/// Elevations of the survey's rings (deg above the horizon): every 4 deg, then ever closer to the horizon,
/// where a thin part lies (the strip of GGX 0.1 + Smith + Schlick at 60 deg is ~1 deg high) and where a peak
/// on the horizon is approached.
const std::vector<double>& rings() {
    static const std::vector<double> r = [] {
        std::vector<double> v;
        for (double e = 88.0; e > 3.0; e -= 4.0) v.push_back(e);
        for (double e : {2.0, 1.0, 0.5, 0.2, 0.05, 0.01, 1e-4}) v.push_back(e);
        return v;
    }();
    return r;
}

struct Lobe {
    const render::Scene& scene;
    dvec3 eye;
    dvec3 wi = scene.light.direction();  // once: its degrees' cos and sin were a third of an evaluation
    double operator()(const dvec3& we) const {
        return we.z > 0.0 ? brdf::luminance(render::surfaceRadiance(scene, wi, eye, we)) : 0.0;
    }
};

dvec3 ringDirection(double elevationDeg, double azimuthDeg) {
    return sphericalDirectionDeg(90.0 - elevationDeg, azimuthDeg);
}

/// Compass search (8 directions) in a chart about `start`: a step that finds a higher point moves there and
/// doubles, else halves, from 1 deg down to 1e-10 rad. Points below the horizon (lobe 0) never win, so a peak
/// on the horizon is approached from above. Diagonals let it climb a thin diagonal ridge (anisotropic lobes).
std::pair<dvec3, double> climb(const Lobe& lobe, const dvec3& start, double until, double first = deg2rad(1.0)) {
    render::Scene about = lobe.scene;
    about.light.chartCenter = glm::normalize(dvec3(start.x, start.y, std::max(start.z, 1e-9)));
    const MirrorChart chart = about.light.chart();
    dvec2 q(0.0);
    double best = lobe(chart.direction(0, 0));
    static const dvec2 dirs[8] = {
        {1, 0}, {-1, 0}, {0, 1}, {0, -1}, {0.7071, 0.7071}, {-0.7071, -0.7071}, {0.7071, -0.7071}, {-0.7071, 0.7071}};
    double step = first;
    for (int iter = 0; iter < 4000 && step > until; ++iter) {
        dvec2 next = q;
        double nextValue = best;
        for (const dvec2& d : dirs) {
            const dvec2 p = q + step * d;
            const double x = lobe(chart.direction(p.x, p.y));
            if (x > nextValue) nextValue = x, next = p;
        }
        if (nextValue > best) {
            best = nextValue, q = next;
            step = std::min(2.0 * step, deg2rad(4.0));
        } else {
            step *= 0.5;
        }
    }
    return {chart.direction(q.x, q.y), best};
}

LobeSurvey scan(const render::Scene& scene);

/// The last result of a survey of a scene, per thread, keyed on the scene's registry values (scene::sceneKey).
/// It holds the scene, so a table the key names by its address stays alive (and its address unused) meanwhile.
struct LastSurvey {
    std::string key;
    render::Scene scene;
    LobeSurvey survey;
    template <class Make>
    const LobeSurvey& get(const render::Scene& s, std::string k, Make make) {
        if (k != key) {
            survey = make();
            key = std::move(k);
            scene = s;
        }
        return survey;
    }
};

/// scan(), kept per thread for the last scene: the GL path, the reference and the row ask for the same lobe,
/// framed about the mirror direction or about its peak (a directional light's lobe is the same either way).
LobeSurvey scannedLobe(const render::Scene& scene) {
    render::Scene key = scene;
    if (key.light.distant()) key.light.chartCenter.reset();
    thread_local LastSurvey last;
    return last.get(key, scene::sceneKey(key), [&] { return scan(scene); });
}

/// Union-find over the grid's samples.
struct Sets {
    std::vector<int> up;
    explicit Sets(size_t n) : up(n) { std::iota(up.begin(), up.end(), 0); }
    int find(int i) { return up[size_t(i)] == i ? i : up[size_t(i)] = find(up[size_t(i)]); }
    void join(int a, int b) { up[size_t(find(a))] = find(b); }
};

/// The lobe's samples and peak: what does not depend on the chart or the threshold (the costly part).
LobeSurvey scan(const render::Scene& scene) {
    const Lobe lobe{scene, render::eyePosition(scene)};
    const MirrorChart mirror = MirrorChart::fromDegrees(scene.light.incidenceDeg, scene.light.azimuthDeg);
    LobeSurvey s;
    s.ringsDeg = rings();
    s.azimuths = kSurveyAzimuths;
    s.azimuth0Deg = scene.light.azimuthDeg + 180.0;  // the forward direction first: the grid is symmetric about it
    const int K = int(s.ringsDeg.size()), J = s.azimuths;
    std::vector<double>& value = s.values;
    std::vector<dvec3>& dir = s.directions;
    value.resize(size_t(K) * size_t(J));
    dir.resize(value.size());
    // ringDirection's products from each ring's and each azimuth's cos and sin, computed once (the same numbers).
    std::vector<double> cosAz(static_cast<size_t>(J)), sinAz(static_cast<size_t>(J));
    for (int j = 0; j < J; ++j) cosSinDeg(s.azimuth0Deg + 360.0 * j / J, cosAz[size_t(j)], sinAz[size_t(j)]);
    for (int k = 0; k < K; ++k) {
        double ct, st;
        cosSinDeg(90.0 - s.ringsDeg[size_t(k)], ct, st);
        for (int j = 0; j < J; ++j) {
            const size_t i = size_t(k) * size_t(J) + size_t(j);
            dir[i] = {st * cosAz[size_t(j)], st * sinAz[size_t(j)], ct};
            value[i] = lobe(dir[i]);
        }
    }
    // Peak: climb from the mirror, light and normal directions and from the grid's four best local maxima.
    std::vector<std::pair<double, dvec3>> starts;
    for (const dvec3& c : {mirror.wr(), scene.light.direction(), dvec3(0, 0, 1)}) {
        const dvec3 d = glm::normalize(dvec3(c.x, c.y, std::max(c.z, 1e-6)));
        starts.push_back({lobe(d), d});
    }
    std::vector<std::pair<double, dvec3>> maxima;
    for (int k = 0; k < K; ++k)
        for (int j = 0; j < J; ++j) {
            const double x = value[size_t(k) * size_t(J) + size_t(j)];
            if (!(x > 0)) continue;
            bool top = true;
            for (auto [dk, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int kk = k + dk, jj = (j + dj + J) % J;
                if (kk >= 0 && kk < K && value[size_t(kk) * size_t(J) + size_t(jj)] > x) top = false;
            }
            if (top) maxima.push_back({x, dir[size_t(k) * size_t(J) + size_t(j)]});
        }
    std::sort(maxima.begin(), maxima.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    if (maxima.size() > 4) maxima.resize(4);
    // Nothing lit on the grid nor at the starts: a lobe thinner than the grid off the mirror direction (a ring
    // of a tabulated NDF at theta_h 0.5-0.7 deg, which the reference called no_highlight while GL measured it).
    // Circles about the mirror direction from 45 deg down to 1e-7 rad, 2^(1/8) apart, 72 azimuths each (as the GL
    // path's blind zoom): the first lit sample is a start. Only when all else is dark: no cost to a lobe found.
    if (maxima.empty() && std::none_of(starts.begin(), starts.end(), [](const auto& st) { return st.first > 0; }))
        for (double r = deg2rad(45.0); r > 1e-7 && maxima.empty(); r /= std::exp2(0.125))
            for (int j = 0; j < kSurveyAzimuths && maxima.empty(); ++j) {
                const double psi = 2.0 * kPi * j / kSurveyAzimuths;
                const dvec3 d = mirror.direction(r * std::cos(psi), r * std::sin(psi));
                if (const double x = lobe(d); x > 0) maxima.push_back({x, d});
            }
    starts.insert(starts.end(), maxima.begin(), maxima.end());
    // Every start to 1e-5 rad (starts within 2 deg of an earlier one are the same hill), then the best to
    // 1e-10 rad: the whole cost of the survey is ~2600 grid samples and ~1500 climbing ones.
    // (A start below 0.3 of the best start is a hill of its own only if a spike hides between the samples,
    // and the one such spike a lobe has, at the mirror direction, is a start itself.)
    double bestStart = 0;
    for (const auto& st : starts) bestStart = std::max(bestStart, st.first);
    std::vector<dvec3> climbed;
    for (const auto& [x, d] : starts) {
        if (!(x > 0) || x < 0.3 * bestStart) continue;
        bool seen = false;
        for (const dvec3& c : climbed) seen = seen || glm::dot(c, d) > std::cos(deg2rad(2.0));
        if (seen) continue;
        climbed.push_back(d);
        const auto [top, v] = climb(lobe, d, 1e-5);
        if (v > s.peak) s.peak = v, s.peakDirection = top;
    }
    if (s.peak > 0) std::tie(s.peakDirection, s.peak) = climb(lobe, s.peakDirection, 1e-10, 2e-5);
    if (!(s.peak > 0)) return s;
    // On the horizon: the lobe at half the peak's elevation (same azimuth) is no lower.
    const double horizontal = std::hypot(s.peakDirection.x, s.peakDirection.y);
    if (s.peakDirection.z < 0.05 && horizontal > 0) {
        const double z = 0.5 * s.peakDirection.z;
        const dvec3 below =
            dvec3(s.peakDirection.x, s.peakDirection.y, 0.0) / horizontal * std::sqrt(1.0 - z * z) + dvec3(0.0, 0.0, z);
        s.peakOnHorizon = lobe(below) >= s.peak;
        // As diagnose's unboundedAtHorizon: 1 / cos theta_o rises 1000-fold from 1e-3 to 1e-6 of the height.
        const dvec3 flat = dvec3(s.peakDirection.x, s.peakDirection.y, 0.0) / horizontal;
        auto at = [&](double h) { return lobe(glm::normalize(flat + dvec3(0.0, 0.0, h * s.peakDirection.z))); };
        s.unbounded = at(1e-6) > 100.0 * at(1e-3);
    }
    // Unbounded toward the horizon anywhere (G = 1: f ~ D / cos theta_o), however far below the survey's
    // lowest ring it starts to show (Beckmann m 0.1 at 30 deg: D ~ 5e-15 of its peak there, so the lobe only
    // passes its peak below 1e-14 rad): the lobe 1e-12 rad above the horizon against 1e-9 rad, per azimuth.
    for (int j = 0; j < J && !s.unbounded; ++j) {
        const double phi = deg2rad(s.azimuth0Deg + 360.0 * j / J);
        auto at = [&](double e) {
            return lobe(dvec3(std::cos(phi) * std::cos(e), std::sin(phi) * std::cos(e), std::sin(e)));
        };
        const double high = at(1e-9);
        s.unbounded = high > 0 && at(1e-12) > 100.0 * high;
    }
    return s;
}

LobeSurvey survey(const render::Scene& scene, double frac) {
    LobeSurvey s = scannedLobe(scene);
    const MirrorChart chart = scene.light.chart();
    if (!(s.peak > 0)) return s;
    s.peakUV = chart.coords(s.peakDirection);
    const int K = int(s.ringsDeg.size()), J = s.azimuths;
    const std::vector<double>& value = s.values;
    const std::vector<dvec3>& dir = s.directions;
    s.level = frac * s.peak;
    // Parts: the samples at or above the level, 4-connected on the grid (azimuth wraps round; the top ring's
    // samples meet across the zenith).
    Sets sets(value.size());
    auto in = [&](int k, int j) { return value[size_t(k) * size_t(J) + size_t((j + J) % J)] >= s.level; };
    auto id = [&](int k, int j) { return k * J + (j + J) % J; };
    for (int k = 0; k < K; ++k)
        for (int j = 0; j < J; ++j) {
            if (!in(k, j)) continue;
            if (in(k, j + 1)) sets.join(id(k, j), id(k, j + 1));
            if (k + 1 < K && in(k + 1, j)) sets.join(id(k, j), id(k + 1, j));
            if (k == 0 && in(0, j + J / 2)) sets.join(id(0, j), id(0, j + J / 2));
        }
    s.labels.assign(value.size(), -1);
    std::vector<int> partOfRoot(value.size(), -1);
    const double grow = deg2rad(5.0);  // the grid's widest step (azimuth, at the horizon)
    for (int k = 0; k < K; ++k)
        for (int j = 0; j < J; ++j) {
            if (!in(k, j)) continue;
            const int i = id(k, j), root = sets.find(i);
            if (partOfRoot[size_t(root)] < 0) {
                partOfRoot[size_t(root)] = int(s.parts.size());
                SurveyPart p;
                p.u0 = p.v0 = 1e9;
                p.u1 = p.v1 = -1e9;
                s.parts.push_back(p);
            }
            const int label = partOfRoot[size_t(root)];
            s.labels[size_t(i)] = label;
            SurveyPart& p = s.parts[size_t(label)];
            const dvec2 q = chart.coords(dir[size_t(i)]);
            p.u0 = std::min(p.u0, q.x - grow), p.u1 = std::max(p.u1, q.x + grow);
            p.v0 = std::min(p.v0, q.y - grow), p.v1 = std::max(p.v1, q.y + grow);
            if (value[size_t(i)] > p.maxValue) p.maxValue = value[size_t(i)], p.seed = q;
            p.horizon = p.horizon || k == K - 1;
            ++p.samples;
        }
    int peakPart = s.partAt(s.peakDirection);
    if (peakPart < 0) {  // a lobe narrower than the grid: the peak is its only sample
        SurveyPart p;
        p.u0 = s.peakUV.x - grow, p.u1 = s.peakUV.x + grow, p.v0 = s.peakUV.y - grow, p.v1 = s.peakUV.y + grow;
        p.maxValue = s.peak;
        p.seed = s.peakUV;
        p.horizon = s.peakDirection.z < 1e-3;
        s.parts.push_back(p);
        peakPart = int(s.parts.size()) - 1;
    }
    s.parts[size_t(peakPart)].holdsPeak = true;
    s.parts[size_t(peakPart)].maxValue = s.peak;
    s.parts[size_t(peakPart)].seed = s.peakUV;
    // The peak's part first, then by decreasing value; relabel the grid to match.
    std::vector<int> order(s.parts.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        const SurveyPart &pa = s.parts[size_t(a)], &pb = s.parts[size_t(b)];
        if (pa.holdsPeak != pb.holdsPeak) return pa.holdsPeak;
        return pa.maxValue > pb.maxValue;
    });
    std::vector<int> rank(order.size());
    std::vector<SurveyPart> sorted;
    for (size_t r = 0; r < order.size(); ++r)
        rank[size_t(order[r])] = int(r), sorted.push_back(s.parts[size_t(order[r])]);
    for (int& l : s.labels)
        if (l >= 0) l = rank[size_t(l)];
    s.parts = std::move(sorted);
    return s;
}

}  // namespace

int LobeSurvey::partAt(const dvec3& we) const {
    if (ringsDeg.empty() || !(we.z > 0)) return -1;
    const double elevation = rad2deg(std::asin(std::min(1.0, we.z)));
    const int K = int(ringsDeg.size());
    int k0 = 0;
    for (int k = 0; k < K; ++k)
        if (std::abs(ringsDeg[size_t(k)] - elevation) < std::abs(ringsDeg[size_t(k0)] - elevation)) k0 = k;
    const double azimuth = rad2deg(std::atan2(we.y, we.x)) - azimuth0Deg;
    const int j0 = int(std::lround(azimuth / 360.0 * azimuths));
    int best = -1;
    double bestAngle = 1e9;
    for (int k = std::max(0, k0 - 2); k <= std::min(K - 1, k0 + 2); ++k)
        for (int dj = -2; dj <= 2; ++dj) {
            const int j = ((j0 + dj) % azimuths + azimuths) % azimuths;
            const int l = labels[size_t(k) * size_t(azimuths) + size_t(j)];
            if (l < 0) continue;
            const dvec3 d = ringDirection(ringsDeg[size_t(k)], azimuth0Deg + 360.0 * j / azimuths);
            const double a = std::acos(std::clamp(glm::dot(d, we), -1.0, 1.0));
            if (a < bestAngle) bestAngle = a, best = l;
        }
    if (best < 0) {  // a part with no sample of its own (narrower than the grid) sits at the peak
        for (size_t p = 0; p < parts.size(); ++p)
            if (parts[p].samples == 0 && std::acos(std::clamp(glm::dot(peakDirection, we), -1.0, 1.0)) < deg2rad(6.0))
                return int(p);
    }
    return best;
}

std::vector<analysis::ChartBox> LobeSurvey::boxes() const {
    std::vector<analysis::ChartBox> b;
    for (const SurveyPart& p : parts) b.push_back({p.u0, p.u1, p.v0, p.v1, p.seed.x, p.seed.y});
    return b;
}

LobeSurvey surveyLobe(const render::Scene& scene, double frac) {
    render::requireTwin(scene, "the hemisphere survey");
    thread_local LastSurvey last;
    return last.get(scene, scene::sceneKey(scene) + ";frac=" + exactText(frac), [&] { return survey(scene, frac); });
}

}  // namespace hilite::measurement
