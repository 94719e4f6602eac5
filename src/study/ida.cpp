#include "adjoin/study/ida.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"

namespace adjoin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An option's value in a message: quoted, cut at 60 characters.
std::string text_excerpt(const std::string& s) { return "\"" + (s.size() > 60 ? s.substr(0, 60) + "..." : s) + "\""; }

}  // namespace

// ---- the intensity measure ----

std::string IntensityMeasure::text() const { return kind == Kind::pga ? "pga" : "sa:" + shortest_text(period); }

IntensityMeasure parse_intensity_measure(const std::string& text) {
  IntensityMeasure im;
  if (text == "pga") return im;
  double period = 0.0;
  if (text.rfind("sa:", 0) == 0 && parse_finite(text.substr(3), &period) && period > 0.0 && period <= 100.0) {
    im.kind = IntensityMeasure::Kind::sa;
    im.period = period;
    return im;
  }
  throw InputError("--im " + text_excerpt(text) +
                   ": expected pga (the peak ground acceleration) or sa:T (the 5 %-damped PSA at period T in s, 0 < T <= 100, e.g. sa:1.0)");
}

double record_intensity(const Record& record, const IntensityMeasure& im) {
  double value = 0.0;
  if (im.kind == IntensityMeasure::Kind::pga) {
    for (double a : record.accel) value = std::max(value, std::abs(a));
    value /= kStandardGravity;
  } else {
    value = spectral_values(record.dt, record.accel, im.period, kIdaDamping).psa;
  }
  if (!(value > 0.0 && std::isfinite(value)))
    throw InputError(record.source + ": its " + im.text() + " is " + shortest_text(value) + " g; a record is scaled to a level by it, so it must be > 0");
  return value;
}

// ---- hunt and fill ----

void TraceOptions::check() const {
  if (!(std::isfinite(start) && start > 0.0)) throw InputError("--trace-start " + shortest_text(start) + ": expected the first IM in g, > 0");
  if (!(std::isfinite(factor) && factor > 1.0 && factor <= 10.0))
    throw InputError("--trace-factor " + shortest_text(factor) + ": expected the hunt's step factor, > 1 and <= 10");
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw InputError("--trace-tol " + shortest_text(tolerance) + ": expected the bracket's relative width, in (0, 1)");
  if (budget < 2 || budget > 10000) throw InputError("--trace-runs " + std::to_string(budget) + ": expected runs per record, 2 to 10000");
}

Trace hunt_and_fill(const std::function<bool(double im)>& event_at, const TraceOptions& o) {
  o.check();
  Trace trace;
  const auto run = [&](double im) {
    const bool event = event_at(im);
    trace.runs.push_back({im, event});
    return event;
  };
  // Hunt: up by the factor until the event; down by halves if the first run already shows it.
  double im = o.start;
  if (run(im)) {
    trace.high = im;
    while (trace.runs.size() < o.budget) {
      im /= 2.0;
      if (!run(im)) {
        trace.low = im;
        break;
      }
      trace.high = im;
    }
  } else {
    trace.low = im;
    while (trace.runs.size() < o.budget) {
      im *= o.factor;
      if (run(im)) {
        trace.high = im;
        break;
      }
      trace.low = im;
    }
  }
  if (!trace.bracketed()) return trace;
  // Bracket: bisection to the tolerance.
  while (trace.runs.size() < o.budget && *trace.high - *trace.low > o.tolerance * *trace.low) {
    const double mid = 0.5 * (*trace.low + *trace.high);
    if (run(mid)) trace.high = mid;
    else trace.low = mid;
  }
  // Fill: halve the widest gap among 0 and the IMs run without the event below the bracket.
  while (trace.runs.size() < o.budget) {
    std::vector<double> ims{0.0};
    for (const auto& r : trace.runs)
      if (!r.event && r.im <= *trace.low) ims.push_back(r.im);
    std::sort(ims.begin(), ims.end());
    std::size_t widest = 1;
    for (std::size_t k = 1; k < ims.size(); ++k)
      if (ims[k] - ims[k - 1] > ims[widest] - ims[widest - 1]) widest = k;
    run(0.5 * (ims[widest] + ims[widest - 1]));  // an event here (non-monotone curve) is kept as run
  }
  return trace;
}

// ---- fractiles ----

namespace {

// The EDP of one curve at `level`: +infinity at and above its first event, linear between its
// runs below, NaN outside them.
double curve_at(const IdaCurve& c, double level) {
  std::vector<std::pair<double, double>> points;
  for (std::size_t k = 0; k < c.im.size(); ++k)
    if (!std::isnan(c.edp[k])) points.emplace_back(c.im[k], c.edp[k]);
  std::sort(points.begin(), points.end());
  double first_event = kInf;
  for (const auto& [im, edp] : points)
    if (std::isinf(edp)) {
      first_event = im;
      break;
    }
  if (level >= first_event) return kInf;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k].first == level) return points[k].second;
    if (k + 1 < points.size() && points[k].first < level && level < points[k + 1].first) {
      if (std::isinf(points[k + 1].second)) return points[k].second;  // below the first event: the last value holds
      const double w = (level - points[k].first) / (points[k + 1].first - points[k].first);
      return points[k].second + w * (points[k + 1].second - points[k].second);
    }
  }
  return kNaN;
}

}  // namespace

std::vector<double> ida_fractile(const std::vector<IdaCurve>& curves, const std::vector<double>& levels, double p) {
  std::vector<double> out;
  for (double level : levels) {
    std::vector<double> values;
    for (const auto& c : curves)
      if (const double v = curve_at(c, level); !std::isnan(v)) values.push_back(v);
    if (values.empty() || 2 * values.size() < curves.size()) {
      out.push_back(kNaN);
      continue;
    }
    std::sort(values.begin(), values.end());
    const double at = p * static_cast<double>(values.size() - 1);
    const std::size_t k = static_cast<std::size_t>(std::floor(at));
    const double w = at - static_cast<double>(k);
    const double lo = values[k], hi = values[std::min(k + 1, values.size() - 1)];
    if (w == 0.0) out.push_back(lo);  // (0 x infinity would be NaN)
    else out.push_back(std::isinf(lo) || std::isinf(hi) ? kInf : lo + w * (hi - lo));
  }
  return out;
}

}  // namespace adjoin
