// `adjoin optimize` in Python (io/optimize_study.hpp): a study file run as the command runs
// it, returning optimum.json's and evaluations.csv's text; with `out`, its files (and the
// cache that makes a rerun free) in that folder. The package's adjoin.optimize parses them.
#include <filesystem>
#include <optional>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/folder_lock.hpp"
#include "adjoin/io/optimize_study.hpp"
#include "adjoin/io/output_place.hpp"
#include "bindings.hpp"

namespace adjoin::python {
namespace {

py::tuple optimize_py(const std::string& study_file, unsigned jobs, const std::string& out) {
  std::string json, csv;
  {
    py::gil_scoped_release unlocked;
    const auto study = [&] {
      try {
        return load_optimize_study(study_file);
      } catch (const InputError& e) {
        if (!e.field().empty()) throw;
        throw InputError(e.what(), "study");
      }
    }();
    OptimizeRequest request;
    request.jobs = jobs;
    std::optional<OutputFolder> folder;
    std::optional<FolderLock> lock;
    if (!out.empty()) {
      try {
        check_output_folder(out, "out");
      } catch (const InputError& e) {
        throw InputError(e.what(), "out");
      }
      request.dir = out;
      folder.emplace(request.dir, "out");
      folder->keep();
      lock.emplace(request.dir, "optimize.lock", "adjoin.optimize " + study_file);
    }
    const OptimizeOutcome outcome = run_optimize_study(study, request);
    if (!out.empty()) write_optimize_files(study, outcome, request.dir);
    json = optimize_json(study, outcome);
    csv = optimize_evaluations_csv(study, outcome);
  }
  return py::make_tuple(json, csv);
}

}  // namespace

void bind_optimize(py::module_& m) {
  m.def("optimize", &optimize_py, py::arg("study"), py::arg("jobs"), py::arg("out"));
}

}  // namespace adjoin::python
