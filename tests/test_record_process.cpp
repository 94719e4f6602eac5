// adjoin record process: the processing of scenes on the command line, written as two columns
// that the readers take back.
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "adjoin/ground/processing.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/core/units.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;

TEST_CASE("record process: baseline, band-pass, resampling and PGA scaling, read back exactly", "[record][process]") {
  const std::string in = std::string(ADJOIN_REAL_RECORDS) + "/two-column/elcentro_NS_full.dat";
  const auto out = std::filesystem::path(ADJOIN_TEST_TMP) / "processed.txt";
  const auto r = test::run_cli("record process '" + in + "' --units g --baseline 0 --bandpass 0.1:20 --resample 0.01 "
                               "--scale-pga 0.3 --out '" + out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  RecordFormat g;
  g.units = AccelUnit::g;
  const Record back = read_record(out, g);
  // The file says its units ("# units: g"): it reads back without them, the same record.
  const Record unaided = read_record(out);
  REQUIRE(unaided.accel.size() == back.accel.size());
  for (std::size_t i = 0; i < back.accel.size(); i += 101) CHECK(unaided.accel[i] == back.accel[i]);
  CHECK(back.dt == 0.01);
  CHECK(back.accel.size() == 5375);  // 53.74 s at 0.01 s
  double pga = 0.0;
  for (double a : back.accel) pga = std::max(pga, std::abs(a));
  CHECK(pga == Approx(0.3 * kStandardGravity).epsilon(1e-14));
  // The same processing through the library gives the same record.
  RecordFormat input_format;
  input_format.units = AccelUnit::g;
  Processing p;
  p.baseline_order = 0;
  ButterworthFilter f;
  f.f_low = 0.1;
  f.f_high = 20.0;
  p.filter = f;
  p.dt = 0.01;
  p.target_pga = 0.3 * kStandardGravity;
  const Record direct = process(read_record(in, input_format), p);
  REQUIRE(direct.accel.size() == back.accel.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < direct.accel.size(); ++i) worst = std::max(worst, std::abs(direct.accel[i] - back.accel[i]));
  CHECK(worst < 1e-14 * kStandardGravity);
  // A band-pass from 0.1 Hz removes the drift that makes the raw record's PGD metres.
  const double mean = std::accumulate(back.accel.begin(), back.accel.end(), 0.0) / static_cast<double>(back.accel.size());
  CHECK(std::abs(mean) < 1e-3);
}

TEST_CASE("record process: bad options exit 2 and name the option", "[record][process]") {
  const std::string in = std::string(ADJOIN_REAL_RECORDS) + "/two-column/elCentro.txt";
  const auto out = std::filesystem::path(ADJOIN_TEST_TMP) / "bad.txt";
  for (const auto& [options, expect] : std::vector<std::pair<std::string, std::string>>{
           {"--bandpass 0.1", "--bandpass 0.1"},
           {"--bandpass 0.1:30", "Nyquist"},
           {"--highpass 0.1 --lowpass 10", "one filter"},
           {"--window a:b", "--window"}}) {
    const auto r = test::run_cli("record process '" + in + "' --units g " + options + " --out '" + out.string() + "'");
    INFO(options << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find(expect) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
  }
}
