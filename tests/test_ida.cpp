// ground.scale and `adjoin ida` (SPEC §9; study/ida.hpp, io/ida_files.hpp, src/cli/ida.cpp):
// a scale factor is exact on a linear structure, stripes are sweep runs, the trace brackets
// the first capacity event, and sa:T scaling puts the record's PSA at the level.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/io/csv_table.hpp"
#include "adjoin/io/ida_files.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/study/ida.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "cli_helpers.hpp"
#include "report_helpers.hpp"

using namespace adjoin;
using adjoin::test::peak;
using adjoin::test::run_cli;
using adjoin::test::shell_word;
using adjoin::test::slurp;
using adjoin::test::write_temp;
namespace fs = std::filesystem;

namespace {

// A record of 3 s at dt = 0.01 s [m/s^2], two columns "t a"; every value times `factor`
// (written to 17 digits, so each reads back as exactly factor x the value).
fs::path record_file(const std::string& name, double factor, double frequency = 2.0) {
  std::string text;
  char line[96];
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.01 * i;
    const double a = 3.0 * std::sin(2.0 * M_PI * frequency * t) * std::exp(-0.8 * t) + 0.7 * std::sin(17.0 * t);
    std::snprintf(line, sizeof line, "%.17g %.17g\n", t, factor * a);
    text += line;
  }
  return write_temp(name, text);
}

// A linear (elastic) two-storey building with storey heights (so drift ratios and a collapse
// check), on `record`.
fs::path tiny_scene(const std::string& name, const fs::path& record) {
  return write_temp(name, "name = \"tiny\"\n[model]\nunits = \"SI\"\n[building.A]\nstoreys = 2\nmass = 1.0e4\n"
                          "stiffness = 4.0e6\ndamping = { model = \"modal\", ratio = 0.05 }\nheight = 3.0\n"
                          "[ground]\nsource = \"record\"\nfile = \"" + record.string() + "\"\nunits = \"m/s2\"\n"
                          "[solver]\nh = 0.005\nt_end = 4.0\nerror_estimate = false\n");
}

fs::path out_dir(const std::string& name) {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / ("ida_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST_CASE("ground.scale 2 doubles a linear building's peaks exactly, as the record's values doubled do", "[ida][ground.scale]") {
  const fs::path one = record_file("scale_one.txt", 1.0), two = record_file("scale_two.txt", 2.0);
  const Report base = run(load_building_scene(tiny_scene("scale_base.toml", one)));
  const Report scaled = run(load_building_scene(tiny_scene("scale_base.toml", one), {"ground.scale=2"}));
  const Report doubled = run(load_building_scene(tiny_scene("scale_doubled.toml", two)));
  for (const char* channel : {"A.x1", "A.x2", "A.drift1", "A.drift2", "A.a2_abs"}) {
    INFO(channel);
    CHECK(peak(scaled, channel) == peak(doubled, channel));  // bit for bit
    CHECK(peak(scaled, channel) == Approx(2.0 * peak(base, channel)).epsilon(1e-12));
  }
  // A factor that is not a power of two: the same response to 1e-12.
  const Report third = run(load_building_scene(tiny_scene("scale_base.toml", one), {"ground.scale=0.3"}));
  CHECK(peak(third, "A.x2") == Approx(0.3 * peak(base, "A.x2")).epsilon(1e-12));
}

TEST_CASE("ground.scale refuses a factor that is not a positive number, naming the key", "[ida][ground.scale]") {
  const fs::path scene = tiny_scene("scale_bad.toml", record_file("scale_bad.txt", 1.0));
  for (const char* value : {"0", "-1.5", "'\"abc\"'", "nan"}) {
    INFO(value);
    const auto r = run_cli("run " + shell_word(scene) + " --out " + shell_word(out_dir("bad")) + " --set ground.scale=" + value);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("error:", 0) == 0);
    CHECK(r.err.find("ground.scale") != std::string::npos);
  }
}

TEST_CASE("scale_ground, the typed ground.scale, wraps any source and names the field", "[ida][ground.scale]") {
  const auto sine = decaying_sine_ground(0.01, 5.0, 0.5);
  CHECK(scale_ground(sine, 1.0) == sine);  // a factor of 1 leaves the source as it is
  const auto scaled = scale_ground(sine, 3.0);
  for (double t : {0.1, 0.7, 2.3}) CHECK(scaled->ag(t) == 3.0 * sine->ag(t));
  CHECK(&unscaled_ground(*scaled) == sine.get());
  for (double bad : {0.0, -2.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    try {
      (void)scale_ground(sine, bad);
      FAIL("accepted " << bad);
    } catch (const FieldError& e) {
      CHECK(e.field() == "ground.scale");
    }
  }
}

TEST_CASE("hunt and fill brackets a threshold within its tolerance and fills below it", "[ida][trace]") {
  const double threshold = 0.4137;
  TraceOptions o;
  o.start = 0.1;
  o.factor = 1.5;
  o.tolerance = 0.02;
  o.budget = 14;
  const Trace t = hunt_and_fill([&](double im) { return im > threshold; }, o);
  REQUIRE(t.bracketed());
  CHECK(*t.low < threshold);
  CHECK(*t.high >= threshold);
  CHECK(*t.high - *t.low <= o.tolerance * *t.low);
  CHECK(t.runs.size() == o.budget);
  // The hunt: 0.1, 0.15, 0.225, 0.3375, 0.50625 (the first event).
  REQUIRE(t.runs.size() >= 5);
  CHECK(t.runs[4].im == Approx(0.50625));
  CHECK(t.runs[4].event);
  // A start above the capacity halves down until a run without the event.
  o.start = 2.0;
  const Trace down = hunt_and_fill([&](double im) { return im > threshold; }, o);
  REQUIRE(down.bracketed());
  CHECK(down.runs[1].im == 1.0);
  CHECK(*down.high - *down.low <= o.tolerance * *down.low);
  // No event within the budget: no bracket.
  o.start = 0.1;
  const Trace none = hunt_and_fill([](double) { return false; }, o);
  CHECK_FALSE(none.bracketed());
  CHECK(none.runs.size() == o.budget);
}

TEST_CASE("IDA fractiles interpolate each curve and stop at a capacity", "[ida][fractile]") {
  const double inf = std::numeric_limits<double>::infinity();
  // Three records: EDP = IM, 2 IM, and 3 IM with its capacity at IM 0.3.
  std::vector<IdaCurve> curves = {{{0.1, 0.2, 0.4}, {0.1, 0.2, 0.4}}, {{0.1, 0.2, 0.4}, {0.2, 0.4, 0.8}}, {{0.1, 0.2, 0.3}, {0.3, 0.6, inf}}};
  const auto median = ida_fractile(curves, {0.1, 0.15, 0.4}, 0.5);
  CHECK(median[0] == Approx(0.2));
  CHECK(median[1] == Approx(0.3));  // 0.15, 0.3, 0.45: interpolated
  CHECK(median[2] == Approx(0.8));  // 0.4, 0.8, inf
  const auto p84 = ida_fractile(curves, {0.4}, 0.84);
  CHECK(std::isinf(p84[0]));
}

TEST_CASE("sa:T scaling puts the scaled record's PSA at T on the level", "[ida][im]") {
  const Record record = read_record(record_file("sa_record.txt", 1.0), [] {
    RecordFormat f;
    f.units = AccelUnit::m_s2;
    return f;
  }());
  const IntensityMeasure im = parse_intensity_measure("sa:0.5");
  const double as_read = record_intensity(record, im);
  CHECK(as_read == spectral_values(record.dt, record.accel, 0.5, 0.05).psa);
  for (double level : {0.05, 0.37, 1.2}) {
    Record scaled = record;
    for (double& a : scaled.accel) a *= level / as_read;
    CHECK(spectral_values(scaled.dt, scaled.accel, 0.5, 0.05).psa == Approx(level).epsilon(1e-9));
  }
  const IntensityMeasure pga = parse_intensity_measure("pga");
  double largest = 0.0;
  for (double a : record.accel) largest = std::max(largest, std::abs(a));
  CHECK(record_intensity(record, pga) == largest / kStandardGravity);
}

TEST_CASE("ida stripes equal the same runs done by adjoin sweep with ground.scale, bit for bit", "[ida][cli]") {
  const fs::path r1 = record_file("stripe_r1.txt", 1.0, 2.0), r2 = record_file("stripe_r2.txt", 1.0, 3.1);
  const fs::path scene = tiny_scene("stripes.toml", r1);
  const fs::path dir = out_dir("stripes");
  const auto ida = run_cli("ida " + shell_word(scene) + " --suite " + shell_word(r1) + " " + shell_word(r2) +
                           " --units m/s2 --im sa:0.3 --levels 0.2,0.5,1.1 --edp A.drift_max,A.roof_max --jobs 2 --out " + shell_word(dir));
  INFO(ida.err);
  REQUIRE(ida.status == 0);
  const CsvTable table = read_csv_table(dir / "ida.csv");
  CHECK(table.columns == std::vector<std::string>{"record", "im", "scale", "A.drift_max", "A.roof_max"});
  REQUIRE(table.rows.size() == 6);
  CHECK(fs::exists(dir / "ida.png"));
  CHECK_FALSE(fs::exists(dir / "sweep.partial.csv"));
  CHECK(ida.out.find("stripe_r1.txt: sa:0.3 = ") != std::string::npos);
  // The record's PSA at 0.3 s times the scale is the level.
  RecordFormat f;
  f.units = AccelUnit::m_s2;
  const double im1 = record_intensity(read_record(r1, f), parse_intensity_measure("sa:0.3"));
  for (std::size_t k = 0; k < 3; ++k) CHECK(std::stod(table.rows[k][2]) * im1 == Approx(std::stod(table.rows[k][1])).epsilon(1e-15));
  // The same runs as a sweep: record 2 as the motion, an axis over ground.scale.
  std::string scales;
  for (std::size_t k = 3; k < 6; ++k) scales += (k > 3 ? ", " : "") + table.rows[k][2];
  const fs::path sweep = write_temp("stripes_sweep.toml", "base = \"" + scene.string() + "\"\n[[axis]]\nkey = \"ground.scale\"\nvalues = [" +
                                                              scales + "]\n[[motion]]\nname = \"r2\"\nset = {\"ground.file\" = \"" +
                                                              r2.string() + "\"}\n");
  const fs::path sweep_dir = out_dir("stripes_sweep");
  const auto s = run_cli("sweep " + shell_word(sweep) + " --quiet --out " + shell_word(sweep_dir));
  INFO(s.err);
  REQUIRE(s.status == 0);
  const CsvTable swept = read_csv_table(sweep_dir / "sweep.csv");
  REQUIRE(swept.rows.size() == 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(table.rows[3 + k][0] == "stripe_r2.txt");
    CHECK(table.rows[3 + k][3] == swept.rows[k][swept.column("A.drift_max")]);
    CHECK(table.rows[3 + k][4] == swept.rows[k][swept.column("A.roof_max")]);
  }
  // Run again: the table is the same (no journal left, every run done again).
  const auto again = run_cli("ida " + shell_word(scene) + " --suite " + shell_word(r1) + " " + shell_word(r2) +
                             " --units m/s2 --im sa:0.3 --levels 0.2,0.5,1.1 --edp A.drift_max,A.roof_max --quiet --out " + shell_word(dir));
  REQUIRE(again.status == 0);
  CHECK(read_csv_table(dir / "ida.csv").rows == table.rows);
}

TEST_CASE("an interrupted ida resumes from its sweep journal", "[ida][cli]") {
  const fs::path r1 = record_file("resume_r1.txt", 1.0, 2.0), r2 = record_file("resume_r2.txt", 1.0, 3.1);
  const fs::path scene = tiny_scene("resume.toml", r1);
  const fs::path dir = out_dir("resume");
  const std::string command = "ida " + shell_word(scene) + " --suite " + shell_word(r1) + " " + shell_word(r2) +
                              " --units m/s2 --im pga --levels 0.1,0.3 --edp A.drift_max --out " + shell_word(dir);
  REQUIRE(run_cli(command + " --quiet").status == 0);
  const CsvTable whole = read_csv_table(dir / "ida.csv");
  // The journal an interruption after two runs leaves: the preamble with the sweep's
  // fingerprint, the header and runs 0 and 2, run 2's demand altered so that its use shows.
  const std::string json = slurp(dir / "sweep.json");
  const auto at = json.find("\"fingerprint\"");
  REQUIRE(at != std::string::npos);
  const auto open = json.find('"', json.find(':', at)) + 1;
  const std::string fingerprint = json.substr(open, json.find('"', open) - open);
  std::istringstream sweep(slurp(dir / "sweep.csv"));
  std::string header, row0, row1, row2;
  REQUIRE(std::getline(sweep, header));
  REQUIRE(std::getline(sweep, row0));
  REQUIRE(std::getline(sweep, row1));
  REQUIRE(std::getline(sweep, row2));
  std::vector<std::string> cells, names;
  REQUIRE(split_csv_line(header, &names));
  REQUIRE(split_csv_line(row2, &cells));
  const std::size_t drift = static_cast<std::size_t>(std::find(names.begin(), names.end(), "A.drift_max") - names.begin());
  cells[drift] = "0.125";
  {
    std::ofstream journal(dir / "sweep.partial.csv", std::ios::binary);
    journal << "# adjoin sweep journal fingerprint=" << fingerprint << " runs=4 shard=0/1\n" << header << "\n" << row0 << "\n"
            << csv_line(cells) << "\n";
  }
  fs::remove(dir / "ida.csv");
  const auto resumed = run_cli(command);
  INFO(resumed.err);
  REQUIRE(resumed.status == 0);
  CHECK(resumed.err.find("resuming: 2 runs from the journal") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "sweep.partial.csv"));
  const CsvTable again = read_csv_table(dir / "ida.csv");
  REQUIRE(again.rows.size() == 4);
  CHECK(again.rows[0] == whole.rows[0]);
  CHECK(again.rows[1] == whole.rows[1]);  // run again
  CHECK(again.rows[2][3] == "0.125");     // taken from the journal
  CHECK(again.rows[3] == whole.rows[3]);
}

TEST_CASE("ida --trace brackets the first capacity event within its tolerance of a fine grid", "[ida][cli][trace]") {
  const fs::path r1 = record_file("trace_r1.txt", 1.0, 2.0);
  const fs::path scene = tiny_scene("trace.toml", r1);
  const double limit = 0.004;  // m of A.drift_max
  const std::string common = "ida " + shell_word(scene) + " --suite " + shell_word(r1) + " --units m/s2 --im pga --edp A.drift_max --quiet ";
  const fs::path trace_dir = out_dir("trace");
  const auto trace = run_cli(common + "--trace --capacity 'A.drift_max > 0.004' --trace-start 0.05 --trace-tol 0.02 --trace-runs 12 --out " + shell_word(trace_dir));
  INFO(trace.err);
  REQUIRE(trace.status == 0);
  const CsvTable t = read_csv_table(trace_dir / "ida.csv");
  REQUIRE(t.rows.size() == 12);
  double low = 0.0, high = 1e300;
  for (const auto& row : t.rows) {
    const double im = std::stod(row[1]);
    if (std::stod(row[3]) > limit) high = std::min(high, im);
  }
  for (const auto& row : t.rows)
    if (std::stod(row[1]) < high) low = std::max(low, std::stod(row[1]));
  REQUIRE(high < 1e300);
  CHECK(high - low <= 0.02 * low);
  // The brute force: a grid of 0.002 g steps around the capacity.
  std::string levels;
  for (int k = 0; k < 40; ++k) levels += (k ? "," : "") + sweep_number_cell(0.92 * low + 0.002 * k);
  const fs::path grid_dir = out_dir("grid");
  const auto grid = run_cli(common + "--levels " + levels + " --out " + shell_word(grid_dir));
  REQUIRE(grid.status == 0);
  const CsvTable g = read_csv_table(grid_dir / "ida.csv");
  double first = 0.0, before = 0.0;
  for (const auto& row : g.rows) {
    if (std::stod(row[3]) > limit) {
      first = std::stod(row[1]);
      break;
    }
    before = std::stod(row[1]);
  }
  REQUIRE(first > 0.0);
  // Both bracket the same threshold: the intervals (low, high] and (before, first] overlap.
  CHECK(low < first);
  CHECK(before < high);
  CHECK(std::abs(first - high) <= 0.02 * low + 0.002);
}

TEST_CASE("the capacity is an event expression of fragility's parser: and, or, parentheses, empty cells unknown", "[ida][capacity]") {
  const fs::path r1 = record_file("capacity_r1.txt", 1.0);
  const SweepSpec spec = ida_sweep(tiny_scene("capacity.toml", r1), {{"r1", r1, 1.0}}, "m/s2", "capacity");
  const auto columns = sweep_columns(spec);
  const auto at = [&](const std::string& name) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c].name == name) return c;
    FAIL("no column " << name);
    return std::size_t{0};
  };
  // A row with the given drift and roof cells ("" = empty), no failure and no collapse.
  const auto row = [&](const std::string& drift, const std::string& roof) {
    std::vector<std::string> cells(columns.size());
    cells[at("A.drift_max")] = drift;
    cells[at("A.roof_max")] = roof;
    return cells;
  };
  const IdaCapacity either = ida_capacity(spec, "A.drift_max > 0.004 or A.roof_max >= 0.01", "--capacity");
  CHECK(either(row("0.005", "0")));
  CHECK(either(row("0.001", "0.01")));
  CHECK_FALSE(either(row("0.001", "0.009")));
  CHECK(either(row("", "0.02")));        // unknown or true = true
  CHECK_FALSE(either(row("", "0.001")));  // unknown stays unknown: not the event
  const IdaCapacity both = ida_capacity(spec, "(A.drift_max > 0.004) and A.roof_max >= 0.01", "--capacity");
  CHECK_FALSE(both(row("0.005", "0")));
  CHECK(both(row("0.005", "0.01")));
  // A failed run is the event whatever the expression says.
  auto failed = row("0", "0");
  failed.back() = "diverged";
  CHECK(both(failed));
  // Messages name the option given.
  for (const char* bad : {"A.drift_max > 0.004 and", "A.nothing > 1", "A.drift_max == 1"}) {
    INFO(bad);
    try {
      ida_capacity(spec, bad, "--capacity");
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).rfind("--capacity \"", 0) == 0);
    }
  }
}

TEST_CASE("ida --trace with a compound --capacity traces the same runs as its one deciding limit", "[ida][cli][trace][capacity]") {
  const fs::path r1 = record_file("compound_r1.txt", 1.0, 2.0);
  const fs::path scene = tiny_scene("compound.toml", r1);
  const std::string common = "ida " + shell_word(scene) + " --suite " + shell_word(r1) +
                             " --units m/s2 --im pga --edp A.drift_max --quiet --trace --trace-start 0.05 --trace-runs 6 ";
  const fs::path one = out_dir("compound_one"), two = out_dir("compound_two");
  const auto a = run_cli(common + "--capacity 'A.drift_max > 0.004' --out " + shell_word(one));
  const auto b = run_cli(common + "--capacity '(A.drift_max > 0.004 or A.drift_max > 99) and A.roof_max >= 0' --out " + shell_word(two));
  INFO(a.err << b.err);
  REQUIRE(a.status == 0);
  REQUIRE(b.status == 0);
  CHECK(slurp(one / "ida.csv") == slurp(two / "ida.csv"));
  // and one that can never hold: no event, so the hunt climbs through the whole budget.
  const fs::path never = out_dir("compound_never");
  const auto c = run_cli(common + "--capacity 'A.drift_max > 0.004 and A.drift_max < 0.001' --out " + shell_word(never));
  REQUIRE(c.status == 0);
  const CsvTable t = read_csv_table(never / "ida.csv");
  REQUIRE(t.rows.size() == 6);
  CHECK(std::stod(t.rows.back()[1]) == Approx(0.05 * std::pow(1.5, 5)).epsilon(1e-12));
}

TEST_CASE("adjoin ida names a bad option (exit 2)", "[ida][cli]") {
  const fs::path r1 = record_file("bad_r1.txt", 1.0);
  const fs::path scene = tiny_scene("bad.toml", r1);
  const std::string head = "ida " + shell_word(scene) + " --suite " + shell_word(r1) + " --units m/s2 --out " + shell_word(out_dir("bad_options")) + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--im sa:x --levels 0.1", "--im"},
      {"--im pgv --levels 0.1", "--im"},
      {"--im pga --levels 0.1,-2", "--levels"},
      {"--im pga --levels 0.1,0.1", "--levels"},
      {"--im pga", "--levels"},
      {"--im pga --levels 0.1 --trace", "--trace"},
      {"--im pga --levels 0.1 --edp A.nothing", "--edp"},
      {"--im pga --trace --capacity 'A.drift_max ~ 3'", "--capacity"},
      {"--im pga --trace --capacity 'A.nothing > 3'", "--capacity"},
      {"--im pga --trace --capacity 'A.drift_max > 3 or'", "--capacity"},
      {"--im pga --levels 0.1 --capacity '(A.drift_max > 3'", "--capacity"},
      {"--im pga --trace --trace-factor 1", "--trace-factor"},
      {"--im pga --trace --trace-tol 0", "--trace-tol"},
  };
  for (const auto& [options, named] : cases) {
    INFO(options);
    const auto r = run_cli(head + options);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("error:", 0) == 0);
    CHECK(r.err.find(named) != std::string::npos);
  }
  const auto missing = run_cli("ida " + shell_word(scene) + " --suite /no/such/record.at2 --im pga --levels 0.1 --out " + shell_word(out_dir("bad_suite")));
  CHECK(missing.status == 2);
  CHECK(missing.err.find("--suite") != std::string::npos);
}
