#pragma once
// Incremental dynamic analysis and multiple stripes (SPEC §9): the numbers of `adjoin ida`
// without its files. A suite of records, each scaled so that its intensity measure (IM) equals
// a level; the runs themselves are sweep runs (study/sweep.hpp; io/ida_sweep.hpp makes the
// sweep), so `adjoin ida` and `adjoin sweep` with `ground.scale` give the same rows.
//
//     IntensityMeasure im = parse_intensity_measure("sa:1.0");
//     double im1 = record_intensity(read_record("RSN1044.AT2"), im);   // g, the record as read
//     double scale = level / im1;                                       // ground.scale of the run
//
// Tracing (Vamvatsikos & Cornell 2002, "hunt and fill"), per record, given a function that runs
// the record at an IM and says whether the capacity event happened:
//   hunt:   IM_1 = start, IM_{k+1} = factor x IM_k until the first event (or the run budget);
//           a first run that already shows the event halves the IM until one does not;
//   bracket: bisection between the highest IM without the event below the first event and that
//           event, until (high - low) <= tolerance x low (or the budget);
//   fill:   the runs left in the budget halve the widest gaps between 0 and the IMs run
//           without the event below the bracket, widest first, so the curve below the
//           capacity is drawn evenly.
// A record that shows no event within the budget reports none (its highest IM is a lower bound).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

// `pga` (the peak ground acceleration, g) or `sa:T` (the 5 %-damped pseudo-spectral
// acceleration at period T [s], g), of the record as read.
struct IntensityMeasure {
  enum class Kind { pga, sa } kind = Kind::pga;
  double period = 0.0;  // s, for sa
  std::string text() const;  // "pga", "sa:1"
};
// InputError naming --im and what it takes.
IntensityMeasure parse_intensity_measure(const std::string& text);
// The damping of `sa:T`.
inline constexpr double kIdaDamping = 0.05;

// The IM of the record in g: max |a| / g, or the PSA at T of post/spectrum.hpp (the code of
// `adjoin spectrum`, its default options) at 5 % damping. InputError if it is not > 0 (a
// record of zeros cannot be scaled to a level).
double record_intensity(const Record& record, const IntensityMeasure& im);

struct TraceOptions {
  double start = 0.1;        // the first IM [g], > 0
  double factor = 1.5;       // the hunt's geometric step, > 1
  double tolerance = 0.05;   // the bracket's relative width, in (0, 1)
  std::size_t budget = 20;   // runs per record, >= 2
  // InputError naming the option (--trace-start, --trace-factor, --trace-tol, --trace-runs).
  void check() const;
};

struct TracePoint {
  double im = 0.0;
  bool event = false;
};

struct Trace {
  std::vector<TracePoint> runs;     // in the order they were run
  std::optional<double> low, high;  // the bracket of the first event (high: the lowest IM seen
                                    // with the event, low: the highest below it without)
  bool bracketed() const { return low && high; }
};

// Hunt, bracket and fill (above); `event_at(im)` runs the record at `im` and says whether the
// capacity event happened. Exceptions from it propagate.
Trace hunt_and_fill(const std::function<bool(double im)>& event_at, const TraceOptions& options);

// ---- fractile curves of a set of IDA curves ----

// One record's IDA curve: its runs (IM, EDP), EDP = +infinity where the capacity event
// happened (the curve's flat line), NaN where the run has no value.
struct IdaCurve {
  std::vector<double> im, edp;
};
// The p-fractiles (p in (0, 1)) of the EDP over the records at each IM of `levels`: each curve
// interpolated linearly in IM between its runs (+infinity at and above its first event; a
// level outside a curve's runs below its first event is left out for that record), then the
// sample quantile (linear between order statistics; +infinity if it falls on a collapsed one).
// Levels where fewer than half the records have a value get NaN.
std::vector<double> ida_fractile(const std::vector<IdaCurve>& curves, const std::vector<double>& levels, double p);

}  // namespace adjoin
