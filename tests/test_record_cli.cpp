// `adjoin record info` through the command line: the project's real records (npts and dt from the
// records README, PGA checked against a plain stream read of the file), a synthetic sine with
// closed-form intensity measures, and defective files (exit 2, "error:", file and line).
// `adjoin record fourier`: its CSV against the library's spectra, and its plot (needs gnuplot).
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/intensity.hpp"
#include "adjoin/post/spectrum.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

namespace fs = std::filesystem;
const std::string records = ADJOIN_REAL_RECORDS;
const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "record_cli";
constexpr double g = 9.80665;

using Result = adjoin::test::CliResult;
using adjoin::test::slurp;

Result run(const std::string& arguments) {
  fs::create_directories(tmp);  // where the tests write their files
  return adjoin::test::run_cli(arguments);
}

std::string q(const std::string& path) { return "\"" + path + "\""; }

fs::path write(const std::string& name, const std::string& text) {
  fs::create_directories(tmp);
  const fs::path p = tmp / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// Max |value| of an AT2 file read with plain streams (4 header lines, then numbers).
double at2_peak(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 4; ++i) std::getline(in, line);
  double x = 0.0, peak = 0.0;
  while (in >> x) peak = std::max(peak, std::abs(x));
  return peak;
}

double two_column_peak(const std::string& path) {
  std::ifstream in(path);
  double t = 0.0, a = 0.0, peak = 0.0;
  while (in >> t >> a) peak = std::max(peak, std::abs(a));
  return peak;
}

}  // namespace

TEST_CASE("record info on the shared AT2 records: npts and dt of the README, PGA of the file", "[record_cli]") {
  struct Case {
    const char* file;
    std::size_t npts;
    double dt;
  };
  for (const Case& c : {Case{"peer/RSN175_IMPVALL.H_H-E12140.AT2", 7814, 0.005}, Case{"peer/RSN1546_CHICHI_TCU122-N.AT2", 18000, 0.005},
                        Case{"peer/RSN1044_DirRot2.AT2", 2000, 0.02}, Case{"peer/RSN8883_14383980_13849090.AT2", 16396, 0.005}}) {
    INFO(c.file);
    const std::string path = records + "/" + c.file;
    const Result r = run("record info --json " + q(path));
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["npts"].get<std::size_t>() == c.npts);
    CHECK(j["dt_s"].get<double>() == c.dt);
    CHECK(j["duration_s"].get<double>() == Approx(c.dt * (c.npts - 1)).epsilon(1e-12));
    CHECK(j["pga_g"].get<double>() == Approx(at2_peak(path)).epsilon(1e-12));  // the header says g
    CHECK(j["arias_m_s"].get<double>() > 0.0);
    CHECK(j["d5_95_s"].get<double>() > 0.0);
    CHECK(j["d5_95_s"].get<double>() < j["duration_s"].get<double>());
  }
}

TEST_CASE("record info on the shared two-column records", "[record_cli]") {
  struct Case {
    const char* file;
    const char* units;
    std::size_t npts;
    double to_g;
  };
  for (const Case& c : {Case{"two-column/elCentro.txt", "g", 1559, 1.0}, Case{"two-column/elcentro_NS_full.dat", "g", 2688, 1.0},
                        Case{"two-column/Kobe.dat", "m/s2", 1250, 1.0 / g}}) {
    INFO(c.file);
    const std::string path = records + "/" + c.file;
    const Result r = run(std::string("record info --json --units ") + c.units + " " + q(path));
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["npts"].get<std::size_t>() == c.npts);
    CHECK(j["dt_s"].get<double>() == 0.02);
    CHECK(j["pga_g"].get<double>() == Approx(two_column_peak(path) * c.to_g).epsilon(1e-12));
    // Without units: exit 2, naming the file and the option.
    const Result bad = run("record info " + q(path));
    CHECK(bad.status == 2);
    CHECK_THAT(bad.err, StartsWith("error:") && Contains(c.file) && Contains("--units"));
  }
  // Chopra's El Centro digitisation has PGA 0.319 g.
  const Result r = run("record info --json --units g " + q(records + "/two-column/elCentro.txt"));
  CHECK(nlohmann::json::parse(r.out)["pga_g"].get<double>() == Approx(0.319).margin(0.001));
}

TEST_CASE("record info of a synthetic sine matches closed forms", "[record_cli]") {
  // a = A sin(2 pi f t) in cm/s2 over whole cycles: Arias = pi A^2 T / (4 g), D5-95 = 0.9 T,
  // predominant period 1/f, PGA = A.
  const double A = 150.0, f = 2.5, dt = 0.004, T = 8.0;
  std::ostringstream text;
  text << std::setprecision(17) << "# synthetic\n";
  for (int i = 0; i <= 2000; ++i) text << i * dt << "\t" << A * std::sin(2.0 * std::numbers::pi * f * i * dt) << "\n";
  const fs::path p = write("sine.txt", text.str());
  const Result r = run("record info --json --units cm/s2 " + q(p.string()));
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.out);
  const double a = A / 100.0;
  CHECK(j["npts"].get<std::size_t>() == 2001);
  CHECK(j["dt_s"].get<double>() == dt);
  CHECK(j["pga_g"].get<double>() == Approx(a / g).epsilon(1e-9));
  CHECK(j["arias_m_s"].get<double>() == Approx(std::numbers::pi * a * a * T / (4.0 * g)).epsilon(1e-9));
  // Chords under |sin|: the trapezoid error (w dt)^2 / 12 of the integral, w = 2 pi f.
  const double w_dt = 2.0 * std::numbers::pi * f * dt;
  CHECK(j["cav_m_s"].get<double>() == Approx(2.0 * a * T / std::numbers::pi * (1.0 - w_dt * w_dt / 12.0)).epsilon(1e-5));
  CHECK(j["d5_95_s"].get<double>() == Approx(0.9 * T).margin(1e-3));
  CHECK(j["pgv_m_s"].get<double>() == Approx(a / (std::numbers::pi * f)).epsilon(1e-3));  // v = A(1-cos)/(2 pi f)
  CHECK(j["predominant_period_s"].get<double>() == Approx(1.0 / f).epsilon(1e-3));

  // The table names every measure; --out writes the same by temporary file and rename.
  const Result table = run("record info --units cm/s2 " + q(p.string()));
  REQUIRE(table.status == 0);
  for (const char* word : {"npts", "dt", "duration", "PGA", "PGV", "PGD", "Arias", "CAV", "D5-95", "predominant period"})
    CHECK_THAT(table.out, Contains(word));
  const fs::path out = tmp / "info.txt";
  fs::remove(out);
  REQUIRE(run("record info --units cm/s2 --out " + q(out.string()) + " " + q(p.string())).status == 0);
  CHECK(slurp(out) == table.out);
  for (const auto& entry : fs::directory_iterator(tmp)) CHECK_THAT(entry.path().filename().string(), !Contains(".tmp."));
}

TEST_CASE("record info on defective files: exit 2, error: file:line", "[record_cli]") {
  const std::string at2_head = "PEER NGA STRONG MOTION DATABASE RECORD\nEvent\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  6, DT=   .0100 SEC,\n";
  struct Case {
    const char* name;
    std::string text;
    const char* where;
    const char* what;
  };
  const Case cases[] = {
      {"token.AT2", at2_head + "  .1  .2  .3\n  .4  x.5 .6\n", "token.AT2:6:", "not a number"},
      {"nan.AT2", at2_head + "  .1  .2  .3\n  .4  NaN .6\n", "nan.AT2:6:", "finite"},
      {"npts.AT2", at2_head + "  .1  .2  .3\n  .4  .5\n", "npts.AT2:6:", "NPTS = 6"},
      {"extra.AT2", at2_head + "  .1  .2  .3\n  .4  .5 .6\n .7\n", "extra.AT2:7:", "more values than NPTS"},
      {"empty.txt", "", "empty.txt:1:", "empty"},
      {"blank.txt", "\n  \n", "blank.txt:2:", "empty"},
      {"uneven.txt", "0.00 1\n0.02 2\n0.04 3\n0.07 4\n0.08 5\n", "uneven.txt:4:", "uniform"},
      {"back.txt", "0.00 1\n0.02 2\n0.01 3\n", "back.txt:3:", "does not increase"},
      {"nan.txt", "0.00 1\n0.02 nan\n", "nan.txt:2:", "finite"},
      {"short.txt", "0.00 1\n0.02 2\n0.04\n", "short.txt:3:", "expected 2 numbers"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const fs::path p = write(c.name, c.text);
    const Result r = run("record info --units g " + q(p.string()));
    CHECK(r.status == 2);
    CHECK_THAT(r.err, StartsWith("error:") && Contains(c.where) && Contains(c.what));
    CHECK(r.out.empty());
  }
  const fs::path ok = write("ok.txt", "0 1\n0.1 2\n");
  CHECK(run("record info --units furlongs " + q(ok.string())).status == 2);
  CHECK(run("record info --units g --format xml " + q(ok.string())).status == 2);
  const Result missing = run("record info --units g " + q((tmp / "no-such-file.txt").string()));
  CHECK(missing.status == 2);
  CHECK_THAT(missing.err, StartsWith("error:") && Contains("no-such-file.txt"));
  CHECK(run("record").status == 2);
}

TEST_CASE("record fourier: raw and Konno-Ohmachi smoothed spectra equal the library's", "[record_cli]") {
  const std::string file = records + "/peer/RSN175_IMPVALL.H_H-E12140.AT2";
  const adjoin::Record record = adjoin::read_record(file);
  const adjoin::FourierSpectrum raw = adjoin::fourier_amplitude_spectrum(record);
  // CSV rows "f,a" -> numbers (10 significant digits).
  auto rows = [](const std::string& csv) {
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);
    CHECK(line == "frequency,amplitude");
    std::vector<std::pair<double, double>> out;
    double f = 0.0, a = 0.0;
    char comma = 0;
    while (in >> f >> comma >> a) out.emplace_back(f, a);
    return out;
  };

  const Result plain = run("record fourier " + q(file));
  REQUIRE(plain.status == 0);
  const auto r = rows(plain.out);
  REQUIRE(r.size() == raw.frequency.size());
  REQUIRE(r.size() == record.accel.size() / 2 + 1);
  for (std::size_t k = 0; k < r.size(); k += 97) {
    INFO("k = " << k);
    CHECK(r[k].first == Approx(raw.frequency[k]).epsilon(1e-9));
    CHECK(r[k].second == Approx(raw.amplitude[k]).epsilon(1e-9).margin(1e-300));
  }

  const fs::path out = tmp / "fourier.csv";
  const Result smooth = run("record fourier " + q(file) + " --smooth 30 --frequencies 0.2:20:30 --out " + q(out.string()));
  REQUIRE(smooth.status == 0);
  const auto s = rows(slurp(out));
  const std::vector<double> centres = adjoin::period_range(0.2, 20.0, 30, adjoin::PeriodSpacing::log);
  const std::vector<double> expected = adjoin::konno_ohmachi(raw, centres, 30.0);
  REQUIRE(s.size() == 30);
  for (std::size_t k = 0; k < s.size(); ++k) {
    CHECK(s[k].first == Approx(centres[k]).epsilon(1e-9));
    CHECK(s[k].second == Approx(expected[k]).epsilon(1e-9));
  }
  // Default points: 200 from 0.1 Hz to 50 Hz (the Nyquist frequency is 100 Hz here).
  const auto d = rows(run("record fourier " + q(file) + " --smooth 40").out);
  REQUIRE(d.size() == 200);
  CHECK(d.front().first == Approx(0.1));
  CHECK(d.back().first == Approx(50.0));

  for (const std::string bad : {"--smooth -1", "--frequencies 0:1:10", "--frequencies 1:2", "--frequencies 1:2:1.5",
                                "--plot spectrum.pdf"}) {
    INFO(bad);
    const Result e = run("record fourier " + q(file) + " " + bad);
    CHECK(e.status == 2);
    CHECK_THAT(e.err, StartsWith("error:") && Contains(bad.substr(0, bad.find(' '))));
  }
}

TEST_CASE("record fourier --plot draws the smoothed spectrum as a PNG", "[record_cli][plot]") {
  adjoin::test::needs_program("gnuplot");
  const std::string file = records + "/peer/RSN175_IMPVALL.H_H-E12140.AT2";
  const fs::path out = tmp / "fourier-plotted.csv", png = tmp / "fourier.png";
  fs::remove(png);
  const Result drawn = run("record fourier " + q(file) + " --smooth 40 --out " + q(out.string()) + " --plot " + q(png.string()));
  INFO(drawn.err);
  REQUIRE(drawn.status == 0);
  adjoin::test::require_png(png, 900, 600);
  const std::string csv = slurp(out);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 201);  // the header and the 200 default frequencies
}
