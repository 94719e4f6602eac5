#include "adjoin/io/building_files.hpp"
#include "adjoin/io/summary.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../detail/finite_output.hpp"
#include "adjoin/errors.hpp"
#include "adjoin/io/atomic_file.hpp"

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

// Streams every `every`-th grid point of a building run.
class BuildingCsvWriter final : public StructureObserver {
 public:
  BuildingCsvWriter(std::ostream& out, std::size_t every) : out_(out), every_(every == 0 ? 1 : every) {}
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override {
    s_ = &s;
    steps_ = o.steps();
    count_ = 0;
    out_ << "t,ag";
    auto floors = [&](const structure::Building& b, const char* what, const char* suffix) {
      for (int i = 1; i <= b.floors(); ++i) out_ << "," << b.name << "." << what << i << suffix;
    };
    floors(s.a, "x", "");
    if (s.b) floors(*s.b, "x", "");
    floors(s.a, "a", "_abs");
    if (s.b) floors(*s.b, "a", "_abs");
    for (std::size_t l = 1; l <= s.links.size(); ++l) out_ << ",link" << l << ".force,link" << l << ".stroke";
    for (std::size_t k = 1; k <= s.contacts.size(); ++k) out_ << ",contact" << k << ".gap";
    out_ << "\n";
  }
  void observe(const StructureState& st) override {
    const std::size_t index = count_++;
    if (index % every_ != 0 && index != steps_) return;
    values_.clear();
    values_.push_back(st.t);
    values_.push_back(st.ag);
    for (int i = 0; i < st.x.size(); ++i) values_.push_back(st.x[i]);
    for (int i = 0; i < st.a_abs.size(); ++i) values_.push_back(st.a_abs[i]);
    for (int l = 0; l < st.link_force.size(); ++l) {
      values_.push_back(st.link_force[l]);
      values_.push_back(st.link_stroke[l]);
    }
    for (const auto& c : s_->contacts)
      values_.push_back(c.gap - (st.x[s_->dof('A', c.floor_a)] - st.x[s_->dof('B', c.floor_b)]));
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
  std::ostream& out_;
  std::size_t every_, steps_ = 0, count_ = 0;
  const structure::Structure* s_ = nullptr;
  std::vector<double> values_;
  std::string buffer_;
};

}  // namespace

std::string building_summary_json(const BuildingScene& scene, const BuildingReport& r) {
  const structure::Structure& s = scene.structure;
  ordered_json j;
  j["scene"] = scene.name;
  j["units"] = "SI";
  j["solver"] = {{"scheme", "implicit"},
                 {"history", to_string(scene.solver.history)},
                 {"h", scene.solver.h},
                 {"steps", r.solver.steps},
                 {"wall_seconds", r.solver.wall_seconds},
                 {"t_end", scene.solver.t_end},
                 {"h_rule", scene.h_rule},
                 {"t_end_rule", scene.t_end_rule}};
  j["ground"] = scene.base.ground->describe();
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
                        {"min_gap", cr.min_gap},
                        {"t_min_gap", cr.t_min_gap},
                        {"contact", cr.contact},
                        {"t_first_contact", cr.contact ? ordered_json(cr.t_first_contact) : ordered_json(nullptr)}});
  }
  j["contacts"] = contacts;
  ordered_json energy;
  for (std::size_t b = 0; b < r.energy.buildings.size(); ++b) {
    const auto& part = r.energy.buildings[b];
    energy[b == 0 ? "A" : "B"] = {{"input", part.input}, {"kinetic", part.kinetic}, {"inherent_damping", part.inherent},
                                  {"storeys", part.storeys}};
  }
  energy["links"] = r.energy.links;
  energy["input"] = r.energy.input;
  energy["residual"] = r.energy.residual;
  j["energy"] = energy;
  require_finite(j, "", scene.solver.t_end);
  return j.dump(2) + "\n";
}

std::string building_brief_report(const BuildingScene& scene, const BuildingReport& r) {
  std::ostringstream o;
  char line[256];
  const structure::Structure& s = scene.structure;
  std::snprintf(line, sizeof line, "%s: %d + %d floors, h = %.4g s (%s), t_end = %.4g s (%s), %zu steps in %.3g s\n",
                scene.name.c_str(), s.a.floors(), s.b ? s.b->floors() : 0, scene.solver.h, scene.h_rule.c_str(),
                scene.solver.t_end, scene.t_end_rule.c_str(), r.solver.steps, r.solver.wall_seconds);
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
    if (s.links[l].type == structure::LinkType::friction) o << ", " << r.links[l].switches << " switches";
    o << "\n";
  }
  for (std::size_t k = 0; k < s.contacts.size(); ++k) {
    std::snprintf(line, sizeof line, "contact%zu: min gap %.4g m at t = %.4g s%s\n", k + 1, r.contacts[k].min_gap, r.contacts[k].t_min_gap,
                  r.contacts[k].contact ? " (the floors touch: pounding is not modelled yet)" : "");
    o << line;
  }
  return o.str();
}

BuildingFiles run_building_to_folder(const BuildingScene& scene, const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError(dir.string() + ": cannot create the output folder: " + error.message());
  FileSet set(dir, {"summary.json", "timeseries.csv", "energy.csv", "spectra.csv"});
  std::unique_ptr<BuildingCsvWriter> writer;
  if (scene.base.output.timeseries) writer = std::make_unique<BuildingCsvWriter>(set.open("timeseries.csv"), scene.base.output.every);
  BuildingFiles files;
  files.report = run_building(scene, writer.get());
  if (!files.report.spectra.empty()) set.open("spectra.csv") << spectra_csv(files.report.spectra);
  set.open("summary.json") << building_summary_json(scene, files.report);
  files.written = set.commit();
  return files;
}

}  // namespace adjoin
