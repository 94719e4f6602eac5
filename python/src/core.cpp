// core/errors.hpp in Python: InputError -> adjoin.InputError (a ValueError) with .field, the
// dotted scene key it is about; NumericalError -> adjoin.NumericalError (an ArithmeticError)
// with .time, the simulation time of the failure. Translated wherever a binding throws, so no
// input, however bad, ends the interpreter.
#include <exception>

#include "adjoin/core/errors.hpp"
#include "bindings.hpp"

namespace adjoin::python {

std::string dotted_field(const std::string& field_path) {
  std::string out;
  for (const char c : field_path) {
    if (c == '[') {
      out += '.';
    } else if (c != ']') {
      out += c;
    }
  }
  return out;
}

namespace {

// The two exception types, made once when the module is imported (they live as long as the
// interpreter: the module holds them too).
PyObject* input_error_type = nullptr;
PyObject* numerical_error_type = nullptr;

PyObject* make_exception(py::module_& m, const char* name, PyObject* base, const char* doc, const char* attribute) {
  const std::string qualified = std::string("adjoin.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (type == nullptr) throw py::error_already_set();
  PyObject_SetAttrString(type, attribute, Py_None);  // the default when raised from Python
  m.add_object(name, py::handle(type));
  return type;
}

void raise_with(PyObject* type, const char* message, const char* attribute, py::object value) {
  py::object exc = py::reinterpret_borrow<py::object>(type)(message);
  exc.attr(attribute) = std::move(value);
  PyErr_SetObject(type, exc.ptr());
}

}  // namespace

void bind_core(py::module_& m) {
  input_error_type = make_exception(m, "InputError", PyExc_ValueError,
                                    "The input is wrong: a scene key, a record's line, an argument.\n\n"
                                    "The message names the file and line, key or argument and what was expected "
                                    "(the same text `adjoin` prints after 'error:'; exit status 2 there).\n\n"
                                    "Attributes:\n"
                                    "    field (str | None): the scene key the error is about, dotted as in "
                                    "Scene.from_dict and load_scene(set=...), e.g. 'link.1.slip_force'; "
                                    "None when it is not about one key (a file that cannot be read).",
                                    "field");
  numerical_error_type = make_exception(m, "NumericalError", PyExc_ArithmeticError,
                                        "The input was valid but the computation failed (instability, "
                                        "non-finite values); exit status 3 for `adjoin`.\n\n"
                                        "Attributes:\n"
                                        "    time (float | None): the simulation time at which it was detected, "
                                        "in the solver's dimensionless time unit.",
                                        "time");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      raise_with(input_error_type, e.what(), "field",
                 e.field().empty() ? py::object(py::none()) : py::object(py::str(dotted_field(e.field()))));
    } catch (const NumericalError& e) {
      raise_with(numerical_error_type, e.what(), "time", py::float_(e.time()));
    }
  });
  m.def("_field_of", &dotted_field, "InputError::field()'s path ('link[1].slip_force') as a dotted key.");
}

}  // namespace adjoin::python
