#include "adjoin/study/run_watch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"

namespace adjoin {
namespace {

constexpr double kCalibrationSeconds = 0.25;  // the first steps timed before estimating
constexpr std::size_t kCheckEvery = 64;       // steps between reads of the clock

std::size_t zener_elements(const structure::Structure& s) {
  std::size_t n = 0;
  for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr})
    if (b)
      for (const auto& d : b->devices)
        if (structure::kind_of(d).family(d) == structure::DeviceFamily::zener) n += d.storeys.size();
  for (const auto& l : s.links)
    if (structure::kind_of(l).family(l) == structure::LinkFamily::zener) ++n;
  return n;
}

}  // namespace

std::string duration_text(double seconds) {
  char text[48];
  if (seconds >= 3600.0) {
    const long minutes = std::lround(seconds / 60.0);
    std::snprintf(text, sizeof text, "%ld h %02ld min", minutes / 60, minutes % 60);
  } else if (seconds >= 60.0) {
    const long s = std::lround(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%.2g s", seconds);
  }
  return text;
}

RunWatch::RunWatch(Options options) : options_(std::move(options)) {}

void RunWatch::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  // (A two-block run's 1 + 1 structure is dimensionless: time_scale gives its step in seconds.)
  start(o.steps(), o.h * options_.time_scale, o.history == HistoryEngine::direct && zener_elements(s) > 0);
}

void RunWatch::observe(const StructureState&) { step(); }

void RunWatch::start(std::size_t steps, double h_seconds, bool direct) {
  ++run_;
  done_ = 0;
  total_ = steps;
  h_ = h_seconds;
  direct_ = direct;
  marks_.clear();
  estimated_ = shown_ = false;
  next_check_ = 1;
  start_ = std::chrono::steady_clock::now();
}

double RunWatch::seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

double RunWatch::estimate() const {
  if (done_ < 2) return 0.0;  // (done_ counts the grid point t_0 too)
  const double n = static_cast<double>(done_ - 1), total = static_cast<double>(total_), t = seconds();
  // Wall time after m steps: a m, and with the direct engine a m + b m^2 / 2 (its sums cost
  // b m at step m), a and b fitted to now and the last mark at most halfway.
  double b = 0.0;
  for (auto it = marks_.rbegin(); it != marks_.rend(); ++it) {
    const double m = static_cast<double>(it->first);
    if (m > 0.5 * n) continue;
    b = std::max(0.0, 2.0 * (t / n - it->second / m) / (n - m));
    break;
  }
  const double a = std::max(0.0, t / n - 0.5 * b * n);
  return a * total + 0.5 * b * total * total;
}

void RunWatch::step() {
  // Called at t_0 too (done_ counts the steps taken after it).
  if (done_++ == 0) return;
  const std::size_t steps = done_ - 1;
  if (direct_ && !estimated_ && steps >= kCheckEvery && (steps & (steps - 1)) == 0) marks_.emplace_back(steps, seconds());
  if (done_ < next_check_) return;
  next_check_ = done_ + kCheckEvery;
  const double elapsed = seconds();
  if (!estimated_) {
    if (elapsed < kCalibrationSeconds) return;
    estimated_ = true;
    calibrated();
  }
  if (!shown_ || !options_.show) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_shown_ < std::chrono::milliseconds(100)) return;
  last_shown_ = now;
  options_.show({run_, steps, total_, h_, options_.h_unit, elapsed, estimate(), false});
}

// The estimate is known: refuse the run, or show it.
void RunWatch::calibrated() {
  const double total = estimate();
  const std::size_t steps = done_ - 1;
  if (options_.refuse_seconds > 0.0 && total > options_.refuse_seconds) {
    char text[600];
    std::snprintf(text, sizeof text,
                  "this run would take about %s (%zu steps of solver.h = %.4g%s at %.3g ms a step%s, timed over its "
                  "first %zu), more than %s: probably not what was meant; raise solver.h or shorten solver.t_end, or pass "
                  "--allow-long to run it",
                  duration_text(total).c_str(), total_, h_, options_.h_unit.c_str(), 1e3 * total / static_cast<double>(std::max<std::size_t>(total_, 1)),
                  direct_ ? " on average: the direct history's sums grow with every step" : "", steps,
                  duration_text(options_.refuse_seconds).c_str());
    throw InputError(text);
  }
  if (total > options_.show_seconds && options_.show) {
    shown_ = true;
    last_shown_ = std::chrono::steady_clock::now();
    options_.show({run_, steps, total_, h_, options_.h_unit, seconds(), total, true});
  }
}

void RunWatch::end() {
  if (shown_ && options_.finish) options_.finish();
  shown_ = false;
}

}  // namespace adjoin
