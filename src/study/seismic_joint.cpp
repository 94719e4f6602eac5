#include "adjoin/study/seismic_joint.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "adjoin/core/errors.hpp"
#include "adjoin/observe/peaks.hpp"
#include "adjoin/observe/pounding.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {
namespace {

// One run with the pair's gap `gap` and no contact law on it, in the scene's units.
struct Trial {
  double min_gap = 0.0, t_min_gap = 0.0;
  double peak_a = 0.0, t_peak_a = 0.0, peak_b = 0.0, t_peak_b = 0.0;
  std::vector<std::string> notes;  // the direct run's observations (other pairs)
};
using RunAt = std::function<Trial(double gap)>;

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// The bisection and the direct value, from runs at chosen gaps.
SeismicJoint find_joint(SeismicJoint j, const SeismicJointOptions& options, const RunAt& run_at) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  const auto start = std::chrono::steady_clock::now();

  // Direct: the response does not depend on the gap without a contact law; at gap 0 the
  // minimum gap is -s_max.
  const Trial direct = run_at(0.0);
  j.s_max = -direct.min_gap;
  j.t_critical = direct.t_min_gap;
  j.peak_a = direct.peak_a;
  j.t_peak_a = direct.t_peak_a;
  j.peak_b = direct.peak_b;
  j.t_peak_b = direct.t_peak_b;
  j.srss = std::hypot(j.peak_a, j.peak_b);
  j.abs_sum = j.peak_a + j.peak_b;
  j.notes = direct.notes;

  // The tolerance: given, or 1e-6 of s_max (of the floors' motion when they never approach).
  double scale = j.s_max > 0.0 ? j.s_max : j.abs_sum;
  if (!(scale > 0.0)) scale = 1.0;
  j.tol = std::isnan(options.tol) ? 1e-6 * scale : options.tol;

  // Bisection on "the run touches" (its minimum gap below 0) alone. The direct run, at gap 0,
  // is the bracket's bottom.
  std::size_t runs = 1;
  auto touches = [&](double gap) {
    if (static_cast<int>(runs) >= options.max_runs)
      throw NumericalError("seismic joint: no bracket after " + std::to_string(runs) +
                           " runs (max_runs); the response may not be bounded", 0.0);
    ++runs;
    return run_at(gap).min_gap < 0.0;
  };
  double lo = 0.0;
  if (!(direct.min_gap < 0.0)) {
    j.joint = j.joint_low = 0.0;
    j.bracket_top = 0.0;
    j.notes.push_back("the floors never approach each other (s <= 0 throughout): a joint of 0 suffices");
  } else {
    double hi = j.s_max > 0.0 ? 2.0 * j.s_max : j.tol;
    while (touches(hi)) {
      lo = hi;
      hi *= 2.0;
      ++j.widenings;
    }
    j.bracket_top = hi;
    while (hi - lo > j.tol) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;  // the bracket is down to rounding
      if (touches(mid))
        lo = mid;
      else
        hi = mid;
    }
    j.joint = hi;
    j.joint_low = lo;
  }
  j.runs = runs;
  j.difference = j.joint - std::max(j.s_max, 0.0);
  const double rounding = 1e-12 * (std::abs(j.s_max) + j.abs_sum + j.tol);
  j.agree = j.difference >= -rounding && j.difference <= j.tol + rounding;
  j.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return j;
}

// A building run's pair `index`: its minimum gap and the peak displacements of its two floors,
// refined in each step on the parabola the solver integrates between grid points (constant
// acceleration, the velocity going linearly from one grid value to the next: the free flight
// in which a contact law's touch is located, solver/contact_step.hpp), so that a gap touches
// here exactly when a run with a contact law would find a touch; and what the other pairs do.
class JointObserver final : public StructureObserver {
 public:
  JointObserver(const structure::Structure& s, std::size_t index)
      : s_(s), index_(index), ia_(s.dof('A', s.contacts[index].floor_a)), ib_(s.dof('B', s.contacts[index].floor_b)) {}

  void begin(const structure::Structure&, const StructureSolverOptions&) override {
    first_ = true;
    impacts_.assign(s_.contacts.size(), 0);
    touch_.assign(s_.contacts.size(), std::numeric_limits<double>::quiet_NaN());
  }

  void observe(const StructureState& st) override {
    const double gap = s_.contacts[index_].gap;
    const double s = st.x[ia_] - st.x[ib_], w = st.v[ia_] - st.v[ib_];
    if (first_) {
      min_gap_ = gap - s;
      t_min_gap_ = st.t;
    } else {
      // The largest s in the step: the parabola's vertex when w turns from > 0 to <= 0.
      const Top top = vertex(last_s_, last_w_, s, w, last_t_, st.t);
      if (gap - top.y < min_gap_) { min_gap_ = gap - top.y; t_min_gap_ = top.t; }
    }
    if (gap - s < min_gap_) { min_gap_ = gap - s; t_min_gap_ = st.t; }
    if (first_) {
      peak_a_.update(st.x[ia_], st.t);
      peak_b_.update(st.x[ib_], st.t);
    } else {
      floor_peak(peak_a_, last_xa_, last_va_, st.x[ia_], st.v[ia_], last_t_, st.t);
      floor_peak(peak_b_, last_xb_, last_vb_, st.x[ib_], st.v[ib_], last_t_, st.t);
    }
    for (std::size_t k = 0; k < s_.contacts.size(); ++k) {
      if (k == index_ || s_.contacts[k].law.model != structure::ContactModel::none || !std::isnan(touch_[k])) continue;
      const auto& pair = s_.contacts[k];
      if (pair.gap - (st.x[s_.dof('A', pair.floor_a)] - st.x[s_.dof('B', pair.floor_b)]) <= 0.0) touch_[k] = st.t;
    }
    last_s_ = s;
    last_w_ = w;
    last_xa_ = st.x[ia_];
    last_va_ = st.v[ia_];
    last_xb_ = st.x[ib_];
    last_vb_ = st.v[ib_];
    last_t_ = st.t;
    first_ = false;
  }

  void impact(const Impact& e) override {
    if (e.contact >= 0 && static_cast<std::size_t>(e.contact) < impacts_.size() && e.complete)
      ++impacts_[static_cast<std::size_t>(e.contact)];
  }

  Trial trial() const {
    Trial t;
    t.min_gap = min_gap_;
    t.t_min_gap = t_min_gap_;
    t.peak_a = peak_a_.max_abs;
    t.t_peak_a = peak_a_.t;
    t.peak_b = peak_b_.max_abs;
    t.t_peak_b = peak_b_.t;
    for (std::size_t k = 0; k < s_.contacts.size(); ++k) {
      if (k == index_) continue;
      const auto& pair = s_.contacts[k];
      const std::string name = "contact " + std::to_string(k + 1) + " (floors " + std::to_string(pair.floor_a) + ", " +
                               std::to_string(pair.floor_b) + ")";
      if (!std::isnan(touch_[k]))
        t.notes.push_back(name + " has no contact law and its floors touch from t = " + number(touch_[k]) +
                          " s: the response from then on, and this joint, are outside the model");
      else if (impacts_[k] > 0)
        t.notes.push_back(name + " pounds (" + std::to_string(impacts_[k]) + (impacts_[k] == 1 ? " impact" : " impacts") +
                          "): the joint is that of the response with its collisions");
    }
    return t;
  }

 private:
  struct Top {
    double t, y;
  };
  // The vertex of y0 + w0 tau + (w1 - w0) tau^2 / (2 h) on the step, if y has a maximum inside
  // (w0 > 0 >= w1); else the end sample.
  static Top vertex(double y0, double w0, double y1, double w1, double t0, double t1) {
    if (!(w0 > 0.0 && w1 <= 0.0)) return {t1, y1};
    const double h = t1 - t0;
    const double tau = w0 * h / (w0 - w1);
    return {t0 + tau, y0 + 0.5 * w0 * tau};
  }
  // |x| peaks on the same parabolas (a maximum of x or of -x inside the step), then the sample.
  static void floor_peak(Peak& peak, double x0, double v0, double x, double v, double t0, double t) {
    if (v0 > 0.0 && v <= 0.0) {
      const Top top = vertex(x0, v0, x, v, t0, t);
      peak.update(top.y, top.t);
    } else if (v0 < 0.0 && v >= 0.0) {
      const Top top = vertex(-x0, -v0, -x, -v, t0, t);
      peak.update(top.y, top.t);
    }
    peak.update(x, t);
  }

  const structure::Structure& s_;
  std::size_t index_;
  int ia_, ib_;
  bool first_ = true;
  double min_gap_ = 0.0, t_min_gap_ = 0.0;
  double last_s_ = 0.0, last_w_ = 0.0, last_t_ = 0.0;
  double last_xa_ = 0.0, last_va_ = 0.0, last_xb_ = 0.0, last_vb_ = 0.0;
  Peak peak_a_, peak_b_;
  std::vector<std::size_t> impacts_;
  std::vector<double> touch_;
};

}  // namespace

bool SeismicJointOptions::IsValid(std::string* error) const {
  if (contact < 1) {
    *error = "contact " + std::to_string(contact) + ": expected a contact pair's number 1, 2, ...";
    return false;
  }
  if (!std::isnan(tol) && !(tol > 0.0 && std::isfinite(tol))) {
    *error = "tol " + number(tol) + ": expected a positive length (the bisection's tolerance)";
    return false;
  }
  if (max_runs < 2) {
    *error = "max_runs: expected at least 2";
    return false;
  }
  return true;
}

namespace {

SeismicJoint two_block_joint(const RunSpec& scene, const SeismicJointOptions& options) {
  SeismicJoint j;
  j.scene = scene.name;
  j.building = false;
  j.gap_key = "model.gap0";
  j.length_unit = scene.scales.si ? "m" : "X0";
  j.time_unit = scene.scales.si ? "s" : "T0";
  const Scales& k = scene.scales;
  Model model = *scene.model;
  if (model.contact.model != structure::ContactModel::none)
    j.notes.push_back(std::string("the scene's contact law (") + structure::to_string(model.contact.model) +
                      ") is not used: with a gap of at least the joint the blocks never touch");
  model.contact = structure::ContactLaw{};
  std::vector<std::string> law_note = j.notes;
  const RunAt run_at = [&](double gap) {
    model.gap0 = gap / k.length;
    PoundingObserver pounding;
    PeakObserver peaks;
    ObserverList observers({&pounding, &peaks});
    simulate(two_block_options(scene), model, *scene.ground, observers);
    Trial t;
    t.min_gap = pounding.margin().min_gap * k.length;
    t.t_min_gap = pounding.margin().t_min_gap * k.time;
    t.peak_a = peaks.peaks().x1.max_abs * k.length;
    t.t_peak_a = peaks.peaks().x1.t * k.time;
    t.peak_b = peaks.peaks().x2.max_abs * k.length;
    t.t_peak_b = peaks.peaks().x2.t * k.time;
    t.notes = law_note;
    return t;
  };
  return find_joint(j, options, run_at);
}

SeismicJoint building_joint(const RunSpec& scene, const SeismicJointOptions& options) {
  const auto& contacts = scene.structure.contacts;
  if (contacts.empty())
    throw InputError(scene.file.string() + ": the scene has no contact pair: add a [[contact]] with floors = [i, j] "
                     "(its gap is the joint)");
  if (options.contact < 1 || static_cast<std::size_t>(options.contact) > contacts.size())
    throw InputError("contact " + std::to_string(options.contact) + ": the scene has " + std::to_string(contacts.size()) +
                     " contact pair" + (contacts.size() == 1 ? "" : "s") + " (expected 1.." +
                     std::to_string(contacts.size()) + ")");
  const auto index = static_cast<std::size_t>(options.contact - 1);
  SeismicJoint j;
  j.scene = scene.name;
  j.building = true;
  j.contact = options.contact;
  j.floor_a = contacts[index].floor_a;
  j.floor_b = contacts[index].floor_b;
  j.gap_key = "contact." + std::to_string(options.contact) + ".gap";
  j.length_unit = "m";
  j.time_unit = "s";

  structure::Structure s = scene.structure;
  std::vector<std::string> law_note;
  if (s.contacts[index].law.model != structure::ContactModel::none)
    law_note.push_back("contact " + std::to_string(options.contact) + "'s law (" +
                       structure::to_string(s.contacts[index].law.model) +
                       ") is not used: with a gap of at least the joint the floors never touch");
  s.contacts[index].law = structure::ContactLaw{};
  const RunAt run_at = [&](double gap) {
    s.contacts[index].gap = gap;
    JointObserver observer(s, index);
    simulate_spec(scene, s, observer);
    Trial t = observer.trial();
    t.notes.insert(t.notes.begin(), law_note.begin(), law_note.end());
    return t;
  };
  return find_joint(j, options, run_at);
}

}  // namespace

SeismicJoint seismic_joint(const RunSpec& scene, const SeismicJointOptions& options) {
  return scene.two_block() ? two_block_joint(scene, options) : building_joint(scene, options);
}

}  // namespace adjoin
