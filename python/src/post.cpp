// post/spectrum.hpp, post/rotd.hpp and post/inelastic.hpp in Python: adjoin.spectrum,
// adjoin.rotd, adjoin.ductility_spectrum. Each takes an adjoin.Record or an array (with dt and
// its unit) and gives a dict of numpy arrays, one entry per row of the CLI's CSV (damping-major,
// as `adjoin spectrum` writes them), the arrays owning their memory.
#include <cmath>
#include <optional>
#include <span>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record.hpp"
#include "adjoin/post/inelastic.hpp"
#include "adjoin/post/rotd.hpp"
#include "adjoin/post/spectrum.hpp"
#include "bindings.hpp"

namespace adjoin::python {

namespace {

// Samples in m/s^2: a Record's own (no copy, no rounding: the CLI's numbers), or an array
// converted from its unit.
struct Samples {
  double dt = 0.0;
  std::vector<double> converted;
  const Record* record = nullptr;
  std::span<const double> values() const {
    return record ? std::span<const double>(record->accel) : std::span<const double>(converted);
  }
};

Samples samples_of(const py::object& accel, std::optional<double> dt, const std::string& units, const char* name) {
  Samples s;
  if (py::isinstance<Record>(accel)) {
    s.record = &accel.cast<const Record&>();
    s.dt = s.record->dt;
    if (dt && std::abs(*dt - s.dt) > 1e-12 * s.dt)
      throw InputError(std::string("dt = ") + std::to_string(*dt) + ": the record's own step is " +
                       std::to_string(s.dt) + " s (leave dt out for a Record)", "dt");
    return s;
  }
  if (!dt) throw InputError(std::string(name) + ": an array needs dt, its step [s]", "dt");
  AccelUnit unit{};
  if (!parse_accel_unit(units, &unit))
    throw InputError("units = '" + units + "': expected g, m/s2, cm/s2 (or gal) or mm/s2", "units");
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(accel);
  if (!array || array.ndim() != 1)
    throw InputError(std::string(name) + ": expected an adjoin.Record or a one-dimensional array of samples", name);
  s.dt = *dt;
  const double factor = to_m_s2(unit);
  s.converted.assign(array.data(), array.data() + array.size());
  for (double& v : s.converted) v *= factor;
  return s;
}

std::vector<double> list_of(const py::object& value) {
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) return {value.cast<double>()};
  return value.cast<std::vector<double>>();
}

bool refine_from(const std::string& peaks) {
  if (peaks == "exact") return true;
  if (peaks == "samples") return false;
  throw InputError("peaks = '" + peaks + "': expected 'exact' (peaks located between sub-steps) or 'samples'", "peaks");
}

// Collects one numpy array per named column, filled row by row.
class Columns {
 public:
  explicit Columns(std::vector<std::string> names) : names_(std::move(names)), values_(names_.size()) {}
  void row(std::initializer_list<double> cells) {
    std::size_t k = 0;
    for (double c : cells) values_[k++].push_back(c);
  }
  std::vector<double>& column(std::size_t k) { return values_[k]; }
  py::dict take() {
    py::dict out;
    for (std::size_t k = 0; k < names_.size(); ++k) out[py::str(names_[k])] = to_array(std::move(values_[k]));
    return out;
  }

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<double>> values_;
};

py::dict spectrum_py(const py::object& accel, std::optional<double> dt, std::optional<std::vector<double>> periods,
                     const py::object& damping, const std::string& units, const std::string& peaks,
                     bool free_vibration, unsigned threads) {
  const Samples s = samples_of(accel, dt, units, "accel");
  SpectrumOptions o;
  if (periods) o.periods = *periods;
  o.dampings = list_of(damping);
  o.refine_peaks = refine_from(peaks);
  o.free_vibration = free_vibration;
  o.threads = threads;
  ResponseSpectrum r;
  {
    py::gil_scoped_release unlocked;
    r = response_spectrum(s.dt, s.values(), o);
  }
  Columns c({"period", "damping", "sd", "sv", "sa", "psv", "psa"});
  for (const SpectralValues& v : r.values) c.row({v.period, v.damping, v.sd, v.sv, v.sa, v.psv, v.psa});
  return c.take();
}

std::string percentile_name(double p) {
  char name[48];
  std::snprintf(name, sizeof name, "rotd%02g", p);
  return name;
}

py::dict rotd_py(const py::object& h1, const py::object& h2, std::optional<double> dt,
                 std::optional<std::vector<double>> periods, const py::object& damping, const std::vector<double>& percentiles,
                 double angle_step, const std::string& units, const std::string& peaks, unsigned threads) {
  const Samples a = samples_of(h1, dt, units, "h1");
  const Samples b = samples_of(h2, dt, units, "h2");
  if (std::abs(a.dt - b.dt) > 1e-9 * a.dt)
    throw InputError("h2: its step " + std::to_string(b.dt) + " s differs from h1's " + std::to_string(a.dt) + " s", "h2");
  RotDOptions o;
  if (periods) o.periods = *periods;
  o.dampings = list_of(damping);
  for (double p : percentiles)
    if (p != 0.0 && p != 50.0 && p != 100.0) o.percentiles.push_back(p);
  o.angle_step = angle_step;
  o.refine_peaks = refine_from(peaks);
  o.threads = threads;
  RotDSpectrum r;
  {
    py::gil_scoped_release unlocked;
    r = rotd_spectrum(a.dt, a.values(), b.values(), o);
  }
  std::vector<std::string> names{"period", "damping", "rotd00", "rotd50", "rotd100", "angle00", "angle100", "gmroti50",
                                 "psa_h1", "psa_h2"};
  for (double p : o.percentiles) names.push_back(percentile_name(p));
  Columns c(names);
  for (const RotDValues& v : r.values) {
    c.row({v.period, v.damping, v.rotd00, v.rotd50, v.rotd100, v.angle00, v.angle100, v.gmroti50, v.psa1, v.psa2});
    for (std::size_t k = 0; k < v.extra.size(); ++k) c.column(10 + k).push_back(v.extra[k]);
  }
  py::dict out = c.take();
  out["gmroti50_angle"] = to_array(std::move(r.gmroti50_angle));
  return out;
}

py::dict ductility_py(const py::object& accel, std::optional<double> dt, std::optional<std::vector<double>> periods,
                      const py::object& ductility, const py::object& damping, const std::string& hysteresis,
                      double hardening, const std::string& units, double tolerance, unsigned threads) {
  const Samples s = samples_of(accel, dt, units, "accel");
  InelasticOptions o;
  if (periods) o.periods = *periods;
  o.dampings = list_of(damping);
  o.ductilities = list_of(ductility);
  if (hysteresis == "epp") {
    o.hysteresis = Hysteresis::elastic_perfectly_plastic;
  } else if (hysteresis == "bilinear") {
    o.hysteresis = Hysteresis::bilinear;
  } else {
    throw InputError("hysteresis = '" + hysteresis + "': expected 'epp' or 'bilinear'", "hysteresis");
  }
  o.hardening = hardening;
  o.tolerance = tolerance;
  o.threads = threads;
  InelasticSpectrum r;
  {
    py::gil_scoped_release unlocked;
    r = constant_ductility_spectrum(s.dt, s.values(), o);
  }
  Columns c({"period", "damping", "ductility", "cy", "uy", "R", "ductility_reached", "peak_displacement"});
  for (const InelasticValues& v : r.values)
    c.row({v.period, v.damping, v.ductility, v.cy, v.uy, v.R, v.ductility_reached, v.peak_displacement});
  return c.take();
}

}  // namespace

void bind_post(py::module_& m) {
  m.def("spectrum", &spectrum_py, py::arg("accel"), py::arg("dt") = py::none(), py::kw_only(),
        py::arg("periods") = py::none(), py::arg("damping") = 0.05, py::arg("units") = "g", py::arg("peaks") = "exact",
        py::arg("free_vibration") = false, py::arg("threads") = 0u);
  m.def("rotd", &rotd_py, py::arg("h1"), py::arg("h2"), py::arg("dt") = py::none(), py::kw_only(),
        py::arg("periods") = py::none(), py::arg("damping") = 0.05,
        py::arg("percentiles") = std::vector<double>{50.0, 100.0}, py::arg("angle_step") = 1.0, py::arg("units") = "g",
        py::arg("peaks") = "exact", py::arg("threads") = 0u);
  m.def("ductility_spectrum", &ductility_py, py::arg("accel"), py::arg("dt") = py::none(), py::kw_only(),
        py::arg("periods") = py::none(), py::arg("ductility") = std::vector<double>{1.0, 2.0, 4.0, 6.0},
        py::arg("damping") = 0.05, py::arg("hysteresis") = "epp", py::arg("hardening") = 0.0, py::arg("units") = "g",
        py::arg("tolerance") = 1e-4, py::arg("threads") = 0u);
  m.def("default_periods", &default_spectrum_periods, "The default periods [s]: 100 log-spaced from 0.01 to 10 s.");
}

}  // namespace adjoin::python
