#pragma once
// The dimensionless model of SPEC §1 (the paper's scaling):
//
//     x1'' = a_g(t) - f1 - q
//     x2'' = a_g(t) + rho (q - f2)
//     f1 + tau_f1 D^a f1 = x1 + tau_x1 D^a x1          (rod 1, stiffness 1)
//     f2 + tau_f2 D^b f2 = eps (x2 + tau_x2 D^b x2)    (rod 2, stiffness eps)
//     q in mu Sign(x1' - x2')
//
// Model::IsValid enforces the thermodynamic restrictions (0 < order < 1, tau_f > 0,
// tau_x > tau_f) and the physical ones (eps > 0, rho > 0, mu >= 0), and the ranges within
// which every reported number stays finite (kMaxRatio below). Its messages name the scene key
// so that a user can find the offending line.
#include <string>

#include "adjoin/structure/contact.hpp"

namespace adjoin {

// The ranges the model supports: ratios rho, eps in [1/kMaxRatio, kMaxRatio], mu and |gap0|
// at most kMaxRatio, relaxation times tau_x at most kMaxRelaxationTime.
inline constexpr double kMaxRatio = 1e6;
inline constexpr double kMaxRelaxationTime = 1e12;

// One fractional Zener rod. `elastic` rods have f = stiffness * x and carry no history;
// order and the relaxation times are then ignored.
struct Rod {
  double order = 0.5;  // fractional order gamma, 0 < gamma < 1
  double tau_x = 1.0;  // strain relaxation time, tau_x > tau_f
  double tau_f = 0.1;  // stress relaxation time, tau_f > 0
  bool elastic = false;

  static Rod Elastic() { Rod r; r.elastic = true; return r; }
  // Checks the restrictions; on failure writes a message naming `prefix`.key and returns false.
  // `field` (optional): the key of the problem (prefix.order, ...), for the reader to spell.
  bool IsValid(const std::string& prefix, std::string* error, std::string* field = nullptr) const;
};

struct Model {
  double rho = 0.5;   // m1 / m2
  double eps = 2.0;   // k2 / k1
  double mu = 0.3;    // damper slip force / (m1 g); 0 means no damper (blocks decoupled)
  double gap0 = 2.0;  // initial gap xi0 between the blocks
  // mu_b (SPEC §7, the paper's suggestion): each block slides on its base with Coulomb friction
  // mu_b m_i g, in parallel with its rod; 0 means none (the paper's system). The implicit
  // schemes only.
  double base_friction = 0.0;
  Rod rod1{0.23, 1.183, 0.004, false};
  Rod rod2{0.53, 4.0, 0.2, false};
  // What happens when the gap closes (SPEC §6), dimensionless: a linear stiffness in units of
  // k1, a Hertz one in k1 / L^(1/2). None: the blocks pass through each other (the paper).
  structure::ContactLaw contact;

  // `field` (optional): the key of the problem (model.rho, model.rod1.order, ...).
  bool IsValid(std::string* error, std::string* field = nullptr) const;
  // The paper's common parameters (SPEC §1, "What the paper reports").
  static Model Paper() { return Model{}; }
};

}  // namespace adjoin
