// The design studies of SPEC §9 in Python: study/ida.hpp with io/ida_files.hpp (the runs of
// `adjoin ida`, without its files) and post/fragility.hpp (the fits of `adjoin fragility`).
// The package's adjoin.ida and adjoin.fragility check the keywords and shape what these return.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <filesystem>
#include <set>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/ida_files.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/post/fragility.hpp"
#include "adjoin/post/fragility_event.hpp"
#include "adjoin/study/ida.hpp"
#include "adjoin/study/sweep.hpp"
#include "bindings.hpp"

namespace adjoin::python {
namespace {

py::object number_or_none(double v) { return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none()); }

// ---- fragility ----

// The fit of `adjoin fragility` (src/cli/fragility.cpp: read_design, fit_design, design_json)
// on a table given as columns: the same keys, levels/n/events as numpy arrays.
py::dict fragility_py(const std::vector<std::string>& records, const std::vector<double>& im,
                      const std::vector<std::string>& columns, const std::vector<std::vector<double>>& values,
                      const std::vector<std::string>& errors, const std::string& event_text, std::size_t bootstrap,
                      std::uint64_t seed, std::optional<double> at) {
  FragilityEvent event;
  try {
    event = FragilityEvent::parse(event_text, columns);
  } catch (const InputError& e) {
    throw InputError(std::string("event: ") + e.what(), "event");
  }
  FragilityOutcomes outcomes;
  std::vector<FragilityLevel> levels;
  FragilityFit fit;
  std::optional<FragilityBounds> bounds;
  std::optional<FirstEventFit> first;
  {
    py::gil_scoped_release unlocked;
    outcomes = fragility_outcomes(event, records, im, values, errors);
    if (outcomes.runs.empty())
      throw InputError("table: no run with a known outcome of the event (" + std::to_string(outcomes.failed) + " failed, " +
                           std::to_string(outcomes.unknown) + " with an empty value the event reads)",
                       "table");
    levels = fragility_levels(outcomes.runs);
    fit = fit_fragility_mle(levels);
    if (fit.fitted && bootstrap > 0) bounds = bootstrap_fragility(outcomes.runs, bootstrap, seed);
    if (outcomes.trace) first = fit_first_event(outcomes.runs);
  }
  std::vector<double> level_im;
  std::vector<std::int64_t> n, k;
  for (const FragilityLevel& l : levels) {
    level_im.push_back(l.im);
    n.push_back(static_cast<std::int64_t>(l.n));
    k.push_back(static_cast<std::int64_t>(l.events));
  }
  std::set<std::string> distinct;
  for (const FragilityRun& r : outcomes.runs) distinct.insert(r.record);
  py::dict d;
  d["event"] = event_text;
  d["fitted"] = fit.fitted;
  d["problem"] = fit.fitted ? py::object(py::none()) : py::object(py::str(fit.problem));
  d["theta"] = number_or_none(fit.theta);
  d["beta"] = number_or_none(fit.beta);
  d["log_likelihood"] = number_or_none(fit.log_likelihood);
  d["levels"] = to_array(std::move(level_im));
  d["n"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(n.size()), n.data());
  d["events"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(k.size()), k.data());
  d["records"] = distinct.size();
  d["runs"] = outcomes.runs.size();
  py::dict skipped;
  skipped["failed"] = outcomes.failed;
  skipped["unknown"] = outcomes.unknown;
  d["skipped"] = skipped;
  if (bounds) {
    py::dict b;
    b["samples"] = bounds->samples;
    b["seed"] = bounds->seed;
    b["degenerate"] = bounds->degenerate;
    b["percentiles"] = py::make_tuple(0.05, 0.95);
    b["theta"] = py::make_tuple(number_or_none(bounds->theta_low), number_or_none(bounds->theta_high));
    b["beta"] = py::make_tuple(number_or_none(bounds->beta_low), number_or_none(bounds->beta_high));
    d["bootstrap"] = b;
  } else {
    d["bootstrap"] = py::none();
  }
  if (first) {
    py::dict f;
    f["fitted"] = first->fitted;
    f["problem"] = first->fitted ? py::object(py::none()) : py::object(py::str(first->problem));
    f["theta"] = number_or_none(first->theta);
    f["beta"] = number_or_none(first->beta);
    f["records"] = first->records;
    f["censored"] = first->censored;
    f["censored_records"] = first->censored_records;
    d["first_event"] = f;
  } else {
    d["first_event"] = py::none();
  }
  if (at) {
    py::dict a;
    a["im"] = *at;
    a["probability"] = fit.fitted ? number_or_none(fragility_probability(fit.theta, fit.beta, *at)) : py::object(py::none());
    d["at"] = a;
  }
  return d;
}

// ---- ida ----

// `work()`, with an InputError without a field given the keyword its message starts with: the
// library names the option it was given ("edp ...", "capacity ...") or the command's
// ("--trace-start ...", spelt here as the keyword), else `fallback`.
struct Spelling {
  std::string prefix, keyword;
};
template <class Work>
auto naming_keyword(const std::vector<Spelling>& spellings, const std::string& fallback, Work&& work) {
  try {
    return work();
  } catch (const InputError& e) {
    if (!e.field().empty()) throw;
    const std::string message = e.what();
    for (const Spelling& s : spellings)
      if (message.rfind(s.prefix + " ", 0) == 0 || message.rfind(s.prefix + ":", 0) == 0)
        throw InputError(s.keyword + message.substr(s.prefix.size()), s.keyword);
    throw InputError(fallback + ": " + message, fallback);
  }
}

// A demand's cells as numbers (an empty cell NaN, true/false 1/0), or as words if one is not.
py::object demand_column(const std::vector<IdaRow>& rows, std::size_t e) {
  std::vector<double> numbers;
  std::vector<std::string> words;
  bool numeric = true;
  for (const IdaRow& r : rows) {
    const std::string& cell = r.edps[e];
    words.push_back(cell);
    double v = std::nan("");
    if (cell == "true") v = 1.0;
    else if (cell == "false") v = 0.0;
    else if (!cell.empty() && !parse_finite(cell, &v)) numeric = false;
    numbers.push_back(v);
  }
  return numeric ? py::object(to_array(std::move(numbers))) : py::object(py::cast(words));
}

// `out` (a folder): DIR/ida.csv and DIR/ida.png as `adjoin ida --out DIR` writes them
// (src/cli/ida.cpp write_ida), the figure of the first demand. InputError naming `out`.
void write_ida_files(const std::string& out, const std::string& scene, const IntensityMeasure& im,
                     const std::vector<std::string>& edps, const std::vector<IdaRow>& rows) {
  const std::filesystem::path dir(out);
  OutputFolder folder(dir, "out");
  {
    AtomicFile csv(dir / "ida.csv");
    csv.stream() << ida_csv(edps, rows);
    csv.commit();
  }
  folder.keep();
  if (edps.empty()) return;
  const bool si = rows.empty() || rows[0].units == "SI";
  naming_keyword({}, "out", [&] {
    plot_ida(rows, 0, edps[0], im.text(), si, "IDA of " + std::filesystem::path(scene).stem().string(), dir / "ida.png", PlotStyle{});
  });
}

// The runs of `adjoin ida SCENE --suite ... --im IM --levels ...|--trace` as columns, in threads
// with the GIL released: stripes (one sweep over the (record, level) pairs) or traces; with
// `out` ("" none) also its ida.csv and ida.png.
py::dict ida_py(const std::string& scene, const std::vector<std::string>& suite, const std::string& im_text,
                const std::vector<double>& levels, bool trace, const TraceOptions& trace_options,
                std::vector<std::string> edps, const std::string& capacity_text, const std::string& units, unsigned jobs,
                const std::string& out_folder) {
  std::vector<IdaRow> rows;
  std::vector<std::string> skipped;
  std::vector<Trace> traces;
  {
    py::gil_scoped_release unlocked;
    const IntensityMeasure im = naming_keyword({{"--im", "im"}}, "im", [&] { return parse_intensity_measure(im_text); });
    if (!out_folder.empty()) naming_keyword({}, "out", [&] { check_output_folder(out_folder, "out"); });
    const std::vector<IdaRecord> records =
        naming_keyword({{"units", "units"}}, "suite", [&] { return read_ida_suite(suite, units, im, &skipped, "units"); });
    if (trace) {
      naming_keyword({{"--trace-start", "trace_start"}, {"--trace-factor", "trace_factor"}, {"--trace-tol", "trace_tol"},
                      {"--trace-runs", "trace_runs"}},
                     "trace", [&] { trace_options.check(); });
      IdaTraceRequest request;
      request.scene = scene;
      request.units = units;
      request.capacity = capacity_text;
      request.options = trace_options;
      request.jobs = jobs;
      request.name = "adjoin.ida " + scene;
      request.edp_option = "edp";
      request.capacity_option = "capacity";
      request.trace_option = "trace";
      naming_keyword({{"edp", "edp"}, {"capacity", "capacity"}, {"trace", "trace"}}, "scene", [&] { rows = ida_traces(request, records, &edps, &traces); });
    } else {
      const SweepSpec spec = naming_keyword({}, "scene", [&] {
        return ida_sweep(scene, ida_stripe_motions(records, levels), units, "adjoin.ida " + scene);
      });
      if (edps.empty()) edps = ida_default_edps(spec);
      naming_keyword({{"edp", "edp"}}, "edp", [&] { check_ida_edps(spec, edps, "edp"); });
      const IdaCapacity capacity =
          naming_keyword({{"capacity", "capacity"}}, "capacity", [&] { return ida_capacity(spec, capacity_text, "capacity"); });
      check_sweep_memory(spec, spec.runs());
      SweepOptions options;
      options.jobs = jobs;
      std::vector<std::vector<std::string>> cells;
      for (const SweepRow& row : run_sweep(spec, options)) cells.push_back(sweep_cells(spec, row));
      rows = ida_stripe_rows(spec, cells, records, levels, edps, capacity);
    }
    if (!out_folder.empty()) write_ida_files(out_folder, scene, im, edps, rows);
  }
  py::dict d;
  std::vector<std::string> record;
  std::vector<double> im, scale;
  std::vector<std::string> error, units_of;
  std::vector<bool> event;
  for (const IdaRow& r : rows) {
    record.push_back(r.record);
    im.push_back(r.im);
    scale.push_back(r.scale);
    error.push_back(r.error);
    event.push_back(r.event);
  }
  d["record"] = record;
  d["im"] = to_array(std::move(im));
  d["scale"] = to_array(std::move(scale));
  for (std::size_t e = 0; e < edps.size(); ++e) d[py::str(edps[e])] = demand_column(rows, e);
  d["error"] = error;
  py::array_t<bool> events(static_cast<py::ssize_t>(event.size()));
  for (std::size_t i = 0; i < event.size(); ++i) events.mutable_at(static_cast<py::ssize_t>(i)) = event[i];
  d["capacity_event"] = events;
  py::dict out;
  out["columns"] = d;
  out["edps"] = edps;
  out["skipped"] = skipped;
  out["units"] = rows.empty() ? std::string() : rows[0].units;
  py::list brackets;  // traces: each record's (low, high) bracket of its first capacity event
  for (const Trace& t : traces)
    brackets.append(py::make_tuple(t.low ? py::object(py::float_(*t.low)) : py::object(py::none()),
                                   t.high ? py::object(py::float_(*t.high)) : py::object(py::none())));
  out["brackets"] = brackets;
  return out;
}

}  // namespace

void bind_design_studies(py::module_& m) {
  m.def("fragility", &fragility_py, py::arg("records"), py::arg("im"), py::arg("columns"), py::arg("values"),
        py::arg("errors"), py::arg("event"), py::arg("bootstrap"), py::arg("seed"), py::arg("at") = py::none());
  m.def(
      "ida",
      [](const std::string& scene, const std::vector<std::string>& suite, const std::string& im,
         const std::vector<double>& levels, bool trace, double start, double factor, double tolerance, std::size_t runs,
         const std::vector<std::string>& edps, const std::string& capacity, const std::string& units, unsigned jobs,
         const std::string& out) {
        return ida_py(scene, suite, im, levels, trace, TraceOptions{start, factor, tolerance, runs}, edps, capacity, units,
                      jobs, out);
      },
      py::arg("scene"), py::arg("suite"), py::arg("im"), py::arg("levels"), py::arg("trace"), py::arg("trace_start"),
      py::arg("trace_factor"), py::arg("trace_tol"), py::arg("trace_runs"), py::arg("edp"), py::arg("capacity"),
      py::arg("units"), py::arg("jobs"), py::arg("out") = "");
}

}  // namespace adjoin::python
