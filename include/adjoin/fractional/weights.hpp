#pragma once
// Convolution weights for fractional derivatives on a uniform grid t_m = m h:
//
//     D^gamma z(t_m) ~ h^{-gamma} sum_{j=0}^{m} w_j z_{m-j}
//
// Grünwald–Letnikov (first order): the coefficients of (1 - zeta)^gamma, by the paper's
// recurrence w_0 = 1, w_j = (1 - (gamma + 1)/j) w_{j-1}; in closed form
// w_j = Gamma(j - gamma) / (Gamma(-gamma) Gamma(j + 1)).
#include <cstddef>
#include <vector>

namespace adjoin {

// w_0 .. w_{count-1} of the Grünwald–Letnikov generating function (1 - zeta)^order.
std::vector<double> grunwald_letnikov_weights(double order, std::size_t count);

// w_0 .. w_{count-1} of the second-order convolution quadrature built on BDF2 (Lubich 1986):
// the coefficients of (3/2 - 2 zeta + zeta^2/2)^order, by J.C.P. Miller's recurrence for a
// power of a polynomial (O(count)). Second order for functions that vanish at t = 0 with
// their first derivative (the solver's case: it starts from rest); otherwise the error near
// t = 0 is O(h^{1+p}) for a t^p leading term.
std::vector<double> bdf2_weights(double order, std::size_t count);

// The two rules by name, for code that chooses one at run time (the history engines).
// Sequences of more than 256 weights are kept for the process, per (rule, order) the longest
// asked for (up to 64 MB in all, the least recently used dropped first), and later calls copy
// their prefix: the same numbers bit for bit (each weight depends on the earlier ones only),
// without the recurrence's cost on every run of a sweep or a ladder. Thread-safe.
enum class WeightRule { grunwald_letnikov, bdf2 };
std::vector<double> convolution_weights(WeightRule rule, double order, std::size_t count);

}  // namespace adjoin
