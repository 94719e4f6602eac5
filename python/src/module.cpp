// The `_adjoin` extension module: the compiled half of the `adjoin` package (python/adjoin/
// holds the Python half, which re-exports these names with their documentation).
#include "bindings.hpp"

PYBIND11_MODULE(_adjoin, m) {
  m.doc() = "adjoin's library, compiled (use the `adjoin` package, which documents it)";
  adjoin::python::bind_core(m);
  adjoin::python::bind_ground(m);
  adjoin::python::bind_post(m);
  adjoin::python::bind_structure(m);
  adjoin::python::bind_io(m);
  adjoin::python::bind_study(m);
  adjoin::python::bind_design_studies(m);
  adjoin::python::bind_optimize(m);
}
