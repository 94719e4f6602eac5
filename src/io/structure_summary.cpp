// summary.json and the terminal report of a structure run (any scene not written with the
// two-block keys; io/summary.hpp summary_json and brief_report choose it): the solver, the
// ground, each building's periods, damping ratios and mode shapes and the coupled periods, the
// peak of every channel (structure/channels.hpp), each link, each contact pair, the flags of
// values outside the model, the energy balance and the error estimate. SI units; no NaN or Inf
// is written (exit 3).
#include "summary_presenters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../detail/finite_output.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"

namespace adjoin::detail {
namespace {

// A dashpot device or link with alpha < 1 (solver/viscous_step.hpp).
bool has_nonlinear_viscous(const structure::Structure& s) {
  for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr})
    if (b)
      for (const auto& d : b->devices)
        if (structure::kind_of(d).family(d) == structure::DeviceFamily::viscous) return true;
  for (const auto& l : s.links)
    if (structure::kind_of(l).family(l) == structure::LinkFamily::viscous) return true;
  return false;
}

using nlohmann::ordered_json;

void require_finite(const ordered_json& j, const std::string& path, double t_end) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    non_finite_output("summary.json", path, j.get<double>(), t_end, t_end);
  if (j.is_object())
    for (const auto& [key, value] : j.items()) require_finite(value, path.empty() ? key : path + "." + key, t_end);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) require_finite(j[i], path + "[" + std::to_string(i) + "]", t_end);
}

std::vector<double> as_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

const char* link_type(structure::LinkType t) { return enum_name(t); }

// A friction link (its family, structure/link_kinds.hpp): it reports its slip force and switches.
bool friction(const structure::Link& l) { return structure::kind_of(l).family(l) == structure::LinkFamily::friction; }

// Values that may be absent: an unstable mode's period and ratios under P-Delta are null.
ordered_json finite_or_null(const Eigen::VectorXd& v) {
  ordered_json out = ordered_json::array();
  for (double x : as_vector(v)) out.push_back(std::isfinite(x) ? ordered_json(x) : ordered_json(nullptr));
  return out;
}

ordered_json modes_json(const structure::Modes& m) {
  ordered_json shapes = ordered_json::array();
  for (int j = 0; j < m.shapes.cols(); ++j) shapes.push_back(as_vector(m.shapes.col(j)));
  ordered_json out = {{"periods", finite_or_null(m.periods)},
                      {"damping_ratios", finite_or_null(m.total_ratio)},
                      {"inherent_ratios", finite_or_null(m.inherent_ratio)},
                      {"device_ratios", finite_or_null(m.device_ratio)},
                      {"zener_stiffening", as_vector(m.zener_stiffening)},
                      {"mode_shapes", shapes}};
  // With P-Delta the periods are K0 + K_G's (null: a mode the geometric stiffness made unstable).
  if (m.p_delta) out["p_delta"] = true;
  return out;
}

// Collapse (SPEC §7): the storey, its drift-ratio channel and the located time.
ordered_json collapse_json(const Collapse& c) {
  const std::string building(1, c.building);
  return {{"building", building},
          {"storey", c.storey},
          {"channel", building + ".drift_ratio" + std::to_string(c.storey)},
          {"t", c.t},
          {"drift_ratio_limit", c.drift_ratio}};
}

// Text for a time that may be absent (NaN): null.
ordered_json time_or_null(bool present, double t) { return present ? ordered_json(t) : ordered_json(nullptr); }

// The message of a pair without a contact law whose floors overlapped (summary flags,
// terminal report).
std::string unmodelled_message(std::size_t k, const structure::Contact& c, double t) {
  char text[320];
  std::snprintf(text, sizeof text,
                "contact%zu: floor %d of A and floor %d of B overlap from t = %.6g s with no contact law: pounding is not "
                "modelled (set contact[%zu].model); every value after t = %.6g s is outside the model",
                k + 1, c.floor_a, c.floor_b, t, k + 1, t);
  return text;
}

// Estimated absolute errors of the reported values (SI), by channel, link and contact pair.
ordered_json structure_error_json(const RunSpec& scene, const ErrorEstimate& e, bool collapsed) {
  if (!e.available) return ordered_json{{"available", false}, {"reason", e.reason}};
  ordered_json peaks = ordered_json::object();
  for (const auto& p : e.peaks) peaks[p.channel] = {{"max_abs", p.error.max_abs}, {"t", p.error.t}};
  ordered_json links = ordered_json::array();
  for (std::size_t l = 0; l < e.links.size(); ++l) {
    const LinkError& le = e.links[l];
    ordered_json o = {{"force_max", le.force_max}, {"stroke_max", le.stroke_max}};
    if (friction(scene.structure.links[l])) {
      o["energy"] = le.energy;
      o["switch_times"] = le.switches_matched ? ordered_json(le.switches) : ordered_json(nullptr);
      o["switches_note"] = le.switches_note;
    }
    links.push_back(o);
  }
  ordered_json contacts = ordered_json::array();
  for (const auto& c : e.contacts) contacts.push_back({{"min_gap", c.min_gap}, {"t_min_gap", c.t_min_gap}});
  ordered_json out{{"available", true},
                      {"method", "richardson"},
                      {"companion_h", e.companion_h},
                      {"order", e.order},
                      {"companion_wall_seconds", e.companion_wall_seconds},
                      {"max_relative_peak", e.max_relative_peak},
                      {"worst_channel", e.worst_channel},
                      {"peaks", peaks},
                      {"links", links},
                      {"contacts", contacts}};
  // A collapse's located time (null: the companion did not collapse in the same storey).
  if (collapsed) out["collapse_t"] = e.collapse_t ? ordered_json(*e.collapse_t) : ordered_json(nullptr);
  return out;
}

}  // namespace

std::string structure_summary_json(const RunSpec& scene, const Report& r, const ErrorEstimate* estimate,
                                  const TolerantRun* tolerant) {
  const structure::Structure& s = scene.structure;
  ordered_json j;
  j["scene"] = scene.name;
  j["units"] = "SI";
  j["solver"] = {{"scheme", scheme_name(scene.solver)},
                 {"history", to_string(scene.solver.history)},
                 {"h", tolerant ? tolerant->h : scene.solver.h},
                 {"steps", r.solver.steps},
                 {"wall_seconds", r.solver.wall_seconds},
                 {"t_end", scene.solver.t_end},
                 {"h_rule", scene.accuracy.h_rule},
                 {"t_end_rule", scene.accuracy.t_end_rule}};
  if (has_nonlinear_viscous(scene.structure)) j["solver"]["viscous_split_steps"] = r.solver.viscous_split_steps;
  if (scene.solver.history == HistoryEngine::soe) {  // the compression's verified bound and size
    j["solver"]["history_error"] = r.solver.history_error;
    j["solver"]["history_modes"] = r.solver.history_modes;
  }
  if (tolerant) {
    j["solver"]["tolerance"] = tolerant->tolerance;
    j["solver"]["steps_tried"] = tolerant->ladder;
    j["solver"]["tolerance_met"] = tolerant->met;
  }
  j["ground"] = scene.ground->describe();
  ordered_json st;
  st["A"] = modes_json(r.modes[0]);
  if (s.b) {
    st["B"] = modes_json(r.modes[1]);
    st["periods_free"] = finite_or_null(r.coupled->periods_free);
    st["periods_locked"] = finite_or_null(r.coupled->periods_locked);
  }
  j["structure"] = st;
  ordered_json peaks = ordered_json::object();
  for (const auto& p : r.peaks) peaks[p.channel] = {{"max_abs", p.peak.max_abs}, {"t", p.peak.t}};
  j["peaks"] = peaks;
  ordered_json links = ordered_json::array();
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const auto& link = s.links[l];
    const LinkReport& lr = r.links[l];
    ordered_json o = {{"type", link_type(link.type)},
                      {"floors", {link.floor_a, link.floor_b}},
                      {"force_max", lr.force_max},
                      {"stroke_max", lr.stroke_max}};
    for (const structure::LinkValue& v : structure::kind_of(link).summary) o[v.name] = v.value(link);  // (its kind's)
    if (friction(link)) {
      o["switches"] = lr.switches;
      o["switch_times"] = lr.switch_times;
    }
    o["energy"] = lr.energy;  // dissipated, whatever the type (SPEC §7)
    links.push_back(o);
  }
  j["links"] = links;
  ordered_json contacts = ordered_json::array();
  for (std::size_t k = 0; k < s.contacts.size(); ++k) {
    const auto& c = s.contacts[k];
    const ContactReport& cr = r.contacts[k];
    contacts.push_back({{"floors", {c.floor_a, c.floor_b}},
                        {"gap", c.gap},
                        {"model", structure::to_string(c.law.model)},
                        {"min_gap", cr.min_gap},
                        {"t_min_gap", cr.t_min_gap},
                        {"contact", cr.contact},
                        {"t_first_contact", time_or_null(cr.contact, cr.t_first_contact)},
                        {"impacts", cr.impacts},
                        {"force_max", cr.force_max},
                        {"t_force_max", time_or_null(cr.impacts > 0, cr.t_force_max)},
                        {"penetration_max", cr.penetration_max},
                        {"impulse", cr.impulse},
                        {"impulse_max", cr.impulse_max},
                        {"energy", cr.dissipated},
                        {"work", cr.work},
                        {"outside_model_from", time_or_null(cr.outside_model(), cr.unmodelled_from)}});
  }
  j["contacts"] = contacts;
  // Values outside the model: a pair without a contact law whose floors overlapped.
  ordered_json flags = ordered_json::array();
  for (std::size_t k = 0; k < s.contacts.size(); ++k)
    if (r.contacts[k].outside_model()) flags.push_back(unmodelled_message(k, s.contacts[k], r.contacts[k].unmodelled_from));
  j["outside_model_from"] = time_or_null(!std::isnan(r.unmodelled_from()), r.unmodelled_from());
  j["flags"] = flags;
  ordered_json energy;
  for (std::size_t b = 0; b < r.energy.buildings.size(); ++b) {
    const auto& part = r.energy.buildings[b];
    energy[b == 0 ? "A" : "B"] = {{"input", part.input}, {"kinetic", part.kinetic}, {"inherent_damping", part.inherent},
                                  {"storeys", part.storeys}};
    if (!part.hysteretic.empty()) energy[b == 0 ? "A" : "B"]["hysteretic"] = part.hysteretic;  // (within storeys)
    if ((b == 0 ? s.a : *s.b).base || (b == 0 ? s.a : *s.b).ground_friction > 0.0) energy[b == 0 ? "A" : "B"]["isolator"] = part.isolator;  // (SPEC §7: slider + pendulum)
  }
  energy["links"] = r.energy.links;
  energy["contacts"] = r.energy.contacts;
  energy["input"] = r.energy.input;
  energy["residual"] = r.energy.residual;
  j["energy"] = energy;
  // SPEC §7: the drifts (and drift ratios) at the run's last grid point; the collapse, if any.
  ordered_json residual = ordered_json::object();
  for (const auto& v : r.residual) residual[v.channel] = v.value;
  j["residual"] = residual;
  if (r.collapse) j["collapse"] = collapse_json(*r.collapse);
  if (!r.yield.empty()) {  // (SPEC §7: per building, per storey)
    ordered_json yield = ordered_json::object();
    for (const BuildingYield& y : r.yield) {
      ordered_json list = ordered_json::array();
      for (const StoreyYield& sy : y.storeys)
        list.push_back({{"storey", sy.storey},
                        {"yielded", sy.yielded},
                        {"t_first", time_or_null(sy.yielded, sy.t_first)},
                        {"excursions", sy.excursions},
                        {"ductility_max", sy.ductility_max},
                        {"plastic_work", sy.plastic_work}});
      yield[std::string(1, y.building)] = list;
    }
    j["yield"] = yield;
  }
  if (!r.bases.empty()) {  // (SPEC §7: per isolated building)
    ordered_json base = ordered_json::object();
    for (const BaseReport& b : r.bases)
      base[std::string(1, b.building)] = {{"max_abs", b.max_abs}, {"t", b.t}, {"residual", b.residual}, {"switches", b.switches}, {"energy", b.energy}};
    j["base"] = base;
  }
  if (estimate) j["error_estimate"] = structure_error_json(scene, *estimate, r.collapse.has_value());
  require_finite(j, "", scene.solver.t_end);
  return j.dump(2) + "\n";
}

std::string structure_brief_report(const RunSpec& scene, const Report& r, const ErrorEstimate* estimate,
                                  const TolerantRun* tolerant) {
  std::ostringstream o;
  char line[512];
  const structure::Structure& s = scene.structure;
  std::string h_rule = scene.accuracy.h_rule;
  if (tolerant)
    h_rule += "; " + std::to_string(tolerant->ladder.size()) + (tolerant->ladder.size() == 1 ? " run" : " runs") +
              (tolerant->met ? "" : "; NOT met, see error_estimate");
  std::snprintf(line, sizeof line, "%s: %d + %d floors, h = %.4g s (%s), t_end = %.4g s (%s), %zu steps in %.3g s\n",
                scene.name.c_str(), s.a.floors(), s.b ? s.b->floors() : 0, tolerant ? tolerant->h : scene.solver.h, h_rule.c_str(),
                scene.solver.t_end, scene.accuracy.t_end_rule.c_str(), r.solver.steps, r.solver.wall_seconds);
  o << line;
  for (std::size_t b = 0; b < r.modes.size(); ++b) {
    if (!std::isfinite(r.modes[b].periods[0])) {  // P-Delta made the first mode unstable
      std::snprintf(line, sizeof line, "building %s: T1 unstable with P-Delta (a storey's tangent k - P/h is negative)\n",
                    b == 0 ? "A" : "B");
      o << line;
      continue;
    }
    const bool yields = (b == 0 ? s.a : *s.b).yields();  // its periods are the initial stiffness's (SPEC §7)
    std::snprintf(line, sizeof line, "building %s: T1 = %.4g s, modal damping %.3g (inherent %.3g, devices %.3g)%s%s\n",
                  b == 0 ? "A" : "B", r.modes[b].periods[0], r.modes[b].total_ratio[0], r.modes[b].inherent_ratio[0],
                  r.modes[b].device_ratio[0], r.modes[b].p_delta ? " with P-Delta" : "",
                  yields ? "; of the initial stiffness (the storeys yield)" : "");
    o << line;
  }
  if (r.collapse) {
    std::snprintf(line, sizeof line,
                  "COLLAPSE: storey %d of building %c passed the drift ratio %.4g at t = %.6g s; the run stopped there (outputs "
                  "end at t = %.6g s)\n",
                  r.collapse->storey, r.collapse->building, std::abs(r.collapse->drift_ratio), r.collapse->t,
                  static_cast<double>(r.solver.steps) * r.solver.h);
    o << line;
  }
  for (const auto& p : r.peaks)
    if (p.channel.find(".x") != std::string::npos && p.channel.find("drift") == std::string::npos) {
      const std::string building = p.channel.substr(0, 1);
      const int top = building == "A" ? s.a.floors() : s.b->floors();
      if (p.channel == building + ".x" + std::to_string(top)) {
        std::snprintf(line, sizeof line, "peak roof displacement %s: %.4g m at t = %.4g s\n", building.c_str(), p.peak.max_abs, p.peak.t);
        o << line;
      }
    }
  // The largest peak drift ratio of each building with storey heights (SPEC §7).
  for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr}) {
    if (!b || !b->has_heights()) continue;
    const ChannelPeak* worst = nullptr;
    for (const auto& p : r.peaks)
      if (p.channel.rfind(b->name + ".drift_ratio", 0) == 0 && (!worst || p.peak.max_abs > worst->peak.max_abs)) worst = &p;
    if (!worst) continue;
    std::snprintf(line, sizeof line, "peak drift ratio %s: %.4g (%s) at t = %.4g s\n", b->name.c_str(), worst->peak.max_abs,
                  worst->channel.c_str(), worst->peak.t);
    o << line;
  }
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    std::snprintf(line, sizeof line, "link%zu (%s): force max %.4g N, stroke max %.4g m", l + 1, link_type(s.links[l].type),
                  r.links[l].force_max, r.links[l].stroke_max);
    o << line;
    if (friction(s.links[l]))
      o << ", " << r.links[l].switches << (r.links[l].switches == 1 ? " switch" : " switches");
    o << "\n";
  }
  for (const BaseReport& b : r.bases) {  // (SPEC §7: an isolated base)
    const structure::Building& building = b.building == 'A' ? s.a : *s.b;
    std::snprintf(line, sizeof line, "base %c (%s): x0 max %.4g m at t = %.4g s, residual %.4g m, %zu %s, slider energy %.4g J\n", b.building,
                  to_string(building.base->model).c_str(), b.max_abs, b.t, b.residual, b.switches, b.switches == 1 ? "switch" : "switches", b.energy);
    o << line;
  }
  for (std::size_t k = 0; k < s.contacts.size(); ++k) {
    const ContactReport& c = r.contacts[k];
    const structure::Contact& pair = s.contacts[k];
    if (pair.law.model == structure::ContactModel::none) {
      std::snprintf(line, sizeof line, "contact%zu: min gap %.4g m at t = %.4g s", k + 1, c.min_gap, c.t_min_gap);
      o << line;
      if (c.outside_model()) {
        std::snprintf(line, sizeof line,
                      " (the floors touch at t = %.4g s: pounding is not modelled (set contact[%zu].model); the results after "
                      "t = %.4g s are not valid)",
                      c.unmodelled_from, k + 1, c.unmodelled_from);
        o << line;
      }
      o << "\n";
    } else if (c.contact && pair.law.model == structure::ContactModel::impact) {
      // (Newton's law has impulses, no forces or penetrations.)
      std::snprintf(line, sizeof line,
                    "contact%zu (%s): %zu impact%s, first contact at t = %.4g s, largest impulse %.4g N s, dissipated %.4g J\n",
                    k + 1, structure::to_string(pair.law.model), c.impacts, c.impacts == 1 ? "" : "s", c.t_first_contact,
                    c.impulse_max, c.dissipated);
      o << line;
    } else if (c.contact) {
      std::snprintf(line, sizeof line,
                    "contact%zu (%s): %zu impact%s, first contact at t = %.4g s, peak force %.4g N at t = %.4g s, max penetration "
                    "%.4g m, dissipated %.4g J\n",
                    k + 1, structure::to_string(pair.law.model), c.impacts, c.impacts == 1 ? "" : "s", c.t_first_contact,
                    c.force_max, c.t_force_max, c.penetration_max, c.dissipated);
      o << line;
    } else {
      std::snprintf(line, sizeof line, "contact%zu (%s): no contact, min gap %.4g m at t = %.4g s\n", k + 1,
                    structure::to_string(pair.law.model), c.min_gap, c.t_min_gap);
      o << line;
    }
  }
  if (estimate && !estimate->available) {
    o << "error estimate: not available (" << estimate->reason << ")\n";
  } else if (estimate) {
    std::snprintf(line, sizeof line, "error estimate (companion h = %.4g s): peaks %.2g relative%s%s%s", estimate->companion_h,
                  estimate->max_relative_peak, estimate->worst_channel.empty() ? "" : " (", estimate->worst_channel.c_str(),
                  estimate->worst_channel.empty() ? "" : ")");
    o << line;
    for (std::size_t l = 0; l < estimate->links.size(); ++l)
      if (!estimate->links[l].switches_matched) o << ", link" << l + 1 << " switches: not estimated (the companion run found other switches)";
    o << "\n";
  }
  return o.str();
}

}  // namespace adjoin::detail
