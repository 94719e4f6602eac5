#pragma once
// Exact (to about 1e-12) reference solution of the two LINEAR cases of the model of SPEC §1
// under the decaying-sine ground motion a_g(t) = u0 W^2 e^{-k t} sin(W t), from rest.
// It shares no code with the time-stepping solvers and serves as the "analytic solution"
// of the convergence study and of convergence tests.
//
//  (a) stuck = true, damper stuck throughout (x1 = x2 = x):
//          x'' = a_g - c (f1 + f2),   c = rho / (rho + 1),   q = (rho f2 - f1) / (rho + 1).
//      VALID ONLY IF THE DAMPER REALLY STAYS STUCK, i.e. |q(t)| <= mu for every t of
//      interest. This class does not check it: the caller must (sample q on a fine grid).
//  (b) stuck = false, no damper (mu = 0, blocks decoupled): x1'' = a_g - f1,
//      x2'' = a_g - rho f2, and q = 0. model.mu is ignored; the result is the response of
//      the model only when mu = 0.
//
// Method. In Laplace space every output is Z(s) = A(s) N(s) / D(s), with
//     A(s) = u0 W^3 / ((s + k)^2 + W^2),
//     G1(s) = (1 + tau_x1 s^a) / (1 + tau_f1 s^a),  G2(s) = eps (1 + tau_x2 s^b) / (1 + tau_f2 s^b)
//     (an elastic rod has G = its stiffness: 1 for rod 1, eps for rod 2),
//     D(s) = s^2 + w1 G1(s) + w2 G2(s)  ((a): w1 = w2 = c; (b): w1 = 1, w2 = 0 for block 1,
//                                          w1 = 0, w2 = rho for block 2),
//     N = 1 (displacement), s (velocity), G1 or G2 (rod forces),
// with the principal branch of s^a. The Bromwich integral is closed to the left around the
// branch cut on the negative real axis:
//     z(t) = sum of residues of Z(s) e^{st}
//            + (1/pi) int_0^inf Im Z(r e^{-i pi}) e^{-r t} dr.
// D has exactly one pair of conjugate zeros in the cut plane (along the upper edge of the cut
// Im D > 0, and D ~ s^2 on a large circle, so the argument principle gives one zero in the
// upper half); it is found by Newton's method. The residues at it and at the ground-motion
// poles -k +- iW are evaluated in closed form, and the cut integral, smooth after r = e^u,
// by adaptive vector-valued Gauss–Kronrod (21-point) quadrature. Elastic rods have no cut:
// the result is then the closed-form modal solution.
//
// Cost: a few hundred microseconds per call of at(t) with fractional rods; thread-safe.
#include <complex>

#include "adjoin/structure/parameters.hpp"

namespace adjoin {

// The response as the model's 1 + 1 structure's (structure/two_block.hpp): index 0 is building
// A's floor and storey (block 1 and rod 1 above), 1 is B's; link 1 is the damper.
struct LinearResponse {
  double x[2] = {0, 0};             // the floors' displacements relative to the base
  double v[2] = {0, 0};             // their velocities
  double storey_force[2] = {0, 0};  // the storeys' (rods') forces
  double link_force = 0;            // the damper's ((a): the stick force; (b): 0)
};

class LinearReference {
 public:
  // Throws InputError if the model is invalid, omega <= 0, k < 0, or the ground motion
  // resonates exactly with the structure (a double pole: k = 0 with W at an undamped
  // natural frequency).
  LinearReference(const Model& model, double u0, double omega, double k, bool stuck);

  // The response at time t (t <= 0: the initial state, all zero). Absolute error about
  // 1e-13 * |u0| * max(1, W^2).
  LinearResponse at(double t) const;

  bool stuck() const { return stuck_; }
  // The zero of D(s) in the upper half of the cut plane for block i (1 or 2; in case (a) both
  // give the common one): a natural frequency (imaginary part) and its decay rate (-real part).
  std::complex<double> natural_pole(int block) const;

 private:
  // One transfer denominator D(s) = s^2 + w1 G1(s) + w2 G2(s) and its outputs.
  struct Channel {
    double w1 = 0, w2 = 0;
    bool has_cut = false;          // some rod with positive weight is fractional
    std::complex<double> root;     // zero of D in the upper half plane
    // Residue coefficients for the outputs N = 1, s, G1, G2: z_res(t) = 2 Re[cp e^{pt} + cr e^{root t}].
    std::complex<double> cp[4], cr[4];
  };

  std::complex<double> G(int rod, std::complex<double> s) const;
  std::complex<double> dG(int rod, std::complex<double> s) const;
  std::complex<double> D(const Channel& ch, std::complex<double> s) const;
  std::complex<double> dD(const Channel& ch, std::complex<double> s) const;
  void setup(Channel& ch) const;

  Model model_;
  double u0_, omega_, k_;
  bool stuck_;
  double scale_;  // |u0| max(1, W^2): size of the forcing, for absolute tolerances
  Channel ch_[2];
};

}  // namespace adjoin
