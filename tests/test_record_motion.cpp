// RecordMotion: sign, scales, piecewise-linear interpolation, zero outside the record.
#include <catch2/catch.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_motion.hpp"

using namespace adjoin;

TEST_CASE("record motion interpolates the negated record in scaled time and units", "[record_motion]") {
  Record r;
  r.source = "test.at2";
  r.dt = 0.02;
  r.accel = {0.0, 9.80665, -2.0 * 9.80665, 4.0};  // m/s^2 at 0, 0.02, 0.04, 0.06 s
  const double T0 = 0.5, g = 9.80665;
  const RecordMotion m(r, T0, g);
  // Samples: t = t_s / T0.
  CHECK(m.ag(0.0) == 0.0);
  CHECK(m.ag(0.02 / T0) == Approx(-1.0).epsilon(1e-14));
  CHECK(m.ag(0.04 / T0) == Approx(2.0).epsilon(1e-14));
  CHECK(m.ag(0.06 / T0) == Approx(-4.0 / g).epsilon(1e-14));
  // Between samples: a quarter of the way from 0.02 s to 0.04 s.
  CHECK(m.ag(0.025 / T0) == Approx(-(1.0 + 0.25 * (-3.0))).epsilon(1e-12));
  // Midway in the last step.
  CHECK(m.ag(0.05 / T0) == Approx(-0.5 * (-2.0 * g + 4.0) / g).epsilon(1e-12));
  // Outside the record.
  CHECK(m.ag(-0.01) == 0.0);
  CHECK(m.ag(0.0601 / T0) == 0.0);
  CHECK(m.ag(100.0) == 0.0);
  CHECK(m.duration() == Approx(0.06 / T0));
  CHECK(m.describe().find("test.at2") != std::string::npos);
  CHECK(m.describe().find("PGA 2 g") != std::string::npos);
}

TEST_CASE("record motion: unit scales and validation", "[record_motion]") {
  Record r;
  r.source = "x";
  r.dt = 0.01;
  r.accel = {1.0, 3.0};
  const RecordMotion si(r, 1.0, 1.0);  // seconds and m/s^2
  CHECK(si.ag(0.005) == Approx(-2.0));
  CHECK_THROWS_AS(RecordMotion(r, 0.0, 1.0), InputError);
  CHECK_THROWS_AS(RecordMotion(r, 1.0, -1.0), InputError);
  Record empty = r;
  empty.accel.clear();
  CHECK_THROWS_AS(RecordMotion(empty, 1.0, 1.0), InputError);
}
