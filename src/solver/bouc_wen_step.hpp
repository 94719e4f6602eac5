#pragma once
// Bouc-Wen elements in the structure step (SPEC §7; internal to the solver): a storey's own
// Bouc-Wen law or a Bouc-Wen storey device, force = b k d + (1 - b) k z with
//     z' = d' - beta' |d'| |z|^(n-1) z - gamma' d' |z|^n,  beta' = beta / u_y^n, gamma' = gamma / u_y^n,
// u_y = F_y / k. The law is smooth, so no event needs locating. As for the bilinear law
// (bilinear_step.hpp) the whole initial stiffness k stays in K0 and K_eff (the step matrix is
// factorised once); the element's remainder r = k_h (z - d), k_h = (1 - b) k, enters the step
// as an offset at its t_n value, and its change over the step as a step force beside the
// friction dampers' (as a nonlinear viscous damper's, viscous_step.hpp):
//
//   Q = theta (r_n+1 - r_n),  v_n+1 = v_free - h A^-1 B_w' Q
//
// (theta: 1/2 trapezoidal, the step's mean of r is (r_n + r_n+1) / 2; 1 backward Euler, r_n+1).
// z_n+1 follows the same rule on its own equation, z_n+1 = z_n + h ((1 - theta) z'_n +
// theta z'(z_n+1, w_n+1)), and d_n+1 = d_n + h ((1 - theta) w_n + theta w_n+1), so each
// element's Q is a function of its own end velocity w_n+1 alone (z_n+1 from a scalar Newton
// solve), and the elements' end velocities solve
//
//   w_1 + G Q(w_1) = w~,  G = h B_w A^-1 B_w'  (w~: their end velocities without their own Q)
//
// by Newton's method on the whole system (J = I + G diag(Q')), falling back to the fixed point
// w_1 = w~ - G Q(w_1) (a contraction: |G Q'| ~ (omega h)^2 / 4). Every solve's convergence is
// checked; the caller stops with exit 3 (the time, the storey, a smaller solver.h) if one fails.
// The trapezoidal rule on z is second order: z' is continuous, only its derivative jumps where
// the velocity turns (|d'|), a local error O(h^3) a few times a cycle.
#include <Eigen/Dense>
#include <vector>

namespace adjoin::detail {

// A Bouc-Wen storey counts as yielded when |z| reaches this fraction of its saturation z_limit
// (= u_y at the defaults beta = gamma = 1/2): z approaches z_limit only asymptotically.
constexpr double kBoucWenYield = 0.9;

// The element as the model knows it.
struct BoucWenElement {
  int i = -1, j = -1;       // its floors (dofs; -1 the ground): d = x_i - x_j
  int storey = -1;          // the storey it stands in (A's first)
  bool storey_law = false;  // the storey spring's own law (its z is the channel X.hystN), or a device
  double k = 0.0;           // k_h = (1 - b) k [N/m]
  double u_y = 0.0;         // F_y / k [m]
  double n = 2.0;           // the exponent
  double beta = 0.0, gamma = 0.0;  // beta / u_y^n, gamma / u_y^n [m^-n]
  double z_limit = 0.0;     // the saturation |z| = u_y (beta + gamma)^(-1/n) [m]: z's bound while loading

  BoucWenElement() = default;
  BoucWenElement(int i, int j, int storey, bool storey_law, double k, double hardening, double yield_force, double n, double beta,
                 double gamma);
  int whole = 0;            // n if it is a whole number (powers by products), else 0
  double rate(double z, double w) const;     // z'
  double rate_dz(double z, double w) const;  // d z' / d z
  double rate_dw(double z, double w) const;  // d z' / d w (w's sign, or loading at w = 0)
  double power(double a, int less = 0) const;  // a^(n - less), a >= 0 (std::pow only for fractional n)
};

// The element's state at t_n and this step's end.
struct BoucWenState {
  double z = 0.0, d = 0.0, w = 0.0;  // at t_n
  double rate = 0.0;                 // z'(z_n, w_n)
  double z1 = 0.0;                   // z_n+1 of the latest solve (at t_n: a guess, extrapolated)
  double offset(const BoucWenElement& e) const { return e.k * (z - d); }  // r_n, the step's offset
};

// z_n+1 for the end velocity w1 (theta, h: the step's rule): false if Newton's method did not
// converge. dz1_dw1: its derivative in w1 (null: not needed).
bool bouc_wen_end_z(const BoucWenElement& e, const BoucWenState& st, double theta, double h, double w1, double* z1,
                    double* dz1_dw1);

// The step's end: the state at t_n+1 from its end deformation d1, velocity w1 and z1.
inline void bouc_wen_commit(const BoucWenElement& e, BoucWenState& st, double d1, double w1, double z1) {
  st.d = d1;
  st.w = w1;
  st.rate = e.rate(z1, w1);
  st.z1 = 2.0 * z1 - st.z;  // (the next step's first guess of its z_n+1)
  st.z = z1;
}

// The elements' end velocities and step forces for one step. Sized once: a solve allocates
// nothing.
class BoucWenSolver {
 public:
  explicit BoucWenSolver(int n);
  // Solves w1 + G Q(w1) = w_tilde (w1 in: a first guess); q the step forces, states' z1 set.
  // Returns -1, or the element whose equation did not converge.
  int solve(const std::vector<BoucWenElement>& elements, std::vector<BoucWenState>& states, double theta, double h,
            const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, Eigen::VectorXd& w1, Eigen::VectorXd& q);

 private:
  // Q(w) and Q'(w) per element; -1 or the element that failed.
  int forces(const std::vector<BoucWenElement>& elements, std::vector<BoucWenState>& states, double theta, double h,
             const Eigen::VectorXd& w, Eigen::VectorXd& q, Eigen::VectorXd* slope);
  Eigen::VectorXd r_, r_try_, w_try_, q_try_, slope_, step_;
  Eigen::MatrixXd jacobian_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

}  // namespace adjoin::detail
