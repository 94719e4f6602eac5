#include "adjoin/fractional/mittag_leffler.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

// Garrappa's optimal parabolic contour (OPC) algorithm, restricted to the two-parameter
// function (his gamma = 1) and evaluated at t = 1. Notation follows the paper: the Laplace
// transform F(s) = s^{alpha-beta} / (s^alpha - z) has a branch point at s = 0 and poles s*
// with s*^alpha = z; the parabola s(u) = mu (1 + i u)^2 passes through the points s with
// phi(s) = (Re s + |s|) / 2 = mu, so sorting the singularities by phi splits the plane into
// regions in which the contour may run. In each admissible region the step h and the number
// of nodes N are optimised to balance discretisation and truncation errors against the target
// tolerance; the region needing fewest nodes wins, and the residues of the poles to the right
// of its contour are added.
namespace adjoin {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr double kTolerance = 1e-15;     // the algorithm's target |E - E~| / (1 + |E|)
constexpr double kTiny = 1e-14;          // "zero" for the singularity strengths p, q
constexpr double kMaxNodes = 200.0;      // relax the tolerance if more nodes would be needed
constexpr double kNoRegion = std::numeric_limits<double>::infinity();
const double kLogMachineEps = std::log(std::numeric_limits<double>::epsilon());

struct Contour {
  double mu = 0.0;
  double h = 0.0;
  double nodes = kNoRegion;  // N: the rule uses 2N + 1 nodes; kNoRegion if not admissible
};

// phi(s) = (Re s + |s|) / 2 without the cancellation of the direct formula when Re s < 0:
// a pole on the negative axis must get phi = 0 (it lies left of every contour), not the
// rounding noise of |s| - |Re s|.
double phi_of(cplx s) {
  const double a = std::abs(s);
  if (s.real() >= 0.0) return 0.5 * (s.real() + a);
  return 0.5 * s.imag() * s.imag() / (a - s.real());
}

// Parameters for a region bounded on the right: phi_j < mu < phi_j1 (paper §4.1, with t = 1).
// p and q are the strengths of the singularities on the left and right boundary.
Contour right_bounded(double phi_j, double phi_j1, double p, double q, double log_eps) {
  constexpr double fac = 1.01;
  const double f_max = std::exp(log_eps - kLogMachineEps);
  const double sq_j = std::sqrt(phi_j);
  const double threshold = 2.0 * std::sqrt(log_eps - kLogMachineEps);
  const double sq_j1 = std::min(std::sqrt(phi_j1), threshold - sq_j);

  double sqbar_j = sq_j, sqbar_j1 = sq_j1, f_bar = 1.0;
  if (p < kTiny && q < kTiny) {
    // Neither boundary is singular: use the whole region.
  } else if (p < kTiny) {
    const double f_min = sq_j > 0.0 ? fac * std::pow(sq_j / (sq_j1 - sq_j), q) : fac;
    if (f_min >= f_max) return {};
    f_bar = f_min + f_min / f_max * (f_max - f_min);
    const double fq = std::pow(f_bar, -1.0 / q);
    sqbar_j1 = (2.0 * sq_j1 - fq * sq_j) / (2.0 + fq);
  } else if (q < kTiny) {
    const double f_min = fac * std::pow(sq_j1 / (sq_j1 - sq_j), p);
    if (f_min >= f_max) return {};
    f_bar = f_min + f_min / f_max * (f_max - f_min);
    const double fp = std::pow(f_bar, -1.0 / p);
    sqbar_j = (2.0 * sq_j + fp * sq_j1) / (2.0 - fp);
  } else {
    double f_min = fac * (sq_j + sq_j1) / std::pow(sq_j1 - sq_j, std::max(p, q));
    if (f_min >= f_max) return {};
    f_min = std::max(f_min, 1.5);
    f_bar = f_min + f_min / f_max * (f_max - f_min);
    const double fp = std::pow(f_bar, -1.0 / p);
    const double fq = std::pow(f_bar, -1.0 / q);
    const double w = -phi_j1 / log_eps;
    const double den = 2.0 + w - (1.0 + w) * fp + fq;
    sqbar_j = ((2.0 + w + fq) * sq_j + fp * sq_j1) / den;
    sqbar_j1 = (-(1.0 + w) * fq * sq_j + (2.0 + w - (1.0 + w) * fp) * sq_j1) / den;
  }
  // The singularities cost a factor f_bar of accuracy; ask the quadrature for that much more.
  log_eps -= std::log(f_bar);
  const double w = -sqbar_j1 * sqbar_j1 / log_eps;
  Contour c;
  const double mid = (1.0 + w) * sqbar_j + sqbar_j1;
  c.mu = std::pow(mid / (2.0 + w), 2);
  c.h = -2.0 * kPi / log_eps * (sqbar_j1 - sqbar_j) / mid;
  c.nodes = std::ceil(std::sqrt(1.0 - log_eps / c.mu) / c.h);
  if (!(c.h > 0.0) || !std::isfinite(c.nodes)) return {};
  return c;
}

// Parameters for the right-unbounded region mu > phi_j (paper §4.2, with t = 1).
Contour right_unbounded(double phi_j, double p, double log_eps) {
  const double sq_j = std::sqrt(phi_j);
  double phibar = phi_j > 0.0 ? phi_j * 1.01 : 0.01;
  double sqbar = std::sqrt(phibar);
  constexpr double f_min = 1.0, f_max = 10.0, f_tar = 5.0;

  double nodes = 0.0, a = 0.0, sq_mu = 0.0;
  // Move the left end of the usable region until the singularity's amplification f_bar of
  // the error lies in [f_min, f_max]; converges in a handful of passes.
  for (int pass = 0; pass < 100; ++pass) {
    const double log_eps_phi = log_eps / phibar;
    nodes = std::ceil(phibar / kPi * (1.0 - 1.5 * log_eps_phi + std::sqrt(1.0 - 2.0 * log_eps_phi)));
    a = kPi * nodes / phibar;
    sq_mu = sqbar * std::abs(4.0 - a) / std::abs(7.0 - std::sqrt(1.0 + 12.0 * a));
    const double f_bar = std::pow((sqbar - sq_j) / sq_mu, -p);
    if (p < kTiny || (f_min < f_bar && f_bar < f_max)) break;
    sqbar = std::pow(f_tar, -1.0 / p) * sq_mu + sq_j;
    phibar = sqbar * sqbar;
  }
  Contour c;
  c.mu = sq_mu * sq_mu;
  c.h = (-3.0 * a - 2.0 + 2.0 * std::sqrt(1.0 + 12.0 * a)) / (4.0 - a) / nodes;
  c.nodes = nodes;

  // A large mu means exp(mu) times rounding swamps the result: cap mu and recompute.
  const double threshold = log_eps - kLogMachineEps;
  if (c.mu > threshold) {
    const double q = std::abs(p) < kTiny ? 0.0 : std::pow(f_tar, -1.0 / p) * std::sqrt(c.mu);
    phibar = std::pow(q + sq_j, 2);
    if (phibar >= threshold) return {};
    const double w = std::sqrt(kLogMachineEps / (kLogMachineEps - log_eps));
    const double u = std::sqrt(-phibar / kLogMachineEps);
    c.mu = threshold;
    c.nodes = std::ceil(w * log_eps / (2.0 * kPi) / (u * w - 1.0));
    c.h = w / c.nodes;
  }
  if (!(c.h > 0.0) || !std::isfinite(c.nodes) || c.nodes < 1.0) return {};
  return c;
}

}  // namespace

double mittag_leffler(double alpha, double beta, double z) {
  if (!(alpha > 0.0) || !std::isfinite(alpha))
    throw std::invalid_argument("mittag_leffler: alpha must be positive and finite");
  if (!(beta > 0.0) || !std::isfinite(beta))
    throw std::invalid_argument("mittag_leffler: beta must be positive and finite");
  if (std::isnan(z)) return z;
  // The series' second term z / Gamma(alpha + beta) is below the tolerance.
  if (std::abs(z) < kTolerance) return 1.0 / std::tgamma(beta);

  // Poles s^alpha = z on the principal sheet: s = |z|^{1/alpha} e^{i (theta + 2 k pi) / alpha}
  // with |theta + 2 k pi| <= alpha pi.
  const double theta = z < 0.0 ? kPi : 0.0;
  const double kmin = std::ceil(-alpha / 2.0 - theta / (2.0 * kPi));
  const double kmax = std::floor(alpha / 2.0 - theta / (2.0 * kPi));
  const double radius = std::pow(std::abs(z), 1.0 / alpha);
  struct Pole { cplx s; double phi; };
  std::vector<Pole> poles;
  for (double k = kmin; k <= kmax; k += 1.0) {
    const cplx s = std::polar(radius, (theta + 2.0 * k * kPi) / alpha);
    const double phi = phi_of(s);
    // Poles with phi = 0 lie left of every parabola: never crossed, no residue.
    if (phi > kTolerance) poles.push_back({s, phi});
  }
  std::sort(poles.begin(), poles.end(), [](const Pole& a, const Pole& b) { return a.phi < b.phi; });

  // Singularities by phi: the branch point at the origin, the poles, then +infinity.
  const std::size_t n_sing = poles.size() + 1;
  std::vector<double> phi(n_sing + 1), p(n_sing, 1.0), q(n_sing, 1.0);
  phi[0] = 0.0;
  for (std::size_t i = 0; i < poles.size(); ++i) phi[i + 1] = poles[i].phi;
  phi[n_sing] = std::numeric_limits<double>::infinity();
  p[0] = std::max(0.0, -2.0 * (alpha - beta + 1.0));  // strength of the branch point
  q[n_sing - 1] = std::numeric_limits<double>::infinity();

  double log_eps = std::log(kTolerance);
  std::vector<Contour> contour(n_sing);
  std::size_t best = 0;
  for (;;) {
    const double round_off_limit = log_eps - kLogMachineEps;
    for (std::size_t j = 0; j < n_sing; ++j) {
      contour[j] = Contour{};
      if (!(phi[j] < round_off_limit && phi[j] < phi[j + 1])) continue;
      contour[j] = j + 1 < n_sing ? right_bounded(phi[j], phi[j + 1], p[j], q[j], log_eps)
                                  : right_unbounded(phi[j], p[j], log_eps);
    }
    best = 0;
    for (std::size_t j = 1; j < n_sing; ++j)
      if (contour[j].nodes < contour[best].nodes) best = j;
    if (contour[best].nodes <= kMaxNodes || log_eps > std::log(1e-5)) break;
    log_eps += std::log(10.0);
  }
  const Contour& c = contour[best];
  if (!std::isfinite(c.nodes))
    throw std::runtime_error("mittag_leffler: no admissible integration contour");

  // Trapezoidal rule for (1 / 2 pi i) ∫ e^s F(s) ds on s(u) = mu (1 + i u)^2. For real z the
  // integrand at -u is minus the conjugate of that at u, so the sum is
  // i (Im g_0 + 2 sum_{k>0} Im g_k) and only half the nodes are needed.
  const long n = static_cast<long>(c.nodes);
  const double am_b = alpha - beta;
  auto node = [&](double u) {
    const cplx s = c.mu * std::pow(cplx(1.0, u), 2);
    const cplx ds = 2.0 * c.mu * cplx(-u, 1.0);
    return std::exp(s) * std::pow(s, am_b) / (std::pow(s, alpha) - z) * ds;
  };
  double sum = node(0.0).imag();
  for (long k = 1; k <= n; ++k) sum += 2.0 * node(c.h * static_cast<double>(k)).imag();
  double e = c.h * sum / (2.0 * kPi);

  // Residues (1/alpha) s^{1-beta} e^s of the poles right of the chosen contour. Complex poles
  // come in conjugate pairs whose imaginary parts cancel.
  for (std::size_t i = best; i < poles.size(); ++i) {
    const cplx s = poles[i].s;
    e += (std::pow(s, 1.0 - beta) * std::exp(s)).real() / alpha;
  }
  return e;
}

}  // namespace adjoin
