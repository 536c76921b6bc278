#pragma once
// A small in-place radix-2 complex FFT (iterative Cooley-Tukey), enough to synthesize periodic random
// height fields on power-of-two grids. Cooley & Tukey 1965. Not tuned: a 1024^2 inverse 2D transform
// takes ~0.1 s.

#include <complex>
#include <vector>

namespace hilite::micro {

using Complex = std::complex<double>;

/// In-place 1D transform of a power-of-two length; inverse uses e^{+2 pi i k n / N} and no 1/N factor.
void fft1d(Complex* a, int n, bool inverse, int stride = 1);
/// In-place 2D transform of an n x n row-major grid (rows then columns), no 1/N^2 factor.
void fft2d(std::vector<Complex>& a, int n, bool inverse);

}  // namespace hilite::micro
