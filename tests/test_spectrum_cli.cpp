// `adjoin spectrum`: its CSV against the library's spectra (post/spectrum, tested in
// test_spectrum.cpp), --peaks samples, --target ratios, the plot (needs gnuplot) and bad input.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"

namespace fs = std::filesystem;
using namespace adjoin;

namespace {

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

// The seven numbers of a `period,damping,sd,sv,sa,psv,psa` row (empty if it does not parse).
std::vector<double> csv_row(const std::string& line) {
  std::vector<double> values(7);
  char comma = 0;
  std::istringstream row(line);
  row >> values[0];
  for (std::size_t i = 1; i < 7; ++i) row >> comma >> values[i];
  if (row.fail()) values.clear();
  return values;
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("adjoin spectrum: CSV to a file and to stdout", "[spectrum][cli]") {
  const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "spectrum";
  fs::create_directories(tmp);
  const fs::path out = tmp / "elcentro.csv";
  fs::remove(out);
  const std::string record = std::string(ADJOIN_REAL_RECORDS) + "/two-column/elCentro.txt";
  const std::string cli = ADJOIN_CLI;
  REQUIRE(run(cli + " spectrum '" + record + "' --units g --damping 0.05,0.02 --range 0.1:2:20:log --out '" +
              out.string() + "'") == 0);
  const std::string text = slurp(out);
  std::istringstream lines(text);
  std::string header;
  std::getline(lines, header);
  CHECK(header == "period,damping,sd,sv,sa,psv,psa");
  int rows = 0;
  std::string line;
  while (std::getline(lines, line)) {
    ++rows;
    CHECK(csv_row(line).size() == 7);
  }
  CHECK(rows == 40);

  // Periods given as a list, to stdout; El Centro at 2 %, T = 1 s: 5.97 in (Chopra).
  const fs::path stdout_file = tmp / "stdout.csv";
  REQUIRE(run(cli + " spectrum '" + record + "' --units g --damping 0.02 --periods 0,0.5,1 > '" +
              stdout_file.string() + "'") == 0);
  const std::string printed = slurp(stdout_file);
  CHECK(printed.rfind("period,damping,sd,sv,sa,psv,psa\n", 0) == 0);
  CHECK(std::count(printed.begin(), printed.end(), '\n') == 4);
  std::istringstream p(printed);
  std::getline(p, line);
  std::getline(p, line);
  std::getline(p, line);
  std::getline(p, line);  // T = 1
  double period = 0.0, damping = 0.0, sd = 0.0;
  char comma;
  std::istringstream row(line);
  row >> period >> comma >> damping >> comma >> sd;
  CHECK(period == 1.0);
  CHECK(sd / 0.0254 == Approx(5.97).epsilon(0.015));
}

TEST_CASE("adjoin spectrum --peaks samples: the exact response's largest sampled values", "[spectrum][cli]") {
  // For comparison with tools that report peaks at the samples: one exact step per sample, no
  // sub-steps (T = dt would otherwise get 10), no search between samples.
  const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "spectrum";
  fs::create_directories(tmp);
  const fs::path file = fs::path(ADJOIN_REAL_RECORDS) / "two-column" / "elCentro.txt";
  RecordFormat format;
  format.units = AccelUnit::g;
  const Record record = read_record(file, format);
  auto spectrum_row = [&](const std::string& peaks) {
    const fs::path out = tmp / ("peaks-" + peaks + ".csv");
    REQUIRE(run(std::string(ADJOIN_CLI) + " spectrum '" + file.string() + "' --units g --periods 0.02 --peaks " +
                peaks + " --out '" + out.string() + "'") == 0);
    std::istringstream lines(slurp(out));
    std::string line;
    std::getline(lines, line);
    std::getline(lines, line);
    const std::vector<double> values = csv_row(line);
    REQUIRE(values.size() == 7);
    return values;
  };
  const std::vector<double> samples = spectrum_row("samples"), exact = spectrum_row("exact");
  const OscillatorHistory h = oscillator_response(record.dt, record.accel, 0.02, 0.05);
  // The CSV carries 10 significant digits.
  CHECK(samples[2] == Approx(max_abs(h.u)).epsilon(1e-9));
  CHECK(samples[3] == Approx(max_abs(h.v)).epsilon(1e-9));
  CHECK(samples[4] == Approx(max_abs(h.a_abs) / kStandardGravity).epsilon(1e-9));
  // At T = dt the samples miss the peaks by several per cent (SV most of all).
  CHECK(exact[2] > samples[2]);
  CHECK(exact[3] > 1.01 * samples[3]);
  CHECK(exact[4] > samples[4]);
}

TEST_CASE("adjoin spectrum --target: PSA against an EC8 spectrum, per damping", "[spectrum][cli]") {
  // The printed ratios are those of the CSV's PSA to the code's spectrum with eta(damping).
  const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "spectrum";
  fs::create_directories(tmp);
  const std::string record = std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN1044_DirRot2.AT2";
  const fs::path csv = tmp / "target.csv", err = tmp / "target.err";
  REQUIRE(run(std::string(ADJOIN_CLI) + " spectrum '" + record + "' --periods 0.1,0.3,0.6,1.5 --damping 0.05,0.02 " +
              "--target ec8:C:0.3:2 --out '" + csv.string() + "' 2> '" + err.string() + "'") == 0);
  std::istringstream lines(slurp(csv));
  std::string line;
  std::getline(lines, line);
  double low[2] = {1e300, 1e300}, high[2] = {0.0, 0.0}, sum[2] = {0.0, 0.0};
  while (std::getline(lines, line)) {
    const std::vector<double> row = csv_row(line);
    REQUIRE(row.size() == 7);
    const std::size_t d = row[1] == 0.05 ? 0 : 1;
    const double ratio = row[6] / ec8_psa(row[0], 'C', 0.3, 2, row[1]);
    low[d] = std::min(low[d], ratio);
    high[d] = std::max(high[d], ratio);
    sum[d] += ratio;
  }
  const std::string printed = slurp(err);
  std::istringstream messages(printed);
  for (std::size_t d = 0; d < 2; ++d) {
    REQUIRE(std::getline(messages, line));
    INFO(line);
    CHECK(line.rfind("target EC8 type 2, ground C, ag = 0.3 g, damping " + std::string(d == 0 ? "5" : "2") + " %", 0) == 0);
    double from = 0.0, to = 0.0, mean = 0.0;
    REQUIRE(std::sscanf(line.c_str() + line.find("from "), "from %lf", &from) == 1);
    REQUIRE(std::sscanf(line.c_str() + line.find(") to "), ") to %lf", &to) == 1);
    REQUIRE(std::sscanf(line.c_str() + line.find("mean "), "mean %lf", &mean) == 1);
    CHECK(from == Approx(low[d]).epsilon(1e-3));
    CHECK(to == Approx(high[d]).epsilon(1e-3));
    CHECK(mean == Approx(sum[d] / 4.0).epsilon(1e-3));
  }
  // A target that is neither: exit 2, naming the option.
  CHECK(run(std::string(ADJOIN_CLI) + " spectrum '" + record + "' --target ec8:Z 2> '" + err.string() + "' > /dev/null") == 2);
  CHECK(slurp(err).find("--target") != std::string::npos);
}

TEST_CASE("adjoin spectrum --plot draws PNG and SVG", "[spectrum][cli][plot]") {
  adjoin::test::needs_program("gnuplot");
  const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "spectrum";
  fs::create_directories(tmp);
  const std::string record = std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN175_IMPVALL.H_H-E12140.AT2";
  const std::string cli = ADJOIN_CLI;
  const fs::path csv = tmp / "impvall.csv";
  for (const char* name : {"impvall.png", "impvall.svg"}) {
    INFO(name);
    const fs::path plot = tmp / name;
    fs::remove(plot);
    const int status = run(cli + " spectrum '" + record + "' --target ec8:B --out '" + csv.string() + "' --plot '" +
                           plot.string() + "' 2> '" + (tmp / "plot.err").string() + "'");
    INFO(slurp(tmp / "plot.err"));
    REQUIRE(status == 0);
    if (plot.extension() == ".png") {
      adjoin::test::require_png(plot, 900, 900);  // PSA over SD: a taller figure
    } else {
      const std::string svg = slurp(plot);
      CHECK(svg.find("<svg") != std::string::npos);
      CHECK(svg.find("EC8") != std::string::npos);  // the target's curve is in the key
    }
  }
}

TEST_CASE("adjoin spectrum --plot without gnuplot: exit 2, the CSV kept, no image", "[spectrum][cli]") {
  const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "spectrum";
  fs::create_directories(tmp);
  const std::string record = std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN175_IMPVALL.H_H-E12140.AT2";
  const std::string cli = ADJOIN_CLI;
  const fs::path csv = tmp / "impvall.csv";
  const fs::path plot = tmp / "nognuplot.png";
  fs::remove(plot);
  fs::remove(csv);
  const fs::path err = tmp / "nognuplot.err";
  const int status = run("PATH=/nonexistent '" + cli + "' spectrum '" + record + "' --out '" + csv.string() +
                         "' --plot '" + plot.string() + "' 2> '" + err.string() + "'");
  CHECK(status == 2);  // the user's setup to fix; never 1 (outside the contract)
  CHECK(slurp(err).rfind("error:", 0) == 0);
  CHECK(slurp(err).find("gnuplot") != std::string::npos);
  CHECK(slurp(err).find("(kept)") != std::string::npos);
  CHECK(fs::exists(csv));
  CHECK_FALSE(fs::exists(plot));
}

TEST_CASE("adjoin spectrum: bad input exits 2 with error:", "[spectrum][cli]") {
  const fs::path tmp = fs::path(ADJOIN_TEST_TMP) / "spectrum";
  fs::create_directories(tmp);
  const std::string record = std::string(ADJOIN_REAL_RECORDS) + "/two-column/elCentro.txt";
  const std::string cli = ADJOIN_CLI;
  const fs::path err = tmp / "bad.err";
  struct Case {
    std::string args, mention;
  };
  const std::vector<Case> cases{
      {"'" + record + "' --units furlongs", "--units"},
      {"'" + record + "' --units g --damping -0.05", "--damping"},
      {"'" + record + "' --units g --damping 0.05,x", "--damping"},
      {"'" + record + "' --units g --periods 0.1,-2", "--periods"},
      {"'" + record + "' --units g --range 1:0.1:10", "--range"},
      {"'" + record + "' --units g --range 0.1:1", "--range"},
      {"'" + record + "' --units g --range 0:1:10:log", "--range"},
      {"'" + record + "' --units g --range 0.1:1:10:cubic", "--range"},
      {"'" + record + "' --units g --plot spectrum.pdf", "--plot"},
      {"'" + record + "' --units g --peaks sometimes", "--peaks"},
      {"'" + (tmp / "no-such-record.at2").string() + "' --units g", "no-such-record.at2"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    CHECK(run(cli + " spectrum " + c.args + " > /dev/null 2> '" + err.string() + "'") == 2);
    const std::string message = slurp(err);
    INFO(message);
    CHECK(message.rfind("error:", 0) == 0);
    CHECK(message.find(c.mention) != std::string::npos);
  }
}
