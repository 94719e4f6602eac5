#pragma once
// The two-parameter Mittag-Leffler function of a real argument,
//
//     E_{alpha,beta}(z) = sum_{k>=0} z^k / Gamma(alpha k + beta),
//
// the exact relaxation function of fractional Zener rods: under a unit step strain the rod of
// SPEC §1 (stiffness k) carries f(t) = k [1 + (tau_x/tau_f - 1) E_g(-t^g / tau_f)].
//
// Contract: alpha > 0 and beta > 0 (the model needs 0 < alpha <= 2; larger alpha works too);
// any real z. The result is within about 1e-13 of the true value relative to 1 + |E| (so
// relative where |E| >= 1 and absolute where E is small). Values too large for a double are
// returned as +-infinity (for z > 0 E grows like exp(z^{1/alpha}) / alpha). Invalid alpha or
// beta throw std::invalid_argument. Thread-safe; no allocation beyond a few locals.
//
// Method: Garrappa's optimal parabolic contour algorithm (R. Garrappa, "Numerical evaluation
// of two and three parameter Mittag-Leffler functions", SIAM J. Numer. Anal. 53 (2015)
// 1350-1369): E is the inverse Laplace transform at t = 1 of s^{alpha-beta} / (s^alpha - z),
// computed by the trapezoidal rule on a parabolic contour chosen between the poles
// s^alpha = z, plus the residues of the poles it leaves to its right.
namespace adjoin {

double mittag_leffler(double alpha, double beta, double z);

// E_alpha(z) = E_{alpha,1}(z).
inline double mittag_leffler(double alpha, double z) { return mittag_leffler(alpha, 1.0, z); }

}  // namespace adjoin
