// Suites of records (`adjoin spectrum --suite`, post/suite.hpp): the statistics and the scaling
// are checked against what the command wrote, recomputed here by hand from its per-record CSV
// files (read with a parser of the test's own), and the factors against the spectra of records
// scaled by them. Refusals are in tests/bad_inputs/suites.toml.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/post/suite.hpp"
#include "cli_helpers.hpp"

namespace {

namespace fs = std::filesystem;
using adjoin::test::run_cli;

const std::string kRecords = ADJOIN_REAL_RECORDS;
// Four records of two formats, two sampling intervals (0.02 s and 0.005 s) and two units.
const std::vector<std::string> kSuite = {
    kRecords + "/peer/RSN1044_DirRot2.AT2", kRecords + "/peer/RSN175_IMPVALL.H_H-E12140.AT2",
    kRecords + "/smc/A-CAT090.AT2.smc", kRecords + "/smc/A-CAT180.AT2.smc"};

// A CSV file as columns of text, by header name (empty cells kept as "").
struct Csv {
  std::map<std::string, std::vector<std::string>> text;
  std::size_t rows = 0;
  std::vector<double> num(const std::string& column) const {
    std::vector<double> out;
    for (const std::string& cell : text.at(column)) out.push_back(std::stod(cell));
    return out;
  }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

Csv read_csv(const fs::path& file) {
  std::ifstream in(file);
  REQUIRE(in);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  Csv csv;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    REQUIRE(cells.size() == header.size());
    for (std::size_t c = 0; c < header.size(); ++c) csv.text[header[c]].push_back(cells[c]);
    ++csv.rows;
  }
  return csv;
}

std::string quoted(const std::vector<std::string>& files) {
  std::string s;
  for (const std::string& f : files) s += " '" + f + "'";
  return s;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / name;
  fs::remove_all(dir);
  return dir;
}

double relative(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// The ASCE 7 table, interpolated linearly in period (independent of TargetSpectrum).
double asce7(double period) {
  static const std::vector<std::pair<double, double>> table = [] {
    std::vector<std::pair<double, double>> rows;
    std::ifstream in(kRecords + "/targets/ASCE7.txt");
    double t = 0.0, a = 0.0;
    while (in >> t >> a) rows.emplace_back(t, a);
    return rows;
  }();
  const auto hi = std::lower_bound(table.begin(), table.end(), std::make_pair(period, -1.0));
  REQUIRE(hi != table.end());
  if (hi->first == period || hi == table.begin()) return hi->second;
  const auto lo = hi - 1;
  return lo->second + (hi->second - lo->second) * (period - lo->first) / (hi->first - lo->first);
}

}  // namespace

TEST_CASE("suite statistics equal a direct computation from the per-record CSV files", "[suite][cli]") {
  const fs::path out = fresh_dir("suite_stats");
  const auto r = run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:4:9 --damping 0.05,0.02 --out '" +
                         out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("suite of 4 records") != std::string::npos);
  CHECK(!fs::exists(out / "factors.csv"));  // not scaled

  std::vector<Csv> each;
  for (const std::string& file : kSuite) {
    const fs::path csv = out / (fs::path(file).filename().string() + ".csv");
    each.push_back(read_csv(csv));
    // Each record's file is its own single spectrum, whatever its dt.
    const fs::path single = fs::path(ADJOIN_TEST_TMP) / "suite_single.csv";
    REQUIRE(run_cli("spectrum '" + file + "' --range 0.05:4:9 --damping 0.05,0.02 --out '" + single.string() + "'")
                .status == 0);
    CHECK(adjoin::test::slurp(csv) == adjoin::test::slurp(single));
  }
  const Csv suite = read_csv(out / "suite.csv");
  REQUIRE(suite.rows == 18);
  const std::vector<double> mean = suite.num("mean"), median = suite.num("median"), lo = suite.num("minus1sigma"),
                            hi = suite.num("plus1sigma");
  for (std::size_t row = 0; row < suite.rows; ++row) {
    std::vector<double> psa;
    for (const Csv& c : each) {
      REQUIRE(c.text.at("period")[row] == suite.text.at("period")[row]);
      REQUIRE(c.text.at("damping")[row] == suite.text.at("damping")[row]);
      psa.push_back(c.num("psa")[row]);
    }
    double m = 0.0;
    for (double a : psa) m += std::log(a) / 4.0;
    double ss = 0.0;
    for (double a : psa) ss += (std::log(a) - m) * (std::log(a) - m);
    const double sigma = std::sqrt(ss / 3.0);  // sample standard deviation, n - 1
    std::sort(psa.begin(), psa.end());
    INFO("row " << row);
    CHECK(relative(mean[row], std::exp(m)) < 1e-9);
    CHECK(relative(median[row], 0.5 * (psa[1] + psa[2])) < 1e-9);  // even count: the two middle ones
    CHECK(relative(lo[row], std::exp(m - sigma)) < 1e-9);
    CHECK(relative(hi[row], std::exp(m + sigma)) < 1e-9);
    CHECK(lo[row] < mean[row]);
    CHECK(mean[row] < hi[row]);
  }
}

TEST_CASE("a suite from a folder takes the files a reader recognises and says which it skipped", "[suite][cli]") {
  const fs::path in = fresh_dir("suite_folder_in"), out = fresh_dir("suite_folder_out");
  fs::create_directories(in);
  for (std::size_t k = 0; k < 3; ++k) fs::copy_file(kSuite[k], in / fs::path(kSuite[k]).filename());
  std::ofstream(in / "notes.txt") << "0 0.1\n0.02 0.3\n";
  const auto r = run_cli("spectrum '" + in.string() + "' --periods 0.1,0.3,1 --out '" + out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("suite of 3 records") != std::string::npos);
  CHECK(r.err.find("warning: skipped " + (in / "notes.txt").string()) != std::string::npos);
  CHECK(!fs::exists(out / "notes.txt.csv"));
  const Csv suite = read_csv(out / "suite.csv");
  REQUIRE(suite.rows == 3);
  for (std::size_t row = 0; row < 3; ++row) {
    std::vector<double> psa;
    for (std::size_t k = 0; k < 3; ++k)
      psa.push_back(read_csv(out / (fs::path(kSuite[k]).filename().string() + ".csv")).num("psa")[row]);
    std::sort(psa.begin(), psa.end());
    CHECK(relative(suite.num("median")[row], psa[1]) < 1e-9);  // odd count: the middle one
  }
}

TEST_CASE("scaling lifts the suite mean to 90 percent of the target at its lowest point in the band", "[suite][cli]") {
  const fs::path out = fresh_dir("suite_scaled");
  const std::string target = kRecords + "/targets/ASCE7.txt";
  const auto r = run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:5:25 --target '" + target +
                         "' --t1 0.7 --out '" + out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("scaled mean / target: 0.9 at T =") != std::string::npos);

  const Csv factors = read_csv(out / "factors.csv");
  REQUIRE(factors.rows == 4);
  std::vector<double> f = factors.num("factor");
  std::vector<std::vector<double>> psa;
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(factors.text.at("record")[k] == kSuite[k]);
    psa.push_back(read_csv(out / (fs::path(kSuite[k]).filename().string() + ".csv")).num("psa"));
  }
  const Csv suite = read_csv(out / "suite.csv");
  const std::vector<double> periods = suite.num("period"), scaled_mean = suite.num("scaled_mean");
  const double band_min = 0.2 * 0.7, band_max = 2.0 * 0.7;
  // The band's ends are among the periods (25 asked + 2).
  REQUIRE(suite.rows == 27);
  CHECK(std::count_if(periods.begin(), periods.end(), [&](double t) { return relative(t, band_min) < 1e-9; }) == 1);
  CHECK(std::count_if(periods.begin(), periods.end(), [&](double t) { return relative(t, band_max) < 1e-9; }) == 1);

  double lowest = 1e300, at = 0.0;
  for (std::size_t i = 0; i < suite.rows; ++i) {
    double m = 0.0;
    for (std::size_t k = 0; k < 4; ++k) m += std::log(f[k] * psa[k][i]) / 4.0;
    INFO("T = " << periods[i]);
    CHECK(relative(scaled_mean[i], std::exp(m)) < 1e-8);  // the factors reproduce the scaled mean
    CHECK(relative(suite.num("target")[i], asce7(periods[i])) < 1e-9);
    if (periods[i] < band_min * (1 - 1e-9) || periods[i] > band_max * (1 + 1e-9)) continue;
    const double ratio = std::exp(m) / asce7(periods[i]);
    if (ratio < lowest) lowest = ratio, at = periods[i];
  }
  CHECK(std::abs(lowest - 0.9) < 1e-8);
  CHECK(at >= band_min * (1 - 1e-9));
  CHECK(at <= band_max * (1 + 1e-9));

  // The fit rule: each factor is one common multiplier times the record's own least-squares
  // level in ln PSA over the band, exp(mean ln(target / PSA_k)).
  std::vector<double> common;
  for (std::size_t k = 0; k < 4; ++k) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < suite.rows; ++i)
      if (periods[i] >= band_min * (1 - 1e-9) && periods[i] <= band_max * (1 + 1e-9)) {
        sum += std::log(asce7(periods[i]) / psa[k][i]);
        ++count;
      }
    common.push_back(f[k] / std::exp(sum / count));
  }
  for (double c : common) CHECK(relative(c, common[0]) < 1e-7);

  // --scaling uniform: one factor for all, the same lowest ratio.
  const fs::path uniform = fresh_dir("suite_uniform");
  REQUIRE(run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:5:25 --target '" + target +
                  "' --t1 0.7 --scaling uniform --out '" + uniform.string() + "'")
              .status == 0);
  const std::vector<double> g = read_csv(uniform / "factors.csv").num("factor");
  for (double x : g) CHECK(relative(x, g[0]) < 1e-12);
  const std::vector<double> u_mean = read_csv(uniform / "suite.csv").num("scaled_mean");
  double u_lowest = 1e300;
  for (std::size_t i = 0; i < suite.rows; ++i)
    if (periods[i] >= band_min * (1 - 1e-9) && periods[i] <= band_max * (1 + 1e-9))
      u_lowest = std::min(u_lowest, u_mean[i] / asce7(periods[i]));
  CHECK(std::abs(u_lowest - 0.9) < 1e-8);
}

TEST_CASE("adjoin spectrum --band scales the suite over a period band of two buildings, as computed here by hand", "[suite][cli]") {
  // Two buildings, T1 = 0.5 s and 0.95 s: the band 0.2 x 0.5 ... 2 x 0.95 = 0.1 ... 1.9 s.
  const fs::path out = fresh_dir("suite_band");
  const std::string target = kRecords + "/targets/ASCE7.txt";
  const auto r = run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:5:25 --target '" + target +
                         "' --band 0.1,1.9 --out '" + out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("over 0.1 ... 1.9 s (--band,") != std::string::npos);
  const std::vector<double> f = read_csv(out / "factors.csv").num("factor");
  REQUIRE(f.size() == 4);
  std::vector<std::vector<double>> psa;
  for (const std::string& record : kSuite) psa.push_back(read_csv(out / (fs::path(record).filename().string() + ".csv")).num("psa"));
  const std::vector<double> periods = read_csv(out / "suite.csv").num("period");
  const double band_min = 0.1, band_max = 1.9;
  CHECK(std::count(periods.begin(), periods.end(), band_min) == 1);  // the band's ends are computed
  CHECK(std::count(periods.begin(), periods.end(), band_max) == 1);
  const auto in_band = [&](double t) { return t >= band_min * (1 - 1e-12) && t <= band_max * (1 + 1e-12); };

  // By hand: a_k = exp(mean over the band of ln(target / PSA_k)); c lifts the lowest ratio of
  // the geometric mean of a_k PSA_k to the target over the band to 0.9; factor_k = c a_k.
  std::vector<double> a;
  for (std::size_t k = 0; k < 4; ++k) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < periods.size(); ++i)
      if (in_band(periods[i])) sum += std::log(asce7(periods[i]) / psa[k][i]), ++count;
    REQUIRE(count >= 10);
    a.push_back(std::exp(sum / count));
  }
  double lowest = 1e300;
  for (std::size_t i = 0; i < periods.size(); ++i) {
    if (!in_band(periods[i])) continue;
    double m = 0.0;
    for (std::size_t k = 0; k < 4; ++k) m += std::log(a[k] * psa[k][i]) / 4.0;
    lowest = std::min(lowest, std::exp(m) / asce7(periods[i]));
  }
  for (std::size_t k = 0; k < 4; ++k) {
    INFO("record " << kSuite[k]);
    CHECK(relative(f[k], 0.9 / lowest * a[k]) < 1e-8);
  }
  // A different band gives different factors (the band is used), and the band
  // 0.2 T1 ... 2 T1 the factors --t1 T1 gives, to the last digit written.
  const fs::path narrow = fresh_dir("suite_band_narrow");
  REQUIRE(run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:5:25 --target '" + target +
                  "' --band 0.5,1.0 --out '" + narrow.string() + "'").status == 0);
  CHECK(relative(read_csv(narrow / "factors.csv").num("factor")[0], f[0]) > 1e-3);
  const fs::path by_band = fresh_dir("suite_band_t1"), by_t1 = fresh_dir("suite_t1_band");
  REQUIRE(run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:5:25 --target '" + target +
                  "' --band 0.14,1.4 --out '" + by_band.string() + "'").status == 0);
  REQUIRE(run_cli("spectrum --suite" + quoted(kSuite) + " --range 0.05:5:25 --target '" + target +
                  "' --t1 0.7 --out '" + by_t1.string() + "'").status == 0);
  CHECK(read_csv(by_band / "factors.csv").text == read_csv(by_t1 / "factors.csv").text);
}

TEST_CASE("a record scaled by its factor has its spectrum scaled by exactly that factor", "[suite][cli]") {
  const fs::path out = fresh_dir("suite_factor");
  const std::vector<std::string> pair(kSuite.begin(), kSuite.begin() + 2);
  REQUIRE(run_cli("spectrum --suite" + quoted(pair) + " --range 0.1:3:6 --target ec8:B --t1 1 --out '" +
                  out.string() + "'")
              .status == 0);
  const double f = read_csv(out / "factors.csv").num("factor")[0];
  const Csv spectrum = read_csv(out / "RSN1044_DirRot2.AT2.csv");

  // The record times f, written in g with every digit, through the single spectrum.
  const adjoin::Record record = adjoin::read_record(pair[0]);
  const fs::path scaled = fs::path(ADJOIN_TEST_TMP) / "suite_scaled_record.txt";
  {
    std::ofstream file(scaled);
    char line[80];
    for (std::size_t i = 0; i < record.accel.size(); ++i) {
      std::snprintf(line, sizeof line, "%.17g %.17g\n", static_cast<double>(i) * record.dt,
                    f * record.accel[i] / 9.80665);
      file << line;
    }
  }
  const fs::path single = fs::path(ADJOIN_TEST_TMP) / "suite_scaled_spectrum.csv";
  const std::string periods = spectrum.text.at("period")[0] + [&] {
    std::string s;
    for (std::size_t i = 1; i < spectrum.rows; ++i) s += "," + spectrum.text.at("period")[i];
    return s;
  }();
  REQUIRE(run_cli("spectrum '" + scaled.string() + "' --units g --periods " + periods + " --out '" + single.string() +
                  "'")
              .status == 0);
  const Csv s = read_csv(single);
  REQUIRE(s.rows == spectrum.rows);
  for (const char* column : {"sd", "sv", "sa", "psv", "psa"})
    for (std::size_t i = 0; i < s.rows; ++i) {
      INFO(column << " at T = " << spectrum.text.at("period")[i]);
      CHECK(relative(s.num(column)[i], f * spectrum.num(column)[i]) < 1e-8);
    }
}

TEST_CASE("suite_statistics by hand on three spectra, and its refusals", "[suite]") {
  auto spectrum = [](std::vector<double> psa) {
    adjoin::ResponseSpectrum s;
    s.periods = {0.5, 1.0};
    s.dampings = {0.05};
    for (std::size_t i = 0; i < 2; ++i) s.values.push_back({s.periods[i], 0.05, 0.0, 0.0, 0.0, 0.0, psa[i]});
    return s;
  };
  const double e = std::exp(1.0);
  std::vector<adjoin::ResponseSpectrum> three{spectrum({1.0, 2.0}), spectrum({e, 2.0}), spectrum({e * e, 2.0})};
  const adjoin::SuiteStatistics s = adjoin::suite_statistics(three);
  // ln PSA = 0, 1, 2: mean 1, sample sigma 1.
  CHECK(s.mean[0] == Approx(e).epsilon(1e-14));
  CHECK(s.median[0] == Approx(e).epsilon(1e-14));
  CHECK(s.minus1sigma[0] == Approx(1.0).epsilon(1e-14));
  CHECK(s.plus1sigma[0] == Approx(e * e).epsilon(1e-14));
  CHECK(s.minus1sigma[1] == Approx(2.0).epsilon(1e-14));  // no spread: sigma 0
  CHECK(s.plus1sigma[1] == Approx(2.0).epsilon(1e-14));
  const std::vector<double> factors{2.0, 2.0, 2.0};
  CHECK(adjoin::suite_statistics(three, {}, factors).mean[0] == Approx(2.0 * e).epsilon(1e-14));

  CHECK_THROWS_WITH(adjoin::suite_statistics(std::span(three.data(), 1)),
                    Catch::Contains("at least two records"));
  std::vector<adjoin::ResponseSpectrum> zero{spectrum({1.0, 2.0}), spectrum({0.0, 2.0})};
  const std::vector<std::string> names{"a.AT2", "quiet.AT2"};
  CHECK_THROWS_WITH(adjoin::suite_statistics(zero, names), Catch::Contains("quiet.AT2: PSA is 0 g at T = 0.5 s"));

  adjoin::SuiteScalingOptions options;
  options.t1 = 1.0;
  CHECK_THROWS_WITH(adjoin::scale_suite(three, adjoin::TargetSpectrum::ec8('B', 0.25), options),
                    Catch::Contains("not inside the periods computed"));
  options.t1 = 0.5;  // band 0.1 ... 1 s: outside too
  CHECK_THROWS_AS(adjoin::scale_suite(three, adjoin::TargetSpectrum::ec8('B', 0.25), options), adjoin::InputError);
  options.t1 = 0.0;
  std::string error;
  CHECK(!options.IsValid(&error));
  CHECK(error.find("t1") == 0);
  // A band given directly: valid alone, not with t1, not reversed; its ends are the band's.
  options.band_from = 0.4;
  options.band_to = 1.6;
  CHECK(options.IsValid(&error));
  CHECK(options.band_min() == 0.4);
  CHECK(options.band_max() == 1.6);
  CHECK(adjoin::suite_periods({0.1, 1.0, 2.0}, options) == std::vector<double>{0.1, 0.4, 1.0, 1.6, 2.0});
  CHECK_THROWS_WITH(adjoin::scale_suite(three, adjoin::TargetSpectrum::ec8('B', 0.25), options),
                    Catch::Contains("the band 0.4 ... 1.6 s is not inside the periods computed"));
  options.t1 = 1.0;
  CHECK(!options.IsValid(&error));
  CHECK(error.find("not both") != std::string::npos);
  options.t1 = 0.0;
  options.band_to = 0.3;
  CHECK(!options.IsValid(&error));
  CHECK(error.find("band_from, band_to") == 0);
}
