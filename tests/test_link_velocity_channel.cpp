// The link velocity channel (linkN.velocity, one row of ADJOIN_QUANTITIES in
// structure/channels.hpp), the quantity that shows a new channel is one row: the velocity of a
// spring link between two undamped one-storey frames against the closed form of the pair's
// free vibration, at the scheme's order 2; a dashpot link's force is c times it at every grid
// point, and so are their peaks in the run's report.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/observe/channel_values.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

constexpr double kMassA = 1.0e4, kMassB = 2.5e4, kSpringA = 4.0e5, kSpringB = 2.0e6, kV0 = 0.5;

// Two one-storey frames joined at floor 1 by one link.
Structure pair(Link l) {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::VectorXd::Constant(1, kMassA);
  s.a.springs = Eigen::VectorXd::Constant(1, kSpringA);
  Building b;
  b.name = "B";
  b.masses = Eigen::VectorXd::Constant(1, kMassB);
  b.springs = Eigen::VectorXd::Constant(1, kSpringB);
  s.b = b;
  l.floor_a = 1;
  l.floor_b = 1;
  s.links = {l};
  return s;
}

}  // namespace

TEST_CASE("a spring link's velocity channel is the closed form's v_A - v_B in free vibration, at order 2", "[channels]") {
  const double k_link = 3.0e5;
  Link spring;
  spring.type = LinkType::spring;
  spring.k = k_link;
  const Structure s = pair(spring);
  const auto channel = find_channel(s, "link1.velocity");
  REQUIRE(channel);
  CHECK(channel->quantity == Quantity::link_velocity);
  CHECK(std::string(info(Quantity::link_velocity).unit) == "m/s");
  // The closed form: K phi = w^2 M phi, phi' M phi = 1; from x = 0, v = v0 (A's floor):
  // v(t) = sum_i phi_i (phi_i' M v0) cos(w_i t).
  Eigen::Matrix2d m, k;
  m << kMassA, 0.0, 0.0, kMassB;
  k << kSpringA + k_link, -k_link, -k_link, kSpringB + k_link;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> modes(k, m);
  const Eigen::Vector2d v0(kV0, 0.0);
  auto relative_velocity = [&](double t) {
    Eigen::Vector2d v = Eigen::Vector2d::Zero();
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector2d phi = modes.eigenvectors().col(i);
      v += phi * (phi.dot(m * v0)) * std::cos(std::sqrt(modes.eigenvalues()[i]) * t);
    }
    return v[0] - v[1];
  };
  const DecayingSine still(0.0, 1.0, 0.0);
  std::vector<double> errors;
  for (double h : {0.004, 0.002, 0.001}) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 3.0;
    o.v0 = v0;
    adjoin::test::StateRecorder r;
    simulate_structure(o, s, still, r);
    const ChannelValues values(s, {*channel});
    double e = 0.0, value = 0.0;
    for (const StructureState& st : r.states) {
      values.read(st, &value);
      CHECK(value == channel_value(s, *channel, st));
      e = std::max(e, std::abs(value - relative_velocity(st.t)));
    }
    errors.push_back(e);
  }
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2] << " m/s of " << kV0);
  CHECK(errors[2] < 2e-3 * kV0);
  CHECK(std::log2(errors[0] / errors[1]) == Approx(2.0).margin(0.1));
  CHECK(std::log2(errors[1] / errors[2]) == Approx(2.0).margin(0.1));
}

TEST_CASE("a dashpot link's force is c times its velocity channel, and so is its peak", "[channels]") {
  const double c = 4.0e4;
  Link dashpot;
  dashpot.type = LinkType::dashpot;
  dashpot.c = c;
  BuildingRunOptions o;
  o.h = 0.005;
  o.t_end = 6.0;
  o.error_estimate = false;
  const RunSpec spec = building_run_spec(pair(dashpot), decaying_sine_ground(0.05, 6.0, 0.3), o);
  const Report r = run(spec);
  const Peak force = r.peak("link1.force"), velocity = r.peak("link1.velocity");
  CHECK(velocity.max_abs > 1e-2);  // (m/s: the link worked)
  // A largest sample each (a friction link's velocity kinks where it sticks): the same grid
  // point, the force c v rounded once.
  CHECK(force.max_abs == c * velocity.max_abs);
  CHECK(force.t == velocity.t);
}
