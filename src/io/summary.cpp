#include "adjoin/io/summary.hpp"

#include "summary_presenters.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../detail/finite_output.hpp"
#include "adjoin/io/two_block_names.hpp"
#include "adjoin/structure/two_block.hpp"

namespace adjoin {
namespace {

using nlohmann::ordered_json;

// Every number of the summary must be finite: nlohmann writes NaN and Inf as null, which a
// reader would take for "not computed".
void require_finite(const ordered_json& j, const std::string& path, double t_end_seconds, double t_end) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    detail::non_finite_output("summary.json", path, j.get<double>(), t_end_seconds, t_end);
  if (j.is_object())
    for (const auto& [key, value] : j.items()) require_finite(value, path.empty() ? key : path + "." + key, t_end_seconds, t_end);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) require_finite(j[i], path + "[" + std::to_string(i) + "]", t_end_seconds, t_end);
}

ordered_json peak_error(const PeakError& e, double scale, double time_scale) {
  return ordered_json{{"max_abs", e.max_abs * scale}, {"t", e.t * time_scale}};
}

// Estimated absolute errors of the reported values, in the scene's units.
ordered_json error_estimate_json(const ErrorEstimate& e, const Scales& k) {
  if (!e.available) return ordered_json{{"available", false}, {"reason", e.reason}};
  // The refined peaks' errors under SPEC §3's names (the estimate names them by channel).
  const char* const refined[] = {"x1", "x2", "drift", "f1", "f2", "q"};
  ordered_json peak_errors = ordered_json::object();
  for (const char* name : refined) {
    const std::string channel = structure::two_block_channel(name);
    double scale = 0.0;
    for (const FrozenName& f : two_block_peak_names())
      if (std::string(f.name) == name) scale = k.*f.unit;
    for (const auto& p : e.peaks)
      if (p.channel == channel) peak_errors[name] = peak_error(p.error, scale, k.time);
  }
  ordered_json switches = nullptr;
  if (e.switches_matched) {
    switches = ordered_json::array();
    for (double s : e.switches) switches.push_back(s * k.time);
  }
  return ordered_json{
      {"available", true},
      {"method", "richardson"},
      {"companion_h", e.companion_h * k.time},
      {"order", e.order},
      {"companion_wall_seconds", e.companion_wall_seconds},
      {"max_relative_peak", e.max_relative_peak},
      {"peaks", peak_errors},
      {"min_gap", e.min_gap * k.length},
      {"t_min_gap", e.t_min_gap * k.time},
      {"friction", e.friction * k.energy},
      {"switches", switches},
      {"switches_note", e.switches_matched ? "" : "the companion run found other phases; instants not estimated"}};
}

// The flag of a run without a contact law whose gap closed (summary and terminal).
std::string outside_model_warning(const Scene& scene, double t_first_contact) {
  char text[320];
  std::snprintf(text, sizeof text,
                "the gap closes at t = %.6g%s and the model has no contact law: the blocks pass through each "
                "other, and every value after that time is outside the model (set [model.contact])",
                t_first_contact * scene.scales.time, scene.scales.si ? " s" : "");
  return text;
}

ordered_json peak(const Peak& p, double scale, double time_scale) {
  return ordered_json{{"max_abs", p.max_abs * scale}, {"t", p.t * time_scale}};
}

}  // namespace

std::string summary_json(const Scene& scene, const Report& r, const ErrorEstimate* estimate,
                         const TolerantRun* tolerant) {
  if (!scene.two_block()) return detail::structure_summary_json(scene, r, estimate, tolerant);
  const Scales& k = scene.scales;
  ordered_json j;
  j["scene"] = scene.name;
  j["units"] = k.units_name();
  j["solver"] = ordered_json{{"scheme", r.solver.scheme},
                             {"history", r.solver.history},
                             {"h", r.solver.h * k.time},
                             {"steps", r.solver.steps},
                             {"wall_seconds", r.solver.wall_seconds},
                             {"t_end", static_cast<double>(r.solver.steps) * r.solver.h * k.time}};
  if (r.solver.history == "soe") {  // the compression's verified bound and size (soe_history.hpp)
    j["solver"]["history_error"] = r.solver.history_error;
    j["solver"]["history_modes"] = r.solver.history_modes;
  }
  if (!scene.accuracy.h_rule.empty()) j["solver"]["h_rule"] = scene.accuracy.h_rule;
  if (!scene.accuracy.t_end_rule.empty()) j["solver"]["t_end_rule"] = scene.accuracy.t_end_rule;
  if (tolerant) {
    ordered_json ladder = ordered_json::array();
    for (double h : tolerant->ladder) ladder.push_back(h * k.time);
    j["solver"]["tolerance"] = tolerant->tolerance;
    j["solver"]["steps_tried"] = ladder;
    j["solver"]["tolerance_met"] = tolerant->met;
  }
  j["ground"] = scene.ground->describe();
  const OutputOptions& asked = scene.output;
  if (asked.phases) {
    ordered_json phases = ordered_json::array();
    for (const auto& p : r.phases)
      phases.push_back(
          ordered_json{{"state", to_string(p.state)}, {"t_start", p.t_start * k.time}, {"t_end", p.t_end * k.time}});
    j["phases"] = phases;
    j["switches"] = r.phases.empty() ? 0 : r.phases.size() - 1;
  } else {
    j["phases"] = nullptr;
  }
  if (asked.peaks) {
    ordered_json peaks = ordered_json::object();
    for (const FrozenName& f : two_block_peak_names())
      peaks[f.name] = peak(r.peak(structure::two_block_channel(f.name)), k.*f.unit, k.time);
    j["peaks"] = peaks;
  } else {
    j["peaks"] = nullptr;
  }
  ordered_json final_values{{"t", r.t_last * k.time}};
  for (const FrozenName& f : two_block_final_names())
    final_values[f.name] = r.last_value(structure::two_block_channel(f.name)) * k.*f.unit;
  final_values["phase"] = to_string(r.last_phase);
  j["final"] = final_values;
  const ContactReport& g = r.contacts.at(0);
  const bool law = g.model != structure::ContactModel::none;
  if (asked.pounding) {
    j["pounding"] = ordered_json{{"min_gap", g.min_gap * k.length},
                                 {"t_min_gap", g.t_min_gap * k.time},
                                 {"contact", g.contact},
                                 {"t_first_contact", g.contact ? ordered_json(g.t_first_contact * k.time) : ordered_json(nullptr)}};
    if (law) {
      ordered_json& p = j["pounding"];
      p["model"] = structure::to_string(g.model);
      p["impacts"] = g.impacts;
      p["force_max"] = g.force_max * k.force;
      p["t_force_max"] = g.force_max > 0.0 ? ordered_json(g.t_force_max * k.time) : ordered_json(nullptr);
      p["penetration_max"] = g.penetration_max * k.length;
      p["impulse"] = g.impulse * k.force * k.time;
      p["impulse_max"] = g.impulse_max * k.force * k.time;
      p["energy"] = g.dissipated * k.energy;
    } else if (g.outside_model()) {
      j["pounding"]["model"] = "none";
      j["pounding"]["outside_model_from"] = g.unmodelled_from * k.time;
    }
  } else {
    j["pounding"] = nullptr;
  }
  if (asked.energy) {
    const TwoBlockEnergy e = two_block_energy(r);
    j["energy"] = ordered_json{{"input", e.input * k.energy},       {"kinetic", e.kinetic * k.energy},
                               {"rod1", e.rod1 * k.energy},         {"rod2", e.rod2 * k.energy},
                               {"friction", e.friction * k.energy}, {"residual", e.residual * k.energy}};
    if (law) {
      // The residual already subtracts the contact term (observe/energy.hpp).
      j["energy"]["contact"] = e.contact * k.energy;
      j["energy"]["contact_dissipated"] = e.contact_dissipated * k.energy;
    }
    // (SPEC §7; the residual already subtracts it)
    if (scene.structure.a.ground_friction > 0.0) j["energy"]["base_friction"] = e.base_friction * k.energy;
  } else {
    j["energy"] = nullptr;
  }
  if (!r.spectra.empty()) {
    ordered_json spectra = ordered_json::object();
    for (const auto& sig : r.spectra) {
      // The peak PSA of each signal at the first damping, as a pointer into spectra.csv.
      const SpectralValues* best = nullptr;
      for (std::size_t i = 0; i < sig.spectrum.periods.size(); ++i)
        if (!best || sig.spectrum.at(0, i).psa > best->psa) best = &sig.spectrum.at(0, i);
      if (best)
        spectra[two_block_signal_name(sig.signal)] =
            ordered_json{{"damping", best->damping}, {"max_psa_g", best->psa}, {"period", best->period}};
    }
    j["spectra"] = spectra;
  }
  if (estimate) j["error_estimate"] = error_estimate_json(*estimate, k);
  // As a building run's summary: the top-level time from which values are outside the model,
  // and its flag in words (only for a run that has one, so a run that never pounds keeps its
  // summary).
  if (g.outside_model()) {
    j["outside_model_from"] = g.unmodelled_from * k.time;
    j["flags"] = ordered_json::array({outside_model_warning(scene, g.unmodelled_from)});
  }
  const double t_end = static_cast<double>(r.solver.steps) * r.solver.h;
  require_finite(j, "", t_end * k.time, t_end);
  return j.dump(2) + "\n";
}

std::string brief_report(const Scene& scene, const Report& r, const ErrorEstimate* estimate,
                         const TolerantRun* tolerant) {
  if (!scene.two_block()) return detail::structure_brief_report(scene, r, estimate, tolerant);
  const Scales& k = scene.scales;
  const bool si = k.si;
  auto u = [&](const char* unit) { return si ? std::string(" ") + unit : std::string(); };
  std::ostringstream s;
  char line[256];
  s << "scene " << scene.name << " (" << k.units_name() << "), ground: " << scene.ground->describe() << "\n";
  std::snprintf(line, sizeof line, "solver %s/%s, h = %g%s, %zu steps, %.3f s wall\n", r.solver.scheme.c_str(),
                r.solver.history.c_str(), r.solver.h * k.time, u("s").c_str(), r.solver.steps, r.solver.wall_seconds);
  s << line;
  if (!scene.accuracy.h_rule.empty() || !scene.accuracy.t_end_rule.empty()) {
    s << "       ";
    if (!scene.accuracy.h_rule.empty()) {
      s << "h " << scene.accuracy.h_rule;
      if (tolerant) {
        s << " (" << tolerant->ladder.size() << (tolerant->ladder.size() == 1 ? " run" : " runs")
          << (tolerant->met ? "" : "; NOT met, see error_estimate") << ")";
      }
      if (!scene.accuracy.t_end_rule.empty()) s << "; ";
    }
    if (!scene.accuracy.t_end_rule.empty()) s << "t_end = " << scene.accuracy.t_end_rule;
    s << "\n";
  }
  if (scene.output.phases) {
    const std::vector<PhaseInterval>& phases = r.phases;
    s << "phases (" << phases.size() << "):";
    const std::size_t shown = 8;
    for (std::size_t i = 0; i < phases.size(); ++i) {
      if (i == shown && phases.size() > shown + 1) {
        s << " ... (" << phases.size() - shown - 1 << " more)";
        i = phases.size() - 1;
      }
      std::snprintf(line, sizeof line, " %s [%.4g, %.4g]", to_string(phases[i].state), phases[i].t_start * k.time,
                    phases[i].t_end * k.time);
      s << line;
    }
    s << "\n";
  }
  if (scene.output.peaks) {
    auto p = [&](const char* name) { return r.peak(structure::two_block_channel(name)); };
    std::snprintf(line, sizeof line, "peaks: |x1| %.6g%s at t = %.4g, |x2| %.6g%s at t = %.4g, |q| %.6g%s\n",
                  p("x1").max_abs * k.length, u("m").c_str(), p("x1").t * k.time, p("x2").max_abs * k.length,
                  u("m").c_str(), p("x2").t * k.time, p("q").max_abs * k.force, u("N").c_str());
    s << line;
    std::snprintf(line, sizeof line, "       |f1| %.6g%s, |f2| %.6g%s\n", p("f1").max_abs * k.force, u("N").c_str(),
                  p("f2").max_abs * k.force, u("N").c_str());
    s << line;
  }
  const ContactReport& g = r.contacts.at(0);
  if (scene.output.pounding && g.model != structure::ContactModel::none) {
    s << "pounding (" << structure::to_string(g.model) << "): ";
    if (!g.contact) {
      std::snprintf(line, sizeof line, "min gap %.6g%s at t = %.4g, no contact\n", g.min_gap * k.length, u("m").c_str(),
                    g.t_min_gap * k.time);
    } else if (g.model == structure::ContactModel::impact) {
      std::snprintf(line, sizeof line, "%zu impact%s from t = %.4g%s, largest impulse %.6g%s, dissipated %.4g%s\n",
                    g.impacts, g.impacts == 1 ? "" : "s", g.t_first_contact * k.time, u("s").c_str(),
                    g.impulse_max * k.force * k.time, u("N s").c_str(), g.dissipated * k.energy, u("J").c_str());
    } else {
      std::snprintf(line, sizeof line,
                    "%zu impact%s from t = %.4g%s, peak force %.6g%s at t = %.4g, max penetration %.4g%s, "
                    "dissipated %.4g%s\n",
                    g.impacts, g.impacts == 1 ? "" : "s", g.t_first_contact * k.time, u("s").c_str(),
                    g.force_max * k.force, u("N").c_str(), g.t_force_max * k.time, g.penetration_max * k.length,
                    u("m").c_str(), g.dissipated * k.energy, u("J").c_str());
    }
    s << line;
  } else if (scene.output.pounding) {
    std::snprintf(
        line, sizeof line, "pounding: min gap %.6g%s at t = %.4g, %s\n", g.min_gap * k.length, u("m").c_str(),
        g.t_min_gap * k.time,
        g.contact ? ("CONTACT first at t = " + std::to_string(g.t_first_contact * k.time)).c_str() : "no contact");
    s << line;
  }
  if (g.outside_model()) s << "WARNING: " << outside_model_warning(scene, g.unmodelled_from) << "\n";
  if (scene.output.energy) {
    const TwoBlockEnergy e = two_block_energy(r);
    std::snprintf(line, sizeof line, "energy%s: input %.6g, kinetic %.6g, rod1 %.6g, rod2 %.6g, friction %.6g, ",
                  si ? " [J]" : " (per unit m1)", e.input * k.energy, e.kinetic * k.energy, e.rod1 * k.energy,
                  e.rod2 * k.energy, e.friction * k.energy);
    s << line;
    if (scene.structure.contacts[0].law.model != structure::ContactModel::none) {
      std::snprintf(line, sizeof line, "contact %.6g, ", e.contact * k.energy);
      s << line;
    }
    if (scene.structure.a.ground_friction > 0.0) {  // (SPEC §7)
      std::snprintf(line, sizeof line, "base friction %.6g, ", e.base_friction * k.energy);
      s << line;
    }
    std::snprintf(line, sizeof line, "residual %.3g\n", e.residual * k.energy);
    s << line;
  }
  if (estimate) {
    if (!estimate->available) {
      s << "error estimate: not available (" << estimate->reason << ")\n";
    } else {
      double worst_switch = 0.0;
      for (double e : estimate->switches) worst_switch = std::max(worst_switch, e);
      std::snprintf(line, sizeof line, "error estimate (companion h = %g%s): peaks %.2g relative, min gap %.2g%s, friction %.2g%s",
                    estimate->companion_h * k.time, u("s").c_str(), estimate->max_relative_peak, estimate->min_gap * k.length,
                    u("m").c_str(), estimate->friction * k.energy, u("J").c_str());
      s << line;
      if (estimate->switches_matched && !estimate->switches.empty()) {
        std::snprintf(line, sizeof line, ", switches %.2g%s", worst_switch * k.time, u("s").c_str());
        s << line;
      } else if (!estimate->switches_matched) {
        s << ", switches: not estimated (the companion run found other phases)";
      }
      s << "\n";
    }
  }
  return s.str();
}

std::string spectra_csv(const Report& report) { return spectra_csv(report.spectra); }

std::string spectra_csv(const std::vector<SignalSpectrum>& spectra) {
  std::ostringstream s;
  s.precision(10);
  s << "signal,period,damping,sd,sv,sa,psv,psa\n";
  for (const auto& sig : spectra)
    for (const auto& v : sig.spectrum.values) {
      for (double x : {v.sd, v.sv, v.sa, v.psv, v.psa})
        if (!std::isfinite(x))
          throw NumericalError("spectra.csv: the " + sig.signal + " spectrum is non-finite at period " +
                                   std::to_string(v.period) + "; check the scene's scales and output.spectra.periods",
                               0.0);
      s << sig.signal << ',' << v.period << ',' << v.damping << ',' << v.sd << ',' << v.sv << ',' << v.sa << ','
        << v.psv << ',' << v.psa << '\n';
    }
  return s.str();
}

}  // namespace adjoin
