// structure/builder.hpp and structure/modal.hpp in Python: adjoin.StructureBuilder (the typed
// builder: buildings, storey devices, links, contact pairs, each problem an InputError naming
// its field) and adjoin.modes (each building's modes, of a built structure or a scene).
#include <optional>

#include "adjoin/core/errors.hpp"
#include "adjoin/structure/builder.hpp"
#include "adjoin/structure/modal.hpp"
#include "bindings.hpp"
#include "run_facade.hpp"
#include "scene_object.hpp"

namespace adjoin::python {

namespace {

using structure::BuildingBuilder;
using structure::ContactBuilder;
using structure::StructureBuilder;

py::array_t<double> vector_of(const Eigen::VectorXd& v) {
  return to_array(std::vector<double>(v.data(), v.data() + v.size()));
}

// An Eigen matrix as a (rows x cols) numpy array owning a row-major copy.
py::array_t<double> matrix_of(const Eigen::MatrixXd& m) {
  std::vector<double> row_major;
  row_major.reserve(static_cast<std::size_t>(m.size()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) row_major.push_back(m(i, j));
  return to_array(std::move(row_major)).reshape({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
}

py::dict modes_dict(const structure::Building& b) {
  const structure::Modes m = structure::building_modes(b);
  py::dict d;
  d["name"] = b.name;
  d["periods"] = vector_of(m.periods);
  d["omega"] = vector_of(m.omega);
  d["shapes"] = matrix_of(m.shapes);
  d["damping"] = vector_of(m.total_ratio);
  d["inherent_damping"] = vector_of(m.inherent_ratio);
  d["device_damping"] = vector_of(m.device_ratio);
  d["zener_stiffening"] = vector_of(m.zener_stiffening);
  d["participation"] = vector_of(m.participation);
  d["effective_mass"] = vector_of(m.effective_mass);
  d["p_delta"] = m.p_delta;  // the periods are K0 + K_G's (inf: a mode P-Delta made unstable)
  if (b.base) {  // (SPEC §7: an isolated base; NaN for a flat slider, which has no period)
    const structure::IsolatedPeriod p = structure::isolated_period(b);
    d["isolated_period"] = p.rigid;
    d["isolated_period_flexible"] = p.flexible;
  }
  return d;
}

// Each building's modes and, with two buildings, the coupled periods (structure/modal.hpp).
py::dict structure_modes(const structure::Structure& s) {
  py::dict out;
  out["A"] = modes_dict(s.a);
  if (s.b) {
    out["B"] = modes_dict(*s.b);
    const structure::CoupledModes c = structure::coupled_modes(s);
    py::dict coupled;
    coupled["periods_free"] = vector_of(c.periods_free);
    coupled["periods_locked"] = vector_of(c.periods_locked);
    out["coupled"] = coupled;
  }
  return out;
}

py::dict scene_modes(const SceneObject& scene) {
  const structure::Structure* s = structure_of(scene.loaded);
  if (!s)
    throw InputError("adjoin.modes: '" + scene.loaded.name() + "' is a two-block scene; modes are computed for "
                     "building scenes");
  return structure_modes(*s);
}

char building_name(const std::string& name) {
  if (name != "A" && name != "B") throw InputError("building '" + name + "': expected 'A' or 'B'", "building");
  return name[0];
}

// A yielding law's yield force: one of the three ways (as a scene's hysteresis table says it).
void check_one_yield(const BuildingBuilder& b, const std::optional<double>& yield_force,
                     const std::optional<std::vector<double>>& yield_forces, const std::optional<double>& yield_drift_ratio) {
  if (yield_force.has_value() + yield_forces.has_value() + yield_drift_ratio.has_value() != 1)
    throw InputError(b.path() + ".hysteresis: give one of yield_force, yield_forces or yield_drift_ratio", b.path() + ".hysteresis");
}

structure::Zener zener_of(double stiffness, double order, double tau_x, double tau_f) {
  return structure::Zener{stiffness, order, tau_x, tau_f};
}

}  // namespace

void bind_structure(py::module_& m) {
  py::class_<structure::Structure>(m, "Structure", "A structure built in code (StructureBuilder.build()).")
      .def_property_readonly("dofs", &structure::Structure::dofs, "The number of floors of both buildings.")
      .def("modes", &structure_modes, "Each building's modes (see adjoin.modes): periods [s], shapes, damping ratios.");

  py::class_<BuildingBuilder>(m, "BuildingBuilder", "One building of a StructureBuilder (SI units).")
      .def("mass", &BuildingBuilder::mass, py::arg("kg"), py::return_value_policy::reference_internal, "Every floor's mass [kg].")
      .def("masses", &BuildingBuilder::masses, py::arg("kg"), py::return_value_policy::reference_internal, "Each floor's mass [kg], floor 1 first.")
      .def("stiffness", &BuildingBuilder::stiffness, py::arg("n_per_m"), py::return_value_policy::reference_internal, "Every storey's spring stiffness [N/m].")
      .def("stiffnesses", &BuildingBuilder::stiffnesses, py::arg("n_per_m"), py::return_value_policy::reference_internal, "Each storey's spring stiffness [N/m], storey 1 first.")
      .def("period", &BuildingBuilder::period, py::arg("seconds"), py::return_value_policy::reference_internal, "The fundamental period [s]: a uniform storey stiffness is found for it.")
      .def("no_damping", &BuildingBuilder::no_damping, py::return_value_policy::reference_internal, "No inherent damping.")
      .def("modal_damping", &BuildingBuilder::modal_damping, py::arg("ratio"), py::return_value_policy::reference_internal, "The same damping ratio [-] (0.05 is 5 %) in every mode.")
      .def("rayleigh_damping", &BuildingBuilder::rayleigh_damping, py::arg("ratio"), py::arg("mode_i") = 1,
           py::arg("mode_j") = 2, py::return_value_policy::reference_internal, "Rayleigh damping with the ratio [-] in modes mode_i and mode_j.")
      .def(
          "device",
          [](BuildingBuilder& b, const std::string& type, const std::vector<int>& storeys, const py::kwargs& keys) -> BuildingBuilder& {
            structure::DeviceType kind;
            if (!parse_enum(type, &kind)) {
              std::string list;
              for (const auto& name : names<structure::DeviceType>()) list += (list.empty() ? "" : ", ") + name;
              throw FieldError(b.path() + ".device.type", "expected one of " + list + ", not \"" + type + "\"");
            }
            std::map<std::string, double> values;
            for (const auto& [key, value] : keys) values[py::cast<std::string>(key)] = py::cast<double>(value);
            return b.device(kind, storeys, values);
          },
          py::arg("type"), py::arg("storeys"), py::return_value_policy::reference_internal,
          "A device of any kind (\"spring\", \"dashpot\", \"kelvin\", ...) in each listed storey (1-based), by its scene "
          "keys as keywords: device(\"kelvin\", [1], stiffness=2e6, c=1e5). The kinds and their keys: docs/reference/scene-keys.md.")
      .def("spring", &BuildingBuilder::spring, py::arg("storeys"), py::arg("k"), py::return_value_policy::reference_internal, "A spring device of stiffness k [N/m] in each listed storey (1-based).")
      .def("dashpot", &BuildingBuilder::dashpot, py::arg("storeys"), py::arg("c"), py::arg("alpha") = 1.0, py::return_value_policy::reference_internal,
           "A dashpot in each listed storey (1-based): F = c |v|^alpha sign v, c [N (s/m)^alpha], alpha in [0.05, 1] (1: linear).")
      .def(
          "zener",
          [](BuildingBuilder& b, const std::vector<int>& storeys, double stiffness, double order, double tau_x,
             double tau_f) -> BuildingBuilder& { return b.zener(storeys, zener_of(stiffness, order, tau_x, tau_f)); },
          py::arg("storeys"), py::kw_only(), py::arg("stiffness"), py::arg("order"), py::arg("tau_x"), py::arg("tau_f"),
          py::return_value_policy::reference_internal, "A fractional Zener device in each listed storey: relaxed stiffness [N/m], order alpha in (0, 1), tau_x and tau_f [s^order].")
      .def("height", &BuildingBuilder::height, py::arg("m"), py::return_value_policy::reference_internal, "Every storey's height [m]: drift ratios, P-Delta and the collapse check need heights.")
      .def("heights", &BuildingBuilder::heights, py::arg("m"), py::return_value_policy::reference_internal, "Each storey's height [m], storey 1 first.")
      .def("p_delta", &BuildingBuilder::p_delta, py::arg("on"), py::return_value_policy::reference_internal, "P-Delta: each storey's geometric stiffness -P_i/h_i (needs heights).")
      .def("collapse_drift_ratio", &BuildingBuilder::collapse_drift_ratio, py::arg("ratio"), py::return_value_policy::reference_internal, "The |drift| / height past which a run stops with a collapse (default 0.10; needs heights).")
      .def(
          "bilinear",
          [](BuildingBuilder& b, std::optional<double> yield_force, std::optional<std::vector<double>> yield_forces,
             std::optional<double> yield_drift_ratio, double hardening) -> BuildingBuilder& {
            check_one_yield(b, yield_force, yield_forces, yield_drift_ratio);
            if (yield_force) return b.bilinear(*yield_force, hardening);
            if (yield_forces) return b.bilinear_per_storey(*yield_forces, hardening);
            return b.bilinear_drift_ratio(*yield_drift_ratio, hardening);
          },
          py::kw_only(), py::arg("yield_force") = py::none(), py::arg("yield_forces") = py::none(),
          py::arg("yield_drift_ratio") = py::none(), py::arg("hardening") = 0.0, py::return_value_policy::reference_internal,
          "Bilinear storeys (kinematic hardening b = hardening in [0, 1)), yielding at yield_force [N] (every storey), "
          "yield_forces [N] (storey 1 first) or yield_drift_ratio [-] (F_y = k x ratio x h: needs heights); one of the three.")
      .def(
          "bouc_wen",
          [](BuildingBuilder& b, std::optional<double> yield_force, std::optional<std::vector<double>> yield_forces,
             std::optional<double> yield_drift_ratio, double hardening, double n, double beta,
             double gamma) -> BuildingBuilder& {
            check_one_yield(b, yield_force, yield_forces, yield_drift_ratio);
            const structure::BoucWenShape shape{n, beta, gamma};
            if (yield_force) return b.bouc_wen(*yield_force, hardening, shape);
            if (yield_forces) return b.bouc_wen_per_storey(*yield_forces, hardening, shape);
            return b.bouc_wen_drift_ratio(*yield_drift_ratio, hardening, shape);
          },
          py::kw_only(), py::arg("yield_force") = py::none(), py::arg("yield_forces") = py::none(),
          py::arg("yield_drift_ratio") = py::none(), py::arg("hardening") = 0.0, py::arg("n") = 2.0, py::arg("beta") = 0.5,
          py::arg("gamma") = 0.5, py::return_value_policy::reference_internal,
          "Bouc-Wen storeys (force = b k d + (1 - b) k z, b = hardening in [0, 1); shape n in [1, 20], beta + gamma > 0 [-]), "
          "yielding at yield_force [N] (every storey), yield_forces [N] (storey 1 first) or yield_drift_ratio [-] "
          "(F_y = k x ratio x h: needs heights); one of the three.")
      .def("bilinear_device", &BuildingBuilder::bilinear_device, py::arg("storeys"), py::kw_only(), py::arg("stiffness"),
           py::arg("yield_force"), py::arg("hardening") = 0.0, py::return_value_policy::reference_internal,
           "A bilinear device (a metallic damper, a buckling-restrained brace) in each listed storey: initial stiffness [N/m], "
           "yield_force [N], hardening b in [0, 1).")
      .def(
          "bouc_wen_device",
          [](BuildingBuilder& b, const std::vector<int>& storeys, double stiffness, double yield_force, double hardening,
             double n, double beta, double gamma) -> BuildingBuilder& {
            return b.bouc_wen_device(storeys, stiffness, yield_force, hardening, {n, beta, gamma});
          },
          py::arg("storeys"), py::kw_only(), py::arg("stiffness"), py::arg("yield_force"), py::arg("hardening") = 0.0,
          py::arg("n") = 2.0, py::arg("beta") = 0.5, py::arg("gamma") = 0.5, py::return_value_policy::reference_internal,
          "A Bouc-Wen device in each listed storey: initial stiffness [N/m], yield_force [N], hardening b in [0, 1), "
          "shape n, beta, gamma [-].")
      .def("flat_slider", &BuildingBuilder::flat_slider, py::kw_only(), py::arg("mass"), py::arg("friction"),
           py::return_value_policy::reference_internal,
           "An isolated base under floor 1: a base floor of mass [kg] sliding on the ground with friction mu in (0, 1) [-] "
           "of the weight of the base and every floor above.")
      .def("friction_pendulum", &BuildingBuilder::friction_pendulum, py::kw_only(), py::arg("mass"), py::arg("friction"),
           py::arg("radius"), py::return_value_policy::reference_internal,
           "An isolated base on a friction pendulum: base mass [kg], friction mu in (0, 1), radius of curvature R [m] "
           "(restoring stiffness W / R, isolated period 2 pi sqrt(R / g)).")
      .def_property_readonly("path", &BuildingBuilder::path, "The building's field path, \"building.A\".")
      .def_property_readonly("storeys", &BuildingBuilder::storeys, "The number of storeys.");

  py::class_<ContactBuilder>(m, "ContactBuilder", "A contact pair of a StructureBuilder.")
      .def(
          "model",
          [](ContactBuilder& c, const std::string& word) -> ContactBuilder& {
            structure::ContactModel model{};
            if (!parse_enum(word, &model))
              throw InputError("model = '" + word + "': expected none, linear, hertz, hertzdamp, jankowski or impact",
                               "model");
            return c.model(model);
          },
          py::arg("model"), py::return_value_policy::reference_internal, "The contact law: none, linear, hertz, hertzdamp, jankowski or impact.")
      .def("stiffness", &ContactBuilder::stiffness, py::arg("k"), py::return_value_policy::reference_internal, "The contact stiffness [N/m, linear; N/m^1.5, Hertz].")
      .def("restitution", &ContactBuilder::restitution, py::arg("e"), py::return_value_policy::reference_internal, "The coefficient of restitution (0 < e <= 1), for the damping.")
      .def("damping", &ContactBuilder::damping, py::arg("value"), py::return_value_policy::reference_internal, "The damping parameter directly, instead of restitution.")
      .def("tension_cut", &ContactBuilder::tension_cut, py::arg("cut"), py::return_value_policy::reference_internal, "Linear law only: no tensile force.");

  py::class_<StructureBuilder>(m, "StructureBuilder",
                              "The typed structure builder (structure/builder.hpp): two buildings, storey devices, links and "
                              "contact pairs, in SI units; each setter returns its builder, so calls chain.")
      .def(py::init<>())
      .def(
          "building",
          [](StructureBuilder& s, const std::string& name, int storeys) -> BuildingBuilder& {
            return s.building(building_name(name), storeys);
          },
          py::arg("name"), py::arg("storeys"), py::return_value_policy::reference_internal, "Building 'A' (left) or 'B' (right) with `storeys` floors, made on the first call.")
      .def("friction_link", &StructureBuilder::friction_link, py::arg("floor_a"), py::arg("floor_b"),
           py::arg("slip_force"), py::return_value_policy::reference_internal, "A friction link between floor_a of A and floor_b of B, slipping at slip_force [N].")
      .def(
          "friction_link_ratio",
          [](StructureBuilder& s, int a, int b, double ratio, const std::string& of) -> StructureBuilder& {
            return s.friction_link_ratio(a, b, ratio, building_name(of));
          },
          py::arg("floor_a"), py::arg("floor_b"), py::arg("slip_ratio"), py::arg("of") = "B",
          py::return_value_policy::reference_internal, "A friction link slipping at slip_ratio [-] of building `of`'s weight.")
      .def(
          "link",
          [](StructureBuilder& s, const std::string& type, int floor_a, int floor_b, const py::kwargs& keys) -> StructureBuilder& {
            structure::LinkType kind;
            if (!parse_enum(type, &kind)) {
              std::string list;
              for (const auto& name : names<structure::LinkType>()) list += (list.empty() ? "" : ", ") + name;
              throw FieldError("link.type", "expected one of " + list + ", not \"" + type + "\"");
            }
            std::map<std::string, double> values;
            for (const auto& [key, value] : keys) values[py::cast<std::string>(key)] = py::cast<double>(value);
            return s.link(kind, floor_a, floor_b, values);
          },
          py::arg("type"), py::arg("floor_a"), py::arg("floor_b"), py::return_value_policy::reference_internal,
          "A link of any kind but friction (\"dashpot\", \"spring\", \"zener\", ...) between floor_a of A and floor_b of B, "
          "by its scene keys as keywords: link(\"dashpot\", 3, 3, c=2e5, alpha=0.5). A friction link: friction_link.")
      .def("dashpot_link", &StructureBuilder::dashpot_link, py::arg("floor_a"), py::arg("floor_b"), py::arg("c"), py::arg("alpha") = 1.0,
           py::return_value_policy::reference_internal,
           "A viscous link between floor_a of A and floor_b of B: F = c |v|^alpha sign v, c [N (s/m)^alpha], alpha in [0.05, 1].")
      .def("spring_link", &StructureBuilder::spring_link, py::arg("floor_a"), py::arg("floor_b"), py::arg("k"),
           py::return_value_policy::reference_internal, "A spring link of k [N/m] between floor_a of A and floor_b of B.")
      .def(
          "zener_link",
          [](StructureBuilder& s, int a, int b, double stiffness, double order, double tau_x, double tau_f)
              -> StructureBuilder& { return s.zener_link(a, b, zener_of(stiffness, order, tau_x, tau_f)); },
          py::arg("floor_a"), py::arg("floor_b"), py::kw_only(), py::arg("stiffness"), py::arg("order"),
          py::arg("tau_x"), py::arg("tau_f"), py::return_value_policy::reference_internal, "A fractional Zener link: relaxed stiffness [N/m], order in (0, 1), tau_x and tau_f [s^order].")
      .def("contact", &StructureBuilder::contact, py::arg("floor_a"), py::arg("floor_b"), py::arg("gap"),
           py::return_value_policy::reference_internal, "A pounding pair at floor_a of A and floor_b of B with a clear gap [m] >= 0; set its law on the ContactBuilder returned (none: the floors pass through).")
      .def("build", &StructureBuilder::build, "The Structure (InputError naming the field, e.g. building.A.masses[3], if a value is wrong).");

  m.def("modes", &scene_modes, py::arg("scene"));
  m.def("modes", &structure_modes, py::arg("structure"));
}

}  // namespace adjoin::python
