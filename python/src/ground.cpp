// ground/record.hpp and ground/record_file.hpp in Python: adjoin.read_record and adjoin.Record.
// A Record keeps its samples in m/s^2 as the library does; .accel gives them in g.
#include <optional>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record.hpp"
#include "adjoin/ground/record_file.hpp"
#include "bindings.hpp"

namespace adjoin::python {

namespace {

AccelUnit unit_named(const std::string& name, const char* argument) {
  AccelUnit unit{};
  if (!parse_accel_unit(name, &unit))
    throw InputError(std::string(argument) + " = '" + name + "': expected g, m/s2, cm/s2 (or gal) or mm/s2", argument);
  return unit;
}

// A read-only numpy view of a vector held by `owner` (the array keeps the owner alive).
py::array_t<double> view_of(const std::vector<double>& values, py::handle owner) {
  py::array_t<double> a(static_cast<py::ssize_t>(values.size()), values.data(), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

Record record_from_samples(const py::array_t<double, py::array::c_style | py::array::forcecast>& accel, double dt,
                           const std::string& units, const std::string& source) {
  if (accel.ndim() != 1) throw InputError("accel: expected a one-dimensional array of samples", "accel");
  if (!(dt > 0.0)) throw InputError("dt = " + std::to_string(dt) + ": expected a step > 0 [s]", "dt");
  const double factor = to_m_s2(unit_named(units, "units"));
  Record r;
  r.source = source;
  r.dt = dt;
  r.accel.resize(static_cast<std::size_t>(accel.size()));
  for (py::ssize_t i = 0; i < accel.size(); ++i) {
    const double v = accel.data()[i];
    if (!std::isfinite(v)) throw InputError("accel[" + std::to_string(i) + "]: expected a finite number", "accel");
    r.accel[static_cast<std::size_t>(i)] = v * factor;
  }
  return r;
}

Record read_record_py(const std::string& path, const std::string& format, const std::optional<std::string>& units,
                      std::optional<double> dt, const std::string& time_column, const std::string& accel_column,
                      const std::string& delimiter, int channel) {
  RecordFormat f;
  if (!parse_record_kind(format, &f.kind))
    throw InputError("format = '" + format + "': expected one of " + record_kind_names(), "format");
  if (units) f.units = unit_named(*units, "units");
  f.dt = dt;
  f.time_column = time_column;
  f.accel_column = accel_column;
  if (delimiter.size() > 1) throw InputError("delimiter = '" + delimiter + "': expected one character", "delimiter");
  f.delimiter = delimiter.empty() ? '\0' : delimiter[0];
  f.channel = channel;
  py::gil_scoped_release unlocked;
  return read_record(path, f);
}

}  // namespace

void bind_ground(py::module_& m) {
  py::class_<Record>(m, "Record",
                     "An accelerogram sampled at a uniform step (ground/record.hpp).\n\n"
                     "Attributes:\n"
                     "    dt (float): the step [s].\n"
                     "    accel (numpy.ndarray): the accelerations [g], accel[i] at t = i dt.\n"
                     "    accel_m_s2 (numpy.ndarray): the same in m/s^2, as the library holds them (read-only view).\n"
                     "    units (str): 'g', the unit of .accel.\n"
                     "    header (str): the file's header text (event, station) when known.\n"
                     "    source (str): the file it was read from.\n"
                     "    duration (float): dt (n - 1) [s].")
      .def(py::init(&record_from_samples), py::arg("accel"), py::arg("dt"), py::arg("units") = "g",
           py::arg("source") = "array",
           "Record(accel, dt, units='g', source='array'): a record from samples (accel in `units`: "
           "g, m/s2, cm/s2 or mm/s2; dt in s).")
      .def_readonly("dt", &Record::dt, "The step [s].")
      .def_property_readonly(
          "accel",
          [](const Record& r) {
            std::vector<double> g(r.accel.size());
            const double factor = to_m_s2(AccelUnit::g);
            for (std::size_t i = 0; i < g.size(); ++i) g[i] = r.accel[i] / factor;
            return to_array(std::move(g));
          },
          "The accelerations [g] (a new array on each access).")
      .def_property_readonly(
          "accel_m_s2", [](py::object self) { return view_of(self.cast<const Record&>().accel, self); },
          "The accelerations [m/s^2] as the library holds them (a read-only view, no copy).")
      .def_property_readonly("units", [](const Record&) { return std::string("g"); }, "The unit of .accel: 'g'.")
      .def_readonly("header", &Record::description, "The file's header text (event, station) when known.")
      .def_readonly("source", &Record::source, "The file it came from.")
      .def_property_readonly("duration", &Record::duration, "dt (n - 1) [s].")
      .def("__len__", [](const Record& r) { return r.accel.size(); })
      .def("__repr__", [](const Record& r) {
        return "<adjoin.Record " + r.source + ": " + std::to_string(r.accel.size()) + " samples, dt = " +
               std::to_string(r.dt) + " s>";
      });

  m.def("read_record", &read_record_py, py::arg("path"), py::kw_only(), py::arg("format") = "auto",
        py::arg("units") = py::none(), py::arg("dt") = py::none(), py::arg("time_column") = "",
        py::arg("accel_column") = "", py::arg("delimiter") = "", py::arg("channel") = 0,
        "Reads an accelerogram file (ground/record_file.hpp) as `adjoin record` does.");
}

}  // namespace adjoin::python
