#include "adjoin/structure/modal.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"

namespace adjoin::structure {
namespace {

// Eigenpairs of (K, M), ascending, shapes mass-normalised with a positive top component.
void solve(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m, Eigen::VectorXd* omega, Eigen::MatrixXd* shapes) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, m);
  if (solver.info() != Eigen::Success) throw NumericalError("modal analysis: the eigensolver did not converge", 0.0);
  const Eigen::VectorXd lambda = solver.eigenvalues();
  *omega = lambda.cwiseMax(0.0).cwiseSqrt();
  if (shapes) {
    *shapes = solver.eigenvectors();  // already M-normalised by Eigen
    for (int j = 0; j < shapes->cols(); ++j)
      if ((*shapes)(shapes->rows() - 1, j) < 0.0) shapes->col(j) *= -1.0;
  }
}

Eigen::VectorXd periods_of(const Eigen::VectorXd& omega) {
  Eigen::VectorXd t(omega.size());
  for (int i = 0; i < omega.size(); ++i) t[i] = omega[i] > 0.0 ? 2.0 * M_PI / omega[i] : INFINITY;
  return t;
}

// Adds a storey-like element of stiffness `k` between two dofs (or a dof and the ground, -1).
template <class Matrix, class Scalar>
void add_between(Matrix& k, int i, int j, Scalar value) {
  if (i >= 0) k(i, i) += value;
  if (j >= 0) k(j, j) += value;
  if (i >= 0 && j >= 0) {
    k(i, j) -= value;
    k(j, i) -= value;
  }
}

}  // namespace

Eigen::MatrixXd mass_matrix(const Building& b) { return b.masses.asDiagonal(); }

Eigen::MatrixXd stiffness_matrix(const Eigen::VectorXd& storey) {
  const int n = static_cast<int>(storey.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int s = 0; s < n; ++s) add_between(k, s, s - 1, storey[s]);  // storey s+1: floors s-1 (ground: -1) and s
  return k;
}

Eigen::MatrixXd dashpot_matrix(const Building& b) {
  const int n = b.floors();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n);
  for (const StoreyDevice& d : b.devices)
    if (const double c_d = kind_of(d).dashpot(d); c_d != 0.0)  // (a nonlinear dashpot has no matrix)
      for (int s : d.storeys) add_between(c, s - 1, s - 2, c_d);
  return c;
}

std::complex<double> zener_stiffness(const Zener& z, double w) {
  const std::complex<double> iw_a = std::pow(w, z.order) * std::polar(1.0, z.order * M_PI / 2.0);
  return z.k * (1.0 + z.tau_x * iw_a) / (1.0 + z.tau_f * iw_a);
}

Eigen::MatrixXcd complex_stiffness_matrix(const Building& b, double w) {
  const int n = b.floors();
  Eigen::MatrixXcd k = Eigen::MatrixXcd::Zero(n, n);
  for (int s = 0; s < n; ++s) add_between(k, s, s - 1, std::complex<double>(b.springs[s], 0.0));
  for (const StoreyDevice& d : b.devices) {
    const DeviceKind& kind = kind_of(d);
    std::complex<double> value = kind.spring(d);  // (a yielding device: its initial stiffness)
    if (kind.family(d) == DeviceFamily::zener) value = zener_stiffness(d.zener, w);
    if (value != 0.0)
      for (int s : d.storeys) add_between(k, s - 1, s - 2, value);
  }
  return k;
}

Eigen::MatrixXd inherent_damping_matrix(const Building& b) {
  const int n = b.floors();
  const InherentDamping& d = b.damping;
  if (d.model == DampingModel::none || d.ratio == 0.0) return Eigen::MatrixXd::Zero(n, n);
  const Eigen::MatrixXd m = mass_matrix(b), k = stiffness_matrix(b.static_stiffness());
  Eigen::VectorXd omega;
  Eigen::MatrixXd phi;
  solve(k, m, &omega, &phi);
  if (d.model == DampingModel::modal) {
    const Eigen::VectorXd diag = 2.0 * d.ratio * omega;
    return m * phi * diag.asDiagonal() * phi.transpose() * m;
  }
  const double wi = omega[d.mode_i - 1], wj = omega[d.mode_j - 1];
  const double a0 = 2.0 * d.ratio * wi * wj / (wi + wj), a1 = 2.0 * d.ratio / (wi + wj);
  return a0 * m + a1 * k;
}

IsolatedPeriod isolated_period(const Building& b) {
  IsolatedPeriod p;
  if (!b.base || b.base->model != BaseModel::friction_pendulum) return p;
  p.rigid = 2.0 * M_PI * std::sqrt(b.base->radius / kStandardGravity);
  // The base below floor 1, on the pendulum's stiffness as a storey 0 to the ground.
  const int n = b.floors();
  Eigen::VectorXd masses = Eigen::VectorXd::Constant(n + 1, b.base->mass);
  Eigen::VectorXd storeys = Eigen::VectorXd::Constant(n + 1, b.base_stiffness());
  masses.tail(n) = b.masses;
  storeys.tail(n) = b.static_stiffness() + b.geometric_stiffness();
  Eigen::VectorXd omega;
  solve(stiffness_matrix(storeys), Eigen::MatrixXd(masses.asDiagonal()), &omega, nullptr);
  p.flexible = periods_of(omega)[0];
  return p;
}

Modes building_modes(const Building& b) {
  Modes out;
  const Eigen::MatrixXd m = mass_matrix(b), k = stiffness_matrix(b.static_stiffness());
  // With P-Delta the modes are those of the tangent K0 + K_G the run integrates about; a mode
  // whose tangent is not positive has omega 0 and an infinite period (it diverges).
  out.p_delta = b.p_delta;
  solve(b.p_delta ? Eigen::MatrixXd(stiffness_matrix(b.static_stiffness() + b.geometric_stiffness())) : k, m, &out.omega,
        &out.shapes);
  out.periods = periods_of(out.omega);
  const int n = b.floors();
  const Eigen::MatrixXd c_inherent = inherent_damping_matrix(b), c_devices = dashpot_matrix(b);
  out.inherent_ratio.resize(n);
  out.device_ratio.resize(n);
  out.zener_stiffening.resize(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd phi = out.shapes.col(j);
    const double w = out.omega[j];
    if (!(w > 0.0)) {  // P-Delta made the mode unstable: no ratio
      out.inherent_ratio[j] = out.device_ratio[j] = std::numeric_limits<double>::quiet_NaN();
      out.zener_stiffening[j] = 1.0;
      continue;
    }
    out.inherent_ratio[j] = phi.dot(c_inherent * phi) / (2.0 * w);
    const Eigen::MatrixXcd kc = complex_stiffness_matrix(b, w);
    const Eigen::VectorXcd phic = phi.cast<std::complex<double>>();
    const std::complex<double> modal_k = phic.dot(kc * phic);  // phi' K*(w) phi (phi real)
    const double static_k = phi.dot(k * phi);
    out.zener_stiffening[j] = modal_k.real() / static_k;
    out.device_ratio[j] = phi.dot(c_devices * phi) / (2.0 * w) + modal_k.imag() / (2.0 * static_k);
  }
  out.total_ratio = out.inherent_ratio + out.device_ratio;
  // Participation: phi' M phi = 1 (mass-normalised), so phi' M 1 alone gives the effective
  // mass; the roof scaling divides Gamma by the roof component (never 0 in a shear building).
  out.participation.resize(n);
  out.effective_mass.resize(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd phi = out.shapes.col(j);
    const double l = phi.dot(b.masses), mass = phi.dot(m * phi);
    out.effective_mass[j] = l * l / mass;
    out.participation[j] = l / mass * phi[n - 1];
  }
  return out;
}

CoupledModes coupled_modes(const Structure& s) {
  // The floors only: an isolated base (SPEC §7) is stuck here, as its slider is below mu W.
  const int n = s.a.floors() + (s.b ? s.b->floors() : 0);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n), k = Eigen::MatrixXd::Zero(n, n);
  const int na = s.a.floors();
  m.topLeftCorner(na, na) = mass_matrix(s.a);
  k.topLeftCorner(na, na) = stiffness_matrix(s.a.static_stiffness() + s.a.geometric_stiffness());
  if (s.b) {
    const int nb = s.b->floors();
    m.bottomRightCorner(nb, nb) = mass_matrix(*s.b);
    k.bottomRightCorner(nb, nb) = stiffness_matrix(s.b->static_stiffness() + s.b->geometric_stiffness());
  }
  std::vector<std::pair<int, int>> locked;
  for (const Link& l : s.links) {
    const int i = s.dof('A', l.floor_a), j = s.dof('B', l.floor_b);
    const LinkKind& kind = kind_of(l);
    if (const double k_l = kind.relaxed(l); k_l != 0.0) add_between(k, i, j, k_l);
    if (kind.family(l) == LinkFamily::friction) locked.emplace_back(i, j);
  }
  CoupledModes out;
  Eigen::VectorXd omega;
  solve(k, m, &omega, nullptr);
  out.periods_free = periods_of(omega);
  if (locked.empty()) {
    out.periods_locked = out.periods_free;
    return out;
  }
  // Rigid friction links: x_i = x_j. Coordinates in the constraints' null space, x = T y.
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(static_cast<int>(locked.size()), n);
  for (std::size_t r = 0; r < locked.size(); ++r) {
    g(static_cast<int>(r), locked[r].first) = 1.0;
    g(static_cast<int>(r), locked[r].second) = -1.0;
  }
  const Eigen::MatrixXd t = Eigen::FullPivLU<Eigen::MatrixXd>(g).kernel();
  solve(t.transpose() * k * t, t.transpose() * m * t, &omega, nullptr);
  out.periods_locked = periods_of(omega);
  return out;
}

}  // namespace adjoin::structure
