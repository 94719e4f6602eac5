// Parse speed of the record readers (bytes per second as reported by Google Benchmark): two
// PEER AT2 records of records/real, read into memory first, and a generated CSV of 10^6
// rows. Run: build/bench/bench_readers
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "adjoin/ground/record_file.hpp"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void parse_text(benchmark::State& state, const std::string& text, const std::string& name, const adjoin::RecordFormat& format) {
  if (text.empty()) {
    state.SkipWithError(("cannot read " + name).c_str());
    return;
  }
  std::size_t npts = 0;
  for (auto _ : state) {
    const adjoin::Record r = adjoin::parse_record(text, name, format);
    npts = r.accel.size();
    benchmark::DoNotOptimize(r.accel.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(text.size()));
  state.counters["npts"] = static_cast<double>(npts);
  state.counters["MB"] = static_cast<double>(text.size()) / 1e6;
}

void BM_at2_chichi(benchmark::State& state) {
  static const std::string path = std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN1546_CHICHI_TCU122-N.AT2";
  static const std::string text = slurp(path);
  parse_text(state, text, path, {});
}

void BM_at2_chino_hills(benchmark::State& state) {
  static const std::string path = std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN8883_14383980_13849090.AT2";
  static const std::string text = slurp(path);
  parse_text(state, text, path, {});
}

std::string generated(char separator, bool header) {
  std::string text;
  if (header) text = separator == ',' ? "time [s],acc [g]\n" : "time acc\n";
  text.reserve(32u << 20);
  char line[64];
  for (int i = 0; i < 1000000; ++i) {
    const double t = i * 0.005;
    const double a = 0.3 * std::sin(0.7 * t) * std::exp(-0.01 * t) + 1e-3 * std::sin(37.0 * t);
    const int n = std::snprintf(line, sizeof line, "%.3f%c%.7e\n", t, separator, a);
    text.append(line, static_cast<std::size_t>(n));
  }
  return text;
}

void BM_csv_1e6_rows(benchmark::State& state) {
  static const std::string text = generated(',', true);
  parse_text(state, text, "generated.csv", {});
}

void BM_two_column_1e6_rows(benchmark::State& state) {
  static const std::string text = generated(' ', false);
  adjoin::RecordFormat format;
  format.units = adjoin::AccelUnit::g;
  parse_text(state, text, "generated.txt", format);
}

}  // namespace

BENCHMARK(BM_at2_chichi)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_at2_chino_hills)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_csv_1e6_rows)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_two_column_1e6_rows)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
