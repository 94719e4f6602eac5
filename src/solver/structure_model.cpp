#include "structure_model.hpp"

#include <algorithm>
#include <cmath>

#include "adjoin/core/errors.hpp"
#include "adjoin/fractional/weights.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "adjoin/structure/modal.hpp"
#include "rod_law.hpp"

namespace adjoin::detail {
namespace {

using structure::DeviceFamily;
using structure::LinkFamily;

// Modes with omega h above this are not resolved by the step (as the two-block implicit
// scheme's kResolvedOmegaH): trapezoidal mechanics passes them undamped.
constexpr double kResolvedOmegaH = 1.0;

Rod rod_of(const structure::Zener& z) { return Rod{z.order, z.tau_x, z.tau_f, false}; }

}  // namespace

StructureModel::StructureModel(const StructureSolverOptions& options_, const structure::Structure& s_)
    : options(options_), s(s_) {
  check_inputs();
  h = options.h;
  n_steps = options.steps();
  n = s.dofs();
  // The set-up: the structure assembled (the matrices only it needs kept in `a`), the
  // step's matrices, the restart rule, the dampers' trial rows.
  Assembly a;
  assemble_elements(a);
  assemble_dampers(a);
  assemble_contacts(a);
  // The step's matrices for the mechanics' weight theta of the step's end (x_n+1 = x_n +
  // h ((1 - theta) v_n + theta v_n+1), and the same for v): 1/2 the trapezoidal rule of every
  // step, 1 the backward-Euler restart after a switch (below). Each is formed and factorised
  // once (constant for a fixed h): A = M + theta h C + theta^2 h^2 K_eff.
  //
  // Inherent damping is per building and a friction link enters the step through the dampers'
  // forces only, so without spring, dashpot or Zener links A and C are block diagonal, one
  // block per building: each is handled on its own (half the dense work of the whole for two
  // equal buildings). Per step a block needs v_free = A^-1 rhs and its damping forces C v_free:
  // both from one matrix-vector product with [A^-1; C A^-1], formed once. (A triangular solve
  // pair costs as many multiplications but runs at a fraction of a product's speed at these
  // sizes; A is M + O(h) and well conditioned, so its explicit inverse is as accurate as the
  // solve.)
  if (s.b && !a.coupled) a.ranges = {{0, s.a.floors()}, {s.a.floors(), s.b->floors()}};
  else a.ranges = {{0, n}};
  trapezoidal = step_matrices(0.5, a);
  restart_steps = restart_rule(a);
  // A nonlinear viscous damper whose velocity turns restarts too (structure_solver.cpp).
  viscous_restarts = nv > 0 && options.restart != StructureSolverOptions::Restart::never;
  if (restart_steps > 0 || viscous_restarts) backward = step_matrices(1.0, a);
  index_blocks_and_dampers(a);
  prepare_trial();
  assemble_storeys();
}

// The inputs the set-up relies on.
void StructureModel::check_inputs() const {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  if (!s.IsValid(&error)) throw InputError(error);
  for (const Eigen::VectorXd* v : {&options.x0, &options.v0})
    if (v->size() != 0 && (v->size() != s.dofs() || !v->allFinite()))
      throw InputError("the initial displacements and velocities need one finite value per floor");
  if (options.x0.size() != 0 && !options.x0.isZero()) {
    bool relaxed = false;  // an element whose state at t = 0 is relaxed (or stuck)
    for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr})
      if (b)
        for (const auto& d : b->devices) {
          const DeviceFamily family = structure::kind_of(d).family(d);
          relaxed = relaxed || family == DeviceFamily::zener || family == DeviceFamily::bilinear || family == DeviceFamily::bouc_wen;
        }
    for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr})
      if (b) relaxed = relaxed || b->hysteresis.model != structure::HysteresisModel::elastic || b->base || b->ground_friction > 0.0;
    for (const auto& l : s.links) {
      const LinkFamily family = structure::kind_of(l).family(l);
      relaxed = relaxed || family == LinkFamily::zener || family == LinkFamily::friction;
    }
    if (relaxed)
      throw InputError("initial displacements need a structure without Zener elements, friction links, yielding storeys or devices and sliding bases");
  }
}

void StructureModel::add_viscous(const Pair& p, int storey, int link, double c_, double alpha) {
  viscous.push_back(ViscousElement{p, storey, link});
  viscous_laws.push_back(ViscousLaw{c_, alpha});
}

void StructureModel::assemble_elements(Assembly& a) {
  // ---- assembly: M, C, elastic K0, Zener elements, friction links ----
  mass.resize(n);
  c = Eigen::MatrixXd::Zero(n, n);
  a.k0_dense = Eigen::MatrixXd::Zero(n, n);
  // A Zener element and its effective stiffness, which needs its quadrature's first weight w_0
  // only (the workspace's histories hold the rest: fractional/history_set.hpp).
  auto zener_element = [&](const Pair& p, int storey, const structure::Zener& z) {
    const Rod rod = rod_of(z);
    const double w0 = convolution_weights(weight_rule(), z.order, 1)[0];
    return ZenerElement{p, storey, rod, z.k, RodLaw::effective_stiffness(rod, z.k, h, w0)};
  };
  auto add_building = [&](const structure::Building& b, int offset) {
    const int nb = b.floors();
    const char name = offset == 0 ? 'A' : 'B';
    // The dof under 0-based storey st: the floor below, the base (SPEC §7) or the ground (-1).
    auto lower = [&](int st) { return s.below(name, st + 1); };
    mass.segment(offset, nb) = b.masses;
    const Eigen::MatrixXd c_fixed = structure::inherent_damping_matrix(b) + structure::dashpot_matrix(b);
    c.block(offset, offset, nb, nb) = c_fixed;
    if (b.base) {
      // An isolated base: its mass, and the fixed-base superstructure's damping acting on the
      // floors' velocities relative to the base, v - v_b 1: C = T' C_fixed T with
      // T = [-1 | I] (base, floors), none on the base's own velocity (the slider is its only
      // damping). The FP's restoring stiffness W / R joins the base to the ground.
      const int base = s.base_dof(name);
      mass[base] = b.base->mass;
      const Eigen::VectorXd c1 = c_fixed.rowwise().sum();
      c(base, base) = c1.sum();
      c.block(offset, base, nb, 1) = -c1;
      c.block(base, offset, 1, nb) = -c1.transpose();
      Pair{base, -1}.add(a.k0_dense, b.base_stiffness());
    }
    for (int st = 0; st < nb; ++st) Pair{offset + st, lower(st)}.add(a.k0_dense, b.springs[st]);
    // P-Delta (SPEC §7): each storey's geometric stiffness -P_i/h_i joins K0 (C above stays K0's without it).
    if (b.p_delta) {
      const Eigen::VectorXd kg = b.geometric_stiffness();
      for (int st = 0; st < nb; ++st) Pair{offset + st, lower(st)}.add(a.k0_dense, kg[st]);
    }
    // Each device by its kind (structure/device_kinds.hpp): its linear spring in K0 (its
    // linear dashpot is in C above: dashpot_matrix), and the step family that steps the rest.
    for (const auto& d : b.devices) {
      const structure::DeviceKind& kind = structure::kind_of(d);
      const DeviceFamily family = kind.family(d);
      if (family == DeviceFamily::bouc_wen) continue;  // (below, after the other devices)
      for (int st : d.storeys) {
        const Pair p{offset + st - 1, lower(st - 1)};
        if (const double k = kind.spring(d); k != 0.0) p.add(a.k0_dense, k);
        if (family == DeviceFamily::viscous) add_viscous(p, offset + st - 1, -1, d.c, d.alpha);
        if (family == DeviceFamily::zener) zener.push_back(zener_element(p, offset + st - 1, d.zener));
        if (family == DeviceFamily::bilinear)  // the slider's slip an offset (bilinear_step.hpp)
          bilinear.push_back({p.i, p.j, offset + st - 1, false, (1.0 - d.hardening) * d.k, (1.0 - d.hardening) * d.yield_force});
      }
    }
    for (const auto& d : b.devices)  // (k in K0; r = k_h (z - d) an offset and a step force: bouc_wen_step.hpp)
      if (structure::kind_of(d).family(d) == DeviceFamily::bouc_wen)
        for (int st : d.storeys) {
          const Pair p{offset + st - 1, lower(st - 1)};
          p.add(a.k0_dense, d.k);
          bouc_wen.emplace_back(p.i, p.j, offset + st - 1, false, d.k, d.hardening, d.yield_force, d.n, d.beta, d.gamma);
        }
    if (const auto& y = b.hysteresis; y.model == structure::HysteresisModel::bouc_wen)
      for (int st = 0; st < nb; ++st)
        bouc_wen.emplace_back(offset + st, lower(st), offset + st, true, b.springs[st], y.hardening,
                              y.yield_forces[st], y.n, y.beta, y.gamma);
    // A bilinear storey spring: k stays in K0; its series element's slip is an offset.
    if (b.hysteresis.model == structure::HysteresisModel::bilinear)
      for (int st = 0; st < nb; ++st) {
        const Pair p{offset + st, lower(st)};
        const double b_ = b.hysteresis.hardening, kh = (1.0 - b_) * b.springs[st];
        bilinear.push_back({p.i, p.j, offset + st, true, kh, (1.0 - b_) * b.hysteresis.yield_forces[st]});
      }
  };
  add_building(s.a, 0);
  if (s.b) add_building(*s.b, s.a.floors());
  a.coupled = false;       // a link other than friction enters A = M + h/2 C + h^2/4 K
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const auto& link = s.links[l];
    const Pair p{s.dof('A', link.floor_a), s.dof('B', link.floor_b)};
    link_pair.push_back(p);
    // By its kind (structure/link_kinds.hpp): its linear spring in K0, its linear dashpot in
    // C, and the step family that steps the rest.
    const structure::LinkKind& kind = structure::kind_of(link);
    const LinkFamily family = kind.family(link);
    if (const double k = kind.spring(link); k != 0.0) p.add(a.k0_dense, k);
    if (family == LinkFamily::viscous) {  // (a step force, as a damper's: A stays as it was)
      add_viscous(p, -1, static_cast<int>(l), link.c, link.alpha);
      continue;
    }
    if (const double c_l = kind.dashpot(link); c_l != 0.0) p.add(c, c_l);
    if (family == LinkFamily::linear) linear_links.push_back({static_cast<int>(l), kind.spring(link), kind.dashpot(link)});
    if (family == LinkFamily::zener) zener.push_back(zener_element(p, -1, link.zener));
    if (family == LinkFamily::friction) friction.push_back(static_cast<int>(l));
    else a.coupled = true;
  }
  // The isolated bases' sliders (SPEC §7): friction dampers between the base and the ground,
  // after the links (their damper index and their place in the state's link arrays:
  // links.size() + k, k = 0 for A's base if any, then B's). A base's dof lies after every
  // floor, outside its building's block of A: one block for the whole.
  // (The two-block scene's base friction under floor 1 is one too, in its building's block.)
  for (const structure::GroundSlider& slider : s.ground_sliders()) {
    friction.push_back(static_cast<int>(link_pair.size()));
    link_pair.push_back(Pair{slider.dof, -1});
    base_slip_force.push_back(slider.slip_force);
    a.coupled = a.coupled || slider.base;
  }
  // Zener links come after the storey devices in `zener`; remember where each link's is.
  link_zener.assign(s.links.size(), -1);
  {
    int z = static_cast<int>(zener.size());
    for (int l = static_cast<int>(s.links.size()) - 1; l >= 0; --l)
      if (structure::kind_of(s.links[l]).family(s.links[l]) == LinkFamily::zener) link_zener[l] = --z;
  }
  nv = static_cast<int>(viscous.size());
  a.bv = Eigen::MatrixXd::Zero(nv, n);
  for (int k = 0; k < nv; ++k) {
    const Pair& p = viscous[static_cast<std::size_t>(k)].pair;
    if (p.i >= 0) a.bv(k, p.i) = 1.0;
    if (p.j >= 0) a.bv(k, p.j) = -1.0;
  }
  a.k_eff_dense = a.k0_dense;
  for (const auto& e : zener) e.pair.add(a.k_eff_dense, e.stiffness);
  // A shear building's stiffness is tridiagonal and a link adds four entries: O(n) products.
  k0 = Banded(a.k0_dense);
  k_eff = Banded(a.k_eff_dense);
}

// The friction dampers: B_f and their slip forces.
void StructureModel::assemble_dampers(Assembly& a) {
  nf = static_cast<int>(friction.size());
  a.bf = Eigen::MatrixXd::Zero(nf, n);
  limit.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const Pair& p = link_pair[friction[f]];
    a.bf(f, p.i) = 1.0;
    if (p.j >= 0) a.bf(f, p.j) = -1.0;  // (a base's slider: j is the ground)
    const auto l = static_cast<std::size_t>(friction[f]);
    limit[f] = l < s.links.size() ? s.links[l].slip_force : base_slip_force[l - s.links.size()];
  }
  // The bilinear elements follow the dampers among the QP's unknowns (held while they slip).
  nh = static_cast<int>(bilinear.size());
  nq = nf + nh;
  a.bq = Eigen::MatrixXd::Zero(nq, n);
  a.bq.topRows(nf) = a.bf;
  for (int e = 0; e < nh; ++e) {
    a.bq(nf + e, bilinear[e].i) = 1.0;
    if (bilinear[e].j >= 0) a.bq(nf + e, bilinear[e].j) = -1.0;
  }
  nw = static_cast<int>(bouc_wen.size());
  a.bw = Eigen::MatrixXd::Zero(nw, n);
  for (int e = 0; e < nw; ++e) {
    a.bw(e, bouc_wen[e].i) = 1.0;
    if (bouc_wen[e].j >= 0) a.bw(e, bouc_wen[e].j) = -1.0;
  }
}

void StructureModel::assemble_contacts(Assembly& a) {
  // Contact pairs (SPEC §6). Each with a law is a step force like a damper's, its impulse found
  // by integrating the pair's own relative motion through the step (solver/contact_step.hpp);
  // it needs A^-1 B_c' (and C A^-1 B_c'), its inverse effective mass kappa = B_c A^-1 B_c' and
  // B_c A^-1 B_f' (how the dampers' step forces move it).
  for (std::size_t k = 0; k < s.contacts.size(); ++k)
    if (s.contacts[k].law.model != structure::ContactModel::none) active.push_back(static_cast<int>(k));
  nc = static_cast<int>(active.size());
  for (const auto& ct : s.contacts) contact_pair.push_back({s.dof('A', ct.floor_a), s.dof('B', ct.floor_b)});
  a.bc = Eigen::MatrixXd::Zero(nc, n);
  for (int ci = 0; ci < nc; ++ci) {
    const Pair& p = contact_pair[active[ci]];
    a.bc(ci, p.i) = 1.0;
    a.bc(ci, p.j) = -1.0;
    const double m_eff = mass[p.i] * mass[p.j] / (mass[p.i] + mass[p.j]);
    contact_stepper.emplace_back(s.contacts[active[ci]].law, m_eff, active[ci]);
  }
}

// The step's matrices for the mechanics' weight theta (the constructor says which).
std::unique_ptr<StepMatrices> StructureModel::step_matrices(double theta, const Assembly& a) const {
  auto m = std::make_unique<StepMatrices>();
  m->theta = theta;
  const Eigen::MatrixXd a_step = Eigen::MatrixXd(mass.asDiagonal()) + theta * h * c + theta * theta * h * h * a.k_eff_dense;
  for (const auto& [offset, size] : a.ranges) {
    StepBlock b;
    b.offset = offset;
    b.size = size;
    b.a.compute(a_step.block(offset, offset, size, size));
    if (b.a.info() != Eigen::Success)
      throw NumericalError("the step matrix M + theta h C + theta^2 h^2 K is not positive definite", 0.0);
    b.c = c.block(offset, offset, size, size);
    Eigen::MatrixXd step(2 * size, size);
    step.topRows(size) = b.a.solve(Eigen::MatrixXd::Identity(size, size));
    step.bottomRows(size) = b.c * step.topRows(size);
    b.step = DenseProduct(std::move(step));
    m->blocks.push_back(std::move(b));
  }
  // No friction link (a building alone): nothing to solve, and Eigen's triangular solve must
  // not see a matrix with no columns (it binds a reference to its null data).
  // (The QP's unknowns: the dampers' step forces, then the bilinear elements'.)
  m->a_inv_bt = Eigen::MatrixXd::Zero(n, nq);
  if (nq > 0)
    for (const StepBlock& b : m->blocks)
      m->a_inv_bt.middleRows(b.offset, b.size) = b.a.solve(a.bq.transpose().middleRows(b.offset, b.size));
  m->c_a_inv_bt = nq > 0 ? Eigen::MatrixXd(c * m->a_inv_bt) : Eigen::MatrixXd(n, 0);
  Eigen::MatrixXd stacked(2 * n, nq);
  stacked << m->a_inv_bt, m->c_a_inv_bt;
  if (nh > 0) m->damper_response_columns = stacked;
  m->damper_response = DenseProduct(std::move(stacked));
  m->delassus = nq > 0 ? Eigen::MatrixXd(h * a.bq * m->a_inv_bt) : Eigen::MatrixXd(0, 0);
  m->qp_matrix = m->delassus;
  for (int e = 0; e < nh; ++e) m->qp_matrix(nf + e, nf + e) -= 1.0 / (theta * theta * bilinear[e].k * h);
  m->a_inv_bc = Eigen::MatrixXd::Zero(n, nc);
  m->kappa.resize(nc);
  if (nc > 0) {
    for (const StepBlock& b : m->blocks)
      m->a_inv_bc.middleRows(b.offset, b.size) = b.a.solve(a.bc.transpose().middleRows(b.offset, b.size));
    for (int ci = 0; ci < nc; ++ci) m->kappa[ci] = a.bc.row(ci).dot(m->a_inv_bc.col(ci));
  }
  m->c_a_inv_bc = nc > 0 ? Eigen::MatrixXd(c * m->a_inv_bc) : Eigen::MatrixXd(n, 0);
  if (nv > 0) {
    m->a_inv_bv.resize(n, nv);
    for (const StepBlock& b : m->blocks)
      m->a_inv_bv.middleRows(b.offset, b.size) = b.a.solve(a.bv.transpose().middleRows(b.offset, b.size));
    m->c_a_inv_bv = c * m->a_inv_bv;
    m->viscous_g = h * a.bv * m->a_inv_bv;
    m->viscous_friction = a.bv * m->a_inv_bt;
  }
  if (nw > 0) {
    m->a_inv_bw.resize(n, nw);
    for (const StepBlock& b : m->blocks)
      m->a_inv_bw.middleRows(b.offset, b.size) = b.a.solve(a.bw.transpose().middleRows(b.offset, b.size));
    m->c_a_inv_bw = c * m->a_inv_bw;
    m->bouc_wen_g = h * a.bw * m->a_inv_bw;
    m->bouc_wen_qp = a.bw * m->a_inv_bt;
  }
  m->contact_friction = Eigen::MatrixXd::Zero(nc, nq);
  for (int ci = 0; ci < nc; ++ci)
    for (int f = 0; f < nq; ++f) {
      const Pair& p = contact_pair[active[ci]];
      m->contact_friction(ci, f) = m->a_inv_bt(p.i, f) - m->a_inv_bt(p.j, f);
    }
  return m;
}

// The backward-Euler steps after a switch: 1 when the restart applies, else 0.
int StructureModel::restart_rule(const Assembly& a) const {
  // The backward-Euler restart (the `implicit` schemes' rule; the two-block scenes' implicit
  // schemes are this stepper: solver/two_block_structure.cpp). Trapezoidal mechanics does not
  // damp the modes the step does not resolve (its amplification tends to -1 as omega h grows): a damper's switch (a jump of
  // its force) excites the stiffest mode, which rings on and can drive a damper's relative
  // velocity through zero again and again (spurious switches). The step after a switch is
  // therefore taken with backward-Euler mechanics, which damps a mode by
  // 1/sqrt(1 + (omega h)^2): automatically when the stiffest mode of the structure (with the
  // Zener elements at their effective stiffness, the dampers free: locking them only lowers
  // it) is unresolved, h omega_max > 1; after every switch with Restart::always (the
  // implicit-damped rule). One first-order step per switch keeps the step second order.
  double omega_max = 0.0;
  if (nf > 0 && options.restart == StructureSolverOptions::Restart::automatic) {
    // Per block (K_eff is block diagonal with the blocks of A), and from the tridiagonal
    // matrix directly where a block is one (a shear building: O(n^2), not the dense O(n^3)).
    for (const auto& [offset, size] : a.ranges) {
      const Eigen::VectorXd inv_sqrt_m = mass.segment(offset, size).cwiseSqrt().cwiseInverse();
      const Eigen::MatrixXd scaled = inv_sqrt_m.asDiagonal() * a.k_eff_dense.block(offset, offset, size, size) * inv_sqrt_m.asDiagonal();
      bool tridiagonal = size > 1;
      for (int j = 0; j < size && tridiagonal; ++j)
        for (int i = 0; i < size; ++i)
          if (std::abs(i - j) > 1 && scaled(i, j) != 0.0) tridiagonal = false;
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes;
      if (tridiagonal) modes.computeFromTridiagonal(scaled.diagonal(), scaled.diagonal(-1), Eigen::EigenvaluesOnly);
      else modes.compute(scaled, Eigen::EigenvaluesOnly);
      omega_max = std::max(omega_max, std::sqrt(std::max(0.0, modes.eigenvalues().maxCoeff())));
    }
  }
  return
      nf > 0 && (options.restart == StructureSolverOptions::Restart::always ||
                 (options.restart == StructureSolverOptions::Restart::automatic && h * omega_max > kResolvedOmegaH))
          ? 1
          : 0;
}

// Each dof's block, B M^-1 B' and the dampers' floors.
void StructureModel::index_blocks_and_dampers(const Assembly& a) {
  const std::vector<StepBlock>& blocks = trapezoidal->blocks;
  block_of.resize(n);
  for (std::size_t bi = 0; bi < blocks.size(); ++bi)
    std::fill_n(block_of.begin() + blocks[bi].offset, blocks[bi].size, static_cast<int>(bi));
  inv_mass = mass.cwiseInverse();
  // B M^-1 B': for the grid-point forces of stuck dampers and the kinks of ended slips.
  g_all.resize(nf, nf);
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nf; ++j) g_all(i, j) = (a.bf.row(i).cwiseProduct(inv_mass.transpose())).dot(a.bf.row(j));
  fi.resize(nf);
  fj.resize(nf);
  for (int f = 0; f < nf; ++f) {
    fi[f] = link_pair[friction[f]].i;
    fj[f] = link_pair[friction[f]].j;
  }
}

void StructureModel::prepare_trial() {
  // The trial step (the dampers' decisions) is read at the dampers' floors only: there its
  // velocities, damping forces and P, for which x at those floors' stiffness columns and at
  // the other ends of their Zener elements.
  for (int f = 0; f < nf; ++f)
    for (int d : {fi[f], fj[f]})
      if (d >= 0) damper_dofs.push_back(d);  // (a base's slider has the ground at j)
  std::sort(damper_dofs.begin(), damper_dofs.end());
  damper_dofs.erase(std::unique(damper_dofs.begin(), damper_dofs.end()), damper_dofs.end());
  for (int k : damper_dofs) {
    const std::vector<int> cols = k0.columns(k);
    trial_dofs.insert(trial_dofs.end(), cols.begin(), cols.end());
    std::vector<std::pair<int, double>> touching;
    for (std::size_t e = 0; e < zener.size(); ++e) {
      const Pair& pr = zener[e].pair;
      if (pr.i != k && pr.j != k) continue;
      touching.emplace_back(static_cast<int>(e), pr.i == k ? 1.0 : -1.0);
      for (int d : {pr.i, pr.j})
        if (d >= 0) trial_dofs.push_back(d);
    }
    damper_zener.push_back(std::move(touching));
    std::vector<std::pair<int, double>> viscous_here;
    for (std::size_t e = 0; e < viscous.size(); ++e) {
      const Pair& pr = viscous[e].pair;
      if (pr.i == k || pr.j == k) viscous_here.emplace_back(static_cast<int>(e), pr.i == k ? 1.0 : -1.0);
    }
    damper_viscous.push_back(std::move(viscous_here));
    std::vector<std::pair<int, double>> elements;
    for (int e = 0; e < nh; ++e) {
      const BilinearElement& el = bilinear[e];
      if (el.i != k && el.j != k) continue;
      elements.emplace_back(e, el.i == k ? 1.0 : -1.0);
      for (int d : {el.i, el.j})
        if (d >= 0) trial_dofs.push_back(d);
    }
    damper_bilinear.push_back(std::move(elements));
    std::vector<std::pair<int, double>> bouc_wen_here;
    for (int e = 0; e < nw; ++e) {
      const BoucWenElement& el = bouc_wen[e];
      if (el.i != k && el.j != k) continue;
      bouc_wen_here.emplace_back(e, el.i == k ? 1.0 : -1.0);
      for (int d : {el.i, el.j})
        if (d >= 0) trial_dofs.push_back(d);
    }
    damper_bouc_wen.push_back(std::move(bouc_wen_here));
  }
  // The bilinear elements' decisions read the trial's velocities at their floors.
  for (const BilinearElement& el : bilinear)
    for (int d : {el.i, el.j})
      if (d >= 0) trial_dofs.push_back(d);
  std::sort(trial_dofs.begin(), trial_dofs.end());
  trial_dofs.erase(std::unique(trial_dofs.begin(), trial_dofs.end()), trial_dofs.end());
  // The rows of A^-1 B' at the trial's floors and below them those of C A^-1 B' at the dampers'.
  // Their products with q are summed column after column (vectorised across the rows), so each
  // row's sum is formed in the order of its columns, as Eigen sums a row of the full matrices.
  nt = static_cast<Eigen::Index>(trial_dofs.size());
  nd = static_cast<Eigen::Index>(damper_dofs.size());
  trial_every_floor = nt == n && (nt == 0 || trial_dofs.back() == n - 1);  // (sorted and unique)
  for (StepMatrices* m : {trapezoidal.get(), backward.get()}) {
    if (m == nullptr) continue;
    m->trial_rows.resize(nt + nd, nq);
    for (Eigen::Index t = 0; t < nt; ++t) m->trial_rows.row(t) = m->a_inv_bt.row(trial_dofs[t]);
    for (Eigen::Index d = 0; d < nd; ++d) m->trial_rows.row(nt + d) = m->c_a_inv_bt.row(damper_dofs[d]);
  }
  pi.resize(nf);
  pj.resize(nf);
  for (int f = 0; f < nf; ++f) {
    pi[f] = static_cast<int>(std::lower_bound(damper_dofs.begin(), damper_dofs.end(), fi[f]) - damper_dofs.begin());
    pj[f] = fj[f] < 0 ? -1 : static_cast<int>(std::lower_bound(damper_dofs.begin(), damper_dofs.end(), fj[f]) - damper_dofs.begin());
  }
}

void StructureModel::assemble_storeys() {
  // Storey forces: the storey springs, spring and dashpot devices, Zener devices.
  storey_spring.assign(n, 0.0);
  storey_dashpot.assign(n, 0.0);
  auto storeys_of = [&](const structure::Building& b, int offset) {
    for (int st = 0; st < b.floors(); ++st) storey_spring[offset + st] += b.springs[st];
    // The storey force includes P-Delta's -P_i/h_i x drift: the force the step integrates (the energy balance closes).
    if (b.p_delta) {
      const Eigen::VectorXd kg = b.geometric_stiffness();
      for (int st = 0; st < b.floors(); ++st) storey_spring[offset + st] += kg[st];
    }
    for (const auto& d : b.devices)
      for (int st : d.storeys) {
        // Its linear spring and dashpot (a yielding device's slip or k_h (z - d): the solver's).
        const structure::DeviceKind& kind = structure::kind_of(d);
        if (const double k = kind.spring(d); k != 0.0) storey_spring[offset + st - 1] += k;
        if (const double c_d = kind.dashpot(d); c_d != 0.0) storey_dashpot[offset + st - 1] += c_d;
      }
  };
  storeys_of(s.a, 0);
  if (s.b) storeys_of(*s.b, s.a.floors());
  const Eigen::Map<const Eigen::VectorXd> dashpot_of(storey_dashpot.data(), n);
  dashpots_a = !dashpot_of.head(s.a.floors()).isZero(0.0);
  dashpots_b = !dashpot_of.tail(n - s.a.floors()).isZero(0.0);  // (with the bases' dofs: no storeys, zeros)
}

}  // namespace adjoin::detail
