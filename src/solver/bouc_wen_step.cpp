#include "bouc_wen_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adjoin::detail {
namespace {

double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

}  // namespace

BoucWenElement::BoucWenElement(int i_, int j_, int storey_, bool storey_law_, double k_, double hardening, double yield_force,
                               double n_, double beta_, double gamma_)
    : i(i_), j(j_), storey(storey_), storey_law(storey_law_), k((1.0 - hardening) * k_), u_y(yield_force / k_), n(n_) {
  const double scale = std::pow(u_y, n);
  beta = beta_ / scale;
  gamma = gamma_ / scale;
  z_limit = u_y * std::pow(beta_ + gamma_, -1.0 / n);
  if (n == std::floor(n) && n <= 20.0) whole = static_cast<int>(n);
}

double BoucWenElement::power(double a, int less) const {
  if (whole == 0) return std::pow(a, n - less);
  double r = 1.0;
  for (int p = less; p < whole; ++p) r *= a;
  return r;
}

// z' = w - beta |w| |z|^(n-1) z - gamma w |z|^n (|z|^(n-1) z = |z|^n sign z).
double BoucWenElement::rate(double z, double w) const {
  const double a = power(std::abs(z));
  return w - beta * std::abs(w) * a * sign(z) - gamma * w * a;
}

double BoucWenElement::rate_dz(double z, double w) const {
  if (z == 0.0 && n > 1.0) return 0.0;
  // (n = 1 at z = 0: the side z's sign takes under loading, sign w)
  const double s = z != 0.0 ? sign(z) : sign(w);
  return -n * power(std::abs(z), 1) * (beta * std::abs(w) + gamma * w * s);
}

double BoucWenElement::rate_dw(double z, double w) const {
  const double a = power(std::abs(z));
  const double sw = w != 0.0 ? sign(w) : (z != 0.0 ? sign(z) : 1.0);  // (at w = 0 the loading side)
  return 1.0 - beta * sw * a * sign(z) - gamma * a;
}

// z1 = c + h theta z'(z1, w1), c = z_n + h (1 - theta) z'_n: Newton's method on
// F(z) = z - c - h theta z'(z, w1), its steps halved while |F| does not fall; converged when a
// step is at rounding level of z, or F at rounding level of its terms.
bool bouc_wen_end_z(const BoucWenElement& e, const BoucWenState& st, double theta, double h, double w1, double* z1,
                    double* dz1_dw1) {
  const double ht = h * theta, c = st.z + h * (1.0 - theta) * st.rate;
  auto residual = [&](double z) { return z - c - ht * e.rate(z, w1); };
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double z = st.z1;  // (the latest solve's, or extrapolated from the last two steps: bouc_wen_commit)
  double f = residual(z);
  auto small = [&](double value, double at) { return std::abs(value) <= 8.0 * eps * (std::abs(c) + ht * std::abs(w1) + std::abs(at)); };
  bool converged = small(f, z);
  for (int it = 0; it < 100 && !converged; ++it) {
    const double slope = 1.0 - ht * e.rate_dz(z, w1);
    if (!(std::isfinite(slope) && slope != 0.0)) return false;
    double step = f / slope;
    if (std::abs(step) <= 4.0 * eps * std::abs(z)) {  // (Newton's last step: below z's rounding)
      z -= step;
      converged = true;
      break;
    }
    double z_try = z - step, f_try = residual(z_try);
    for (int halving = 0; halving < 30 && !(std::abs(f_try) < std::abs(f)); ++halving) {
      step *= 0.5;
      z_try = z - step;
      f_try = residual(z_try);
    }
    if (!(std::abs(f_try) < std::abs(f))) return false;  // (no descent: not converging)
    z = z_try;
    f = f_try;
    converged = small(f, z);
  }
  if (!converged || !std::isfinite(z)) return false;
  *z1 = z;
  if (dz1_dw1) *dz1_dw1 = ht * e.rate_dw(z, w1) / (1.0 - ht * e.rate_dz(z, w1));
  return true;
}

BoucWenSolver::BoucWenSolver(int n) {
  for (Eigen::VectorXd* v : {&r_, &r_try_, &w_try_, &q_try_, &slope_, &step_}) v->resize(n);
  jacobian_.resize(n, n);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
}

// Q = theta (r_n+1 - r_n) = theta k_h ((z1 - z_n) - (d1 - d_n)), d1 - d_n = h ((1 - theta) w_n + theta w1).
int BoucWenSolver::forces(const std::vector<BoucWenElement>& elements, std::vector<BoucWenState>& states, double theta, double h,
                          const Eigen::VectorXd& w, Eigen::VectorXd& q, Eigen::VectorXd* slope) {
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const BoucWenElement& e = elements[k];
    BoucWenState& st = states[k];
    double dz = 0.0;
    if (!bouc_wen_end_z(e, st, theta, h, w[i], &st.z1, slope ? &dz : nullptr)) return static_cast<int>(k);
    const double dd = h * ((1.0 - theta) * st.w + theta * w[i]);
    q[i] = theta * e.k * ((st.z1 - st.z) - dd);
    if (slope) (*slope)[i] = theta * e.k * (dz - theta * h);
  }
  return -1;
}

int BoucWenSolver::solve(const std::vector<BoucWenElement>& elements, std::vector<BoucWenState>& states, double theta, double h,
                         const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, Eigen::VectorXd& w1, Eigen::VectorXd& q) {
  double scale = w_tilde.cwiseAbs().maxCoeff();
  for (const BoucWenState& st : states) scale = std::max(scale, std::abs(st.w));
  const double tolerance = 1e-13 * scale;
  auto residual = [&](const Eigen::VectorXd& w, const Eigen::VectorXd& qq, Eigen::VectorXd& r) {
    r = w - w_tilde;
    r.noalias() += g * qq;
    return r.cwiseAbs().maxCoeff();
  };
  // Newton's method, each iterate kept only if it lowers the residual: first with the
  // Jacobian's diagonal 1 + G_kk Q'_k (G Q' ~ (omega h)^2 / 4 off the diagonal: a few cheap
  // iterations, no factorisation), then with the whole J = I + G diag(Q') if that stalls.
  if (const int bad = forces(elements, states, theta, h, w1, q, &slope_); bad >= 0) return bad;
  double norm = residual(w1, q, r_);
  bool current = true;  // the states' z1 are those of w1
  for (const bool whole : {false, true})
    for (int it = 0; it < (whole ? 30 : 60) && norm > tolerance; ++it) {
      if (whole) {
        jacobian_ = g * slope_.asDiagonal();
        jacobian_.diagonal().array() += 1.0;
        lu_.compute(jacobian_);
        step_ = lu_.solve(r_);
      } else {
        step_.array() = r_.array() / (1.0 + g.diagonal().array() * slope_.array());
      }
      w_try_ = w1 - step_;
      current = false;
      const bool failed = forces(elements, states, theta, h, w_try_, q_try_, &slope_) >= 0;
      const double next = failed ? norm : residual(w_try_, q_try_, r_try_);
      if (!(next < norm)) {  // (the next method takes over from the best iterate, its slopes)
        current = forces(elements, states, theta, h, w1, q, &slope_) < 0;
        break;
      }
      current = true;
      w1.swap(w_try_);
      q.swap(q_try_);
      r_.swap(r_try_);
      norm = next;
    }
  if (norm <= tolerance) return current ? -1 : forces(elements, states, theta, h, w1, q, nullptr);
  // The fixed point w1 = w~ - G Q(w1): a contraction for the steps that resolve the structure.
  for (int it = 0; it < 500; ++it) {
    if (const int bad = forces(elements, states, theta, h, w1, q, nullptr); bad >= 0) return bad;
    w_try_ = w_tilde;
    w_try_.noalias() -= g * q;
    const double change = (w_try_ - w1).cwiseAbs().maxCoeff();
    w1.swap(w_try_);
    if (change <= tolerance) return forces(elements, states, theta, h, w1, q, nullptr);
  }
  Eigen::Index worst = 0;
  residual(w1, q, r_);
  r_.cwiseAbs().maxCoeff(&worst);
  return static_cast<int>(worst);
}

}  // namespace adjoin::detail
