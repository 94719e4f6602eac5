#pragma once
// Collapse as an outcome (SPEC §7; study/run.cpp, internal): watches the drift ratio of every
// storey of a building with storey heights and is done (StructureObserver::done: the time loop
// ends the run there, exit 0) at the first grid point where a storey's |drift / h| exceeds its
// building's collapse_drift_ratio. The crossing is located inside that step on the cubic
// Hermite interpolant of the storey's drift through the step's two grid points (drifts and
// drift velocities), so the located time carries the scheme's own error, O(h^2), and none of
// the grid's. Without heights nothing is watched.
#include <cmath>
#include <optional>
#include <vector>

#include "adjoin/structure/observer.hpp"
#include "adjoin/study/report.hpp"

namespace adjoin::detail {

class CollapseObserver final : public StructureObserver {
 public:
  // Whether `s` has a building this observer watches (one with storey heights).
  static bool watches(const structure::Structure& s) { return s.a.has_heights() || (s.b && s.b->has_heights()); }

  void begin(const structure::Structure& s, const StructureSolverOptions&) override {
    storeys_.clear();
    for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr}) {
      if (!b || !b->has_heights()) continue;
      const char name = b->name.empty() ? 'A' : b->name[0];
      for (int i = 1; i <= b->floors(); ++i)
        storeys_.push_back({name, i, s.dof(name, i), s.below(name, i), b->heights[i - 1] * b->collapse_drift_ratio, b->collapse_drift_ratio});
    }
    previous_.assign(storeys_.size(), {});
    collapse_.reset();
    first_ = true;
  }

  void observe(const StructureState& st) override {
    if (collapse_) return;
    for (std::size_t k = 0; k < storeys_.size(); ++k) {
      const Storey& s = storeys_[k];
      const Sample now{st.t, drift(st.x, s), drift(st.v, s)};
      if (std::abs(now.d) > s.limit) {
        // At t = 0 (an initial displacement past the limit) there is no step to locate it in.
        const double t = first_ ? now.t : crossing(previous_[k], now, std::copysign(s.limit, now.d));
        if (!collapse_ || t < collapse_->t)
          collapse_ = Collapse{s.building, s.storey, t, std::copysign(s.ratio, now.d)};
      }
      previous_[k] = now;
    }
    first_ = false;
  }

  bool done() const override { return collapse_.has_value(); }
  const std::optional<Collapse>& collapse() const { return collapse_; }

 private:
  struct Storey {
    char building;
    int storey, dof;
    int below;     // the dof under it (-1: the ground; storey 1 of an isolated building: its base)
    double limit;  // collapse_drift_ratio x h [m]
    double ratio;  // collapse_drift_ratio
  };
  struct Sample {
    double t = 0.0, d = 0.0, v = 0.0;  // time, drift, drift velocity
  };

  static double drift(const Eigen::VectorXd& x, const Storey& s) { return x[s.dof] - (s.below >= 0 ? x[s.below] : 0.0); }

  // The time in (a.t, b.t] where the cubic Hermite interpolant of the drift reaches `target`
  // (a.d is on the near side of it, b.d past it), by bisection to the last bit.
  static double crossing(const Sample& a, const Sample& b, double target) {
    const double h = b.t - a.t;
    auto value = [&](double s) {  // s in [0, 1]
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * a.d + (s3 - 2 * s2 + s) * h * a.v + (-2 * s3 + 3 * s2) * b.d + (s3 - s2) * h * b.v;
    };
    const double sign = target > 0.0 ? 1.0 : -1.0;
    double lo = 0.0, hi = 1.0;  // sign x (value - target): <= 0 at lo, > 0 at hi
    for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (sign * (value(mid) - target) > 0.0) hi = mid;
      else lo = mid;
    }
    return a.t + hi * h;
  }

  std::vector<Storey> storeys_;
  std::vector<Sample> previous_;
  std::optional<Collapse> collapse_;
  bool first_ = true;
};

}  // namespace adjoin::detail
