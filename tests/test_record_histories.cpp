// Velocity and displacement of a record (ground/integration.hpp, `record process --integrate`)
// and the record's figure (`plot record`): trapezoid integrals against the closed forms of a
// sine, second order in dt; a constant offset's drift removed by the baseline correction; the
// CSV written by --integrate read back by the readers and by `adjoin spectrum`; PNG and SVG
// figures produced.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/ground/integration.hpp"
#include "adjoin/ground/processing.hpp"
#include "adjoin/ground/record_file.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"
#include "record_helpers.hpp"

using namespace adjoin;
using adjoin::test::run_cli;
using adjoin::test::sampled_record;
using adjoin::test::shell_word;
using adjoin::test::slurp;
using adjoin::test::write_temp;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

constexpr double g = 9.80665;
constexpr double w = 2.0 * std::numbers::pi;  // 1 Hz
const std::string real = ADJOIN_REAL_RECORDS;

// a = sin(w t): v = (1 - cos w t) / w, d = t / w - sin(w t) / w^2 (from rest).
double v_exact(double t) { return (1.0 - std::cos(w * t)) / w; }
double d_exact(double t) { return t / w - std::sin(w * t) / (w * w); }

struct Errors {
  double v = 0.0, d = 0.0;
};

Errors errors(const MotionHistories& h) {
  Errors e;
  for (std::size_t i = 0; i < h.velocity.size(); ++i) {
    const double t = static_cast<double>(i) * h.dt;
    e.v = std::max(e.v, std::abs(h.velocity[i] - v_exact(t)));
    e.d = std::max(e.d, std::abs(h.displacement[i] - d_exact(t)));
  }
  return e;
}

// A two-column file in g of a(t) [m/s^2] over [0, T].
fs::path two_columns(const std::string& name, double dt, double duration, const auto& a) {
  std::ostringstream s;
  s.precision(17);
  s << "# units: g\n";
  const auto n = static_cast<std::size_t>(std::llround(duration / dt)) + 1;
  for (std::size_t i = 0; i < n; ++i) s << static_cast<double>(i) * dt << " " << a(static_cast<double>(i) * dt) / g << "\n";
  return write_temp(name, s.str());
}

// The CSV of --integrate: rows of t, a [g], v, d after the comment lines and the header.
std::vector<std::vector<double>> read_histories(const fs::path& file, std::string* header) {
  std::istringstream in(slurp(file));
  std::string line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header->empty()) {
      *header = line;
      continue;
    }
    std::vector<double> row;
    std::istringstream fields(line);
    std::string cell;
    while (std::getline(fields, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("trapezoid integration: closed forms of a sine, second order in dt", "[record][integrate]") {
  Errors previous;
  for (const double dt : {0.02, 0.01, 0.005, 0.0025}) {
    const Record r = sampled_record(dt, static_cast<std::size_t>(std::llround(4.0 / dt)) + 1, [](double t) { return std::sin(w * t); });
    const MotionHistories h = integrate_record(r);
    REQUIRE(h.velocity.size() == r.accel.size());
    CHECK(h.velocity[0] == 0.0);
    CHECK(h.displacement[0] == 0.0);
    CHECK(h.accel == r.accel);
    const Errors e = errors(h);
    INFO("dt = " << dt << ": errors v " << e.v << ", d " << e.d);
    CHECK(e.v < 2e-3);
    CHECK(e.d < 2e-3);
    if (previous.v > 0.0) {
      CHECK(previous.v / e.v == Approx(4.0).epsilon(0.1));  // halving dt divides the error by 4
      CHECK(previous.d / e.d == Approx(4.0).epsilon(0.1));
    }
    previous = e;
  }
  // Exact for a linear acceleration (the trapezoid rule integrates it exactly): a = t.
  const Record ramp = sampled_record(0.1, 11, [](double t) { return t; });
  const MotionHistories h = integrate_record(ramp);
  CHECK(h.velocity.back() == Approx(0.5).epsilon(1e-12));
}

TEST_CASE("baseline correction removes a constant offset's drift", "[record][integrate]") {
  // sin over 4 whole periods plus an offset of 0.05 m/s^2: uncorrected, v drifts by 0.05 t and
  // d by 0.025 t^2; removing the mean first leaves the sine's closed forms.
  const double offset = 0.05, dt = 0.005;
  const Record r = sampled_record(dt, 801, [&](double t) { return std::sin(w * t) + offset; });
  const Errors raw = errors(integrate_record(r));
  CHECK(raw.v == Approx(offset * 4.0).epsilon(0.02));
  CHECK(raw.d == Approx(0.5 * offset * 16.0).epsilon(0.02));
  const Errors corrected = errors(integrate_record(remove_baseline(r, 0)));
  CHECK(corrected.v < 0.01 * raw.v);
  CHECK(corrected.d < 0.01 * raw.d);
}

TEST_CASE("record process --integrate: t, a, v, d that the readers and spectrum take back", "[record][integrate][cli]") {
  const fs::path in = two_columns("sine-offset.txt", 0.01, 4.0, [](double t) { return std::sin(w * t) + 0.05; });
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / std::to_string(::getpid()) / "histories.csv";
  const auto r = run_cli("record process " + shell_word(in) + " --integrate --out " + shell_word(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains("t [s], a [g], v [m/s], d [m]"));
  std::string header;
  const auto rows = read_histories(out, &header);
  CHECK(header == "t [s],a [g],v [m/s],d [m]");
  REQUIRE(rows.size() == 401);
  // The columns are the library's integrals of the record as read.
  const Record input = read_record(in);
  const MotionHistories h = integrate_record(input);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() == 4);
    CHECK(rows[i][0] == Approx(0.01 * static_cast<double>(i)).margin(1e-12));
    CHECK(rows[i][1] * g == Approx(input.accel[i]).epsilon(1e-14).margin(1e-300));
    CHECK(rows[i][2] == Approx(h.velocity[i]).epsilon(1e-14).margin(1e-300));
    CHECK(rows[i][3] == Approx(h.displacement[i]).epsilon(1e-14).margin(1e-300));
  }
  // The readers take the acceleration back without options (columns t and a [g] found by name),
  // or with --accel-column; so does `adjoin spectrum`.
  const Record back = read_record(out);
  REQUIRE(back.accel.size() == input.accel.size());
  for (std::size_t i = 0; i < back.accel.size(); ++i) REQUIRE(back.accel[i] == Approx(input.accel[i]).epsilon(1e-14).margin(1e-300));
  CHECK(back.dt == Approx(0.01).epsilon(1e-12));
  RecordFormat by_name;
  by_name.accel_column = "a";
  CHECK(read_record(out, by_name).accel == back.accel);
  const auto spectrum = run_cli("spectrum " + shell_word(out) + " --accel-column 2 --out " + shell_word(out.string() + ".spectrum.csv"));
  INFO(spectrum.err);
  CHECK(spectrum.status == 0);
  const auto info = run_cli("record info " + shell_word(out));
  CHECK(info.status == 0);

  // With --baseline 0 the offset's drift is gone from the displacement.
  const auto corrected = run_cli("record process " + shell_word(in) + " --baseline 0 --integrate --out " + shell_word(out));
  REQUIRE(corrected.status == 0);
  header.clear();
  const auto rows0 = read_histories(out, &header);
  CHECK(std::abs(rows.back()[3]) == Approx(0.5 * 0.05 * 16.0 + 4.0 / w).epsilon(0.02));  // offset drift + t/w
  CHECK(std::abs(rows0.back()[3] - d_exact(4.0)) < 0.01);
}

TEST_CASE("plot record draws acceleration, velocity, displacement and the Husid plot", "[record][plot][cli]") {
  adjoin::test::needs_program("gnuplot");
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / std::to_string(::getpid()) / "plot_record";
  fs::create_directories(dir);
  const fs::path png = dir / "acat.png", svg = dir / "cosmos.svg";
  const auto r = run_cli("plot record " + shell_word(real + "/smc/A-CAT090.AT2.smc") + " --size 800x700 --out " + shell_word(png));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Contains("wrote") && Contains("acat.png"));
  adjoin::test::require_png(png, 800, 700);
  // SVG of a multi-channel file's channel: the panels' labels and D5-95 in the key.
  const auto s = run_cli("plot record " + shell_word(std::string(ADJOIN_SOURCE_DIR) + "/tests/data/records/cosmos-v2-two-channels.v2") +
                         " --channel 1 --out " + shell_word(svg));
  INFO(s.err);
  REQUIRE(s.status == 0);
  const std::string text = slurp(svg);
  CHECK_THAT(text, Contains("<svg") && Contains("a [g]") && Contains("v [m/s]") && Contains("d [m]") && Contains("Husid") &&
                       Contains("5-95"));
}

TEST_CASE("plot record on bad input: exit 2, the file or option named, no image left behind", "[record][plot][cli]") {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / std::to_string(::getpid()) / "plot_record_bad";
  fs::create_directories(dir);
  const auto missing = run_cli("plot record " + shell_word((dir / "none.AT2").string()) + " --out " + shell_word((dir / "none.png").string()));
  CHECK(missing.status == 2);
  CHECK_THAT(missing.err, Contains("error:") && Contains("none.AT2"));
  CHECK_FALSE(fs::exists(dir / "none.png"));
  const auto channels = run_cli("plot record " + shell_word(std::string(ADJOIN_SOURCE_DIR) + "/tests/data/records/cosmos-v2-two-channels.v2") +
                                " --out " + shell_word((dir / "c.png").string()));
  CHECK(channels.status == 2);
  CHECK_THAT(channels.err, Contains("--channel"));
  CHECK_FALSE(fs::exists(dir / "c.png"));
  const auto bad = run_cli("plot record " + shell_word(real + "/smc/A-CAT090.AT2.smc") + " --out " + shell_word((dir / "x.gif").string()));
  CHECK(bad.status == 2);
  CHECK_THAT(bad.err, Contains("error:") && Contains("x.gif"));
  CHECK_FALSE(fs::exists(dir / "x.gif"));
}
