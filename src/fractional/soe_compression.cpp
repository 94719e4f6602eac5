// The sum-of-exponentials compression of the convolution weights (soe_history.hpp has the
// method): the quadrature of the real-axis integral, its modes, and the verification
// against the exact weights that sets the step and gives the reported bound.
#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "adjoin/fractional/soe_history.hpp"

namespace adjoin {
namespace {

constexpr std::size_t kWindow = 32;                      // n0
constexpr std::size_t kMinDesign = std::size_t{1} << 10;  // N at least: short runs share one
constexpr std::size_t kDense = 1024;                     // verified at every lag below this
constexpr int kPerOctave = 64;                           // and at this many lags per octave above
constexpr std::size_t kPairedLags = 400;  // two-term modes (|lambda| < 0.74) vanish beyond n0 + this
constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxNodes = 2000;  // on either side of u_c (a tolerance of 1e-15 takes about 80)

// delta(zeta) = d0 + d1 zeta + d2 zeta^2.
struct Delta {
  double d0, d1, d2;
};
Delta delta_of(WeightRule rule) { return rule == WeightRule::bdf2 ? Delta{1.5, -2.0, 0.5} : Delta{1.0, -1.0, 0.0}; }

// log Gamma(z) - (z - 1/2) log z + z: the tail of Stirling's series (z >= 1000: the next term is
// below 1e-27).
long double stirling_tail(long double z) {
  const long double z2 = z * z;
  return (1.0L / 12 - (1.0L / 360 - (1.0L / 1260 - 1.0L / (1680 * z2)) / z2) / z2) / z;
}

// log(Gamma(n - a) / Gamma(n + 1)) up to a constant, for n >= 1000, written so that the large
// terms of the two Stirling series cancel exactly (z1 - z2 = -(1 + a)).
long double log_gamma_ratio(long double n, long double a) {
  const long double z1 = n - a, z2 = n + 1, dz = -(1 + a);
  return (z1 - 0.5L) * std::log1p(dz / z2) + dz * std::log(z2) - dz + stirling_tail(z1) - stirling_tail(z2);
}

// The exact weights at any lag: J.C.P. Miller's recurrence in long double up to kDense; above,
// the Grünwald–Letnikov weight g_n = Gamma(n - a) / (Gamma(-a) Gamma(n + 1)) from g_kDense and
// the ratio of Gamma functions by Stirling's series, and for BDF2 (delta = (1 - zeta)(3 - zeta)/2)
// its convolution with the coefficients (3/2)^a g_k 3^-k of ((3 - zeta)/2)^a, which fall below
// 1e-19 of the first past k = 40. (GSL's Pochhammer symbol was tried: 1e-9 off at n = 2^22.)
class ExactWeights {
 public:
  ExactWeights(WeightRule rule, double order) : rule_(rule), order_(order), dense_(kDense + 1) {
    const Delta d = delta_of(rule);
    const long double a = order;
    dense_[0] = std::pow(static_cast<long double>(d.d0), a);
    long double g = 1.0L;  // the GL weights alongside
    for (std::size_t n = 1; n <= kDense; ++n) {
      const long double dn = static_cast<long double>(n);
      long double s = ((a + 1) - dn) * d.d1 * dense_[n - 1];
      if (n >= 2) s += ((a + 1) * 2 - dn) * d.d2 * dense_[n - 2];
      dense_[n] = s / (dn * d.d0);
      g *= 1.0L - (a + 1) / dn;
    }
    log_anchor_ = std::log(-g) - log_gamma_ratio(kDense, a);  // g_n < 0 for n >= 1
    long double gk = 1.0L, third = 1.0L;
    for (std::size_t k = 0; k < kTail; ++k) {
      tail_[k] = std::pow(1.5L, a) * gk * third;
      gk *= 1.0L - (a + 1) / static_cast<long double>(k + 1);
      third /= 3.0L;
    }
  }

  long double at(std::size_t n) const {
    if (n <= kDense) return dense_[n];
    const long double a = order_;
    long double g = -std::exp(log_anchor_ + log_gamma_ratio(static_cast<long double>(n), a));
    if (rule_ == WeightRule::grunwald_letnikov) return g;
    long double sum = 0.0L;
    for (std::size_t k = 0; k < kTail; ++k) {  // g_{n-k}, going down: g_{j-1} = g_j j / (j - a - 1)
      sum += tail_[k] * g;
      const long double j = static_cast<long double>(n - k);
      g *= j / (j - a - 1);
    }
    return sum;
  }

 private:
  static constexpr std::size_t kTail = 41;
  WeightRule rule_;
  double order_;
  std::vector<long double> dense_;
  long double tail_[kTail];
  long double log_anchor_ = 0.0L;
};

// e_n(x) for n = n0 - 1, n0, n0 + 1 (the coefficients of 1/(delta + x)), by their recurrence.
struct Local {
  long double before, at, after;
};
Local local_e(const Delta& d, double x, std::size_t n0) {
  const long double den = d.d0 + static_cast<long double>(x), a = -d.d1 / den, b = -d.d2 / den;
  long double e2 = 0.0L, e1 = 1.0L / den;  // e_{-1} = 0, e_0
  for (std::size_t n = 1; n <= n0 - 1; ++n) {
    const long double e = a * e1 + b * e2;
    e2 = e1;
    e1 = e;
  }
  const long double at = a * e1 + b * e2;
  return {e1, at, a * at + b * e1};
}

void pad(std::vector<double>& v) { v.resize((v.size() + 3) / 4 * 4, 0.0); }

// The quadrature nodes x_q and weights C_q of w_n = -(sin(pi a)/pi) int_0^inf x^a e_n(x) dx for
// n in [n0, N], by the trapezoidal rule with step `step` in u, x = exp(u - exp(-(u - u_c))), the
// ends where a node adds less than `cut` relative to the smallest weight it serves.
void add_nodes(const Delta& d, double order, std::size_t n0, std::size_t design, double step, double cut,
               const ExactWeights& exact, std::vector<double>* xs, std::vector<double>* cs) {
  const double scale = -std::sin(kPi * order) / kPi;
  const double uc = std::log(0.1 / static_cast<double>(design));
  const double small_n = std::fabs(static_cast<double>(exact.at(n0)));
  const double small_N = std::fabs(static_cast<double>(exact.at(design)));
  auto node = [&](double u) {
    const double grade = std::exp(-(u - uc));
    const double x = std::exp(u - grade);
    xs->push_back(x);
    cs->push_back(scale * step * std::pow(x, order) * x * (1.0 + grade));
  };
  for (int k = 0; k > -kMaxNodes; --k) {  // towards x = 0: e_n(x) <= 1 there
    node(uc + k * step);
    if (std::fabs(cs->back()) < cut * small_N) break;
  }
  for (int k = 1; k < kMaxNodes; ++k) {  // towards large x: e_n0 is the largest of those served
    node(uc + k * step);
    const double x = xs->back();
    if (x > 1.0 && std::fabs(cs->back() * static_cast<double>(local_e(d, x, n0).at)) < cut * small_n) break;
  }
}

// The modes of one node (soe_history.hpp: one-term for GL, and for BDF2 below x = 0.3 where the
// recurrence's roots are real and apart; two-term above).
void add_modes(const Delta& d, std::size_t n0, double x, double c, double negligible, SoeCompression* out) {
  const double n0d = static_cast<double>(n0);
  if (d.d2 == 0.0) {  // e_n = lambda^(n+1), lambda = 1/(1 + x)
    out->decay.push_back(x / (1.0 + x));
    out->gain.push_back(c * std::exp(-(n0d + 1.0) * std::log1p(x)));
    return;
  }
  if (x < 0.3) {  // roots 1/(1 + t) (near 1) and 1/(2 + root), e_n = g1 l1^n + g2 l2^n
    const double root = std::sqrt(1.0 - 2.0 * x), t = 2.0 * x / (1.0 + root);
    const double l1 = 1.0 / (1.0 + t), l2 = 1.0 / (2.0 + root);
    const double g1 = 2.0 * l1 * l1 * l2 / (l1 - l2), g2 = -2.0 * l1 * l2 * l2 / (l1 - l2);
    out->decay.push_back(t / (1.0 + t));
    out->gain.push_back(c * g1 * std::exp(-n0d * std::log1p(t)));
    // l2 < 0.4: the second mode only matters at lags near n0; mostly below 1e-13 of w_n0 there.
    const double gain2 = c * g2 * std::pow(l2, n0d);
    if (std::fabs(gain2) >= negligible) {
      out->decay.push_back(1.0 - l2);
      out->gain.push_back(gain2);
    }
    return;
  }
  const Local e = local_e(d, x, n0);
  const double den = d.d0 + x, a = -d.d1 / den, b = -d.d2 / den;
  out->a.push_back(a);
  out->b.push_back(b);
  out->p.push_back(c * static_cast<double>(e.at));
  out->r.push_back(c * b * static_cast<double>(e.before));
}

// The lags at which a compression is verified: all up to kDense, then kPerOctave per octave, and N.
std::vector<std::size_t> sample_lags(std::size_t n0, std::size_t design) {
  std::vector<std::size_t> lags;
  for (std::size_t n = n0; n <= std::min(kDense, design); ++n) lags.push_back(n);
  for (double n = static_cast<double>(kDense); n < static_cast<double>(design);) {
    n *= std::exp2(1.0 / kPerOctave);
    const auto lag = std::min(design, static_cast<std::size_t>(n));
    if (lag > lags.back()) lags.push_back(lag);
  }
  if (lags.back() != design) lags.push_back(design);
  return lags;
}

struct Built {
  SoeCompression c;
  std::vector<double> log_keep;  // log(1 - decay) per one-term mode
  std::vector<double> paired_sum;  // the two-term modes' weights summed, lags n0..n0+kPairedLags
};

// The compression's weight at a lag n > kDense (the modes that have decayed by e^-60 or more,
// below 1e-20 of any weight served, are left out).
double weight_of(const Built& b, std::size_t n) {
  const SoeCompression& c = b.c;
  const double k = static_cast<double>(n - c.window);
  double w = n - c.window < b.paired_sum.size() ? b.paired_sum[n - c.window] : 0.0;
  for (std::size_t q = 0; q < c.single; ++q)
    if (const double e = k * b.log_keep[q]; e > -60.0) w += c.gain[q] * std::exp(e);
  return w;
}

// The largest relative error over the sampled lags: up to kDense by stepping each mode's
// weight in long double (1024 products lose under 1e-16), beyond it by weight_of.
double largest_error(const Built& b, const ExactWeights& exact) {
  const SoeCompression& c = b.c;
  std::vector<long double> mode(c.gain.begin(), c.gain.begin() + static_cast<std::ptrdiff_t>(c.single));
  std::vector<long double> keep(c.single);
  for (std::size_t q = 0; q < c.single; ++q) keep[q] = 1.0L - c.decay[q];
  double error = 0.0;
  for (std::size_t n : sample_lags(c.window, c.design_length)) {
    long double w = 0.0L;
    if (n <= kDense) {  // every lag from n0: the modes are at lag n
      w = n - c.window < b.paired_sum.size() ? b.paired_sum[n - c.window] : 0.0;
      for (std::size_t q = 0; q < c.single; ++q) {
        w += mode[q];
        mode[q] *= keep[q];
      }
    } else {
      w = weight_of(b, n);
    }
    const long double exact_w = exact.at(n);
    error = std::max(error, static_cast<double>(std::fabs((w - exact_w) / exact_w)));
  }
  return error;
}

Built build(WeightRule rule, double order, double tolerance, std::size_t design, double step, double cut,
            const ExactWeights& exact) {
  const Delta d = delta_of(rule);
  Built out;
  SoeCompression& c = out.c;
  c.rule = rule;
  c.order = order;
  c.tolerance = tolerance;
  c.window = kWindow;
  c.near = convolution_weights(rule, order, kWindow);
  c.near_shifted.assign(kWindow, 0.0);  // entry i: the weight of y_{m-n0-1+i}, lag n0 + 1 - i
  for (std::size_t j = 2; j < kWindow; ++j) c.near_shifted[kWindow + 1 - j] = c.near[j];
  c.design_length = design;
  std::vector<double> xs, cs;
  add_nodes(d, order, kWindow, design, step, cut, exact, &xs, &cs);
  const double negligible = cut * std::fabs(static_cast<double>(exact.at(kWindow)));
  for (std::size_t q = 0; q < xs.size(); ++q) add_modes(d, kWindow, xs[q], cs[q], negligible, &c);
  c.single = c.decay.size();
  c.paired = c.a.size();
  for (std::size_t q = 0; q < c.single; ++q) out.log_keep.push_back(std::log1p(-c.decay[q]));
  out.paired_sum.assign(kPairedLags + 1, 0.0);
  for (std::size_t q = 0; q < c.paired; ++q) {
    double w2 = 0.0, w1 = c.p[q];  // W_{n0-1} (any: b W is r), W_n0
    out.paired_sum[0] += w1;
    double next = c.r[q] + c.a[q] * w1;
    for (std::size_t k = 1; k <= kPairedLags; ++k) {
      out.paired_sum[k] += next;
      w2 = w1;
      w1 = next;
      next = c.a[q] * w1 + c.b[q] * w2;
    }
  }
  for (auto* v : {&c.decay, &c.gain, &c.a, &c.b, &c.p, &c.r}) pad(*v);
  c.error = largest_error(out, exact);
  return out;
}

// Refines the quadrature's step until the verified error is within the tolerance. The first
// step is from the trapezoidal rule's error estimate exp(-2 pi d / step) with d = 1.45, a little
// under the strip's half-width pi/2; most orders verify at once, the others after a refinement
// or two by 5 % (at 1e-12, orders 0.05 to 0.95: Q = 52 to 57 modes at N = 2^13, 77 to 82 at
// 2^24, errors up to 9.2e-13, 1.26 attempts on average). The fixed d = 1.3 of before
// verified every order at once, with errors of 1e-14 to 1e-13 and about 10 % more modes. Past
// three small refinements (tolerances near the doubles' precision), larger ones.
std::shared_ptr<const SoeCompression> make(WeightRule rule, double order, double tolerance, std::size_t design) {
  const ExactWeights exact(rule, order);
  double step = 2.0 * kPi * 1.45 / (std::log(1.0 / tolerance) + 3.0);
  double cut = 0.1 * tolerance;
  Built best = build(rule, order, tolerance, design, step, cut, exact);
  for (int attempt = 0; attempt < 11 && best.c.error > tolerance; ++attempt) {
    step *= attempt < 3 ? 0.95 : 0.85;
    cut *= attempt < 3 ? 0.5 : 0.1;
    Built next = build(rule, order, tolerance, design, step, cut, exact);
    if (next.c.error < best.c.error) best = std::move(next);
  }
  return std::make_shared<const SoeCompression>(std::move(best.c));
}

}  // namespace

double SoeCompression::weight(std::size_t n) const {
  if (n < window) return near[n];
  const std::size_t k = n - window;
  double w = 0.0;
  for (std::size_t q = 0; q < single; ++q) w += gain[q] * std::exp(static_cast<double>(k) * std::log1p(-decay[q]));
  if (k <= kPairedLags)
    for (std::size_t q = 0; q < paired; ++q) {
      double w2 = 0.0, w1 = p[q], next = r[q] + a[q] * p[q];
      for (std::size_t i = 0; i < k; ++i) {
        w2 = w1;
        w1 = next;
        next = a[q] * w1 + b[q] * w2;
      }
      w += w1;
    }
  return w;
}

std::size_t SoeCompression::bytes() const {
  return sizeof(*this) + (near.capacity() + near_shifted.capacity() + decay.capacity() + gain.capacity() + a.capacity() + b.capacity() +
                          p.capacity() + r.capacity()) * sizeof(double);
}

std::shared_ptr<const SoeCompression> soe_compression(WeightRule rule, double order, double tolerance,
                                                      std::size_t last_lag) {
  if (!(order > 0.0 && order < 1.0)) throw std::invalid_argument("soe history: the order must lie in (0, 1)");
  if (!(tolerance >= 1e-15 && tolerance < 1.0))
    throw std::invalid_argument("soe history: the tolerance must lie in [1e-15, 1)");
  static std::mutex mutex;
  static std::map<std::tuple<WeightRule, double, double, std::size_t>, std::shared_ptr<const SoeCompression>> cache;
  // The design length is the run's own, rounded up to a power of two: a short run pays for a
  // short compression (fewer nodes, fewer lags to verify, smaller Q), and a run's modes depend
  // on its length only, never on the runs made before it in the process.
  const std::size_t design = std::max(kMinDesign, std::bit_ceil(last_lag));
  const std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[{rule, order, tolerance, design}];
  if (!entry) entry = make(rule, order, tolerance, design);
  return entry;
}

}  // namespace adjoin
