#pragma once
// The yielding storeys' report (SPEC §7; study/run.cpp, internal): per building whose storeys
// have a bilinear law, per storey, whether and when it first yielded (the solver's located
// instant), its excursions (elastic -> plastic transitions), its largest ductility |d|max / u_y
// and the work its slider dissipated (the plastic work): the slider's force F_h = (1 - b) F_y
// times its slip u_p = d - z in each step (it slips only at |q| = F_h; exact for the grid's
// d and z, so the work converges at the step's order, where a trapezoidal rule over the
// power q d' would see the yield kinks). A Bouc-Wen storey (SPEC §7) yields when |z| reaches
// 0.9 of its saturation u_y (beta + gamma)^(-1/n) (the solver locates the instant; an excursion
// is each such crossing from below); its plastic work is the hysteretic work (1 - b) k ∫ z dd
// (the trapezoidal rule on the grid's z and d: z is smooth, second order) less the energy
// (1 - b) k z^2 / 2 its z still stores at the end.
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
      y.bouc_wen = b.hysteresis.model == structure::HysteresisModel::bouc_wen;
      y.offset = s.dof(name, 1);
      y.base = s.base_dof(name);
      for (int i = 0; i < b.floors(); ++i) {
        const double k = b.springs[i], f = b.hysteresis.yield_forces[i];
        y.f_h.push_back((1.0 - b.hysteresis.hardening) * f);
        y.k_h.push_back((1.0 - b.hysteresis.hardening) * k);
        y.u_y.push_back(f / k);
        StoreyYield r;
        r.storey = i + 1;
        y.storeys.push_back(r);
      }
      y.slip.assign(y.storeys.size(), 0.0);
      y.z.assign(y.storeys.size(), 0.0);
      y.drift.assign(y.storeys.size(), 0.0);
      buildings_.push_back(std::move(y));
    };
    add(s.a, 'A');
    if (s.b) add(*s.b, 'B');
  }

  // Whether any building yields (else a run need not call it at all).
  bool watches() const { return !buildings_.empty(); }

  void observe(const StructureState& st) override {
    for (Building& b : buildings_)
      for (std::size_t i = 0; i < b.storeys.size(); ++i) {
        StoreyYield& r = b.storeys[i];
        const int k = b.offset + static_cast<int>(i);
        const double drift = st.x[k] - (i > 0 ? st.x[k - 1] : (b.base >= 0 ? st.x[b.base] : 0.0));
        const double slip = drift - (st.hyst.size() > k ? st.hyst[k] : 0.0);
        r.ductility_max = std::max(r.ductility_max, std::abs(drift) / b.u_y[i]);
        if (st.hyst_yield.size() > static_cast<std::size_t>(k) && !std::isnan(st.hyst_yield[k])) {
          if (!r.yielded) r.t_first = st.hyst_yield[k];
          r.yielded = true;
          ++r.excursions;
        }
        const double z = st.hyst.size() > k ? st.hyst[k] : 0.0;
        if (!first_ && b.bouc_wen) r.plastic_work += b.k_h[i] * 0.5 * (z + b.z[i]) * (drift - b.drift[i]);
        else if (!first_) r.plastic_work += b.f_h[i] * std::abs(slip - b.slip[i]);
        b.slip[i] = slip;
        b.z[i] = z;
        b.drift[i] = drift;
      }
    first_ = false;
  }

  std::vector<BuildingYield> report() const {
    std::vector<BuildingYield> out;
    for (const Building& b : buildings_) {
      out.push_back({b.name, b.storeys});
      if (b.bouc_wen)  // (less what z still stores)
        for (std::size_t i = 0; i < b.storeys.size(); ++i) out.back().storeys[i].plastic_work -= 0.5 * b.k_h[i] * b.z[i] * b.z[i];
    }
    return out;
  }

 private:
  struct Building {
    char name = 'A';
    int offset = 0;
    int base = -1;  // its isolated base's dof (SPEC §7), or -1
    bool bouc_wen = false;
    std::vector<double> f_h, k_h, u_y, slip;  // F_h, k_h, u_y, and the slip u_p at the last grid point
    std::vector<double> z, drift;             // z and the drift at the last grid point (Bouc-Wen)
    std::vector<StoreyYield> storeys;
  };
  std::vector<Building> buildings_;
  bool first_ = true;
};

}  // namespace adjoin::detail
