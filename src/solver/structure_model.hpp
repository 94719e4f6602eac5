#pragma once
// The structure stepper's constant part (internal to the solver; the Model of Pinocchio's
// Model/Data split): the structure assembled for one step size, M, C, K0 and K_eff, the
// friction dampers' and contact pairs' indexing, the step's matrices factorised once (the
// trapezoidal step's and, where the restart rule applies, the backward-Euler step's), and the
// rule itself. Nothing in it changes during a run; what does (the state, the Zener elements'
// histories, the work vectors) is the StepWorkspace (structure_workspace.hpp).
#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "adjoin/fractional/weights.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/parameters.hpp"
#include "banded.hpp"
#include "bilinear_step.hpp"
#include "bouc_wen_step.hpp"
#include "contact_step.hpp"
#include "dense_product.hpp"
#include "viscous_step.hpp"

namespace adjoin::detail {

// A two-node element: dof i and dof j (-1: the ground); its deformation is x_i - x_j.
struct Pair {
  int i = -1, j = -1;
  double of(const Eigen::VectorXd& x) const { return (i >= 0 ? x[i] : 0.0) - (j >= 0 ? x[j] : 0.0); }
  void add(Eigen::VectorXd& f, double value) const {
    if (i >= 0) f[i] += value;
    if (j >= 0) f[j] -= value;
  }
  void add(Eigen::MatrixXd& k, double value) const {
    if (i >= 0) k(i, i) += value;
    if (j >= 0) k(j, j) += value;
    if (i >= 0 && j >= 0) {
      k(i, j) -= value;
      k(j, i) -= value;
    }
  }
};

// A Zener element (a storey device or a link) as the model knows it: where it acts, its law's
// parameters and its effective stiffness at the step (the workspace holds its law's history).
struct ZenerElement {
  Pair pair;
  int storey = -1;  // the storey it stands in (A's first), or -1 for a link
  Rod rod;
  double k = 0.0;
  double stiffness = 0.0;  // df/dx at the step: RodLaw::stiffness()
};

// A nonlinear viscous damper (a dashpot device or link with alpha < 1; viscous_step.hpp): where
// it acts and its law. Linear dashpots are in C.
struct ViscousElement {
  Pair pair;
  int storey = -1;  // the storey it stands in, or -1 for a link
  int link = -1;    // the link it is, or -1 for a storey device
};

// One diagonal block of the step matrix A (one per building when only friction links join
// them, else the whole).
struct StepBlock {
  int offset = 0, size = 0;
  Eigen::LDLT<Eigen::MatrixXd> a;  // A's diagonal block, factorised
  Eigen::MatrixXd c;               // C's diagonal block
  DenseProduct step;               // [A^-1; C A^-1] of the block (2 size x size)
};

// The step's matrices for one weight theta of the mechanics (1/2 trapezoidal, 1 backward Euler).
struct StepMatrices {
  double theta = 0.5;
  std::vector<StepBlock> blocks;
  // A^-1 B' (the floors' velocity response to the dampers' step forces) and C A^-1 B' (the
  // damping forces of that response): per step the velocities are v = v_free - h A^-1 B' Q
  // and their damping forces C v = C v_free - h C A^-1 B' Q, O(n nf) for any Q tried.
  Eigen::MatrixXd a_inv_bt, c_a_inv_bt;
  DenseProduct damper_response;  // [A^-1 B'; C A^-1 B']: one product per step
  Eigen::MatrixXd damper_response_columns;  // ... as a matrix (with bilinear elements: their nonzero columns only)
  Eigen::MatrixXd delassus;      // S = h B A^-1 B'
  // The QP's matrix: S with the bilinear elements' compliance -1 / (theta^2 k_h h) on their
  // diagonal (bilinear_step.hpp); S itself without them.
  Eigen::MatrixXd qp_matrix;
  Eigen::MatrixXd a_inv_bc, c_a_inv_bc, contact_friction;  // A^-1 B_c', C A^-1 B_c', B_c A^-1 B_f'
  Eigen::VectorXd kappa;                                   // B_c A^-1 B_c' per pair
  // The nonlinear viscous dampers' A^-1 B_v', C A^-1 B_v', G = h B_v A^-1 B_v' and B_v A^-1 B_f'.
  Eigen::MatrixXd a_inv_bv, c_a_inv_bv, viscous_g, viscous_friction;
  // The Bouc-Wen elements' A^-1 B_w', C A^-1 B_w', G = h B_w A^-1 B_w' and B_w A^-1 B_q' (bouc_wen_step.hpp).
  Eigen::MatrixXd a_inv_bw, c_a_inv_bw, bouc_wen_g, bouc_wen_qp;
  Eigen::MatrixXd trial_rows;  // the trial's rows of A^-1 B' and C A^-1 B' (structure_model.cpp)
};

// What the model's set-up assembles and needs only while it builds the step's matrices.
struct Assembly {
  Eigen::MatrixXd k0_dense, k_eff_dense;    // K0, and K_eff (the Zener elements at their effective stiffness)
  Eigen::MatrixXd bf, bc;                   // B of the friction dampers, of the contact pairs with a law
  Eigen::MatrixXd bv;                       // B of the nonlinear viscous dampers
  Eigen::MatrixXd bw;                       // B of the Bouc-Wen elements
  Eigen::MatrixXd bq;                       // B of the QP's unknowns: the friction dampers', then the bilinear elements'
  bool coupled = false;                     // a link other than friction enters A = M + h/2 C + h^2/4 K
  std::vector<std::pair<int, int>> ranges;  // A's diagonal blocks: (offset, size)
};

class StructureModel {
 public:
  // Checks the inputs (InputError) and assembles; NumericalError if a step matrix is not
  // positive definite. The options and the structure must outlive the model.
  StructureModel(const StructureSolverOptions& options, const structure::Structure& s);
  StructureModel(const StructureModel&) = delete;
  StructureModel& operator=(const StructureModel&) = delete;

  // The step after a damper's switch is backward Euler (the restart rule applies).
  bool restarts() const { return restart_steps > 0; }
  // The Zener elements' quadrature rule: BDF2, or Grünwald–Letnikov (implicit-gl).
  WeightRule weight_rule() const {
    return options.quadrature == StructureSolverOptions::Quadrature::bdf2 ? WeightRule::bdf2 : WeightRule::grunwald_letnikov;
  }

  // ---- the run's inputs ----
  const StructureSolverOptions& options;
  const structure::Structure& s;
  double h = 0.0;
  std::size_t n_steps = 0;
  int n = 0;  // floors (dofs)

  // ---- the structure, assembled ----
  Eigen::VectorXd mass, inv_mass;
  Eigen::MatrixXd c;  // C, the inherent damping and the dashpots
  std::vector<ZenerElement> zener;
  std::vector<Pair> link_pair;  // per link, then per ground slider (an isolated base's, a base friction's): (dof, ground)
  std::vector<double> base_slip_force;  // per ground slider (Structure::ground_sliders()), its slip force
  std::vector<int> friction;    // link indices (a base's slider: links.size() + its base's index)
  std::vector<int> link_zener;  // per link, its Zener element (or -1)
  // The links of the linear family, their force k * stroke + c * velocity (their kind's spring
  // and dashpot: structure/link_kinds.hpp).
  struct LinearLink {
    int link;
    double k, c;
  };
  std::vector<LinearLink> linear_links;
  Banded k0, k_eff;             // K0 and K_eff (with the Zener elements' effective stiffness)
  std::vector<double> storey_spring, storey_dashpot;  // per storey: springs and spring devices; dashpots
  bool dashpots_a = false, dashpots_b = false;        // a building has dashpot devices

  // ---- the nonlinear viscous dampers ----
  std::vector<ViscousElement> viscous;
  std::vector<ViscousLaw> viscous_laws;  // (in the order of `viscous`)
  int nv = 0;
  // Per damper dof (damper_dofs), the viscous elements acting there: (element, sign).
  std::vector<std::vector<std::pair<int, double>>> damper_viscous;

  // ---- the friction dampers ----
  int nf = 0;                 // how many
  Eigen::VectorXd limit;      // their slip forces
  Eigen::MatrixXd g_all;      // B M^-1 B'
  std::vector<int> fi, fj;    // each damper's two floors
  std::vector<int> damper_dofs, trial_dofs;  // the dampers' floors; the floors the trial step reads
  std::vector<std::vector<std::pair<int, double>>> damper_zener;  // per damper dof: (element, sign), in order
  Eigen::Index nt = 0, nd = 0;  // trial_dofs.size(), damper_dofs.size()
  bool trial_every_floor = false;  // trial_dofs is 0, 1, ..., n - 1 (bilinear storeys: one pass over the floors)
  std::vector<int> pi, pj;      // each damper's floors' places in damper_dofs (pj -1: the ground)

  // ---- the bilinear elements (bilinear_step.hpp): the QP's unknowns after the dampers' ----
  std::vector<BilinearElement> bilinear;
  int nh = 0;  // how many
  int nq = 0;  // nf + nh: the QP's unknowns
  std::vector<std::vector<std::pair<int, double>>> damper_bilinear;  // per damper dof: (element, sign)

  // ---- the Bouc-Wen elements (bouc_wen_step.hpp): step forces beside the QP's ----
  std::vector<BoucWenElement> bouc_wen;
  int nw = 0;  // how many
  std::vector<std::vector<std::pair<int, double>>> damper_bouc_wen;  // per damper dof: (element, sign)

  // ---- the contact pairs ----
  std::vector<int> active;  // contacts with a law
  int nc = 0;               // how many
  std::vector<Pair> contact_pair;
  std::vector<ContactStepper> contact_stepper;

  // ---- the step ----
  std::unique_ptr<StepMatrices> trapezoidal, backward;  // theta = 1/2, and 1 for the restart
  int restart_steps = 0;                                // backward-Euler steps after a switch
  bool viscous_restarts = false;                        // ... and one after a viscous damper turns
  std::vector<int> block_of;                            // each dof's block

 private:
  void check_inputs() const;
  void assemble_elements(Assembly& a);
  void add_viscous(const Pair& p, int storey, int link, double c, double alpha);
  void assemble_dampers(Assembly& a);
  void assemble_contacts(Assembly& a);
  std::unique_ptr<StepMatrices> step_matrices(double theta, const Assembly& a) const;
  int restart_rule(const Assembly& a) const;
  void index_blocks_and_dampers(const Assembly& a);
  void prepare_trial();
  void assemble_storeys();
};

}  // namespace adjoin::detail
