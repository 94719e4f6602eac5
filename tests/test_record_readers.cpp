// The readers of the registry (src/ground/readers/): USGS SMC (the project's real A-CAT pair,
// and a written file), COSMOS V1/V2, K-NET/KiK-net, ESM and CSMIP/DMG V2 (files written from
// the formats' descriptions, tests/data/records/README.md). For each: values, dt, npts, units and
// scale factors; the automatic choice; header variants; errors that name the header line (dt
// missing or zero, units unknown, npts larger than the data, a non-number); and a round trip
// through the two-column writer.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "corrupted_text.hpp"
#include "adjoin/ground/record.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/ground/synthesis.hpp"
#include "adjoin/io/record_writer.hpp"

using namespace adjoin;
using Catch::Matchers::Contains;
using Kind = RecordFormat::Kind;

namespace {

constexpr double g = 9.80665;
const std::string real = ADJOIN_REAL_RECORDS;
const std::string data = std::string(ADJOIN_SOURCE_DIR) + "/tests/data/records/";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

RecordFormat kind(Kind k, int channel = 0) {
  RecordFormat f;
  f.kind = k;
  f.channel = channel;
  return f;
}

RecordFormat channel(int c) { return kind(Kind::automatic, c); }

// 1-based number of the first line holding `marker`.
std::size_t line_of(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

// `text` with the first occurrence of `from` replaced by `to`.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string error_of(const std::string& text, const std::string& name, const RecordFormat& format = {}) {
  try {
    parse_record(text, name, format);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string at(const std::string& name, std::size_t line) { return name + ":" + std::to_string(line) + ":"; }

double pga(const Record& r) {
  double m = 0.0;
  for (double a : r.accel) m = std::max(m, std::abs(a));
  return m;
}

}  // namespace

TEST_CASE("SMC: the real A-CAT pair (npts, dt, units, PGA of the header)", "[record_readers]") {
  // Checked against the files themselves: integer 17 = 1646 values, real 2 = 50 samples/s,
  // values in cm/s^2 (the AT2 values in g scaled by 981), real 30 / 32 the maximum / minimum and
  // the text header's "pk mtn" the larger in magnitude.
  const Record r090 = read_record(real + "/smc/A-CAT090.AT2.smc");
  CHECK(r090.accel.size() == 1646);
  CHECK(r090.dt == 0.02);
  CHECK(pga(r090) == Approx(0.4135543).epsilon(1e-7));         // real 30: 0.4135543E+02 cm/s^2
  CHECK(pga(r090) * 100.0 == Approx(41.36).margin(0.005));       // pk mtn = 4.136E+1
  CHECK(r090.accel.front() == Approx(9.5746585E-04 * 0.01).epsilon(1e-12));
  CHECK(r090.accel.back() == Approx(4.1989844E-02 * 0.01).epsilon(1e-12));
  CHECK_THAT(r090.description, Contains("WHITTIER") && Contains("PEA2SMC"));
  const Record r180 = read_record(real + "/smc/A-CAT180.AT2.smc");
  CHECK(r180.accel.size() == 1646);
  CHECK(r180.dt == 0.02);
  CHECK(*std::min_element(r180.accel.begin(), r180.accel.end()) == Approx(-0.5800918).epsilon(1e-7));  // real 32
  // The automatic choice is the SMC reader; units given must agree with cm/s^2.
  CHECK(read_record(real + "/smc/A-CAT090.AT2.smc", kind(Kind::smc)).accel == r090.accel);
  RecordFormat cm;
  cm.units = AccelUnit::cm_s2;
  CHECK(read_record(real + "/smc/A-CAT090.AT2.smc", cm).accel == r090.accel);
  RecordFormat in_g;
  in_g.units = AccelUnit::g;
  CHECK_THROWS_WITH(read_record(real + "/smc/A-CAT090.AT2.smc", in_g), Contains("cm/s2") && Contains("g was given"));
}

TEST_CASE("SMC: a written corrected file, and its defects by header line", "[record_readers]") {
  const std::string text = slurp(data + "smc-corrected.smc");
  const Record r = parse_record(text, "c.smc");
  REQUIRE(r.accel.size() == 7);
  CHECK(r.dt == 0.01);  // real 2 = 100 samples/s
  CHECK(r.accel[0] == Approx(0.005));
  CHECK(r.accel[6] == Approx(0.065));
  CHECK_THAT(r.description, Contains("CORRECTED ACCELEROGRAM") && Contains("written for adjoin tests"));
  // dt missing (the no-value 1.7E+38) or zero: line 18, where real 2 is.
  CHECK_THAT(error_of(with(text, "  1.0000000E+02", "  1.7000000E+38"), "c.smc"), Contains(at("c.smc", 18)) && Contains("sampling rate"));
  CHECK_THAT(error_of(with(text, "  1.0000000E+02", "  0.0000000E+00"), "c.smc"), Contains(at("c.smc", 18)) && Contains("samples per second > 0"));
  // npts larger than the data: the file ends, and the message names integer 17's line (14).
  CHECK_THAT(error_of(with(text, "\n         7    -32768", "\n         9    -32768"), "c.smc"),
             Contains("ends after 7 values") && Contains("line 14 says 9"));
  // a non-number among the values, on its line (30)
  CHECK_THAT(error_of(with(text, "-1.5000000E+00", "-1.5000000X+00"), "c.smc"), Contains(at("c.smc", 29)) && Contains("not a number"));
  // a non-number in the integer header
  CHECK_THAT(error_of(with(text, "\n         7    -32768", "\n      seven   -32768"), "smc-x.smc", kind(Kind::smc)),
             Contains(at("smc-x.smc", 14)) && Contains("8I10"));
  // velocity files are refused on line 1
  CHECK_THAT(error_of(with(text, "2 CORRECTED ACCELEROGRAM", "3 VELOCITY            "), "c.smc"), Contains(at("c.smc", 1)) && Contains("velocity"));
  // more values than integer 17 says
  CHECK_THAT(error_of(text + "  1.0\n", "c.smc"), Contains(at("c.smc", 31)) && Contains("more values"));
}

TEST_CASE("COSMOS V2 with two channels: each channel's values, dt and units", "[record_readers]") {
  const std::string file = data + "cosmos-v2-two-channels.v2";
  const Record c1 = read_record(file, channel(1));
  REQUIRE(c1.accel.size() == 10);
  CHECK(c1.dt == Approx(0.01).epsilon(1e-15));  // real 62 = 10 ms
  // 8F10.5 fields: "123.45678-123.45678" are two values; cm/sec2 (04) -> m/s^2
  const std::vector<double> expected = {1.5, -2.25, 123.45678, -123.45678, -45.0, 0.00001, 7.0, -8.125, 9.5, -0.5};
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(c1.accel[i] == Approx(expected[i] * 0.01).epsilon(1e-12));
  const Record c2 = read_record(file, channel(2));
  REQUIRE(c2.accel.size() == 12);
  CHECK(c2.dt == Approx(0.005).epsilon(1e-15));
  CHECK(c2.accel[0] == Approx(0.01 * g));  // units=g(02)
  CHECK(c2.accel[11] == Approx(-0.12 * g));
  CHECK_THAT(c2.description, Contains("channel 2 of 2"));
  // No channel: an error listing them; a channel that is not there.
  CHECK_THROWS_WITH(read_record(file), Contains("holds 2 channels") && Contains("Sta Chan  1: 360 deg") && Contains("--channel"));
  CHECK_THROWS_WITH(read_record(file, channel(3)), Contains("channel 3 was asked"));
  CHECK(read_record(file, kind(Kind::cosmos, 1)).accel == c1.accel);
}

TEST_CASE("COSMOS V1: one channel, 6F13.6 reals, one value a line, CRLF, End-of-data line", "[record_readers]") {
  const Record r = read_record(data + "cosmos-v1-one-channel.v1");
  REQUIRE(r.accel.size() == 7);
  CHECK(r.dt == Approx(0.02).epsilon(1e-15));
  for (std::size_t i = 0; i < 7; ++i) CHECK(r.accel[i] == Approx(0.001 * double(i + 1) * (i % 2 ? 1 : -1) * 0.01).epsilon(1e-6));
  CHECK(read_record(data + "cosmos-v1-one-channel.v1", channel(1)).accel == r.accel);
  CHECK_THROWS_WITH(read_record(data + "cosmos-v1-one-channel.v1", channel(2)), Contains("holds 1 channel"));
}

TEST_CASE("COSMOS defects name the header line", "[record_readers]") {
  const std::string text = slurp(data + "cosmos-v2-two-channels.v2");
  const RecordFormat one = channel(1);
  // Real 62 (sampling interval, ms) is on the 13th line of 5F15.6 reals: 25 + 13 = 38.
  const std::string real62 = "      10.000000";
  REQUIRE(line_of(text, real62) == 38);
  CHECK_THAT(error_of(with(text, real62, "    -999.000000"), "x.v2", one), Contains(at("x.v2", 38)) && Contains("real 62") && Contains("unknown"));
  CHECK_THAT(error_of(with(text, real62, "       0.000000"), "x.v2", one), Contains(at("x.v2", 38)) && Contains("step > 0"));
  // Units the reader does not know, or raw counts: the data line (49).
  CHECK_THAT(error_of(with(text, "units=cm/sec2(04)", "units=furlong(99)"), "x.v2", one), Contains(at("x.v2", 49)) && Contains("'furlong(99)'"));
  CHECK_THAT(error_of(with(text, "units=cm/sec2(04)", "units=counts(50)"), "x.v2", one), Contains(at("x.v2", 49)) && Contains("not an acceleration"));
  // npts larger than the data: the block stops short.
  CHECK_THAT(error_of(with(text, "      10  acceleration pts", "      99  acceleration pts"), "x.v2", one),
             Contains("x.v2:51:") && Contains("10 of the 99 acceleration values line 49 announces"));
  // a non-number in the values
  CHECK_THAT(error_of(with(text, "  -8.12500", "  -8.12x00"), "x.v2", one), Contains(at("x.v2", 50)) && Contains("not a number"));
  // a velocity file
  CHECK_THAT(error_of(with(text, "Corrected acceleration ", "Velocity               "), "x.v2", one), Contains(at("x.v2", 1)) && Contains("not an acceleration"));
  // the integer-header count line itself
  CHECK_THAT(error_of(with(text, " 100 Integer-header values follow on  10 lines", " abc Integer-header values follow on  10 lines"), "x.v2", one),
             Contains(at("x.v2", 14)));
}

TEST_CASE("K-NET and KiK-net: counts times the scale factor, offset removed", "[record_readers]") {
  const Record k = read_record(data + "knet-tiny.EW");
  REQUIRE(k.accel.size() == 20);
  CHECK(k.dt == 0.01);  // 100Hz
  // counts 10000 + c: the mean (10000) is removed; 7845 gal / 8223790 counts; gal -> m/s^2
  const double factor = 7845.0 / 8223790.0 * 0.01;
  CHECK(k.accel[0] == Approx(0.0).margin(1e-15));
  CHECK(k.accel[1] == Approx(100.0 * factor).epsilon(1e-12));
  CHECK(k.accel[8] == Approx(-1000.0 * factor).epsilon(1e-12));
  CHECK(pga(k) * 100.0 == Approx(0.954).margin(5e-4));  // the header's "Max. Acc. (gal)"
  CHECK_THAT(k.description, Contains("TST001") && Contains("E-W"));

  const Record kik = read_record(data + "kiknet-tiny.NS2");
  REQUIRE(kik.accel.size() == 11);
  CHECK(kik.dt == 0.005);  // 200Hz
  const double kik_factor = 2000.0 / 8388608.0 * 0.01;
  CHECK(kik.accel[1] == Approx(8388.0 * kik_factor).epsilon(1e-12));
  CHECK(pga(kik) * 100.0 == Approx(2.0).margin(5e-4));

  const std::string text = slurp(data + "knet-tiny.EW");
  CHECK_THAT(error_of(with(text, "100Hz", "0Hz"), "k.EW"), Contains(at("k.EW", 11)) && Contains("sampling frequency"));
  CHECK_THAT(error_of(with(text, "Sampling Freq(Hz) 100Hz", "Sampling Freq(Hz) Hz"), "k.EW"), Contains(at("k.EW", 11)));
  CHECK_THAT(error_of(with(text, "7845(gal)", "7845(ft/s2)"), "k.EW"), Contains(at("k.EW", 14)) && Contains("unknown units"));
  CHECK_THAT(error_of(with(text, "/8223790", "/0"), "k.EW"), Contains(at("k.EW", 14)) && Contains("zero"));
  CHECK_THAT(error_of(with(text, "9750", "97x0"), "k.EW"), Contains(at("k.EW", 18)) && Contains("not a number"));
  CHECK_THAT(error_of(with(text, "Sampling Freq(Hz) 100Hz\n", ""), "k.EW", kind(Kind::knet)), Contains("Sampling Freq"));
}

TEST_CASE("K-NET: a scale factor with a negative, zero or non-finite part is refused naming its line", "[record_readers]") {
  // '/-1' was read as a factor of -7845 gal a count (a PGA of 40 g for this file's counts).
  const std::string text = slurp(data + "knet-tiny.EW");
  struct Case {
    const char* scale;
    const char* says;
  };
  for (const Case& c : {Case{"7845(gal)/-1", "the denominator is negative"}, Case{"-7845(gal)/8223790", "the numerator is negative"},
                        Case{"7845(gal)/-0", "the denominator is zero"}, Case{"0(gal)/8223790", "the numerator is zero"},
                        Case{"7845(gal)/1e999", "the denominator is not a finite number"}, Case{"inf(gal)/8223790", "the numerator is not a finite number"},
                        Case{"nan(gal)/8223790", "the numerator is not a finite number"}}) {
    INFO(c.scale);
    CHECK_THAT(error_of(with(text, "7845(gal)/8223790", c.scale), "k.EW", kind(Kind::knet)),
               Contains(at("k.EW", 14)) && Contains(c.says) && Contains("expected a finite number > 0"));
  }
  CHECK_NOTHROW(parse_record(with(text, "7845(gal)/8223790", "7845(gal)/1"), "k.EW", kind(Kind::knet)));
}

TEST_CASE("CSMIP/DMG: a file cut inside a later channel is refused at the line where it stops", "[record_readers]") {
  // Cut anywhere in channel 2, the file was read as a one-channel file (its header) or its
  // cut went unseen when channel 1 was asked; COSMOS refuses the same cuts.
  std::string text = slurp(data + "dmg-v2-two-channels.V2");
  const std::string second = "Corrected accelerogram   99999-T0001-20001.01       Chan  2";
  const std::size_t start = line_of(text, second);
  auto cut_after = [&](std::size_t lines) {  // the first `lines` lines
    std::size_t at = 0;
    for (std::size_t i = 0; i < lines; ++i) at = text.find('\n', at) + 1;
    return text.substr(0, at);
  };
  // In the text header: no acceleration block.
  CHECK_THAT(error_of(cut_after(start + 9), "d.V2"),
             Contains(at("d.V2", start + 9)) && Contains("the file ends inside channel 2 (from line " + std::to_string(start) + ")") &&
                 Contains("points of accel data"));
  // In the acceleration values, whichever channel is asked.
  const std::size_t block = line_of(text.substr(text.find(second)), "points of accel data") + start - 1;
  for (int c : {0, 1, 2})
    CHECK_THAT(error_of(cut_after(block + 1), "d.V2", channel(c)), Contains(at("d.V2", block + 1)) && Contains("the file ends inside channel 2"));
  // A damaged value in the channel not asked for is found too.
  CHECK_THAT(error_of(with(text, "6.000000", "6.0x0000"), "d.V2", channel(1)), Contains("not a number"));
  // In the velocity block: no "/&" end line, where channel 1 has one.
  const std::size_t veloc = line_of(text.substr(text.find(second)), "points of veloc data") + start - 1;
  CHECK_THAT(error_of(cut_after(veloc + 1), "d.V2", channel(1)),
             Contains(at("d.V2", veloc + 1)) && Contains("the file ends inside channel 2") && Contains("'/&'"));
  // Text after the last channel that starts none.
  CHECK_THAT(error_of(text + "some trailing text\r\n", "d.V2", channel(1)), Contains("channel 3") && Contains("without an acceleration block"));
  // The whole file still reads, and so does a one-channel file that ends without "/&".
  CHECK(parse_record(text, "d.V2", channel(2)).accel.size() == 6);
  const std::string one = slurp(data + "dmg-v2-upper-case.V2");
  const std::size_t end = one.rfind("/&");
  REQUIRE(end != std::string::npos);
  CHECK(parse_record(one.substr(0, end), "u.V2").accel.size() == 10);
}

TEST_CASE("ESM ASCII: NDATA values at SAMPLING_INTERVAL_S, in the header's UNITS", "[record_readers]") {
  const Record e = read_record(data + "esm-tiny.HNE.ACC.ASC");
  REQUIRE(e.accel.size() == 10);
  CHECK(e.dt == 0.005);
  CHECK(e.accel[1] == Approx(0.0125));  // 1.25 cm/s^2
  CHECK(e.accel[8] == Approx(-0.1));
  CHECK_THAT(e.description, Contains("STATION_CODE: TST1"));
  // Variant: units m/s^2, no DATA_TYPE line.
  const Record m = read_record(data + "esm-tiny-m.HNN.ACC.ASC");
  REQUIRE(m.accel.size() == 5);
  CHECK(m.dt == 0.01);
  CHECK(m.accel[4] == Approx(0.5));

  const std::string text = slurp(data + "esm-tiny.HNE.ACC.ASC");
  CHECK_THAT(error_of(with(text, "SAMPLING_INTERVAL_S: 0.005000", "SAMPLING_INTERVAL_S: 0"), "e.ASC"), Contains(at("e.ASC", 14)) && Contains("step > 0"));
  CHECK_THAT(error_of(with(text, "SAMPLING_INTERVAL_S: 0.005000", "SAMPLING_INTERVAL_S: fast"), "e.ASC"), Contains(at("e.ASC", 14)) && Contains("not a number"));
  CHECK_THAT(error_of(with(text, "SAMPLING_INTERVAL_S: 0.005000\n", ""), "e.ASC", kind(Kind::esm)), Contains("no SAMPLING_INTERVAL_S"));
  CHECK_THAT(error_of(with(text, "UNITS: cm/s^2", "UNITS: furlong/s^2"), "e.ASC"), Contains(at("e.ASC", 18)) && Contains("unknown units"));
  CHECK_THAT(error_of(with(text, "NDATA: 10", "NDATA: 12"), "e.ASC"), Contains("ends after 10 values") && Contains("line 15 says 12"));
  CHECK_THAT(error_of(with(text, "DATA_TYPE: ACCELERATION", "DATA_TYPE: VELOCITY"), "e.ASC"), Contains(at("e.ASC", 21)) && Contains("ACCELERATION"));
  CHECK_THAT(error_of(with(text, "\n-2.500000", "\n-2.5x0000"), "e.ASC"), Contains(at("e.ASC", 26)) && Contains("not a number"));
}

TEST_CASE("CSMIP/DMG V2: the acceleration block of each channel, both header generations", "[record_readers]") {
  const std::string file = data + "dmg-v2-two-channels.V2";
  const Record c1 = read_record(file, channel(1));
  REQUIRE(c1.accel.size() == 9);
  CHECK(c1.dt == 0.005);
  // 8f10.6 fields: "12.345678-12.345678-77.280340" are three values
  const std::vector<double> expected = {0.5, -0.25, 12.345678, -12.345678, -77.28034, 0.000001, 3.0, -4.0, 5.0};
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(c1.accel[i] == Approx(expected[i] * 0.01).epsilon(1e-12));
  const Record c2 = read_record(file, channel(2));
  REQUIRE(c2.accel.size() == 6);
  CHECK(c2.accel[5] == Approx(0.06));
  CHECK_THROWS_WITH(read_record(file), Contains("holds 2 channels") && Contains("Chan  1: 360 Deg") && Contains("Chan  2:  Up"));
  // The older, upper-case header: "(UNITS: CM/SEC/SEC)", no layout given.
  const Record old = read_record(data + "dmg-v2-upper-case.V2");
  REQUIRE(old.accel.size() == 10);
  CHECK(old.dt == 0.02);
  CHECK(old.accel[9] == Approx(-0.05659));

  const std::string text = slurp(file);
  const RecordFormat one = channel(1);
  CHECK_THAT(error_of(with(text, "spaced at  .005 sec, in cm/sec2", "spaced at  .000 sec, in cm/sec2"), "d.V2", one),
             Contains(at("d.V2", 46)) && Contains("step"));
  CHECK_THAT(error_of(with(text, "spaced at  .005 sec, in cm/sec2", "spaced at  sec, in cm/sec2"), "d.V2", one),
             Contains(at("d.V2", 46)) && Contains("no step"));
  CHECK_THAT(error_of(with(text, "in cm/sec2.", "in furlongs."), "d.V2", one), Contains(at("d.V2", 46)) && Contains("unknown units"));
  CHECK_THAT(error_of(with(text, "     9 points of accel", "    19 points of accel"), "d.V2", one), Contains("d.V2:48:") && Contains("9 of the 19 acceleration values line 46 announces"));
  CHECK_THAT(error_of(with(text, "  3.000000", "  3.0x0000"), "d.V2", one), Contains(at("d.V2", 47)) && Contains("not a number"));
}

TEST_CASE("the automatic format picks the right reader for every file", "[record_readers]") {
  struct Case {
    std::string path;
    Kind kind;
    int channel;
  };
  const Case cases[] = {
      {real + "/smc/A-CAT090.AT2.smc", Kind::smc, 0},      {data + "smc-corrected.smc", Kind::smc, 0},
      {data + "cosmos-v2-two-channels.v2", Kind::cosmos, 2}, {data + "cosmos-v1-one-channel.v1", Kind::cosmos, 0},
      {data + "knet-tiny.EW", Kind::knet, 0},              {data + "kiknet-tiny.NS2", Kind::knet, 0},
      {data + "esm-tiny.HNE.ACC.ASC", Kind::esm, 0},        {data + "esm-tiny-m.HNN.ACC.ASC", Kind::esm, 0},
      {data + "dmg-v2-two-channels.V2", Kind::dmg, 1},     {data + "dmg-v2-upper-case.V2", Kind::dmg, 0},
      {real + "/peer/RSN175_IMPVALL.H_H-E12140.AT2", Kind::at2, 0},
  };
  for (const Case& c : cases) {
    INFO(c.path);
    const Record automatic = read_record(c.path, channel(c.channel));
    const Record explicit_kind = read_record(c.path, kind(c.kind, c.channel));
    CHECK(automatic.accel == explicit_kind.accel);
    CHECK(automatic.dt == explicit_kind.dt);
    // Every other explicit reader refuses the file (or reads something else): the sniffers are not needed to be right by luck.
    for (Kind other : {Kind::smc, Kind::cosmos, Kind::knet, Kind::esm, Kind::dmg}) {
      if (other == c.kind) continue;
      try {
        const Record r = read_record(c.path, kind(other, c.channel ? 1 : 0));
        CHECK(r.accel != automatic.accel);
      } catch (const InputError&) {
      }
    }
  }
  // Names: one table for parse_record_kind and to_string.
  for (Kind k : {Kind::automatic, Kind::at2, Kind::one_column, Kind::two_column, Kind::delimited, Kind::smc, Kind::cosmos,
                 Kind::knet, Kind::esm, Kind::dmg}) {
    Kind parsed{};
    REQUIRE(parse_record_kind(to_string(k), &parsed));
    CHECK(parsed == k);
    CHECK_THAT(record_kind_names(), Contains(to_string(k)));
  }
  Kind parsed{};
  CHECK(parse_record_kind("KiK-net", &parsed));
  CHECK(parsed == Kind::knet);
  CHECK(parse_record_kind("csmip", &parsed));
  CHECK(parsed == Kind::dmg);
  CHECK_FALSE(parse_record_kind("seed", &parsed));
  // A channel above 1 for a single-channel format is an error.
  CHECK_THROWS_WITH(read_record(data + "knet-tiny.EW", channel(2)), Contains("holds one channel"));
  CHECK_THROWS_WITH(read_record(real + "/peer/RSN175_IMPVALL.H_H-E12140.AT2", channel(2)), Contains("holds one channel"));
}

TEST_CASE("round trip: every reader's record through the two-column writer reads back the same", "[record_readers]") {
  const std::filesystem::path tmp = std::filesystem::path(ADJOIN_TEST_TMP) / "record_readers";
  std::filesystem::create_directories(tmp);
  for (const auto& [path, c] : {std::pair{real + "/smc/A-CAT180.AT2.smc", 0}, {data + "cosmos-v2-two-channels.v2", 1},
                                {data + "knet-tiny.EW", 0}, {data + "esm-tiny.HNE.ACC.ASC", 0}, {data + "dmg-v2-two-channels.V2", 2}}) {
    INFO(path);
    const Record r = read_record(path, channel(c));
    const std::filesystem::path out = tmp / "round-trip.txt";
    write_record_g(r, out, {"round trip of " + path});
    const Record back = read_record(out);  // two columns, "# units: g"
    REQUIRE(back.accel.size() == r.accel.size());
    CHECK(back.dt == Approx(r.dt).epsilon(1e-12));
    for (std::size_t i = 0; i < r.accel.size(); ++i) REQUIRE(back.accel[i] == Approx(r.accel[i]).epsilon(1e-14).margin(1e-300));
  }
}

TEST_CASE("random corruptions of every written file parse or throw InputError, nothing else", "[record_readers]") {
  const char* files[] = {"smc-corrected.smc", "cosmos-v2-two-channels.v2", "cosmos-v1-one-channel.v1", "knet-tiny.EW",
                         "esm-tiny.HNE.ACC.ASC", "dmg-v2-two-channels.V2", "dmg-v2-upper-case.V2"};
  std::uint64_t state = 2024;
  auto next = [&]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::size_t>(state >> 33);
  };
  const std::string alphabet = "0123456789.-+eE ,:()/|&\n\r#abcdfgnptsxHzNPTS";
  const Kind kinds[] = {Kind::automatic, Kind::smc, Kind::cosmos, Kind::knet, Kind::esm, Kind::dmg};
  std::size_t parsed = 0, rejected = 0;
  for (const char* file : files) {
    const std::string seed = slurp(data + file);
    for (int trial = 0; trial < 400; ++trial) {
      std::string text = seed;
      const std::size_t edits = 1 + next() % 4;
      for (std::size_t e = 0; e < edits && !text.empty(); ++e) {
        const std::size_t where = next() % text.size();
        switch (next() % 4) {
          case 0: text[where] = alphabet[next() % alphabet.size()]; break;
          case 1: text.erase(where, 1 + next() % 40); break;
          case 2: text.insert(where, 1, alphabet[next() % alphabet.size()]); break;
          default: text.resize(where); break;
        }
      }
      RecordFormat f = kind(kinds[next() % 6], static_cast<int>(next() % 3));
      if (test::parses_or_is_refused(text, f)) ++parsed;
      else ++rejected;
    }
  }
  CHECK(parsed > 0);
  CHECK(rejected > 0);
}
