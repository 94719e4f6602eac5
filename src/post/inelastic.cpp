// Inelastic (elastic-perfectly-plastic and bilinear) spectra with exact branch switching (the
// method is described in adjoin/post/inelastic.hpp).
#include "adjoin/post/inelastic.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"
#include "spectrum_oscillator.hpp"

namespace adjoin {

namespace {

using spectrum_detail::kMaxTerms;
using spectrum_detail::taylor;
using spectrum_detail::taylor_terms;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kSmallestEta = 1e-4;   // f_y / f_e

// The strength scan (see constant_ductility): steps in x = log eta sized so that mu cannot
// reach the target before the next strength while |d log mu / d log eta| <= kSlopeBound, never
// finer than kFinestStep (0.5 % in strength) nor coarser than kCoarsestStep (10 %). On El
// Centro 1940 NS (the longer record; periods 0.05-5 s, mu up to 7, on a 0.1 % grid) the slope
// stays below 10 except at periods under 0.08 s (12-13 at 0.05-0.065 s); a bound of 10 and a
// finest step of 0.5 % cost about 4 times the former fixed 10 % steps (bench_inelastic).
constexpr double kSlopeBound = 10.0;
constexpr double kFinestStep = 0.005;
constexpr double kCoarsestStep = 0.105;

// The scan's step in log eta from a strength whose ductility mu is below the target.
double scan_step(double mu, double target) {
  if (!(mu > 0.0)) return kCoarsestStep;
  return std::clamp(std::log(target / mu) / kSlopeBound, kFinestStep, kCoarsestStep);
}

// The root of sum c[m] s^m / m! = target on (lo, hi); the series is above target at lo if
// lo_above, below at hi then (and the other way round). Newton kept inside the bracket.
double series_root(const double* c, int terms, double target, double lo, double hi, bool lo_above) {
  const double width = hi - lo;
  double s = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = taylor(c, terms, s) - target;
    if (f == 0.0) break;
    if ((f > 0.0) == lo_above) lo = s; else hi = s;
    const double fp = taylor(c + 1, terms, s);
    double next = fp != 0.0 ? s - f / fp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double change = std::abs(next - s);
    s = next;
    if (change <= 1e-15 * width || hi - lo <= 1e-15 * width) break;
  }
  return s;
}

// The inelastic oscillator over one record, for one yield displacement.
class Sdof {
 public:
  Sdof(double omega, double zeta, double alpha, double h)
      : el_(spectrum_detail::branch_step_coefficients(omega, zeta, 1.0, h)),
        pl_(spectrum_detail::branch_step_coefficients(omega, zeta, alpha, h)),
        h_(h),
        c_(2.0 * zeta * omega),
        w2_(omega * omega),
        alpha_(alpha),
        terms_(std::min(taylor_terms(std::max(1.0, 2.0 * zeta) * omega * h), kMaxTerms - 4)) {}

  // max |u| over the record (n sub-steps a sample interval) for the yield displacement uy.
  double peak(const double* accel, std::size_t samples, std::size_t n, double uy) {
    u_ = v_ = up_ = umax_ = f_el_ = 0.0;
    branch_ = 0;
    uy_ = uy;
    f_pl_ = std::isfinite(uy) ? w2_ * (1.0 - alpha_) * uy : 0.0;
    spectrum_detail::for_each_substep(accel, samples, n, [this](double p0, double p1) { step(p0, p1); });
    return umax_;
  }

 private:
  void step(double p0, double p1) {
    if (branch_ == 0) {
      const double q0 = p0 + f_el_, q1 = p1 + f_el_;
      const double u1 = el_.a_uu * u_ + el_.a_uv * v_ + el_.b_u0 * q0 + el_.b_u1 * q1;
      const double v1 = el_.a_vu * u_ + el_.a_vv * v_ + el_.b_v0 * q0 + el_.b_v1 * q1;
      if (std::abs(u1 - up_) > uy_) return slow(p0, p1);
      if (v_ * v1 < 0.0) {
        // u turns inside the step: by at most h^2/8 max|u''| beyond the end values.
        const double a0 = q0 - c_ * v_ - w2_ * u_, a1 = q1 - c_ * v1 - w2_ * u1;
        const double amax = std::max(std::abs(a0), std::abs(a1));
        const double margin =
            0.25 * h_ * h_ * (amax + h_ * (std::abs(p1 - p0) / h_ + c_ * amax + w2_ * std::max(std::abs(v_), std::abs(v1))));
        const double zend = std::max(std::abs(u_ - up_), std::abs(u1 - up_));
        if (zend + margin >= uy_ || std::max(std::abs(u_), std::abs(u1)) + margin >= umax_) return slow(p0, p1);
      }
      u_ = u1;
      v_ = v1;
    } else {
      const double f = -static_cast<double>(branch_) * f_pl_;
      const double q0 = p0 + f, q1 = p1 + f;
      const double u1 = pl_.a_uu * u_ + pl_.a_uv * v_ + pl_.b_u0 * q0 + pl_.b_u1 * q1;
      const double v1 = pl_.a_vu * u_ + pl_.a_vv * v_ + pl_.b_v0 * q0 + pl_.b_v1 * q1;
      if (static_cast<double>(branch_) * v1 <= 0.0) return slow(p0, p1);
      u_ = u1;
      v_ = v1;
    }
    umax_ = std::max(umax_, std::abs(u_));
  }

  // The step with its events located: Taylor series of the current branch from the current
  // instant, the earliest event, the state carried there, the branch changed, and again.
  [[gnu::noinline]] void slow(double p0, double p1) {
    const double slope = (p1 - p0) / h_;
    std::array<double, kMaxTerms + 4> d{};
    const int n = terms_ + 3;
    double t = 0.0;
    for (int events = 0; t < h_; ++events) {
      const double rem = h_ - t;
      const bool elastic = branch_ == 0;
      const double kw2 = elastic ? w2_ : alpha_ * w2_;
      const double force = elastic ? f_el_ : -static_cast<double>(branch_) * f_pl_;
      d[0] = u_;
      d[1] = v_;
      d[2] = p0 + slope * t + force - c_ * v_ - kw2 * u_;
      d[3] = slope - c_ * d[2] - kw2 * d[1];
      for (int m = 4; m < n; ++m)
        d[static_cast<std::size_t>(m)] = -c_ * d[static_cast<std::size_t>(m - 1)] - kw2 * d[static_cast<std::size_t>(m - 2)];
      double event = -1.0;
      if (events < 16) {  // (more events in one sub-step would be rounding noise)
        if (elastic) {
          const double v_end = taylor(d.data() + 1, terms_, rem);
          double from = 0.0;  // a crossing is looked for after the turning point, if any
          if (v_ * v_end < 0.0) {
            const double turn = series_root(d.data() + 1, terms_, 0.0, 0.0, rem, v_ > 0.0);
            const double u_turn = taylor(d.data(), terms_, turn);
            if (std::abs(u_turn - up_) > uy_) {
              const double target = up_ + std::copysign(uy_, u_turn - up_);
              event = series_root(d.data(), terms_, target, 0.0, turn, u_ > target);
            } else {
              umax_ = std::max(umax_, std::abs(u_turn));
              from = turn;
            }
          }
          if (event < 0.0) {
            const double u_end = taylor(d.data(), terms_, rem);
            if (std::abs(u_end - up_) > uy_) {
              const double target = up_ + std::copysign(uy_, u_end - up_);
              const double u_from = taylor(d.data(), terms_, from);
              event = series_root(d.data(), terms_, target, from, rem, u_from > target);
            }
          }
        } else {
          const double v_end = taylor(d.data() + 1, terms_, rem);
          if (static_cast<double>(branch_) * v_end <= 0.0)
            event = v_end == 0.0 ? rem : series_root(d.data() + 1, terms_, 0.0, 0.0, rem, branch_ > 0);
        }
      }
      const double s = event < 0.0 ? rem : event;
      u_ = taylor(d.data(), terms_, s);
      v_ = taylor(d.data() + 1, terms_, s);
      umax_ = std::max(umax_, std::abs(u_));
      t = event < 0.0 ? h_ : t + s;
      if (event < 0.0) break;
      if (elastic) {
        // Yield: z = +-uy from here on.
        const double sign = u_ - up_ > 0.0 ? 1.0 : -1.0;
        up_ = u_ - sign * uy_;
        f_el_ = w2_ * (1.0 - alpha_) * up_;
        const double accel = p0 + slope * t + f_el_ - c_ * v_ - w2_ * u_;
        if (sign * v_ > 0.0 || (v_ == 0.0 && sign * accel > 0.0)) branch_ = sign > 0.0 ? 1 : -1;
      } else {
        // Unloading: elastic again, the plastic offset where it stopped.
        v_ = 0.0;
        up_ = u_ - static_cast<double>(branch_) * uy_;
        f_el_ = w2_ * (1.0 - alpha_) * up_;
        branch_ = 0;
      }
    }
  }

  StepCoefficients el_, pl_;
  double h_, c_, w2_, alpha_;
  int terms_;
  double uy_ = 0.0, f_pl_ = 0.0, f_el_ = 0.0;
  double u_ = 0.0, v_ = 0.0, up_ = 0.0, umax_ = 0.0;
  int branch_ = 0;  // 0 elastic, +1 yielding in +u, -1 yielding in -u
};

void check_history(double dt, std::span<const double> accel) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream out;
    out << "inelastic spectrum: the time step must be a positive number, got dt = " << dt;
    throw InputError(out.str());
  }
  if (accel.empty()) throw InputError("inelastic spectrum: the acceleration history is empty");
  for (std::size_t i = 0; i < accel.size(); ++i)
    if (!std::isfinite(accel[i])) {
      std::ostringstream out;
      out << "inelastic spectrum: acceleration sample " << i << " (t = " << static_cast<double>(i) * dt
          << " s) is not a finite number";
      throw InputError(out.str());
    }
}

std::size_t substeps(double dt, double period, const InelasticOptions& options) {
  return static_cast<std::size_t>(std::max(1.0, std::ceil(options.points_per_period * dt / period)));
}

double hardening_of(const InelasticOptions& options) {
  return options.hysteresis == Hysteresis::bilinear ? options.hardening : 0.0;
}

std::vector<double> periods_of(const InelasticOptions& options) {
  if (!options.periods.empty()) return options.periods;
  return default_spectrum_periods();
}

// One oscillator (period, damping) and its record.
struct Problem {
  const double* accel;
  std::size_t samples, n;
  double omega;
  Sdof sdof;
  double sd = 0.0;  // elastic peak [m]

  Problem(double dt, std::span<const double> a, double period, double zeta, const InelasticOptions& options)
      : accel(a.data()),
        samples(a.size()),
        n(substeps(dt, period, options)),
        omega(kTwoPi / period),
        sdof(omega, zeta, hardening_of(options), dt / static_cast<double>(substeps(dt, period, options))) {
    sd = sdof.peak(accel, samples, n, std::numeric_limits<double>::infinity());
    if (!std::isfinite(sd)) throw NumericalError("inelastic spectrum: the elastic response is not finite", 0.0);
  }
  // Ductility at strength ratio eta (u_y = eta SD); the peak displacement too.
  double ductility(double eta, double* peak) {
    const double uy = eta * sd;
    const double u = sdof.peak(accel, samples, n, uy);
    if (!std::isfinite(u)) throw NumericalError("inelastic spectrum: the response is not finite", 0.0);
    if (peak) *peak = u;
    return u / uy;
  }
};

void fill(InelasticValues& v, const Problem& problem, double eta, double mu, double peak) {
  const double fy = problem.omega * problem.omega * eta * problem.sd;  // per unit mass
  v.cy = fy / kStandardGravity;
  v.uy = eta * problem.sd;
  v.R = 1.0 / eta;
  v.ductility_reached = mu;
  v.peak_displacement = peak;
}

// The constant-ductility values of one oscillator for all targets: for each, the largest
// strength ratio eta whose ductility reaches it (SPEC 3).
//
// Why the largest root is not stepped over. mu(eta) is not monotonic, so the targets' roots are
// found by scanning eta down from 1 (mu = 1 there). Every strength above the reported bracket
// was evaluated and had mu below the target; the scan's next strength is ln(target / mu) /
// kSlopeBound below the last one in log eta (clamped to [kFinestStep, kCoarsestStep]). So a
// root above the reported one can be missed only (a) where |d log mu / d log eta| exceeds
// kSlopeBound (10; see there for the records' slopes), or (b) where mu rises above the target
// and falls back below it inside one finest step, a band of strengths narrower than 0.5 %
// (ratio e^-0.005), the final bracket's width at most. The roots are
// ordered -- mu is continuous and mu(1) = 1, so mu crosses a smaller target above any root of a
// larger one -- so the targets, in ascending order, share one scan: the steps sized for a
// smaller target are finer than a larger target needs. A step of ratio 0.9 throughout (the
// earlier scan) stepped over bands up to 10 % wide: on El Centro 1940 NS (the longer record),
// T = 0.163 s, mu = 6, it reported a strength 19 % below the largest root.
void constant_ductility(Problem& problem, const InelasticOptions& options, InelasticValues* out) {
  const std::vector<double>& targets = options.ductilities;
  if (!(problem.sd > 0.0)) {  // no motion: any strength stays elastic
    for (std::size_t k = 0; k < targets.size(); ++k) {
      out[k].cy = out[k].uy = out[k].peak_displacement = 0.0;
      out[k].R = out[k].ductility_reached = 1.0;
    }
    return;
  }
  // Evaluated strengths, eta decreasing: the scan's grid, then the iterations' points.
  struct Point {
    double eta, mu, peak;
  };
  std::vector<Point> points;
  auto evaluate = [&](double eta) {
    Point p{eta, 0.0, 0.0};
    p.mu = problem.ductility(eta, &p.peak);
    return p;
  };
  points.push_back(evaluate(1.0));
  const double tol = options.tolerance;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const double target = targets[k];
    // The first evaluated strength, from the top, whose ductility reaches the target.
    std::size_t j = 0;
    while (true) {
      while (j < points.size() && points[j].mu < target * (1.0 - tol)) ++j;
      if (j < points.size() || points.back().eta <= kSmallestEta) break;
      const double step = scan_step(points.back().mu, target);
      points.push_back(evaluate(std::max(points.back().eta * std::exp(-step), kSmallestEta)));
    }
    if (j == points.size()) {  // not reached down to the smallest strength
      const Point& p = points.back();
      fill(out[k], problem, p.eta, p.mu, p.peak);
      continue;
    }
    if (j == 0 || std::abs(points[j].mu / target - 1.0) <= tol) {
      fill(out[k], problem, points[j].eta, points[j].mu, points[j].peak);
      continue;
    }
    // Illinois on f(x) = log mu - log target, x = log eta; f(lo) > 0 > f(hi).
    Point lo = points[j], hi = points[j - 1];
    double xlo = std::log(lo.eta), xhi = std::log(hi.eta);
    double flo = std::log(lo.mu / target), fhi = std::log(hi.mu / target);
    int side = 0;
    Point best = std::abs(flo) < std::abs(fhi) ? lo : hi;
    for (int iteration = 0; iteration < 100 && xhi - xlo > 1e-13; ++iteration) {
      double x = (xlo * fhi - xhi * flo) / (fhi - flo);
      if (!(x > xlo && x < xhi)) x = 0.5 * (xlo + xhi);
      const Point p = evaluate(std::exp(x));
      // Keep the points in eta order, for the next targets' brackets.
      points.insert(std::upper_bound(points.begin(), points.end(), p,
                                     [](const Point& a, const Point& b) { return a.eta > b.eta; }),
                    p);
      const double f = std::log(p.mu / target);
      if (std::abs(f) < std::abs(std::log(best.mu / target))) best = p;
      if (std::abs(p.mu / target - 1.0) <= tol) break;
      if (f > 0.0) {
        xlo = x, flo = f;
        if (side == -1) fhi *= 0.5;
        side = -1;
      } else {
        xhi = x, fhi = f;
        if (side == 1) flo *= 0.5;
        side = 1;
      }
    }
    fill(out[k], problem, best.eta, best.mu, best.peak);
  }
}

// Runs `compute(task, values)` over (damping, period) tasks on the options' threads.
template <typename Compute>
void for_each_task(std::size_t total, unsigned wanted, const Compute& compute) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto work = [&]() {
    try {
      for (std::size_t t = next.fetch_add(1); t < total && !failed; t = next.fetch_add(1)) compute(t);
    } catch (...) {
      if (!failed.exchange(true)) failure = std::current_exception();
    }
  };
  spectrum_detail::run_workers(wanted, total, work);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

bool InelasticOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  std::ostringstream out;
  for (double t : periods)
    if (!(t >= 1e-4 && t <= 1e4)) {
      out << "inelastic spectrum periods must be from 1e-4 s to 1e4 s, got " << t;
      return fail(out.str());
    }
  if (dampings.empty()) return fail("inelastic spectrum dampings: at least one damping ratio is needed");
  for (double z : dampings)
    if (!(z >= 0.0 && z < 1.0)) {
      out << "inelastic spectrum damping ratios must be in [0, 1) (0.05 is 5 %), got " << z;
      return fail(out.str());
    }
  for (double mu : ductilities)
    if (!(mu >= 1.0 && mu <= 100.0)) {
      out << "target ductilities must be from 1 to 100, got " << mu;
      return fail(out.str());
    }
  if (hysteresis == Hysteresis::elastic_perfectly_plastic && hardening != 0.0) {
    out << "hardening " << hardening << " is for the bilinear hysteresis (elastic-perfectly-plastic has none)";
    return fail(out.str());
  }
  if (!(hardening >= 0.0 && hardening < 1.0)) {
    out << "hardening (post-yield stiffness ratio) must be in [0, 1), got " << hardening;
    return fail(out.str());
  }
  if (!(points_per_period >= 8.0 && points_per_period <= 1e4)) {
    out << "inelastic spectrum points_per_period must be from 8 to 1e4, got " << points_per_period;
    return fail(out.str());
  }
  if (!(tolerance >= 1e-8 && tolerance <= 0.1)) {
    out << "inelastic spectrum ductility tolerance must be from 1e-8 to 0.1, got " << tolerance;
    return fail(out.str());
  }
  return true;
}

InelasticSpectrum constant_ductility_spectrum(double dt, std::span<const double> accel,
                                              const InelasticOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  if (options.ductilities.empty()) throw InputError("constant-ductility spectrum: no target ductility given");
  check_history(dt, accel);
  InelasticSpectrum s;
  s.periods = periods_of(options);
  s.dampings = options.dampings;
  s.ductilities = options.ductilities;
  std::sort(s.ductilities.begin(), s.ductilities.end());
  s.ductilities.erase(std::unique(s.ductilities.begin(), s.ductilities.end()), s.ductilities.end());
  InelasticOptions sorted = options;
  sorted.ductilities = s.ductilities;
  const std::size_t np = s.periods.size(), nk = s.ductilities.size();
  s.values.resize(s.dampings.size() * np * nk);
  for_each_task(s.dampings.size() * np, options.threads, [&](std::size_t task) {
    const double period = s.periods[task % np], zeta = s.dampings[task / np];
    InelasticValues* out = s.values.data() + task * nk;
    for (std::size_t k = 0; k < nk; ++k) {
      out[k].period = period;
      out[k].damping = zeta;
      out[k].ductility = s.ductilities[k];
    }
    Problem problem(dt, accel, period, zeta, sorted);
    constant_ductility(problem, sorted, out);
  });
  return s;
}

InelasticSpectrum constant_strength_spectrum(double dt, std::span<const double> accel,
                                             const std::vector<double>& strengths, StrengthMeasure measure,
                                             const InelasticOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  if (strengths.empty()) throw InputError("constant-strength spectrum: no strength given");
  for (double x : strengths)
    if (!(x > 0.0 && x <= 1e6)) {
      std::ostringstream out;
      out << (measure == StrengthMeasure::reduction_factor ? "strength reduction factors R" : "yield strength coefficients cy")
          << " must be > 0 (at most 1e6), got " << x;
      throw InputError(out.str());
    }
  check_history(dt, accel);
  InelasticSpectrum s;
  s.periods = periods_of(options);
  s.dampings = options.dampings;
  const std::size_t np = s.periods.size(), nk = strengths.size();
  s.values.resize(s.dampings.size() * np * nk);
  for_each_task(s.dampings.size() * np, options.threads, [&](std::size_t task) {
    const double period = s.periods[task % np], zeta = s.dampings[task / np];
    Problem problem(dt, accel, period, zeta, options);
    for (std::size_t k = 0; k < nk; ++k) {
      InelasticValues& v = s.values[task * nk + k];
      v.period = period;
      v.damping = zeta;
      if (!(problem.sd > 0.0)) {
        v.ductility = v.ductility_reached = 1.0;
        v.R = measure == StrengthMeasure::reduction_factor ? strengths[k] : 1.0;
        v.cy = measure == StrengthMeasure::yield_coefficient ? strengths[k] : 0.0;
        v.uy = v.cy * kStandardGravity / (problem.omega * problem.omega);
        continue;
      }
      const double fe = problem.omega * problem.omega * problem.sd;  // per unit mass
      const double eta = measure == StrengthMeasure::reduction_factor ? 1.0 / strengths[k]
                                                                      : strengths[k] * kStandardGravity / fe;
      double peak = 0.0;
      const double mu = problem.ductility(eta, &peak);
      fill(v, problem, eta, mu, peak);
      v.ductility = mu;
    }
  });
  return s;
}

double inelastic_peak_displacement(double dt, std::span<const double> accel, double period, double damping,
                                   double uy, const InelasticOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  check_history(dt, accel);
  if (!(period >= 1e-4 && period <= 1e4)) throw InputError("inelastic oscillator: period must be from 1e-4 s to 1e4 s");
  if (!(damping >= 0.0 && damping < 1.0)) throw InputError("inelastic oscillator: damping ratio must be in [0, 1)");
  if (!(uy > 0.0)) throw InputError("inelastic oscillator: the yield displacement must be > 0");
  const std::size_t n = substeps(dt, period, options);
  Sdof sdof(kTwoPi / period, damping, hardening_of(options), dt / static_cast<double>(n));
  return sdof.peak(accel.data(), accel.size(), n, uy);
}

}  // namespace adjoin
