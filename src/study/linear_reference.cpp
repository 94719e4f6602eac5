#include "adjoin/study/linear_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"

namespace adjoin {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr int kOutputs = 4;  // x, v, f1, f2 of one channel
using Values = std::array<double, kOutputs>;

// 21-point Gauss–Kronrod rule on [-1, 1] (QUADPACK qk21): xgk[1], xgk[3], ... are the
// 10-point Gauss nodes (weights wg), xgk[10] = 0 is the centre.
constexpr double kXgk[11] = {
    0.995657163025808080735527280689003, 0.973906528517171720077964012084452,
    0.930157491355708226001207180059508, 0.865063366688984510732096688423493,
    0.780817726586416897063717578345042, 0.679409568299024406234327365114874,
    0.562757134668604683339000099272694, 0.433395394129247190799265943165784,
    0.294392862701460198131126603103866, 0.148874338981631210884826001129720,
    0.000000000000000000000000000000000};
constexpr double kWgk[11] = {
    0.011694638867371874278064396062192, 0.032558162307964727478818972459390,
    0.054755896574351996031381300244580, 0.075039674810919952767043140916190,
    0.093125454583697605535065465083366, 0.109387158802297641899210590325805,
    0.123491976262065851077958109831074, 0.134709217311473325928054001771707,
    0.142775938577060080797094273138717, 0.147739104901338491374841515972068,
    0.149445554002916905664936468389821};
constexpr double kWg[5] = {
    0.066671344308688137593568809893332, 0.149451349150580593145776339657697,
    0.219086362515982043995534934228163, 0.269266719309996355091226921569469,
    0.295524224714752870173892994651338};

struct Panel {
  double a, b;
  Values value, error;
  Values floor;   // rounding level of the panel's sum: no subdivision gets below it
  double weight;  // sum over outputs of error / tolerance
};

// Adaptive Gauss–Kronrod quadrature of a vector-valued smooth integrand over [a, b], bisecting
// the panel with the largest (scaled) error until the absolute error of every output is below
// `tol` (estimated by |K21 - G10|, which bounds the error of the far more accurate K21 result)
// or is at the rounding level of the sums.
template <class F>
Values integrate(const F& f, double a, double b, double tol, int initial_panels) {
  auto rule = [&](double lo, double hi) {
    Panel p{lo, hi, {}, {}, {}, 0.0};
    const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    Values k{}, g{}, kabs{};
    const Values fc = f(c);
    for (int n = 0; n < kOutputs; ++n) {
      k[n] = kWgk[10] * fc[n];
      kabs[n] = kWgk[10] * std::abs(fc[n]);
    }
    for (int j = 0; j < 10; ++j) {
      const Values f1 = f(c - h * kXgk[j]);
      const Values f2 = f(c + h * kXgk[j]);
      for (int n = 0; n < kOutputs; ++n) {
        const double sum = f1[n] + f2[n];
        k[n] += kWgk[j] * sum;
        kabs[n] += kWgk[j] * (std::abs(f1[n]) + std::abs(f2[n]));
        if (j % 2 == 1) g[n] += kWg[j / 2] * sum;
      }
    }
    for (int n = 0; n < kOutputs; ++n) {
      p.value[n] = h * k[n];
      p.floor[n] = 50.0 * std::numeric_limits<double>::epsilon() * std::abs(h) * kabs[n];
      p.error[n] = std::max(std::abs(h * (k[n] - g[n])), p.floor[n]);
      p.weight += p.error[n] / tol;
    }
    return p;
  };
  auto lighter = [](const Panel& x, const Panel& y) { return x.weight < y.weight; };
  std::vector<Panel> heap;
  heap.reserve(256);
  for (int i = 0; i < initial_panels; ++i) {
    heap.push_back(rule(a + (b - a) * i / initial_panels, a + (b - a) * (i + 1) / initial_panels));
  }
  std::make_heap(heap.begin(), heap.end(), lighter);
  constexpr int kMaxPanels = 4000;
  while (static_cast<int>(heap.size()) < kMaxPanels) {
    Values total_error{}, total_floor{};
    for (const Panel& p : heap) {
      for (int n = 0; n < kOutputs; ++n) {
        total_error[n] += p.error[n];
        total_floor[n] += p.floor[n];
      }
    }
    bool done = true;
    for (int n = 0; n < kOutputs; ++n) {
      done = done && total_error[n] <= std::max(tol, 2.0 * total_floor[n]);
    }
    if (done) break;
    std::pop_heap(heap.begin(), heap.end(), lighter);
    const Panel worst = heap.back();
    heap.pop_back();
    const double mid = 0.5 * (worst.a + worst.b);
    heap.push_back(rule(worst.a, mid));
    std::push_heap(heap.begin(), heap.end(), lighter);
    heap.push_back(rule(mid, worst.b));
    std::push_heap(heap.begin(), heap.end(), lighter);
  }
  Values sum{};
  for (const Panel& p : heap) {
    for (int n = 0; n < kOutputs; ++n) sum[n] += p.value[n];
  }
  return sum;
}

}  // namespace

LinearReference::LinearReference(const Model& model, double u0, double omega, double k,
                                 bool stuck)
    : model_(model), u0_(u0), omega_(omega), k_(k), stuck_(stuck) {
  std::string error;
  if (!model.IsValid(&error)) throw InputError(error);
  if (!(omega > 0.0) || !std::isfinite(omega)) {
    throw InputError("linear reference: ground.omega must be positive");
  }
  if (!(k >= 0.0) || !std::isfinite(k)) {
    throw InputError("linear reference: ground.k must be >= 0");
  }
  if (!std::isfinite(u0)) throw InputError("linear reference: ground.u0 must be finite");
  scale_ = std::abs(u0) * std::max(1.0, omega * omega);
  if (stuck) {
    const double c = model.rho / (model.rho + 1.0);
    ch_[0].w1 = c;
    ch_[0].w2 = c;
    setup(ch_[0]);
    ch_[1] = ch_[0];
  } else {
    ch_[0].w1 = 1.0;
    ch_[0].w2 = 0.0;
    ch_[1].w1 = 0.0;
    ch_[1].w2 = model.rho;
    setup(ch_[0]);
    setup(ch_[1]);
  }
}

cplx LinearReference::G(int rod, cplx s) const {
  const Rod& r = rod == 1 ? model_.rod1 : model_.rod2;
  const double stiffness = rod == 1 ? 1.0 : model_.eps;
  if (r.elastic) return stiffness;
  const cplx z = std::pow(s, r.order);  // principal branch
  return stiffness * (1.0 + r.tau_x * z) / (1.0 + r.tau_f * z);
}

cplx LinearReference::dG(int rod, cplx s) const {
  const Rod& r = rod == 1 ? model_.rod1 : model_.rod2;
  const double stiffness = rod == 1 ? 1.0 : model_.eps;
  if (r.elastic) return 0.0;
  const cplx z = std::pow(s, r.order);
  const cplx den = 1.0 + r.tau_f * z;
  return stiffness * r.order * (z / s) * (r.tau_x - r.tau_f) / (den * den);
}

cplx LinearReference::D(const Channel& ch, cplx s) const {
  cplx d = s * s;
  if (ch.w1 > 0.0) d += ch.w1 * G(1, s);
  if (ch.w2 > 0.0) d += ch.w2 * G(2, s);
  return d;
}

cplx LinearReference::dD(const Channel& ch, cplx s) const {
  cplx d = 2.0 * s;
  if (ch.w1 > 0.0) d += ch.w1 * dG(1, s);
  if (ch.w2 > 0.0) d += ch.w2 * dG(2, s);
  return d;
}

void LinearReference::setup(Channel& ch) const {
  ch.has_cut = (ch.w1 > 0.0 && !model_.rod1.elastic) || (ch.w2 > 0.0 && !model_.rod2.elastic);

  // The zero of D in the upper half of the cut plane. It exists and is unique (argument
  // principle: D ~ s^2 on a large half circle, and Im D > 0 all along the upper edge of the
  // cut, so arg D winds exactly once), hence any converged Newton iterate is it.
  auto weighted = [&](cplx s) { return D(ch, s) - s * s; };
  const double k_static = std::abs(weighted(cplx(1e-300, 0.0)));
  const double k_high = std::abs(weighted(cplx(1e12, 0.0)));
  std::vector<cplx> starts;
  {
    cplx s(0.0, std::sqrt(k_static));
    for (int i = 0; i < 30; ++i) s = cplx(0.0, 1.0) * std::sqrt(weighted(s));
    starts.push_back(s);
  }
  starts.emplace_back(0.0, std::sqrt(k_static));
  starts.emplace_back(0.0, std::sqrt(k_high));
  starts.emplace_back(0.0, std::sqrt(std::sqrt(k_static * k_high)));
  for (double radius : {0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0}) {
    for (double angle : {0.5, 0.6, 0.7, 0.8, 0.9, 0.97}) {
      starts.push_back(std::polar(radius * std::sqrt(std::max(k_static, 1e-300)), angle * kPi));
    }
  }
  bool found = false;
  for (cplx s : starts) {
    bool converged = false;
    for (int it = 0; it < 100 && std::isfinite(s.real()) && std::isfinite(s.imag()); ++it) {
      const cplx step = D(ch, s) / dD(ch, s);
      // Damp steps that would jump across the cut or far away.
      const double limit = 0.5 * std::abs(s) + 1e-3;
      const cplx taken = std::abs(step) > limit ? step * (limit / std::abs(step)) : step;
      s -= taken;
      if (std::abs(taken) <= 1e-15 * std::abs(s)) {
        converged = true;
        break;
      }
    }
    if (!converged || !std::isfinite(s.real()) || !std::isfinite(s.imag()) || s.imag() == 0.0) {
      continue;
    }
    if (s.imag() < 0.0) s = std::conj(s);
    if (std::abs(D(ch, s)) > 1e-11 * (std::abs(s * s) + std::abs(weighted(s)))) continue;
    ch.root = s;
    found = true;
    break;
  }
  if (!found) {
    throw NumericalError("linear reference: could not locate the natural pole of the model", 0.0);
  }

  // Residues. Ground poles p, conj(p) with p = -k + iW: A = u0 W^3 / ((s - p)(s - conj p)).
  const cplx p(-k_, omega_);
  const cplx dp = D(ch, p);
  const double size = std::abs(p * p) + std::abs(weighted(p));
  if (std::abs(dp) <= 1e-9 * size || std::abs(ch.root - p) <= 1e-7 * std::abs(p)) {
    std::ostringstream m;
    m << "linear reference: the ground motion (omega = " << omega_ << ", k = " << k_
      << ") resonates exactly with the structure (double pole); change omega or k";
    throw InputError(m.str());
  }
  const double a0 = u0_ * omega_ * omega_ * omega_;
  auto numerators = [&](cplx s) {
    return std::array<cplx, 4>{1.0, s, G(1, s), G(2, s)};
  };
  const cplx ground = a0 / (cplx(0.0, 2.0 * omega_) * dp);
  const auto np = numerators(p);
  const cplx s1 = ch.root;
  const cplx natural = a0 / (((s1 + k_) * (s1 + k_) + omega_ * omega_) * dD(ch, s1));
  const auto nr = numerators(s1);
  for (int n = 0; n < kOutputs; ++n) {
    ch.cp[n] = ground * np[n];
    ch.cr[n] = natural * nr[n];
  }
}

LinearResponse LinearReference::at(double t) const {
  LinearResponse out;
  if (!(t > 0.0) || scale_ == 0.0) return out;
  const cplx p(-k_, omega_);
  const cplx ep = std::exp(p * t);

  auto channel_values = [&](const Channel& ch) {
    const cplx er = std::exp(ch.root * t);
    Values v{};
    for (int n = 0; n < kOutputs; ++n) v[n] = 2.0 * std::real(ch.cp[n] * ep + ch.cr[n] * er);
    if (!ch.has_cut) return v;

    // (1/pi) int_0^inf Im Z(r e^{-i pi}) e^{-rt} dr with r = e^u. On the lower edge of the cut
    // s = -r, s^2 = r^2, s^g = r^g e^{-i g pi}.
    const Rod& r1 = model_.rod1;
    const Rod& r2 = model_.rod2;
    const bool frac1 = ch.w1 > 0.0 && !r1.elastic, frac2 = ch.w2 > 0.0 && !r2.elastic;
    const cplx phase1 = std::polar(1.0, -r1.order * kPi);
    const cplx phase2 = std::polar(1.0, -r2.order * kPi);
    const double a0 = u0_ * omega_ * omega_ * omega_;
    const double eps = model_.eps;
    auto integrand = [&](double u) {
      const double r = std::exp(u);
      const double weight = r * std::exp(-r * t) / kPi;
      Values f{};
      if (weight == 0.0) return f;
      const double a = a0 / ((k_ - r) * (k_ - r) + omega_ * omega_);
      cplx g1 = 1.0, g2 = eps;
      if (!r1.elastic) {
        const cplx z = std::exp(r1.order * u) * phase1;
        g1 = (1.0 + r1.tau_x * z) / (1.0 + r1.tau_f * z);
      }
      if (!r2.elastic) {
        const cplx z = std::exp(r2.order * u) * phase2;
        g2 = eps * (1.0 + r2.tau_x * z) / (1.0 + r2.tau_f * z);
      }
      const cplx x = a / (r * r + ch.w1 * g1 + ch.w2 * g2);
      f[0] = weight * x.imag();
      f[1] = -r * f[0];
      f[2] = weight * (g1 * x).imag();
      f[3] = weight * (g2 * x).imag();
      return f;
    };
    // Im Z ~ r^g near r = 0 (g the smallest fractional order present) and decays
    // exponentially through e^{-rt}: truncate where the integrand is below ~1e-20 * scale.
    double g_min = 1.0;
    if (frac1) g_min = std::min(g_min, r1.order);
    if (frac2) g_min = std::min(g_min, r2.order);
    const double u_lo = std::log(1e-22) / (1.0 + g_min);
    const double u_hi = std::log(std::min(48.0 / t, 1e8));
    if (u_hi <= u_lo) return v;
    const int panels = std::max(4, static_cast<int>(std::ceil((u_hi - u_lo) / 3.0)));
    const Values cut = integrate(integrand, u_lo, u_hi, 1e-15 * scale_, panels);
    for (int n = 0; n < kOutputs; ++n) v[n] += cut[n];
    return v;
  };

  const Values a = channel_values(ch_[0]);
  if (stuck_) {
    out.x[0] = out.x[1] = a[0];
    out.v[0] = out.v[1] = a[1];
    out.storey_force[0] = a[2];
    out.storey_force[1] = a[3];
    out.link_force = (model_.rho * out.storey_force[1] - out.storey_force[0]) / (model_.rho + 1.0);
  } else {
    const Values b = channel_values(ch_[1]);
    out.x[0] = a[0];
    out.v[0] = a[1];
    out.storey_force[0] = a[2];
    out.x[1] = b[0];
    out.v[1] = b[1];
    out.storey_force[1] = b[3];
    out.link_force = 0.0;
  }
  return out;
}

std::complex<double> LinearReference::natural_pole(int block) const {
  return ch_[stuck_ || block == 1 ? 0 : 1].root;
}

}  // namespace adjoin
