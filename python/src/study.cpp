// study/run.hpp in Python (through run_facade.hpp): adjoin.run and
// adjoin.run_many. A run gives back what `adjoin run` writes, in memory: the summary.json text
// (the package parses it with json), each CSV's columns as numpy arrays (numbers) or lists
// (words: the phase, an impact's `complete`), and the terminal report.
#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <exception>
#include <stdexcept>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "bindings.hpp"
#include "run_facade.hpp"
#include "scene_object.hpp"

namespace adjoin::python {

namespace {

std::vector<std::string_view> cells_of(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

bool parse_double(std::string_view cell, double* value) {
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), *value);
  return ec == std::errc() && end == cell.data() + cell.size();
}

// A CSV that adjoin wrote (a header, then rows of the same width) as {column: values}: a column
// whose first value is a number is a numpy array of float64 (the values read back exactly:
// the writers print the shortest text that reads back to the same double), any other a list
// of str. The CSV text is "" when `adjoin run` would not write the file: an empty dict.
py::dict columns_of(const std::string& csv, const char* what) {
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < csv.size();) {
    const std::size_t end = std::min(csv.find('\n', start), csv.size());
    if (end > start) lines.emplace_back(csv.data() + start, end - start);
    start = end + 1;
  }
  py::dict out;
  if (lines.empty()) return out;
  const std::vector<std::string_view> names = cells_of(lines[0]);
  std::vector<std::vector<double>> numbers(names.size());
  std::vector<std::vector<std::string>> words(names.size());
  std::vector<bool> numeric(names.size(), true);
  if (lines.size() > 1) {
    const auto first = cells_of(lines[1]);
    double ignored = 0.0;
    for (std::size_t k = 0; k < names.size() && k < first.size(); ++k) numeric[k] = parse_double(first[k], &ignored);
  }
  for (std::size_t k = 0; k < names.size(); ++k) numbers[k].reserve(lines.size() - 1);
  for (std::size_t r = 1; r < lines.size(); ++r) {
    const auto cells = cells_of(lines[r]);
    if (cells.size() != names.size())
      throw std::runtime_error(std::string(what) + ": row " + std::to_string(r) + " has " + std::to_string(cells.size()) +
                               " cells, the header " + std::to_string(names.size()));
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (!numeric[k]) {
        words[k].emplace_back(cells[k]);
        continue;
      }
      double v = 0.0;
      if (!parse_double(cells[k], &v))
        throw std::runtime_error(std::string(what) + ": row " + std::to_string(r) + ", column " + std::string(names[k]) +
                                 ": not a number");
      numbers[k].push_back(v);
    }
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    const py::str name(std::string(names[k]));
    if (numeric[k]) {
      out[name] = to_array(std::move(numbers[k]));
    } else {
      out[name] = py::cast(words[k]);
    }
  }
  return out;
}

py::dict result_of(RunTexts&& texts) {
  py::dict r;
  r["summary_json"] = py::str(texts.summary_json);
  r["timeseries"] = columns_of(texts.timeseries_csv, "timeseries.csv");
  r["impacts"] = columns_of(texts.impacts_csv, "impacts.csv");
  r["spectra"] = columns_of(texts.spectra_csv, "spectra.csv");
  r["energy"] = columns_of(texts.energy_csv, "energy.csv");
  r["brief"] = py::str(texts.brief);
  return r;
}

RunRequest request_of(bool timeseries, std::size_t every, bool allow_long) { return RunRequest{timeseries, every, allow_long}; }

py::dict run_py(const SceneObject& scene, bool timeseries, std::size_t every, bool allow_long) {
  RunTexts texts;
  {
    py::gil_scoped_release unlocked;
    texts = run(scene.loaded, request_of(timeseries, every, allow_long));
  }
  return result_of(std::move(texts));
}

// The failure of scenes[index] again, its message starting with "scenes[index]: " (the same
// exception class, field and time).
[[noreturn]] void rethrow_naming(std::exception_ptr failure, std::size_t index) {
  const std::string prefix = "scenes[" + std::to_string(index) + "]: ";
  try {
    std::rethrow_exception(failure);
  } catch (const NumericalError& e) {
    throw NumericalError(prefix + e.what(), e.time());
  } catch (const InputError& e) {
    throw InputError(prefix + e.what(), e.field());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(prefix + e.what());
  }
}

py::list run_many_py(const std::vector<const SceneObject*>& scenes, unsigned jobs, bool timeseries, std::size_t every,
                     bool allow_long) {
  std::vector<LoadedScene> loaded;
  for (const SceneObject* s : scenes) loaded.push_back(s->loaded);
  std::vector<RunTexts> results(loaded.size());
  std::vector<std::exception_ptr> failures(loaded.size());
  {
    py::gil_scoped_release unlocked;  // every run below is C++ only
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t threads = std::min<std::size_t>(jobs == 0 ? cores : jobs, loaded.size());
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i = next++; i < loaded.size(); i = next++) {
        try {
          results[i] = run(loaded[i], request_of(timeseries, every, allow_long));
        } catch (...) {
          failures[i] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
  }
  for (std::size_t i = 0; i < failures.size(); ++i)
    if (failures[i]) rethrow_naming(failures[i], i);
  py::list out;
  for (auto& r : results) out.append(result_of(std::move(r)));
  return out;
}

py::dict joint_py(const SceneObject& scene, int contact, std::optional<double> tol, bool allow_long) {
  if (tol && !(*tol > 0.0 && std::isfinite(*tol)))
    throw InputError("tol = " + std::to_string(*tol) + ": expected a positive length (the scene's length unit)", "tol");
  JointOut j;
  {
    py::gil_scoped_release unlocked;
    j = joint(scene.loaded, contact, tol.value_or(std::numeric_limits<double>::quiet_NaN()), allow_long);
  }
  py::dict d;
  d["scene"] = j.scene;
  d["gap_key"] = j.gap_key;
  d["length_unit"] = j.length_unit;
  d["time_unit"] = j.time_unit;
  d["contact"] = j.contact;
  d["floors"] = py::make_tuple(j.floor_a, j.floor_b);
  d["joint"] = j.joint;
  d["touching_below"] = j.joint_low;
  d["tolerance"] = j.tol;
  d["runs"] = j.runs;
  d["widenings"] = j.widenings;
  d["bracket_top"] = j.bracket_top;
  d["s_max"] = j.s_max;
  d["t_critical"] = j.t_critical;
  d["difference"] = j.difference;
  d["agree"] = j.agree;
  d["peak_a"] = j.peak_a;
  d["t_peak_a"] = j.t_peak_a;
  d["peak_b"] = j.peak_b;
  d["t_peak_b"] = j.t_peak_b;
  d["srss"] = j.srss;
  d["abs_sum"] = j.abs_sum;
  d["wall_seconds"] = j.wall_seconds;
  d["notes"] = j.notes;
  return d;
}

// A structure built in code, run on a record (run_facade.hpp run_structure). A bad run value
// names its keyword ("h", "scale_pga"), not the scene key building_run_spec blames.
py::dict run_structure_py(const structure::Structure& structure, const std::string& record, std::optional<double> scale_pga,
                          double scale,
                          std::optional<double> h, std::optional<double> t_end, std::optional<double> tolerance,
                          const std::string& name, bool timeseries, std::size_t every, bool allow_long) {
  RunTexts texts;
  try {
    py::gil_scoped_release unlocked;
    texts = run_structure(structure, StructureRun{name, record, scale_pga, scale, h, t_end, tolerance},
                          request_of(timeseries, every, allow_long));
  } catch (const FieldError& e) {
    // "solver.h", "solver.t_end", "solver.tolerance", "ground.scale_pga", "ground.scale": the keyword after the dot.
    for (const std::string keyword : {"h", "t_end", "tolerance", "scale_pga", "scale"})
      if (e.field().ends_with("." + keyword)) throw InputError(keyword + ": " + e.problem(), keyword);
    throw;
  }
  return result_of(std::move(texts));
}

}  // namespace

void bind_study(py::module_& m) {
  m.def("run_structure", &run_structure_py, py::arg("structure"), py::arg("record"), py::kw_only(),
        py::arg("scale_pga") = py::none(), py::arg("scale") = 1.0, py::arg("h") = py::none(), py::arg("t_end") = py::none(),
        py::arg("tolerance") = py::none(), py::arg("name") = "building", py::arg("timeseries") = true,
        py::arg("every") = 0u, py::arg("allow_long") = false);
  m.def("run", &run_py, py::arg("scene"), py::kw_only(), py::arg("timeseries") = true, py::arg("every") = 0u,
        py::arg("allow_long") = false);
  m.def("run_many", &run_many_py, py::arg("scenes"), py::kw_only(), py::arg("jobs") = 0u,
        py::arg("timeseries") = true, py::arg("every") = 0u, py::arg("allow_long") = false);
  m.def("joint", &joint_py, py::arg("scene"), py::kw_only(), py::arg("contact") = 1, py::arg("tol") = py::none(),
        py::arg("allow_long") = false);
  m.def("_columns_of", [](const std::string& csv) { return columns_of(csv, "csv"); },
        "A CSV text as {column: array or list} (for tests).");
}

}  // namespace adjoin::python
