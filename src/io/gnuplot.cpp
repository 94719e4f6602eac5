#include "adjoin/io/gnuplot.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <memory>

#include "adjoin/core/errors.hpp"

extern char** environ;

namespace adjoin {

std::string gnuplot_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\'') q += "''";
    else if (c == '\n') q += "\\n";
    else if (c == '\t') q += "\\t";
    else if (c == '\r') q += "\\r";
    else if (byte < 0x20 || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      q += hex;
    } else {
      q += c;
    }
  }
  return q + "'";
}

std::string gnuplot_quote_wrapped(const std::string& text, std::size_t width) {
  std::string expression, line;
  for (char c : text) {
    if (c == ' ' && line.size() >= width) {
      expression += gnuplot_quote(line) + ".\"\\n\".";
      line.clear();
      continue;
    }
    line += c;
  }
  return expression + gnuplot_quote(line);
}

std::string gnuplot_number(double v) {
  if (!std::isfinite(v)) return "NaN";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

std::string gnuplot_tick_format(const char* axis, const std::vector<double>& values, bool log) {
  double big = 0.0, small = INFINITY;
  for (double v : values)
    if (std::isfinite(v) && v != 0.0) big = std::max(big, std::abs(v)), small = std::min(small, std::abs(v));
  const bool scientific = big >= 1e5 || (big > 0.0 && big < 1e-3) || (log && small < 1e-3);
  if (!scientific) return std::string("set format ") + axis + " '%g'\n";
  return std::string("set format ") + axis + (log ? " '%.0te%T'\n" : " '%.1te%T'\n");
}

std::string gnuplot_tick_step(const char* axis, const std::vector<double>& values, double scale) {
  double lo = 0.0, hi = 0.0;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v / scale), hi = std::max(hi, v / scale);
  const double span = hi - lo;
  if (!(span > 0.0)) return std::string("set ") + axis + "tics autofreq\n";
  const double raw = span / 4.0, power = std::pow(10.0, std::floor(std::log10(raw))), m = raw / power;
  const double step = (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * power;
  return std::string("set ") + axis + "tics " + gnuplot_number(step) + "\n";
}

// A gnuplot datablock named $name with whitespace-separated rows; NaN cells are written as
// NaN (gnuplot skips those points and breaks the line there).
void gnuplot_datablock(std::ostringstream& script, const std::string& name, const std::vector<std::vector<double>>& columns) {
  script << "$" << name << " << EOD\n";
  const std::size_t n = columns.empty() ? 0 : columns.front().size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) script << (c ? " " : "") << gnuplot_number(columns[c][i]);
    script << "\n";
  }
  script << "EOD\n";
}

// Common look: light grid, readable fonts, 12 colours that differ (no two blues), each
// linetype with its own marker so that curves differ in print too. A 13th curve takes the
// first colour again: callers with more curves than that change the dash type as well.
const char* const kGnuplotPreamble =
    "set encoding utf8\n"
    "set grid lc rgb '#d0d0d0' lw 1\n"
    "set border lw 1.2\n"
    "set key opaque box lc rgb '#b0b0b0' samplen 2.5 spacing 1.1\n"
    "set linetype 1 lc rgb '#1f5fa8' lw 2 pt 7\n"
    "set linetype 2 lc rgb '#d0451b' lw 2 pt 5\n"
    "set linetype 3 lc rgb '#2e8b3a' lw 2 pt 9\n"
    "set linetype 4 lc rgb '#7b3fa0' lw 2 pt 11\n"
    "set linetype 5 lc rgb '#c08a00' lw 2 pt 13\n"
    "set linetype 6 lc rgb '#0f9b9b' lw 2 pt 6\n"
    "set linetype 7 lc rgb '#555555' lw 2 pt 4\n"
    "set linetype 8 lc rgb '#e377c2' lw 2 pt 8\n"
    "set linetype 9 lc rgb '#8c564b' lw 2 pt 10\n"
    "set linetype 10 lc rgb '#7fb8e6' lw 2 pt 12\n"
    "set linetype 11 lc rgb '#a5a815' lw 2 pt 1\n"
    "set linetype 12 lc rgb '#000000' lw 2 pt 2\n"
    "set linetype cycle 12\n";

namespace {

// An anonymous temporary file (removed by the system when closed, never left behind).
struct TempFile {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file{std::tmpfile(), &std::fclose};
  int fd() const { return ::fileno(file.get()); }
  std::string contents() const {
    std::string bytes;
    std::rewind(file.get());
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0;) bytes.append(buffer, n);
    return bytes;
  }
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A whole image: PNG signature and IEND chunk (with its CRC) at the end; an SVG closed.
bool complete_image(const std::string& bytes, const std::string& format) {
  if (format == "png")
    return bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0 && ends_with(bytes, std::string("IEND\xae\x42\x60\x82", 8));
  const auto end = bytes.find_last_not_of(" \t\r\n");
  return bytes.find("<svg") != std::string::npos && end != std::string::npos &&
         ends_with(bytes.substr(0, end + 1), "</svg>");
}

// gnuplot reads the script from a file (a failing command stops it with a non-zero status,
// which it does not when reading a pipe) and writes the image to another; no shell.
int spawn_gnuplot(const TempFile& script, const TempFile& image, const TempFile& errors) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, script.fd(), 0);
  posix_spawn_file_actions_adddup2(&actions, image.fd(), 1);
  posix_spawn_file_actions_adddup2(&actions, errors.fd(), 2);
  char program[] = "gnuplot", input[] = "/dev/stdin";
  char* argv[] = {program, input, nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, program, &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -2;
  return status;
}

}  // namespace

std::string run_gnuplot(const std::string& script, const std::string& format, const std::string& what) {
  TempFile script_file, image, errors;
  if (!script_file.file || !image.file || !errors.file)
    throw InputError(what + ": cannot create a temporary file for gnuplot (is the temporary folder full?)");
  if (std::fwrite(script.data(), 1, script.size(), script_file.file.get()) != script.size() ||
      std::fflush(script_file.file.get()) != 0)
    throw InputError(what + ": cannot write the gnuplot script to a temporary file (is the temporary folder full?)");
  std::rewind(script_file.file.get());
  const int status = spawn_gnuplot(script_file, image, errors);
  if (status == -1) throw InputError(what + ": cannot run gnuplot (is it installed? scripts/setup.sh installs it)");
  if (status != 0) {
    std::string message = errors.contents();
    if (message.size() > 2000) message = message.substr(0, 2000) + "...";
    const std::string how = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                                : "exit status " + std::to_string(WEXITSTATUS(status));
    throw InputError(what + ": gnuplot failed (" + how + ")" + (message.empty() ? "" : ": " + message));
  }
  std::string bytes = image.contents();
  if (!complete_image(bytes, format))
    throw InputError(what + ": gnuplot wrote an incomplete " + format + " image (" + std::to_string(bytes.size()) +
                     " bytes: its write failed, on a full disk or over a file size limit); nothing was written");
  return bytes;
}

std::string gnuplot_log_tics(const char* axis, double lo, double hi) {
  if (!(lo > 0.0 && hi > lo) || hi / lo >= 100.0) return "";
  std::string list;
  for (int e = static_cast<int>(std::floor(std::log10(lo))) - 1; e <= static_cast<int>(std::ceil(std::log10(hi))); ++e)
    for (double m : hi / lo < 10.0 ? std::vector<double>{1, 1.5, 2, 3, 4, 5, 6, 8} : std::vector<double>{1, 2, 5}) {
      const double v = m * std::pow(10.0, e);
      if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9)) continue;
      char text[64];
      std::snprintf(text, sizeof text, "%s\"%g\" %.12g", list.empty() ? "" : ", ", v, v);
      list += text;
    }
  return list.empty() ? "" : "set " + std::string(axis) + "tics (" + list + ")\n";
}

}  // namespace adjoin
