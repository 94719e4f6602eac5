#pragma once
// Runs the built adjoin program from a test and captures its exit status and output.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace adjoin::test {

struct CliResult {
  int status = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `text` (a path, an option's value) as one single-quoted word of a POSIX shell command line.
inline std::string shell_word(const std::string& text) {
  std::string word = "'";
  for (char c : text) word += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return word + "'";
}
inline std::string shell_word(const std::filesystem::path& path) { return shell_word(path.string()); }

// `arguments` is pasted into a shell command line after the program path.
inline CliResult run_cli(const std::string& arguments) {
  static int counter = 0;
  const std::filesystem::path tmp = ADJOIN_TEST_TMP;
  std::filesystem::create_directories(tmp);
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const auto out = tmp / ("cli_" + tag + ".out"), err = tmp / ("cli_" + tag + ".err");
  const std::string command = std::string("'") + ADJOIN_CLI + "' " + arguments + " >'" + out.string() +
                              "' 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  CliResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Writes `text` to a fresh file under the test scratch folder and returns its path.
inline std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace adjoin::test
