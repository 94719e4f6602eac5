#pragma once
// Velocity and displacement histories of an accelerogram: cumulative trapezoid integrals from
// rest, v(0) = d(0) = 0,
//     v_i = v_{i-1} + dt (a_{i-1} + a_i) / 2,    d_i = d_{i-1} + dt (v_{i-1} + v_i) / 2,
// second-order accurate in dt for a smooth record. No correction is made here: a baseline
// offset in the record grows linearly in v and quadratically in d, so remove it first
// (remove_baseline, a high-pass filter: ground/processing.hpp) when asked to.
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

struct MotionHistories {
  double dt = 0.0;                  // s
  std::vector<double> accel;        // m/s^2, the record's
  std::vector<double> velocity;     // m/s
  std::vector<double> displacement; // m
};

MotionHistories integrate_record(const Record& record);

}  // namespace adjoin
