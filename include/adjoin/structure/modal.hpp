#pragma once
// Modal analysis before a run (SPEC §5): each building's natural periods, mass-normalised mode
// shapes and modal damping ratios, and the coupled system's periods with the links free and
// locked. Eigen's generalized self-adjoint eigensolver on (K, M); K from the static storey
// stiffnesses (springs plus the relaxed stiffness of Zener devices), plus the P-Delta geometric
// stiffness of a building with p_delta (SPEC §7; coupled periods too).
//
// Damping ratios per mode n (mass-normalised shape phi_n, circular frequency w_n):
//  - inherent: the ratio the building's classical damping gives the mode (modal: the ratio
//    itself; Rayleigh C = a0 M + a1 K fitted at two modes: a0 / (2 w_n) + a1 w_n / 2);
//  - devices: dashpots phi_n' C phi_n / (2 w_n); Zener storeys the equivalent ratio from the
//    complex stiffness at the mode's frequency, K*(w) = k (1 + tau_x (i w)^a) / (1 + tau_f (i w)^a):
//    phi_n' Im K*(w_n) phi_n / (2 phi_n' K phi_n), with the dynamic stiffening
//    phi_n' Re K*(w_n) phi_n / phi_n' K phi_n reported beside it (modes are not recomputed
//    with it: the periods are those of the static stiffness, as engineers quote them);
//  - total: their sum.
//
// Participation under a uniform ground motion (influence vector 1): with the shape scaled to 1
// at the roof, Gamma_n = phi_n' M 1 / phi_n' M phi_n (the roof's share of the ground
// displacement in mode n); the effective modal mass (phi_n' M 1)^2 / phi_n' M phi_n does not
// depend on the scaling, and the modes' effective masses sum to the total mass.
#include <Eigen/Dense>
#include <complex>
#include <limits>

#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

struct Modes {
  Eigen::VectorXd omega;     // rad/s, ascending
  Eigen::VectorXd periods;   // s
  Eigen::MatrixXd shapes;    // columns, mass-normalised (phi' M phi = 1), roof component > 0
  Eigen::VectorXd inherent_ratio, device_ratio, total_ratio;
  Eigen::VectorXd zener_stiffening;  // phi' Re K*(w_n) phi / phi' K phi (1 without Zener devices)
  Eigen::VectorXd participation;     // Gamma_n of the shape scaled to 1 at the roof (dimensionless)
  Eigen::VectorXd effective_mass;    // kg (the building's mass unit), sums to the total mass
  // P-Delta (SPEC §7): the periods and shapes are those of K0 + K_G (each storey's geometric
  // stiffness -P_i/h_i added); the inherent damping is still built from K0. A mode with a
  // non-positive tangent has omega 0, period +inf and NaN damping ratios.
  bool p_delta = false;
};

// Shear-building matrices of one building: M (diagonal), K (tridiagonal, static stiffness),
// the device dashpots' C, and the classical (inherent) damping matrix.
Eigen::MatrixXd mass_matrix(const Building& b);
Eigen::MatrixXd stiffness_matrix(const Eigen::VectorXd& storey_stiffness);
Eigen::MatrixXd dashpot_matrix(const Building& b);
Eigen::MatrixXd inherent_damping_matrix(const Building& b);
// The complex storey stiffness of a building at circular frequency w (springs, device
// springs, Zener devices).
Eigen::MatrixXcd complex_stiffness_matrix(const Building& b, double w);
std::complex<double> zener_stiffness(const Zener& z, double w);

Modes building_modes(const Building& b);

// An isolated building's period while its base slides (SPEC §7). A friction pendulum's restoring
// stiffness W / R makes the whole a pendulum of length R: `rigid` = 2 pi sqrt(R / g), the
// period with a rigid superstructure, whatever the masses; `flexible` is the first period of
// the base and the floors on W / R with the storeys at their initial stiffness (K0, + K_G with
// P-Delta), which the storeys' flexibility lengthens a little. While the base sticks (the
// ground's push below mu W) the building has its fixed-base periods (building_modes). NaN for
// both with a flat slider (no restoring force: it has no period) or a fixed base.
struct IsolatedPeriod {
  double rigid = std::numeric_limits<double>::quiet_NaN(), flexible = std::numeric_limits<double>::quiet_NaN();
};
IsolatedPeriod isolated_period(const Building& b);

struct CoupledModes {
  Eigen::VectorXd periods_free;    // links' friction dampers free (springs and Zener links at relaxed k)
  Eigen::VectorXd periods_locked;  // friction dampers rigid (the two floors move together)
};
// Requires building B and at least one link for `periods_locked` to differ from free.
CoupledModes coupled_modes(const Structure& s);

}  // namespace adjoin::structure
