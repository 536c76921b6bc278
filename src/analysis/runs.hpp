#pragma once
// Runs of kRun pixels of a row: the unit that measureImage's scans skip or visit whole (analysis/measure_image.cpp)
// and table_error's band and rounds do too (measurement/in_frame_twin.cpp), one 32-bit mask a run; and the
// compares that read a run four pixels at a time.

#include <algorithm>
#include <cstdint>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace hilite::analysis {

constexpr int kRun = 32;  ///< pixels per run of a row: one 32-bit mask

/// Bit x: lo <= c[x] <= hi, of the n <= kRun values c (a NaN sets no bit).
inline uint32_t bitsWithin(const float* c, int n, float lo, float hi) {
    uint32_t bits = 0;
    int x = 0;
#if defined(__SSE2__)
    const __m128 l = _mm_set1_ps(lo), h = _mm_set1_ps(hi);
    for (; x + 4 <= n; x += 4) {
        const __m128 v = _mm_loadu_ps(c + x);
        bits |= uint32_t(_mm_movemask_ps(_mm_and_ps(_mm_cmpge_ps(v, l), _mm_cmple_ps(v, h)))) << x;
    }
#endif
    for (; x < n; ++x) bits |= uint32_t(c[x] >= lo && c[x] <= hi) << x;
    return bits;
}

/// The smallest and the largest of the n >= 1 values c.
inline std::pair<float, float> extremes(const float* c, int n) {
    float lo = c[0], hi = c[0];
    int x = 0;
#if defined(__SSE2__)
    if (n >= 4) {
        __m128 l = _mm_loadu_ps(c), h = l;
        for (x = 4; x + 4 <= n; x += 4) {
            const __m128 v = _mm_loadu_ps(c + x);
            l = _mm_min_ps(l, v), h = _mm_max_ps(h, v);
        }
        alignas(16) float ls[4], hs[4];
        _mm_store_ps(ls, l), _mm_store_ps(hs, h);
        for (int k = 0; k < 4; ++k) lo = std::min(lo, ls[k]), hi = std::max(hi, hs[k]);
    }
#endif
    for (; x < n; ++x) lo = std::min(lo, c[x]), hi = std::max(hi, c[x]);
    return {lo, hi};
}

}  // namespace hilite::analysis
