#include "adjoin/io/building_files.hpp"
#include "adjoin/io/summary.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../detail/finite_output.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/observe/channel_values.hpp"
#include "adjoin/structure/channels.hpp"

namespace adjoin {
namespace {

using nlohmann::ordered_json;

void require_finite(const ordered_json& j, const std::string& path, double t_end) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    detail::non_finite_output("summary.json", path, j.get<double>(), t_end, t_end);
  if (j.is_object())
    for (const auto& [key, value] : j.items()) require_finite(value, path.empty() ? key : path + "." + key, t_end);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) require_finite(j[i], path + "[" + std::to_string(i) + "]", t_end);
}

std::vector<double> as_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

const char* link_type(structure::LinkType t) {
  switch (t) {
    case structure::LinkType::friction: return "friction";
    case structure::LinkType::dashpot: return "dashpot";
    case structure::LinkType::spring: return "spring";
    case structure::LinkType::zener: return "zener";
  }
  return "";
}

ordered_json modes_json(const structure::Modes& m) {
  ordered_json shapes = ordered_json::array();
  for (int j = 0; j < m.shapes.cols(); ++j) shapes.push_back(as_vector(m.shapes.col(j)));
  return {{"periods", as_vector(m.periods)},
          {"damping_ratios", as_vector(m.total_ratio)},
          {"inherent_ratios", as_vector(m.inherent_ratio)},
          {"device_ratios", as_vector(m.device_ratio)},
          {"zener_stiffening", as_vector(m.zener_stiffening)},
          {"mode_shapes", shapes}};
}

// A CSV value as to_chars writes it (about 17 digits, sign, exponent) and its comma: the
// size estimate of a time series before it is written.
constexpr double kBytesPerCsvValue = 20.0;
constexpr double kLargeCsvBytes = 50e6;  // warned before writing

// Streams every `every`-th grid point of a building run (building_output_every, from each
// run's own step): t, a_g, then every channel the registry marks for the time series
// (structure/channels.hpp), in its order, and `outside_model` when a contact pair has no law.
// Before a run whose file would exceed 50 MB it tells `warn` the size.
class BuildingCsvWriter final : public StructureObserver {
 public:
  BuildingCsvWriter(std::ostream& out, const BuildingScene& scene, RunWarning warn)
      : out_(out), scene_(scene), warn_(std::move(warn)) {}
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override {
    s_ = &s;
    steps_ = o.steps();
    every_ = building_output_every(scene_, o.h);
    count_ = 0;
    std::vector<structure::Channel> columns;
    for (auto& c : structure::channels(s))
      if (structure::info(c.quantity).timeseries) columns.push_back(std::move(c));
    columns_ = ChannelValues(s, std::move(columns));
    unmodelled_ = false;
    flagged_ = std::any_of(s.contacts.begin(), s.contacts.end(),
                           [](const structure::Contact& c) { return c.law.model == structure::ContactModel::none; });
    warn_if_large(o.h);
    out_ << "t,ag";
    for (const auto& c : columns_.channels()) out_ << "," << c.name;
    if (flagged_) out_ << ",outside_model";
    out_ << "\n";
    // The gap of each pair without a law, read at every grid point (not only the written
    // ones): its first overlap puts every later row outside the model.
    gaps_.clear();
    for (std::size_t k = 0; k < s.contacts.size(); ++k)
      if (s.contacts[k].law.model == structure::ContactModel::none)
        gaps_.push_back({"", structure::Quantity::contact_gap, 'A', static_cast<int>(k + 1), -1});
  }
  void observe(const StructureState& st) override {
    const std::size_t index = count_++;
    for (const auto& gap : gaps_)
      if (channel_value(*s_, gap, st) <= 0.0) unmodelled_ = true;
    if (index % every_ != 0 && index != steps_) return;
    values_.resize(2 + columns_.size());
    values_[0] = st.t;
    values_[1] = st.ag;
    columns_.read(st, values_.data() + 2);
    if (flagged_) values_.push_back(unmodelled_ ? 1.0 : 0.0);
    char number[32];
    for (std::size_t i = 0; i < values_.size(); ++i) {
      detail::require_finite_output(values_[i], "timeseries.csv", "a value", st.t, st.t);
      auto [end, ec] = std::to_chars(number, number + sizeof number, values_[i]);
      buffer_.append(number, end);
      buffer_.push_back(i + 1 < values_.size() ? ',' : '\n');
    }
    if (buffer_.size() > (1 << 16)) { out_ << buffer_; buffer_.clear(); }
  }
  void end() override { out_ << buffer_; buffer_.clear(); }

 private:
  // Once per size: a run to a tolerance begins again with each rung.
  void warn_if_large(double h) {
    const double rows = static_cast<double>(steps_ / every_ + 2);
    const double columns = static_cast<double>(2 + columns_.size() + (flagged_ ? 1 : 0));
    const double bytes = rows * columns * kBytesPerCsvValue;
    if (!warn_ || bytes <= kLargeCsvBytes || bytes <= 2.0 * warned_bytes_) return;
    warned_bytes_ = bytes;
    char text[400];
    std::snprintf(text, sizeof text,
                  "timeseries.csv will be about %.0f MB (%.0f rows of %.0f columns: a row every %zu steps of h = %.4g s); "
                  "set output.every (a row every output.every steps) to write fewer rows",
                  bytes / 1e6, rows, columns, every_, h);
    warn_(text);
  }

  std::ostream& out_;
  const BuildingScene& scene_;
  RunWarning warn_;
  double warned_bytes_ = 0.0;
  std::size_t every_ = 1, steps_ = 0, count_ = 0;
  const structure::Structure* s_ = nullptr;
  ChannelValues columns_;
  std::vector<structure::Channel> gaps_;
  std::vector<double> values_;
  std::string buffer_;
  bool flagged_ = false, unmodelled_ = false;
};

std::string number_text(double v) {
  char number[32];
  auto [end, ec] = std::to_chars(number, number + sizeof number, v);
  return std::string(number, end);
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

// Estimated absolute errors of the reported values (SI), shaped as a two-block run's.
ordered_json building_error_json(const BuildingScene& scene, const ErrorEstimate& e) {
  if (!e.available) return ordered_json{{"available", false}, {"reason", e.reason}};
  ordered_json peaks = ordered_json::object();
  for (const auto& p : e.peaks) peaks[p.channel] = {{"max_abs", p.error.max_abs}, {"t", p.error.t}};
  ordered_json links = ordered_json::array();
  for (std::size_t l = 0; l < e.links.size(); ++l) {
    const LinkError& le = e.links[l];
    ordered_json o = {{"force_max", le.force_max}, {"stroke_max", le.stroke_max}};
    if (scene.structure.links[l].type == structure::LinkType::friction) {
      o["energy"] = le.energy;
      o["switch_times"] = le.switches_matched ? ordered_json(le.switches) : ordered_json(nullptr);
      o["switches_note"] = le.switches_note;
    }
    links.push_back(o);
  }
  ordered_json contacts = ordered_json::array();
  for (const auto& c : e.contacts) contacts.push_back({{"min_gap", c.min_gap}, {"t_min_gap", c.t_min_gap}});
  return ordered_json{{"available", true},
                      {"method", "richardson"},
                      {"companion_h", e.companion_h},
                      {"order", e.order},
                      {"companion_wall_seconds", e.companion_wall_seconds},
                      {"max_relative_peak", e.max_relative_peak},
                      {"worst_channel", e.worst_channel},
                      {"peaks", peaks},
                      {"links", links},
                      {"contacts", contacts}};
}

// The streamed writer, started afresh with each run it sees: a run to a tolerance streams every
// rung it tries into the same file, and the rung it keeps is the last one written.
class RestartingWriter final : public StructureObserver {
 public:
  RestartingWriter(RunOutputs& set, StructureObserver& writer) : set_(set), writer_(writer) {}
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override {
    if (started_) set_.restart();
    started_ = true;
    writer_.begin(s, o);
  }
  void observe(const StructureState& st) override { writer_.observe(st); }
  void impact(const Impact& e) override { writer_.impact(e); }
  void end() override { writer_.end(); }

 private:
  RunOutputs& set_;
  StructureObserver& writer_;
  bool started_ = false;
};

}  // namespace

double building_output_interval(const BuildingScene& scene) {
  if (scene.output.every > 0 || scene.accuracy.h_rule == "given") return 0.0;
  const auto& contacts = scene.structure.contacts;
  const bool impacts = std::any_of(contacts.begin(), contacts.end(),
                                   [](const structure::Contact& c) { return c.law.model != structure::ContactModel::none; });
  return impacts ? 1e-3 : 5e-3;
}

std::size_t building_output_every(const BuildingScene& scene, double h) {
  if (scene.output.every > 0) return scene.output.every;
  const double interval = building_output_interval(scene);
  if (!(interval > 0.0 && h > 0.0)) return 1;
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(interval / h * (1.0 + 1e-9))));
}

std::string building_summary_json(const BuildingScene& scene, const Report& r, const ErrorEstimate* estimate,
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
    st["periods_free"] = as_vector(r.coupled->periods_free);
    st["periods_locked"] = as_vector(r.coupled->periods_locked);
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
    if (link.type == structure::LinkType::friction) {
      o["slip_force"] = link.slip_force;
      o["switches"] = lr.switches;
      o["switch_times"] = lr.switch_times;
      o["energy"] = lr.friction_energy;
    }
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
  }
  energy["links"] = r.energy.links;
  energy["contacts"] = r.energy.contacts;
  energy["input"] = r.energy.input;
  energy["residual"] = r.energy.residual;
  j["energy"] = energy;
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
  if (estimate) j["error_estimate"] = building_error_json(scene, *estimate);
  require_finite(j, "", scene.solver.t_end);
  return j.dump(2) + "\n";
}

std::string building_brief_report(const BuildingScene& scene, const Report& r, const ErrorEstimate* estimate,
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
    std::snprintf(line, sizeof line, "building %s: T1 = %.4g s, modal damping %.3g (inherent %.3g, devices %.3g)\n",
                  b == 0 ? "A" : "B", r.modes[b].periods[0], r.modes[b].total_ratio[0], r.modes[b].inherent_ratio[0],
                  r.modes[b].device_ratio[0]);
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
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    std::snprintf(line, sizeof line, "link%zu (%s): force max %.4g N, stroke max %.4g m", l + 1, link_type(s.links[l].type),
                  r.links[l].force_max, r.links[l].stroke_max);
    o << line;
    if (s.links[l].type == structure::LinkType::friction)
      o << ", " << r.links[l].switches << (r.links[l].switches == 1 ? " switch" : " switches");
    o << "\n";
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

std::string building_impacts_csv(const Report& r) {
  std::vector<Impact> all;
  for (const auto& c : r.contacts) all.insert(all.end(), c.impact_list.begin(), c.impact_list.end());
  std::stable_sort(all.begin(), all.end(), [](const Impact& a, const Impact& b) { return a.start < b.start; });
  std::string out = "contact,t_start,duration,force_max,t_force_max,penetration_max,approach_speed,rebound_speed,impulse,complete\n";
  for (const Impact& e : all) {
    const double values[] = {e.start, e.duration, e.force_max, e.t_force_max, e.penetration_max, e.approach_speed, e.rebound_speed,
                             e.impulse};
    out += std::to_string(e.contact + 1);
    for (double v : values) {
      detail::require_finite_output(v, "impacts.csv", "a value", e.start, e.start);
      out += ',' + number_text(v);
    }
    out += e.complete ? ",true\n" : ",false\n";
  }
  return out;
}

RunFiles run_building_to(const BuildingScene& scene, RunOutputs& set, const RunWarning& warn) {
  std::unique_ptr<BuildingCsvWriter> writer;
  std::unique_ptr<RestartingWriter> restarting;
  if (scene.output.timeseries) {
    writer = std::make_unique<BuildingCsvWriter>(set.open("timeseries.csv"), scene, warn);
    restarting = std::make_unique<RestartingWriter>(set, *writer);
  }
  RunFiles files;
  const AccuracyOptions& accuracy = scene.accuracy;
  if (accuracy.tolerance) {
    files.tolerant = run_to_tolerance(scene, *accuracy.tolerance, {restarting.get()});
    files.report = files.tolerant->report;
    files.estimate = files.tolerant->estimate;
  } else {
    files.report = run(scene, {restarting.get()});
    if (accuracy.error_estimate) files.estimate = estimate_error(scene, files.report);
  }
  if (!files.report.spectra.empty()) set.open("spectra.csv") << spectra_csv(files.report.spectra);
  const auto& contacts = scene.structure.contacts;
  if (std::any_of(contacts.begin(), contacts.end(),
                  [](const structure::Contact& c) { return c.law.model != structure::ContactModel::none; }))
    set.open("impacts.csv") << building_impacts_csv(files.report);
  set.open("summary.json") << building_summary_json(scene, files.report, files.estimate ? &*files.estimate : nullptr,
                                                    files.tolerant ? &*files.tolerant : nullptr);
  files.written = set.commit();
  return files;
}

}  // namespace adjoin
