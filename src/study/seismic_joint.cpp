#include "adjoin/study/seismic_joint.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {
namespace {

// One pair in one run: its minimum gap and its floors' peak displacements.
struct PairTrial {
  double min_gap = 0.0, t_min_gap = 0.0;
  double peak_a = 0.0, t_peak_a = 0.0, peak_b = 0.0, t_peak_b = 0.0;
};

// One run with the sized pairs' gap `gap` and no contact law on them, in the scene's units:
// each sized pair's values, and the closest approach over them (the run touches when it is < 0).
struct Trial {
  std::vector<PairTrial> pairs;
  std::size_t critical = 0;        // the pair with the smallest minimum gap
  double min_gap() const { return pairs[critical].min_gap; }
  std::vector<std::string> notes;  // the direct run's observations (other pairs)
  void find_critical() {
    critical = 0;
    for (std::size_t k = 1; k < pairs.size(); ++k)
      if (pairs[k].min_gap < pairs[critical].min_gap) critical = k;
  }
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

  // Direct: the response does not depend on the gap without a contact law; at gap 0 each
  // pair's minimum gap is -s_max (j.pairs came with each pair's number and floors).
  const Trial direct = run_at(0.0);
  for (std::size_t k = 0; k < j.pairs.size(); ++k) {
    PairJoint& p = j.pairs[k];
    const PairTrial& t = direct.pairs.at(k);
    p.s_max = -t.min_gap;
    p.t_critical = t.t_min_gap;
    p.peak_a = t.peak_a;
    p.t_peak_a = t.t_peak_a;
    p.peak_b = t.peak_b;
    p.t_peak_b = t.t_peak_b;
    p.srss = std::hypot(p.peak_a, p.peak_b);
    p.abs_sum = p.peak_a + p.peak_b;
  }
  const PairJoint& critical = j.pairs.at(direct.critical);
  j.contact = critical.contact;
  j.floor_a = critical.floor_a;
  j.floor_b = critical.floor_b;
  j.s_max = critical.s_max;
  j.t_critical = critical.t_critical;
  j.peak_a = critical.peak_a;
  j.t_peak_a = critical.t_peak_a;
  j.peak_b = critical.peak_b;
  j.t_peak_b = critical.t_peak_b;
  j.srss = critical.srss;
  j.abs_sum = critical.abs_sum;
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
    return run_at(gap).min_gap() < 0.0;
  };
  double lo = 0.0;
  if (!(direct.min_gap() < 0.0)) {
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

// A building run's sized pairs (`sized`, 0-based): each one's minimum gap and the peak
// displacements of its two floors, refined in each step on the parabola the solver integrates
// between grid points (constant acceleration, the velocity going linearly from one grid value
// to the next: the free flight in which a contact law's touch is located,
// solver/contact_step.hpp), so that a gap touches here exactly when a run with a contact law
// would find a touch; and what the other pairs do.
class JointObserver final : public StructureObserver {
 public:
  JointObserver(const structure::Structure& s, const std::vector<std::size_t>& sized) : s_(s), sized_(s.contacts.size(), 0) {
    for (std::size_t index : sized) {
      sized_[index] = 1;
      Track t;
      t.index = index;
      t.ia = s.dof('A', s.contacts[index].floor_a);
      t.ib = s.dof('B', s.contacts[index].floor_b);
      tracks_.push_back(t);
    }
  }

  void begin(const structure::Structure&, const StructureSolverOptions&) override {
    first_ = true;
    impacts_.assign(s_.contacts.size(), 0);
    touch_.assign(s_.contacts.size(), std::numeric_limits<double>::quiet_NaN());
  }

  void observe(const StructureState& st) override {
    for (Track& k : tracks_) follow(k, st);
    for (std::size_t k = 0; k < s_.contacts.size(); ++k) {
      if (sized_[k] || s_.contacts[k].law.model != structure::ContactModel::none || !std::isnan(touch_[k])) continue;
      const auto& pair = s_.contacts[k];
      if (pair.gap - (st.x[s_.dof('A', pair.floor_a)] - st.x[s_.dof('B', pair.floor_b)]) <= 0.0) touch_[k] = st.t;
    }
    last_t_ = st.t;
    first_ = false;
  }

  void impact(const Impact& e) override {
    if (e.contact >= 0 && static_cast<std::size_t>(e.contact) < impacts_.size() && e.complete)
      ++impacts_[static_cast<std::size_t>(e.contact)];
  }

  Trial trial() const {
    Trial t;
    for (const Track& k : tracks_) {
      PairTrial p;
      p.min_gap = k.min_gap;
      p.t_min_gap = k.t_min_gap;
      p.peak_a = k.peak_a.max_abs;
      p.t_peak_a = k.peak_a.t;
      p.peak_b = k.peak_b.max_abs;
      p.t_peak_b = k.peak_b.t;
      t.pairs.push_back(p);
    }
    t.find_critical();
    for (std::size_t k = 0; k < s_.contacts.size(); ++k) {
      if (sized_[k]) continue;
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
  // A sized pair: where it is, and what has been seen of it.
  struct Track {
    std::size_t index = 0;
    int ia = 0, ib = 0;
    double min_gap = 0.0, t_min_gap = 0.0;
    double last_s = 0.0, last_w = 0.0;
    double last_xa = 0.0, last_va = 0.0, last_xb = 0.0, last_vb = 0.0;
    Peak peak_a, peak_b;
  };
  struct Top {
    double t, y;
  };

  void follow(Track& k, const StructureState& st) const {
    const double gap = s_.contacts[k.index].gap;
    const double s = st.x[k.ia] - st.x[k.ib], w = st.v[k.ia] - st.v[k.ib];
    if (first_) {
      k.min_gap = gap - s;
      k.t_min_gap = st.t;
    } else {
      // The largest s in the step: the parabola's vertex when w turns from > 0 to <= 0.
      const Top top = vertex(k.last_s, k.last_w, s, w, last_t_, st.t);
      if (gap - top.y < k.min_gap) { k.min_gap = gap - top.y; k.t_min_gap = top.t; }
    }
    if (gap - s < k.min_gap) { k.min_gap = gap - s; k.t_min_gap = st.t; }
    if (first_) {
      k.peak_a.update(st.x[k.ia], st.t);
      k.peak_b.update(st.x[k.ib], st.t);
    } else {
      floor_peak(k.peak_a, k.last_xa, k.last_va, st.x[k.ia], st.v[k.ia], last_t_, st.t);
      floor_peak(k.peak_b, k.last_xb, k.last_vb, st.x[k.ib], st.v[k.ib], last_t_, st.t);
    }
    k.last_s = s;
    k.last_w = w;
    k.last_xa = st.x[k.ia];
    k.last_va = st.v[k.ia];
    k.last_xb = st.x[k.ib];
    k.last_vb = st.v[k.ib];
  }
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
  std::vector<char> sized_;  // per contact pair: sized here (else another pair, watched)
  std::vector<Track> tracks_;
  bool first_ = true;
  double last_t_ = 0.0;
  std::vector<std::size_t> impacts_;
  std::vector<double> touch_;
};

}  // namespace

bool SeismicJointOptions::IsValid(std::string* error) const {
  if (contact < 0) {
    *error = "contact " + std::to_string(contact) + ": expected a contact pair's number 1, 2, ... (or 0: every pair)";
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
  j.pairs.push_back(PairJoint{});  // the blocks' pair, floors 1-1
  const Scales& k = scene.scales;
  // Each trial is the scene's run (run()) with the gap edited, without a contact law, reporting
  // only its peaks and its pounding margin, unwatched (the joint shows its own progress).
  RunSpec trial = scene;
  structure::Contact& pair = trial.structure.contacts.at(0);  // the blocks' (dimensionless)
  trial.watch = nullptr;
  trial.output = OutputOptions{};
  trial.output.phases = trial.output.energy = false;
  trial.accuracy.error_estimate = false;
  if (pair.law.model != structure::ContactModel::none)
    j.notes.push_back(std::string("the scene's contact law (") + structure::to_string(pair.law.model) +
                      ") is not used: with a gap of at least the joint the blocks never touch");
  pair.law = structure::ContactLaw{};
  std::vector<std::string> law_note = j.notes;
  const RunAt run_at = [&](double gap) {
    pair.gap = gap / k.length;
    const Report r = run(trial);
    PairTrial p;
    p.min_gap = r.contacts.at(0).min_gap * k.length;
    p.t_min_gap = r.contacts.at(0).t_min_gap * k.time;
    const Peak a = r.peak("A.x1"), b = r.peak("B.x1");
    p.peak_a = a.max_abs * k.length;
    p.t_peak_a = a.t * k.time;
    p.peak_b = b.max_abs * k.length;
    p.t_peak_b = b.t * k.time;
    Trial t;
    t.pairs.push_back(p);
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
  if (options.contact < 0 || static_cast<std::size_t>(options.contact) > contacts.size())
    throw InputError("contact " + std::to_string(options.contact) + ": the scene has " + std::to_string(contacts.size()) +
                     " contact pair" + (contacts.size() == 1 ? "" : "s") + " (expected 1.." +
                     std::to_string(contacts.size()) + ", or 0 for every pair)");
  // The pairs sized: the one asked for, or every pair (at one uniform gap).
  std::vector<std::size_t> sized;
  if (options.contact == 0)
    for (std::size_t k = 0; k < contacts.size(); ++k) sized.push_back(k);
  else
    sized.push_back(static_cast<std::size_t>(options.contact - 1));
  SeismicJoint j;
  j.scene = scene.name;
  j.building = true;
  j.every_pair = options.contact == 0;
  j.gap_key = j.every_pair ? "contact.*.gap" : "contact." + std::to_string(options.contact) + ".gap";
  j.length_unit = "m";
  j.time_unit = "s";

  structure::Structure s = scene.structure;
  std::vector<std::string> law_note;
  for (std::size_t index : sized) {
    PairJoint p;
    p.contact = static_cast<int>(index) + 1;
    p.floor_a = contacts[index].floor_a;
    p.floor_b = contacts[index].floor_b;
    j.pairs.push_back(p);
    if (s.contacts[index].law.model != structure::ContactModel::none)
      law_note.push_back("contact " + std::to_string(index + 1) + "'s law (" + structure::to_string(s.contacts[index].law.model) +
                         ") is not used: with a gap of at least the joint the floors never touch");
    s.contacts[index].law = structure::ContactLaw{};
  }
  const RunAt run_at = [&](double gap) {
    for (std::size_t index : sized) s.contacts[index].gap = gap;
    JointObserver observer(s, sized);
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
