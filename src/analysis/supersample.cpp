#include "analysis/supersample.hpp"

#include "hilite/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace hilite::analysis {

std::vector<dvec2> jitterGrid(int n) {
    std::vector<dvec2> out;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) out.emplace_back((i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5);
    return out;
}

Supersampler::Supersampler(int width, int height, int samples) : m_width(width), m_height(height), m_samples(samples) {
    if (width < 1 || height < 1) throw InputError("Supersampler: empty image");
    if (samples < 1 || samples > 1024)
        throw InputError("Supersampler: samples must be in [1, 1024] (got " + std::to_string(samples) + ")");
    const size_t n = size_t(width) * size_t(height);
    m_L.assign(n * size_t(samples), -1.f);
    m_sums.assign(n, {});
}

void Supersampler::add(const float* pixels) {
    if (m_added >= m_samples) throw InputError("Supersampler: more renders than samples");
    const size_t n = m_sums.size(), s = size_t(m_added), k = size_t(m_samples);
    for (size_t p = 0; p < n; ++p) {
        const float* q = pixels + 4 * p;
        if (!(q[3] > 0.f)) continue;                   // sees no surface: stays -1, adds nothing to the position
        const float L = std::max(0.f, q[0]);           // (a negative or NaN L counts as 0, as in measureImage)
        if (!std::isfinite(q[0])) m_nonFinite = true;  // float_overflow, as in measureImage
        m_L[p * k + s] = L;
        PixelSums& ps = m_sums[p];
        ps.u += q[1], ps.v += q[2], ps.w += q[3], ++ps.visible;
        if (L > m_peak) m_peak = L, m_peakPixel = p;
    }
    ++m_added;
}

namespace {

/// Per pixel of the combined frame: coverage in [0, 1] and, where some sample sees the surface, the
/// mean position and weight.
struct Combined {
    int width, height;
    std::vector<double> coverage, u, v, w;
    std::vector<char> visible;  ///< some sample sees the surface
    std::vector<char> partial;  ///< some sample sees no surface while another does (the horizon crosses it)

    size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
    dvec2 uv(size_t i) const { return {u[i], v[i]}; }
};

/// Width of the region along the line through pixel (x, y) in steps (dx, dy): each pixel's coverage
/// times the distance to its neighbour's centre, walking both ways until a pixel with no coverage.
double lineWidth(const Combined& c, int x, int y, int dx, int dy) {
    double width = 0;
    for (int dir : {1, -1})
        for (int k = dir > 0 ? 0 : 1;; ++k) {
            const int px = x + dir * k * dx, py = y + dir * k * dy;
            if (!c.inside(px, py) || c.coverage[c.index(px, py)] <= 0) break;
            const size_t i = c.index(px, py);
            size_t j = i;  // a visible neighbour along the line gives the local pitch
            for (int s : {1, -1})
                if (c.inside(px + s * dx, py + s * dy) && c.visible[c.index(px + s * dx, py + s * dy)] && j == i)
                    j = c.index(px + s * dx, py + s * dy);
            width += c.coverage[i] * (j == i ? 0.0 : glm::length(c.uv(j) - c.uv(i)));
        }
    return width;
}

}  // namespace

Shape Supersampler::measure(const Options& opt) const {
    validate(opt);
    if (m_added != m_samples)
        throw InputError("Supersampler: " + std::to_string(m_added) + " of " + std::to_string(m_samples) +
                         " renders added");
    Shape s;
    if (m_nonFinite) {  // as measureImage: pixels past float's range
        setUnmeasured(s, Flag::FloatOverflow);
        return s;
    }
    if (!(m_peak > 0.f)) {
        s.flags.insert(Flag::NoHighlight);
        return s;
    }
    const double T = opt.level > 0 ? opt.level : opt.threshold * double(m_peak);
    if (T < double(std::numeric_limits<float>::min())) {  // as measureImage: a level among the denormals
        setUnmeasured(s, Flag::FloatUnderflow);
        return s;
    }
    if (!(double(m_peak) >= T)) {
        s.flags.insert(Flag::NoHighlight);
        return s;
    }
    const size_t n = m_sums.size(), k = size_t(m_samples);
    Combined c{m_width,
               m_height,
               std::vector<double>(n, 0.0),
               std::vector<double>(n, 0.0),
               std::vector<double>(n, 0.0),
               std::vector<double>(n, 0.0),
               std::vector<char>(n, 0),
               std::vector<char>(n, 0)};
    for (size_t p = 0; p < n; ++p) {
        const PixelSums& ps = m_sums[p];
        if (ps.visible == 0) continue;
        int in = 0;
        for (size_t q = p * k; q < p * k + k; ++q) in += double(m_L[q]) >= T;
        c.coverage[p] = double(in) / double(k);
        c.u[p] = ps.u / ps.visible, c.v[p] = ps.v / ps.visible, c.w[p] = ps.w / ps.visible;
        c.visible[p] = 1;
        c.partial[p] = ps.visible < m_samples;
    }
    // Moments about the peak pixel's position (against cancellation), flags from the covered pixels.
    const dvec2 shift = c.uv(m_peakPixel);
    double s0 = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0, coveredPixels = 0;
    bool border = false, horizon = false, coversAll = true;
    for (int y = 0; y < m_height; ++y)
        for (int x = 0; x < m_width; ++x) {
            const size_t i = c.index(x, y);
            if (!c.visible[i]) continue;
            const double f = c.coverage[i];
            coversAll = coversAll && f >= 1.0;
            if (f <= 0) continue;
            const double wt = f * c.w[i], du = c.u[i] - shift.x, dv = c.v[i] - shift.y;
            s0 += wt, su += wt * du, sv += wt * dv, suu += wt * du * du, suv += wt * du * dv, svv += wt * dv * dv;
            coveredPixels += f;
            s.region_pixels += 2 * f >= 1.0;
            border = border || x == 0 || y == 0 || x == m_width - 1 || y == m_height - 1;
            horizon = horizon || c.partial[i];
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                horizon = horizon || (c.inside(x + dx, y + dy) && !c.visible[c.index(x + dx, y + dy)]);
        }
    AreaMoments m;
    m.area = s0;
    const double mu = su / s0, mv = sv / s0;
    m.mean_u = shift.x + mu, m.mean_v = shift.y + mv;
    m.cuu = suu / s0 - mu * mu, m.cuv = suv / s0 - mu * mv, m.cvv = svv / s0 - mv * mv;
    setEllipse(s, m);
    s.peak = m_peak;
    s.peak_u_deg = rad2deg(shift.x), s.peak_v_deg = rad2deg(shift.y);
    // Widths through the peak pixel; the image rows run along u or v (the measurement camera: columns along u).
    const int px = int(m_peakPixel % size_t(m_width)), py = int(m_peakPixel / size_t(m_width));
    const double alongRow = lineWidth(c, px, py, 1, 0), alongCol = lineWidth(c, px, py, 0, 1);
    const size_t right = c.inside(px + 1, py) ? c.index(px + 1, py) : c.index(std::max(0, px - 1), py);
    const dvec2 step = c.uv(right) - shift;
    const bool rowsU = std::abs(step.x) > std::abs(step.y);
    s.fwhm_u_deg = rad2deg(rowsU ? alongRow : alongCol), s.fwhm_v_deg = rad2deg(rowsU ? alongCol : alongRow);
    const double pitch = std::sqrt(s0 / coveredPixels);
    s.minor_pixels = 2.0 * deg2rad(s.minor_deg) / pitch;
    if (border) s.flags.insert(Flag::Clipped);
    if (horizon) s.flags.insert(Flag::HorizonCut);
    if (s.minor_pixels < opt.minPixelsAcross) s.flags.insert(Flag::UnderResolved);
    if (coversAll) s.flags.insert(Flag::CoversFrame);
    return s;
}

}  // namespace hilite::analysis
