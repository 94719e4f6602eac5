#pragma once
// Progress on the terminal: a bar on stderr, only when stderr is a terminal (never in files
// or pipes), for a sweep's runs and for a long run's steps (study/run_watch.hpp).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "adjoin/study/run_watch.hpp"

namespace adjoin::cli {

class Progress {
 public:
  Progress(bool enabled, std::size_t done, std::size_t total, std::string unit = "runs")
      : enabled_(enabled && isatty(STDERR_FILENO)), start_done_(done), done_(done), total_(total), unit_(std::move(unit)),
        start_(std::chrono::steady_clock::now()) {
    draw();
  }
  void tick() { update(done_ + 1); }
  // `remaining`: the time left [s] when the caller knows it better than the rate so far does
  // (a run whose steps grow dearer: study/run_watch.hpp); negative: from the rate.
  void update(std::size_t done, double remaining = -1.0) {
    done_ = done;
    remaining_ = remaining;
    const auto now = std::chrono::steady_clock::now();
    if (done_ == total_ || now - last_ > std::chrono::milliseconds(100)) {
      last_ = now;
      draw();
    }
  }
  void finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  void draw() {
    if (!enabled_ || total_ == 0) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = seconds > 0 ? static_cast<double>(done_ - start_done_) / seconds : 0.0;
    const int width = 30;
    const int filled = static_cast<int>(static_cast<double>(width) * static_cast<double>(done_) / static_cast<double>(total_));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar += std::string(static_cast<std::size_t>(width - filled), '.');
    char eta[32] = "--:--";
    if (rate > 0 || remaining_ >= 0.0) {
      const long remaining =
          std::lround(remaining_ >= 0.0 ? remaining_ : static_cast<double>(total_ - done_) / rate);
      std::snprintf(eta, sizeof eta, "%ld:%02ld", remaining / 60, remaining % 60);
    }
    std::fprintf(stderr, "\r[%s] %zu/%zu %s, %.3g %s/s, ETA %s   ", bar.c_str(), done_, total_, unit_.c_str(), rate,
                 unit_.c_str(), eta);
    std::fflush(stderr);
  }
  bool enabled_;
  std::size_t start_done_, done_, total_;
  double remaining_ = -1.0;
  std::string unit_;
  std::chrono::steady_clock::time_point start_, last_{};
};

// A command's RunWatch (study/run_watch.hpp): runs estimated at more than 2 hours refused
// unless `allow_long` (--allow-long); on a terminal and without --quiet, a run estimated at
// more than 5 s (ADJOIN_PROGRESS_AFTER seconds if set: the tests' 0) shows its estimate and a
// bar of its steps on stderr.
inline RunWatch::Options watch_options(bool quiet, bool allow_long) {
  RunWatch::Options o;
  if (allow_long) o.refuse_seconds = 0.0;
  if (const char* after = std::getenv("ADJOIN_PROGRESS_AFTER")) o.show_seconds = std::atof(after);
  if (quiet || !isatty(STDERR_FILENO)) return o;
  auto bar = std::make_shared<std::unique_ptr<Progress>>();
  o.show = [bar](const RunProgress& p) {
    if (p.first) {
      std::fprintf(stderr, "run %zu: %zu steps of h = %.4g%s, about %s\n", p.run, p.total, p.h, p.h_unit.c_str(),
                   duration_text(p.estimate).c_str());
      *bar = std::make_unique<Progress>(true, p.done, p.total, "steps");
    } else if (*bar) {
      (*bar)->update(p.done, std::max(0.0, p.estimate - p.elapsed));
    }
  };
  o.finish = [bar]() {
    if (*bar) (*bar)->finish();
    bar->reset();
  };
  return o;
}

}  // namespace adjoin::cli
