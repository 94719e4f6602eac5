// Record readers: every AT2 header variant, one/two columns, delimited text, and every defect
// reported as an InputError naming the file and line.
#include <catch2/catch.hpp>
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <string>

#include "adjoin/core/errors.hpp"
#include "corrupted_text.hpp"
#include "adjoin/ground/record.hpp"
#include "adjoin/ground/record_file.hpp"

using namespace adjoin;
using Catch::Matchers::Contains;

namespace {

constexpr double g = 9.80665;
const std::string records = ADJOIN_REAL_RECORDS;

RecordFormat with_units(AccelUnit unit, RecordFormat::Kind kind = RecordFormat::Kind::automatic) {
  RecordFormat f;
  f.kind = kind;
  f.units = unit;
  return f;
}

// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const RecordFormat& format = with_units(AccelUnit::g)) {
  try {
    parse_record(text, "bad.txt", format);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("accel units: factors, names, round trip", "[record_file]") {
  CHECK(to_m_s2(AccelUnit::g) == g);
  CHECK(to_m_s2(AccelUnit::m_s2) == 1.0);
  CHECK(to_m_s2(AccelUnit::cm_s2) == 0.01);
  CHECK(to_m_s2(AccelUnit::mm_s2) == 0.001);
  AccelUnit u{};
  for (auto [name, unit] : {std::pair{"g", AccelUnit::g}, {"G", AccelUnit::g}, {"m/s2", AccelUnit::m_s2},
                            {"m/s^2", AccelUnit::m_s2}, {"cm/s2", AccelUnit::cm_s2}, {"gal", AccelUnit::cm_s2},
                            {"CM/SEC/SEC", AccelUnit::cm_s2}, {"mm/s2", AccelUnit::mm_s2}, {"m/s\xc2\xb2", AccelUnit::m_s2}}) {
    INFO(name);
    REQUIRE(parse_accel_unit(name, &u));
    CHECK(u == unit);
  }
  for (AccelUnit unit : {AccelUnit::g, AccelUnit::m_s2, AccelUnit::cm_s2, AccelUnit::mm_s2}) {
    REQUIRE(parse_accel_unit(to_string(unit), &u));
    CHECK(u == unit);
  }
  CHECK_FALSE(parse_accel_unit("ft/s2", &u));
  CHECK_FALSE(parse_accel_unit("", &u));
  CHECK_FALSE(parse_accel_unit("m/s", &u));
}

TEST_CASE("AT2 files of the real records: NPTS, DT and units as in the README", "[record_file]") {
  struct Case {
    const char* file;
    double dt;
    std::size_t npts;
    double first_g;
  };
  for (const Case& c : {Case{"peer/RSN175_IMPVALL.H_H-E12140.AT2", 0.005, 7814, .3654112E-03},
                        Case{"peer/RSN1546_CHICHI_TCU122-N.AT2", 0.005, 18000, -.8090828E-04},
                        Case{"peer/RSN1044_DirRot2.AT2", 0.02, 2000, -1.65951E-03},
                        Case{"peer/RSN8883_14383980_13849090.AT2", 0.005, 16396, 8.6900441E-08}}) {
    INFO(c.file);
    const Record r = read_record(records + "/" + c.file);
    CHECK(r.dt == c.dt);
    CHECK(r.accel.size() == c.npts);
    CHECK(r.accel.front() == Approx(c.first_g * g).epsilon(1e-15));
    CHECK(r.source == records + "/" + c.file);
    CHECK_THAT(r.description, Contains("PEER NGA STRONG MOTION DATABASE RECORD"));
  }
  // The last value of RSN8883 is alone on its line.
  const Record r = read_record(records + "/peer/RSN8883_14383980_13849090.AT2");
  CHECK(r.accel.back() == Approx(2.3375500E-05 * g).epsilon(1e-15));
  // Units given that agree with the header are fine; disagreeing ones are an error.
  CHECK(read_record(records + "/peer/RSN1044_DirRot2.AT2", with_units(AccelUnit::g)).accel.size() == 2000);
  CHECK_THROWS_AS(read_record(records + "/peer/RSN1044_DirRot2.AT2", with_units(AccelUnit::cm_s2)), InputError);
}

TEST_CASE("The suite of records/real/suite: twenty files, npts, dt and PGA as in the README", "[record_file]") {
  // Ten stations, both horizontal components each (records/real/README.md, "The suite"); the
  // how-to compare-dampers-by-fragility runs all of them. PGA is the README's, to its 3 digits.
  struct Case {
    const char* file;
    std::size_t npts;
    double dt;
    double pga_g;
  };
  const Case cases[] = {
      {"RSN125_FRIULI.A_A-TMZ000.AT2", 7277, 0.005, 0.357},    {"RSN125_FRIULI.A_A-TMZ270.AT2", 7279, 0.005, 0.315},
      {"RSN149_COYOTELK_G04270.AT2", 5437, 0.005, 0.233},      {"RSN149_COYOTELK_G04360.AT2", 5442, 0.005, 0.252},
      {"RSN181_IMPVALL.H_H-E06140.AT2", 7817, 0.005, 0.447},   {"RSN181_IMPVALL.H_H-E06230.AT2", 7818, 0.005, 0.449},
      {"RSN288_ITALY_A-BRZ000.AT2", 12064, 0.0029, 0.220},     {"RSN288_ITALY_A-BRZ270.AT2", 12064, 0.0029, 0.183},
      {"RSN595_WHITTIER.A_A-JAB207.AT2", 6852, 0.005, 0.229},  {"RSN595_WHITTIER.A_A-JAB297.AT2", 6853, 0.005, 0.222},
      {"RSN724_SUPER.B_B-PLS045.AT2", 2214, 0.01, 0.137},      {"RSN724_SUPER.B_B-PLS135.AT2", 2223, 0.01, 0.200},
      {"RSN763_LOMAP_GIL067.AT2", 7999, 0.005, 0.359},         {"RSN763_LOMAP_GIL337.AT2", 7999, 0.005, 0.327},
      {"RSN862_LANDERS_IND000.AT2", 3000, 0.02, 0.104},        {"RSN862_LANDERS_IND090.AT2", 3000, 0.02, 0.109},
      {"Rinaldi228.AT2", 1991, 0.01, 0.874},                   {"Rinaldi318.AT2", 1991, 0.01, 0.472},
      {"RSN1162_KOCAELI_GYN000.AT2", 5096, 0.005, 0.137},      {"RSN1162_KOCAELI_GYN090.AT2", 5096, 0.005, 0.120}};
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(records + "/suite"))
    if (entry.is_regular_file()) ++files;
  CHECK(files == std::size(cases));  // adjoin ida --suite reads every file of the folder
  for (const Case& c : cases) {
    INFO(c.file);
    const Record r = read_record(records + "/suite/" + c.file);
    CHECK(r.accel.size() == c.npts);
    CHECK(r.dt == c.dt);
    double peak = 0.0;
    for (double a : r.accel) peak = std::max(peak, std::abs(a));
    CHECK(peak / g == Approx(c.pga_g).margin(0.0005));
  }
}

TEST_CASE("AT2 header variants", "[record_file]") {
  const RecordFormat automatic;
  SECTION("NPTS line without trailing comma, DT written .0100, 5E15.7, CRLF") {
    const std::string text =
        "PEER NGA STRONG MOTION DATABASE RECORD\r\nSome event\r\nACCELERATION TIME SERIES IN UNITS OF G\r\n"
        "NPTS=     7, DT=   .0100 SEC\r\n  .1000000E+00  -.2000000E+00  .3000000E-01  0.4000000E+00  -5.0000000E-01\r\n"
        "  6.0000000E-02  7.0000000E-03\r\n";
    const Record r = parse_record(text, "variant.at2", automatic);
    REQUIRE(r.accel.size() == 7);
    CHECK(r.dt == 0.01);
    CHECK(r.accel[1] == Approx(-0.2 * g));
    CHECK(r.accel[6] == Approx(0.007 * g));
  }
  SECTION("8F10.5 layout with values that touch, rotated header, units in cm/s2") {
    const std::string text =
        "PEER NGA STRONG MOTION DATABASE RECORD - Rotated\nRSN1, Clockwise rot. 10 deg.\n"
        "ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC\nNPTS=  10, DT=   0.020 SEC,\n"
        "   1.00000   2.00000-123.12345  -4.00000   5.00000   6.00000   7.00000   8.00000\n"
        "   9.00000  10.00000\n";
    const Record r = parse_record(text, "rot.txt", automatic);
    REQUIRE(r.accel.size() == 10);
    CHECK(r.dt == 0.02);
    CHECK(r.accel[2] == Approx(-1.2312345));
    CHECK(r.accel[9] == Approx(0.1));
  }
  SECTION("older header: numbers before 'NPTS, DT', unit word on the acceleration line") {
    const std::string text = "Title\nEvent\nAcceleration (g)\n    3    0.0050    NPTS, DT\n 0.1 0.2 0.3\n";
    const Record r = parse_record(text, "old.AT2", automatic);
    REQUIRE(r.accel.size() == 3);
    CHECK(r.dt == 0.005);
    CHECK(r.accel[2] == Approx(0.3 * g));
  }
  SECTION("no units in the header: given units are used, none is an error") {
    const std::string text = "Title\nEvent\nsomething\nNPTS= 2, DT= 0.01\n1 2\n";
    CHECK(parse_record(text, "x.at2", with_units(AccelUnit::m_s2)).accel[1] == 2.0);
    CHECK_THAT(error_of(text, automatic), Contains("bad.txt:4:"));
    CHECK_THAT(error_of(text, automatic), Contains("units"));
  }
  SECTION("a velocity file is refused") {
    const std::string text = "PEER\nEvent\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 2, DT= 0.01\n1 2\n";
    CHECK_THAT(error_of(text, automatic), Contains("bad.txt:3:") && Contains("velocity"));
  }
}

TEST_CASE("AT2 defects name the line", "[record_file]") {
  const RecordFormat automatic;
  const std::string head = "PEER\nEvent\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  4, DT=   .0050 SEC,\n";
  CHECK_THAT(error_of(head + "1 2\n3 x4\n", automatic), Contains("bad.txt:6:") && Contains("'x4'") && Contains("not a number"));
  CHECK_THAT(error_of(head + "1 2\n3 nan\n", automatic), Contains("bad.txt:6:") && Contains("finite"));
  CHECK_THAT(error_of(head + "1 2\ninf 4\n", automatic), Contains("bad.txt:6:") && Contains("finite"));
  CHECK_THAT(error_of(head + "1 2\n3\n", automatic), Contains("bad.txt:6:") && Contains("NPTS = 4") && Contains("3 values"));
  CHECK_THAT(error_of(head + "1 2\n3 4\n5\n", automatic), Contains("bad.txt:7:") && Contains("more values than NPTS"));
  CHECK_THAT(error_of(head, automatic), Contains("bad.txt:4:") && Contains("0 values"));
  CHECK_THAT(error_of("PEER\nEvent\nACCELERATION IN UNITS OF G\nNPTS= 4 DT .005\n1 2 3 4\n", automatic),
             Contains("bad.txt:4:") && Contains("DT="));
  CHECK_THAT(error_of("PEER\nEvent\nACCELERATION IN UNITS OF G\nNPTS= 4.5, DT= .005\n1 2 3 4\n", automatic),
             Contains("bad.txt:4:") && Contains("whole number"));
  CHECK_THAT(error_of("PEER\nEvent\nACCELERATION IN UNITS OF G\nNPTS= 4, DT= -0.1\n1 2 3 4\n", automatic),
             Contains("bad.txt:4:") && Contains("DT"));
  RecordFormat at2;
  at2.kind = RecordFormat::Kind::at2;
  CHECK_THAT(error_of("", at2), Contains("bad.txt:1:") && Contains("empty"));
  CHECK_THAT(error_of("a\nb\nc\n", at2), Contains("bad.txt:3:") && Contains("NPTS"));
}

TEST_CASE("two-column files of the real records", "[record_file]") {
  struct Case {
    const char* file;
    AccelUnit unit;
    std::size_t npts;
    double first;
  };
  for (const Case& c : {Case{"two-column/elCentro.txt", AccelUnit::g, 1559, 0.00630 * g},
                        Case{"two-column/elcentro_NS_full.dat", AccelUnit::g, 2688, -1.4275799e-003 * g},
                        Case{"two-column/Kobe.dat", AccelUnit::m_s2, 1250, 0.0}}) {
    INFO(c.file);
    const Record r = read_record(records + "/" + c.file, with_units(c.unit));
    CHECK(r.accel.size() == c.npts);
    CHECK(r.dt == 0.02);  // exactly, after rounding to 12 significant digits
    CHECK(r.accel.front() == Approx(c.first).margin(1e-15));
    // Without units: an error naming the option.
    try {
      read_record(records + "/" + c.file);
      FAIL("no error without units");
    } catch (const InputError& e) {
      CHECK_THAT(std::string(e.what()), Contains(c.file) && Contains("--units"));
    }
  }
}

TEST_CASE("two columns: separators, comments, rounding of printed times", "[record_file]") {
  const RecordFormat f = with_units(AccelUnit::m_s2);
  SECTION("tabs, blanks, exponents, comments, a time origin that is not 0") {
    const Record r = parse_record("# comment\n% another\n\n0.10\t1\n 0.15  2e0 \n0.2 3.0E+00\n", "x", f);
    REQUIRE(r.accel.size() == 3);
    CHECK(r.dt == Approx(0.05).epsilon(1e-14));
    CHECK(r.accel[2] == 3.0);
    CHECK_THAT(r.description, Contains("shifted"));
  }
  SECTION("commas") {
    const Record r = parse_record("0,1\n0.5,2\n1.0,3\n", "x", f);
    CHECK(r.dt == 0.5);
    CHECK(r.accel[1] == 2.0);
  }
  SECTION("a step of 1/300 s printed with 4 decimals is uniform within the print resolution") {
    const Record r = parse_record("0.0000 1\n0.0033 2\n0.0067 3\n0.0100 4\n", "x", f);
    CHECK(r.dt == Approx(0.01 / 3.0).epsilon(1e-11));
  }
  SECTION("defects") {
    CHECK_THAT(error_of("0 1\n0.02 2\n0.04 x\n", f), Contains("bad.txt:3:") && Contains("'x'"));
    CHECK_THAT(error_of("0 1\n0.02 NaN\n", f), Contains("bad.txt:2:") && Contains("finite"));
    CHECK_THAT(error_of("0 1\n0.02 2\n0.02 3\n", f), Contains("bad.txt:3:") && Contains("does not increase"));
    CHECK_THAT(error_of("0 1\n0.02 2\n0.01 3\n", f), Contains("bad.txt:3:") && Contains("does not increase"));
    CHECK_THAT(error_of("0 1\n0.02 2\n0.04 3\n0.08 4\n0.10 5\n", f), Contains("bad.txt:4:") && Contains("uniform"));
    CHECK_THAT(error_of("0 1\n1 2\n3 3\n4 4\n", f), Contains("bad.txt:3:") && Contains("uniform"));
    CHECK_THAT(error_of("0 1\n0.0200 2\n0.0410 3\n0.0600 4\n", f), Contains("bad.txt:3:") && Contains("uniform"));
    CHECK_THAT(error_of("0 1\n0.02 2\n0.04\n", f), Contains("bad.txt:3:") && Contains("1 field"));
    CHECK_THAT(error_of("0 1\n0.02 2 3\n", f), Contains("bad.txt:2:") && Contains("3 fields"));
    CHECK_THAT(error_of("0 1\n", f), Contains("bad.txt:1:") && Contains("only one sample"));
    CHECK_THAT(error_of("", f), Contains("bad.txt:1:") && Contains("empty"));
    CHECK_THAT(error_of("# only a comment\n\n", f), Contains("bad.txt:2:") && Contains("empty"));
    CHECK_THAT(error_of("0 1\n0.02 1e999\n", f), Contains("bad.txt:2:") && Contains("range"));
    RecordFormat two = f;
    two.kind = RecordFormat::Kind::two_column;
    CHECK_THAT(error_of("", two), Contains("bad.txt:1:"));
    CHECK_THAT(error_of("t a\n0 1\n", two), Contains("bad.txt:1:") && Contains("'t'"));
    two.dt = 0.03;
    CHECK_THAT(error_of("0 1\n0.02 2\n", two), Contains("dt = 0.03"));
  }
}

TEST_CASE("one column with a given dt", "[record_file]") {
  RecordFormat f = with_units(AccelUnit::cm_s2);
  f.dt = 0.01;
  const Record r = parse_record("100\n-200\n# note\n+300\n1.5D+02\n", "one.txt", f);
  REQUIRE(r.accel.size() == 4);
  CHECK(r.dt == 0.01);
  CHECK(r.accel[0] == Approx(1.0));
  CHECK(r.accel[1] == Approx(-2.0));
  CHECK(r.accel[2] == Approx(3.0));
  CHECK(r.accel[3] == Approx(1.5));
  f.dt.reset();
  CHECK_THAT(error_of("1\n2\n", f), Contains("bad.txt") && Contains("--dt"));
  f.dt = 0.01;
  f.units.reset();
  CHECK_THAT(error_of("1\n2\n", f), Contains("bad.txt") && Contains("--units"));
  f.units = AccelUnit::g;
  CHECK_THAT(error_of("1\n2\n3 4 5\n", f), Contains("found 3 numbers") || Contains("bad.txt:3:"));
  f.kind = RecordFormat::Kind::one_column;
  CHECK_THAT(error_of("1\n2\n3 4\n", f), Contains("bad.txt:3:") && Contains("2 fields"));
  f.dt = -1.0;
  CHECK_THAT(error_of("1\n2\n", f), Contains("positive"));
}

TEST_CASE("delimited text with a header", "[record_file]") {
  SECTION("CSV, columns by name, units from the column name") {
    const std::string text = "# export\n\"time [s]\",\"vel\",\"acc [cm/s2]\"\n0.0,9,100\n0.01,9,200\n0.02,9,-50\n";
    const Record r = parse_record(text, "a.csv", RecordFormat{});
    REQUIRE(r.accel.size() == 3);
    CHECK(r.dt == Approx(0.01).epsilon(1e-14));
    CHECK(r.accel[1] == Approx(2.0));
    CHECK(r.accel[2] == Approx(-0.5));
  }
  SECTION("columns by index, semicolons, units given") {
    RecordFormat f = with_units(AccelUnit::g, RecordFormat::Kind::delimited);
    f.time_column = "3";
    f.accel_column = "1";
    const Record r = parse_record("x;y;z\n0.5;7;0\n0.25;7;0.02\n", "b.csv", f);
    REQUIRE(r.accel.size() == 2);
    CHECK(r.dt == Approx(0.02));
    CHECK(r.accel[1] == Approx(0.25 * g));
  }
  SECTION("blank separated, by name, no time column with dt") {
    RecordFormat f = with_units(AccelUnit::m_s2);
    f.dt = 0.1;
    f.accel_column = "ag";
    const Record r = parse_record("id ag\n1 0.5\n2 0.7\n", "c.txt", f);
    REQUIRE(r.accel.size() == 2);
    CHECK(r.dt == 0.1);
    CHECK(r.accel[1] == 0.7);
  }
  SECTION("defects") {
    RecordFormat f = with_units(AccelUnit::g);
    CHECK_THAT(error_of("t,a\n0,1\n0.1,\n", f), Contains("bad.txt:3:") && Contains("empty field"));
    CHECK_THAT(error_of("t,a\n0,1\n0.1,2,3\n", f), Contains("bad.txt:3:") && Contains("header on line 1"));
    CHECK_THAT(error_of("t,x,y\n0,1,2\n", f), Contains("bad.txt:1:") && Contains("--accel-column"));
    CHECK(parse_record("t,a,\n0,1,\n0.5,2,\n", "x", f).accel[1] == Approx(2 * g));
    f.accel_column = "nope";
    CHECK_THAT(error_of("t,a,b\n0,1,2\n", f), Contains("bad.txt:1:") && Contains("'nope'") && Contains("1:t, 2:a, 3:b"));
    f.accel_column = "4";
    CHECK_THAT(error_of("t,a,b\n0,1,2\n", f), Contains("bad.txt:1:") && Contains("does not exist"));
    f.accel_column = "2";
    CHECK_THAT(error_of("t,a,b\n0,1,2\n0.1,nan,2\n", f), Contains("bad.txt:3:") && Contains("finite"));
    CHECK_THAT(error_of("t,a,b\n", f), Contains("bad.txt:1:") && Contains("no data rows"));
  }
}

TEST_CASE("record kinds by name", "[record_file]") {
  RecordFormat::Kind k{};
  for (auto kind : {RecordFormat::Kind::automatic, RecordFormat::Kind::at2, RecordFormat::Kind::one_column,
                    RecordFormat::Kind::two_column, RecordFormat::Kind::delimited}) {
    REQUIRE(parse_record_kind(to_string(kind), &k));
    CHECK(k == kind);
  }
  CHECK(parse_record_kind("csv", &k));
  CHECK(k == RecordFormat::Kind::delimited);
  CHECK_FALSE(parse_record_kind("xml", &k));
}

TEST_CASE("missing file and folder", "[record_file]") {
  CHECK_THROWS_AS(read_record(records + "/no-such-file.AT2"), InputError);
  CHECK_THROWS_AS(read_record(records), InputError);
}

TEST_CASE("random corruptions parse or throw InputError, nothing else", "[record_file]") {
  const std::string seeds[] = {
      "PEER\nEvent\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  6, DT=   .0100 SEC,\n  .1E-01  -.2E+00  .3\n 4.  5. -6.\n",
      "# c\n0.00\t1.5\n0.01\t-2e-3\n0.02\t3\n0.03\t4\n",
      "t [s],acc [g]\n0,1\n0.5,2\n1.0,3\n",
  };
  std::uint64_t state = 12345;
  auto next = [&]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::size_t>(state >> 33);
  };
  const std::string alphabet = "0123456789.-+eEdD,; \t\n\r#%NPTSDT=nanifx";
  std::size_t parsed = 0, rejected = 0;
  for (const std::string& seed : seeds) {
    for (int trial = 0; trial < 3000; ++trial) {
      std::string text = seed;
      const std::size_t edits = 1 + next() % 3;
      for (std::size_t e = 0; e < edits && !text.empty(); ++e) {
        const std::size_t at = next() % text.size();
        switch (next() % 3) {
          case 0: text[at] = alphabet[next() % alphabet.size()]; break;
          case 1: text.erase(at, 1 + next() % 4); break;
          default: text.insert(at, 1, alphabet[next() % alphabet.size()]); break;
        }
      }
      RecordFormat f;
      f.units = AccelUnit::g;
      if (test::parses_or_is_refused(text, f)) ++parsed;
      else ++rejected;
    }
  }
  CHECK(parsed > 0);
  CHECK(rejected > 0);
}
