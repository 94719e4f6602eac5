#pragma once
// Records made from a function of time, for the post-processors' tests.
#include <cstddef>

#include "adjoin/ground/record.hpp"

namespace adjoin::test {

// n samples a[i] = f(i dt) [m/s^2].
inline Record sampled_record(double dt, std::size_t n, const auto& f) {
  Record r;
  r.source = "synthetic";
  r.dt = dt;
  r.accel.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.accel[i] = f(static_cast<double>(i) * dt);
  return r;
}

}  // namespace adjoin::test
