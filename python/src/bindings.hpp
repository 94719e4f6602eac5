#pragma once
// The pieces of the `_adjoin` extension module, one per component of include/adjoin/ (the
// package mirrors the library: SPEC §4, §8), and the helpers they share.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

namespace adjoin::python {

namespace py = pybind11;

void bind_core(py::module_& m);       // core.cpp: the exceptions
void bind_ground(py::module_& m);     // ground.cpp: records
void bind_post(py::module_& m);       // post.cpp: spectra, RotD, inelastic spectra
void bind_structure(py::module_& m);  // structure.cpp: the typed structure builder, modes
void bind_io(py::module_& m);         // io.cpp: scenes from files, text and dicts
void bind_study(py::module_& m);      // study.cpp: run, run_many
void bind_design_studies(py::module_& m);  // design_studies.cpp: ida, fragility (SPEC §9)
void bind_optimize(py::module_& m);   // optimize.cpp: a study of `adjoin optimize` (SPEC §9)

// A numpy array that takes over `values` (no copy): the vector moves to the heap and a capsule
// frees it when the last array viewing it is gone.
inline py::array_t<double> to_array(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), free_when_done);
}

// InputError::field() ("link[1].slip_force") as Python spells it: the scene's dotted key
// ("link.1.slip_force").
std::string dotted_field(const std::string& field_path);

}  // namespace adjoin::python
