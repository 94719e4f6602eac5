#pragma once
// The yielding storeys' report (SPEC §7; study/run.cpp, internal): per building whose storeys
// have a bilinear law, per storey, whether and when it first yielded (the solver's located
// instant), its excursions (elastic -> plastic transitions), its largest ductility |d|max / u_y
// and the work its slider dissipated (the plastic work): the work done on its hysteretic
// element, integrated by the trapezoidal rule over the grid, less the element's stored energy
// q^2 / (2 k_h), q = k_h z.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "adjoin/structure/observer.hpp"
#include "adjoin/study/report.hpp"

namespace adjoin::detail {

class YieldObserver final : public StructureObserver {
 public:
  explicit YieldObserver(const structure::Structure& s) {
    auto add = [&](const structure::Building& b, char name) {
      if (b.hysteresis.model == structure::HysteresisModel::elastic) return;
      Building y;
      y.name = name;
      y.offset = s.dof(name, 1);
      for (int i = 0; i < b.floors(); ++i) {
        const double k = b.springs[i], f = b.hysteresis.yield_forces[i];
        y.k_h.push_back((1.0 - b.hysteresis.hardening) * k);
        y.u_y.push_back(f / k);
        StoreyYield r;
        r.storey = i + 1;
        y.storeys.push_back(r);
      }
      y.work.assign(y.storeys.size(), 0.0);
      y.power.assign(y.storeys.size(), 0.0);
      buildings_.push_back(std::move(y));
    };
    add(s.a, 'A');
    if (s.b) add(*s.b, 'B');
  }

  void observe(const StructureState& st) override {
    for (Building& b : buildings_)
      for (std::size_t i = 0; i < b.storeys.size(); ++i) {
        StoreyYield& r = b.storeys[i];
        const int k = b.offset + static_cast<int>(i);
        const double drift = st.x[k] - (i > 0 ? st.x[k - 1] : 0.0);
        const double rate = st.v[k] - (i > 0 ? st.v[k - 1] : 0.0);
        const double q = b.k_h[i] * (st.hyst.size() > k ? st.hyst[k] : 0.0);
        r.ductility_max = std::max(r.ductility_max, std::abs(drift) / b.u_y[i]);
        if (st.hyst_yield.size() > static_cast<std::size_t>(k) && !std::isnan(st.hyst_yield[k])) {
          if (!r.yielded) r.t_first = st.hyst_yield[k];
          r.yielded = true;
          ++r.excursions;
        }
        const double power = q * rate;
        if (!first_) b.work[i] += 0.5 * (st.t - last_t_) * (power + b.power[i]);
        b.power[i] = power;
        r.plastic_work = b.work[i] - 0.5 * q * q / b.k_h[i];
      }
    last_t_ = st.t;
    first_ = false;
  }

  std::vector<BuildingYield> report() const {
    std::vector<BuildingYield> out;
    for (const Building& b : buildings_) out.push_back({b.name, b.storeys});
    return out;
  }

 private:
  struct Building {
    char name = 'A';
    int offset = 0;
    std::vector<double> k_h, u_y, work, power;
    std::vector<StoreyYield> storeys;
  };
  std::vector<Building> buildings_;
  double last_t_ = 0.0;
  bool first_ = true;
};

}  // namespace adjoin::detail
