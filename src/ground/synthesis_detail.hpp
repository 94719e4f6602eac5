#pragma once
// Private helpers of the ground-motion synthesis (synthesis.cpp, spectrum_matching.cpp, fftw_plans.cpp):
// FFTW arrays and cached one-dimensional real transforms. Plans are made once per length (FFTW_ESTIMATE, out of place, on fftw_malloc
// arrays, so the same length always gives the same plan and bit-for-bit the same results) and
// kept for the life of the process; planning is serialised by a mutex (FFTW's planner is not
// thread-safe), executing a cached plan on new arrays of the same alignment is.
#include <fftw3.h>

#include <complex>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "adjoin/ground/synthesis.hpp"

namespace adjoin::detail {

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
using RealArray = std::unique_ptr<double[], FftwFree>;
using ComplexArray = std::unique_ptr<fftw_complex[], FftwFree>;

RealArray real_array(std::size_t n);
ComplexArray complex_array(std::size_t n);

// out[j] = sum_k in[k] e^{+2 pi i j k / n} (Hermitian input of n/2 + 1 values; destroys `in`).
void inverse_real_fft(std::size_t n, fftw_complex* in, double* out);
// out[k] = sum_j in[j] e^{-2 pi i j k / n}, k = 0 .. n/2.
void forward_real_fft(std::size_t n, double* in, fftw_complex* out);

// The stationary synthesized process (synthesis.hpp) on the whole FFT grid of
// synthesis_fft_length(n) samples, with S0 = options.s0 (1 if absent); no envelope, no scaling.
std::vector<double> stationary_process(const SynthesisOptions& options);

// "filtered noise: clough-penzien omega_g=... ; envelope ...; duration=... dt=... seed=...";
// the intensity (S0 / target PGA) only if `intensity`.
std::string describe(const SynthesisOptions& options, bool intensity);

// Smallest even number >= n of the form 2^a 3^b 5^c 7^d.
std::size_t smooth_fft_length(std::size_t n);

}  // namespace adjoin::detail
