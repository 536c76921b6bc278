#include "micro/fft.hpp"

#include "hilite/core/math.hpp"

#include <utility>

namespace hilite::micro {

void fft1d(Complex* a, int n, bool inverse, int stride) {
    auto at = [&](int i) -> Complex& { return a[size_t(i) * size_t(stride)]; };
    for (int i = 1, j = 0; i < n; ++i) {  // bit-reversal permutation
        int bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(at(i), at(j));
    }
    for (int len = 2; len <= n; len <<= 1) {
        const double ang = 2.0 * kPi / len * (inverse ? 1.0 : -1.0);
        const Complex wl(std::cos(ang), std::sin(ang));
        for (int i = 0; i < n; i += len) {
            Complex w(1.0, 0.0);
            for (int k = 0; k < len / 2; ++k) {
                const Complex u = at(i + k), v = at(i + k + len / 2) * w;
                at(i + k) = u + v;
                at(i + k + len / 2) = u - v;
                w *= wl;
            }
        }
    }
}

void fft2d(std::vector<Complex>& a, int n, bool inverse) {
    for (int r = 0; r < n; ++r) fft1d(a.data() + size_t(r) * size_t(n), n, inverse, 1);
    for (int c = 0; c < n; ++c) fft1d(a.data() + c, n, inverse, n);
}

}  // namespace hilite::micro
