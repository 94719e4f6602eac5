// adjoin spectrum --suite RECORD|FOLDER... --out DIR [--target T --t1 S|--band TA,TB [--scaling fit|uniform]]
//
// The elastic spectra of a suite of records and their statistics (post/suite.hpp), written as
// one set into DIR (temporary files renamed only when all are complete, io/atomic_file.hpp):
//   <record file name>.csv  each record's spectrum, period,damping,sd,sv,sa,psv,psa (unscaled)
//   suite.csv               period,damping,mean,median,minus1sigma,plus1sigma (PSA in g), then
//                           target with --target (empty where the table does not reach) and
//                           scaled_mean with --t1 or --band
//   factors.csv             record,factor with --t1 or --band (removed when a run does not scale)
// --t1 scales the suite over 0.2 T1 ... 2 T1, --band TA,TB over TA ... TB (rule in post/suite.hpp): --scaling fit (default) first scales each
// record to its own least-squares fit of the target in ln PSA over 0.2 T1 ... 2 T1, uniform
// leaves them; then one common multiplier puts the scaled geometric mean's lowest ratio to
// the target over the band at exactly 0.9. A summary goes to stdout. Which inputs are records: every file named; in a folder (not its
// subfolders, not hidden files) every file whose header a reader recognises (the automatic
// format's content sniffers), or every file when --format names one. Folder files nobody
// recognises (column text, notes) are skipped with a warning that names them. Two records
// whose output names collide (the same file name in two folders) are refused, as are a file
// given twice and a suite of one (its standard deviation is undefined).
#include "spectrum_suite.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/csv_line.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

namespace fs = std::filesystem;

struct Member {
  std::string path;    // as given, or folder / file name
  std::string output;  // <file name>.csv
};

// The records of the suite; `skipped` gets the folder files that are not records (reported
// once the suite is written: an error, if any, comes first on stderr).
std::vector<Member> collect(const SuiteRequest& r, std::vector<std::string>* skipped) {
  std::vector<Member> members;
  const bool any_format = r.format.kind == RecordFormat::Kind::automatic;
  for (const std::string& input : r.inputs) {
    std::error_code ec;
    if (!fs::is_directory(input, ec)) {
      members.push_back({input, fs::path(input).filename().string() + ".csv"});
      continue;
    }
    std::vector<fs::path> files;
    for (auto it = fs::directory_iterator(input, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
      if (it->is_regular_file(ec) && it->path().filename().string().front() != '.') files.push_back(it->path());
    if (ec) throw InputError(input + ": cannot list the folder: " + ec.message());
    std::sort(files.begin(), files.end());
    std::size_t taken = 0;
    for (const fs::path& file : files) {
      if (any_format && detect_record_format(file) == RecordFormat::Kind::automatic) {
        skipped->push_back(file.string());
        continue;
      }
      members.push_back({file.string(), file.filename().string() + ".csv"});
      ++taken;
    }
    if (taken == 0)
      throw InputError(input + ": " +
                       (files.empty() ? std::string("an empty folder (expected record files)")
                                      : "none of its " + std::to_string(files.size()) +
                                            " files has a header a record reader recognises (column text "
                                            "needs --format), e.g. " + files[0].filename().string()));
  }
  // One file twice, or two outputs of one name, would leave one spectrum counted twice or
  // overwritten: refuse them with both names.
  std::map<std::string, std::string> seen_path, seen_output{{"suite.csv", ""}, {"factors.csv", ""}};
  for (const Member& m : members) {
    std::error_code ec;
    const std::string canonical = fs::weakly_canonical(m.path, ec).string();
    const auto [at, fresh] = seen_path.emplace(ec ? m.path : canonical, m.path);
    if (!fresh) throw InputError(m.path + ": given twice in the suite (also as " + at->second + ")");
    const auto [out, free] = seen_output.emplace(m.output, m.path);
    if (!free)
      throw InputError(m.path + (out->second.empty() ? ": its spectrum would be written to " + m.output +
                                                           ", a name the suite's own file has (rename the record)"
                                                     : " and " + out->second + " have the same file name: both "
                                                           "spectra would be " + m.output + " (rename one)"));
  }
  if (members.size() < 2)
    throw InputError("--suite: a suite of one record (" + (members.empty() ? std::string("none") : members[0].path) +
                     "): its standard deviation is undefined; for one record's spectrum leave out --suite");
  return members;
}

std::string cell(double v) {
  char s[32];
  std::snprintf(s, sizeof s, ",%.10g", v);
  return s;
}

void write_suite_csv(std::ostream& out, const SuiteStatistics& s, const SuiteRequest& r, const SuiteStatistics* scaled) {
  out << "period,damping,mean,median,minus1sigma,plus1sigma" << (r.target ? ",target" : "")
      << (scaled ? ",scaled_mean" : "") << "\n";
  for (std::size_t d = 0; d < s.dampings.size(); ++d)
    for (std::size_t i = 0; i < s.periods.size(); ++i) {
      const std::size_t at = d * s.periods.size() + i;
      const double t = s.periods[i];
      std::string line = cell(t).substr(1) + cell(s.dampings[d]) + cell(s.mean[at]) + cell(s.median[at]) +
                         cell(s.minus1sigma[at]) + cell(s.plus1sigma[at]);
      // Empty, not NaN, where a target table does not reach the period.
      if (r.target)
        line += t >= r.target->min_period() && t <= r.target->max_period() ? cell(r.target->psa_at(t, s.dampings[d]))
                                                                           : std::string(",");
      if (scaled) line += cell(scaled->mean[at]);
      out << line << "\n";
    }
}

// Every record thin, the statistics thick, at the first damping (the one a target is for).
void plot_suite(const SuiteRequest& r, const std::vector<Member>& members, const std::vector<ResponseSpectrum>& spectra,
                const SuiteStatistics& s, const SuiteScale* scale) {
  std::ostringstream script;
  std::string plots;
  const std::size_t np = s.periods.size();
  auto block = [&](const std::string& name, auto value) {
    script << "$" << name << " << EOD\n";
    for (std::size_t i = 0; i < np; ++i)
      if (s.periods[i] > 0.0) script << s.periods[i] << " " << value(i) << "\n";
    script << "EOD\n";
  };
  for (std::size_t k = 0; k < spectra.size(); ++k) {
    const double f = scale ? scale->factors[k] : 1.0;
    block("r" + std::to_string(k), [&](std::size_t i) { return f * spectra[k].at(0, i).psa; });
    plots += "$r" + std::to_string(k) + " using 1:2 with lines lw 0.7 lc rgb '#b8b8b8' " +
             (k == 0 ? "title " + gnuplot_quote(std::to_string(members.size()) + " records") : "notitle") + ", ";
  }
  block("mean", [&](std::size_t i) { return s.mean[i]; });
  block("median", [&](std::size_t i) { return s.median[i]; });
  block("lo", [&](std::size_t i) { return s.minus1sigma[i]; });
  block("hi", [&](std::size_t i) { return s.plus1sigma[i]; });
  plots += "$mean using 1:2 with lines lw 2.5 lc rgb '#1f5fa8' title 'mean (geometric)', "
           "$median using 1:2 with lines lw 2 lc rgb '#2e8b3a' title 'median', "
           "$lo using 1:2 with lines lw 1.5 dt 2 lc rgb '#1f5fa8' title '-1σ: mean / exp(σ of ln PSA)', "
           "$hi using 1:2 with lines lw 1.5 dt 2 lc rgb '#1f5fa8' title '+1σ: mean × exp(σ of ln PSA)'";
  if (r.target) {
    const double zeta = s.dampings[0];
    auto covered = [&](std::size_t i) {
      return s.periods[i] >= r.target->min_period() && s.periods[i] <= r.target->max_period();
    };
    script << "$target << EOD\n";
    for (std::size_t i = 0; i < np; ++i)
      if (s.periods[i] > 0.0 && covered(i))
        script << s.periods[i] << " " << r.target->psa_at(s.periods[i], zeta) << "\n";
    script << "EOD\n";
    plots += ", $target using 1:2 with lines lw 2 dt 3 lc rgb 'black' title " +
             gnuplot_quote("target: " + (r.target->kind == TargetSpectrum::Kind::table
                                             ? fs::path(r.target->name).filename().string()
                                             : r.target->name));
    if (scale) {
      char label[64];
      std::snprintf(label, sizeof label, "%g × target", r.scaling->min_ratio);
      plots += ", $target using 1:($2*" + std::to_string(r.scaling->min_ratio) +
               ") with lines lw 1 dt 4 lc rgb '#d0451b' title " + gnuplot_quote(label);
      script << "set arrow from " << scale->band_min << ", graph 0 to " << scale->band_min
             << ", graph 1 nohead dt 2 lc rgb '#d0451b'\nset arrow from " << scale->band_max << ", graph 0 to "
             << scale->band_max << ", graph 1 nohead dt 2 lc rgb '#d0451b'\n";
    }
  }
  char title[160];
  std::snprintf(title, sizeof title, "Suite of %zu records, PSA at %g %%%s", members.size(), 100.0 * s.dampings[0],
                !scale ? "" : r.scaling->t1 > 0.0 ? ", scaled (band 0.2 T_1 ... 2 T_1 marked)" : ", scaled (band marked)");
  script << "set title " << gnuplot_quote(title) << "\nset logscale xy\nset format x '%g'\nset format y '%g'\n"
         << "set grid xtics mxtics ytics lc rgb '#d0d0d0'\nset xlabel 'period T [s]'\nset ylabel 'PSA [g]'\n"
         << "set key bottom left noenhanced\nplot " << plots << "\n";
  render_gnuplot(script.str(), r.plot, r.style);
}

}  // namespace

int suite_command(const SuiteRequest& r) {
  if (r.out.empty())
    throw InputError("--out: a suite writes a folder (DIR/<record>.csv, DIR/suite.csv, DIR/factors.csv): give --out DIR");
  check_output_folder(r.out);  // a suite writes a folder
  std::vector<std::string> skipped;
  const std::vector<Member> members = collect(r, &skipped);

  SpectrumOptions options = r.options;
  if (options.periods.empty()) options.periods = default_spectrum_periods();
  if (r.scaling) options.periods = suite_periods(options.periods, *r.scaling);
  std::vector<ResponseSpectrum> spectra;
  std::vector<std::string> names;
  std::vector<Record> records;
  for (const Member& m : members) {
    records.push_back(read_record(m.path, r.format));
    spectra.push_back(response_spectrum(records.back(), options));
    names.push_back(m.path);
  }
  const SuiteStatistics stats = suite_statistics(spectra, names);
  std::optional<SuiteScale> scale;
  std::optional<SuiteStatistics> scaled;
  if (r.scaling) {
    try {
      scale = scale_suite(spectra, *r.target, *r.scaling, names);
    } catch (const InputError& e) {
      throw InputError(std::string(r.scaling->t1 > 0.0 ? "--t1" : "--band") + "/--target: " + e.what());
    }
    scaled = suite_statistics(spectra, names, scale->factors);
  }

  std::vector<std::string> set_names{"suite.csv", "factors.csv"};
  for (const Member& m : members) set_names.push_back(m.output);
  FileSet files(r.out, set_names);
  for (std::size_t k = 0; k < members.size(); ++k) write_spectrum_csv(files.open(members[k].output), spectra[k]);
  write_suite_csv(files.open("suite.csv"), stats, r, scaled ? &*scaled : nullptr);
  if (scale) {
    std::ostream& f = files.open("factors.csv");
    f << "record,factor\n";
    for (std::size_t k = 0; k < members.size(); ++k) f << csv_line({members[k].path}) << cell(scale->factors[k]) << "\n";
  }
  files.commit();

  std::printf("suite of %zu records, %zu periods, damping %s:\n", members.size(), options.periods.size(),
              [&] {
                std::string d;
                for (double z : options.dampings) d += (d.empty() ? "" : ", ") + cell(100.0 * z).substr(1) + " %";
                return d;
              }().c_str());
  int width = 0;
  for (const Member& m : members) width = std::max(width, static_cast<int>(m.path.size()));
  for (std::size_t k = 0; k < members.size(); ++k)
    std::printf("  %-*s  dt %g s, %zu samples%s\n", width, members[k].path.c_str(), records[k].dt, records[k].accel.size(),
                scale ? ("  factor " + cell(scale->factors[k]).substr(1)).c_str() : "");
  if (scale) {
    const char* rule = r.scaling->rule == SuiteScaling::fit
                           ? "each record fitted to the target (least squares in ln PSA), all then multiplied by"
                           : "one factor for all records,";
    char band[64];
    if (r.scaling->t1 > 0.0) std::snprintf(band, sizeof band, "T1 = %g s", r.scaling->t1);
    else std::snprintf(band, sizeof band, "--band");
    std::printf("scaled to %s over %g ... %g s (%s, %zu periods): %s c = %.6g\n"
                "  scaled mean / target: %.4g at T = %g s (lowest), %.4g at T = %g s (highest)\n",
                r.target->name.c_str(), scale->band_min, scale->band_max, band, scale->band_periods, rule,
                scale->common, r.scaling->min_ratio, scale->min_ratio_period, scale->max_ratio,
                scale->max_ratio_period);
  }
  std::printf("written to %s: suite.csv%s and %zu record spectra\n", r.out.c_str(), scale ? ", factors.csv" : "",
              members.size());
  std::fflush(stdout);
  for (const std::string& file : skipped)
    std::cerr << "warning: skipped " << file
              << ": no record header recognised (column text is read when named, or with --format)\n";

  if (r.plot.empty()) return 0;
  return draw_figure([&] { plot_suite(r, members, spectra, scaled ? *scaled : stats, scale ? &*scale : nullptr); },
                     "the suite was written to " + r.out);
}

}  // namespace adjoin::cli
