#pragma once
// Which structures the structure stepper steps by its pair step (structure_solver.cpp,
// advance_pair): two buildings of one floor each, joined by one friction damper between their
// floors and nothing else that the step must solve for (no contact law, no nonlinear viscous,
// bilinear or Bouc-Wen element, no isolated base, no other link). The two-block scenes' 1 + 1
// structure is one, and so is a building pair of one storey each with one friction link.
//
// Why a step of its own: on two floors the general step's loops over its device lists, its
// work vectors' dynamic sizes and its calls cost several times the arithmetic (about 1.9k
// instructions a step against the pair's few hundred). The pair step repeats the general
// step's floating-point operations in their order on the same work vectors, so a run gives
// the same numbers bit for bit either way (tests/test_pair_step.cpp checks it).
#include "structure_model.hpp"

namespace adjoin::detail {

inline bool takes_pair_step(const StructureModel& m) {
  if (!m.options.pair_step) return false;
  if (m.n != 2 || m.nf != 1 || m.nc != 0 || m.nv != 0 || m.nh != 0 || m.nw != 0) return false;
  if (!m.s.b || m.s.a.floors() != 1 || m.s.b->floors() != 1) return false;
  if (m.s.base_dof('A') >= 0 || m.s.base_dof('B') >= 0) return false;
  // The damper is the only link, between the two floors.
  if (m.s.links.size() != 1 || m.link_pair.size() != 1 || m.friction[0] != 0 || m.link_zener[0] >= 0) return false;
  if (!m.linear_links.empty() || m.fi[0] < 0 || m.fj[0] < 0 || m.fi[0] == m.fj[0]) return false;
  // The trial reads both floors (the dampers' floors are 0 and 1, sorted).
  return m.trial_every_floor && m.nt == 2 && m.nd == 2;
}

}  // namespace adjoin::detail
