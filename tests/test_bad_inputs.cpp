// The catalogue of bad and extreme inputs: every case in tests/bad_inputs/*.toml runs the
// adjoin program on an input that once broke the contract (or could), and checks the contract:
//
//  - the exit status is the one the case expects (0, 2 bad input, 3 numerical failure; never
//    anything else);
//  - a failure says "error:" and the message names the place (the case lists the substrings
//    that must appear: the file, line, key or option, what is expected);
//  - stderr is printable text (no raw NUL bytes, control characters or binary garbage), and
//    never "internal:";
//  - the files the case names as `absent` did not appear, those named `finite` hold no NaN or
//    Inf, and no temporary file (*.tmp.*) is left anywhere in the case's folder.
//
// Case file format (TOML, one or more [[case]] tables per file, files grouped by topic):
//
//   [[case]]
//   name = "short description"            # unique over the catalogue
//   guards = "what defect it guards"      # optional, for the record
//   args = ["record", "info", "{tmp}/x"]  # the command line after `adjoin`
//   exit = 2
//   stderr = ["x:3:", "expected"]         # substrings stderr must contain
//   stderr_not = ["did you mean"]         # substrings it must not contain
//   absent = ["{tmp}/out"]                # paths that must not exist afterwards
//   exists = ["{tmp}/a.csv"]              # paths that must exist afterwards
//   finite = ["{tmp}/a.csv"]              # files with no nan/inf token (must exist)
//   same_as_before = ["{tmp}/out/a.json"] # files the command must leave as they were
//   cwd = "{tmp}/a/b"                     # working folder (default {tmp}; created)
//   env = { NAME = "value" }              # extra environment
//   seconds = 30                          # killed (and failed) if it runs longer: a case that
//                                         # guards a refusal must not hang without it
//   [[case.file]]                         # made before the command, in order
//   path = "{tmp}/scene.toml"
//   hex = "00ff.."      # content, in this order: hex bytes, a copied file, text, append
//   copy = "{scenes}/paper-strong.toml"
//   text = "..."
//   append = "..."
//   size = 1000000      # then resized (sparse zeros) to this many bytes
//   kind = "dir" | "fifo" | "readonly-dir"   # instead of a file (root ignores read-only
//                                            # folders: CI may run as root, so a case must not
//                                            # rely on one being refused)
//
// Placeholders: {tmp} the case's own empty folder, {records} records/real, {scenes}
// records/scenes, {source} the source tree, {long} 100,000 letters x (a key, value or line
// that must not be quoted whole: no line of stderr may be longer than 1,000 bytes).
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <cctype>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "cli_helpers.hpp"

namespace {

namespace fs = std::filesystem;

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

struct Placeholders {
  std::map<std::string, std::string> values;
  std::string operator()(std::string s) const {
    for (const auto& [k, v] : values) s = replace_all(s, k, v);
    return s;
  }
};

std::string shell_quote(const std::string& s) { return "'" + replace_all(s, "'", "'\\''") + "'"; }

std::vector<std::string> strings(const toml::table& t, const char* key, const Placeholders& p) {
  std::vector<std::string> out;
  if (const auto* a = t[key].as_array())
    for (const auto& v : *a) out.push_back(p(*v.value<std::string>()));
  return out;
}

std::string from_hex(const std::string& hex) {
  std::string out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return out;
}

void make_file(const toml::table& f, const Placeholders& p) {
  const fs::path path = p(f["path"].value_or(std::string()));
  REQUIRE(!path.empty());
  fs::create_directories(path.parent_path());
  const std::string kind = f["kind"].value_or(std::string("file"));
  if (kind == "dir") {
    fs::create_directories(path);
  } else if (kind == "readonly-dir") {
    fs::create_directories(path);
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_exec);
  } else if (kind == "fifo") {
    REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
  } else {
    std::string content;
    if (auto hex = f["hex"].value<std::string>()) content += from_hex(*hex);
    if (auto copy = f["copy"].value<std::string>()) content += adjoin::test::slurp(p(*copy));
    if (auto text = f["text"].value<std::string>()) content += p(*text);
    if (auto append = f["append"].value<std::string>()) content += p(*append);
    std::ofstream(path, std::ios::binary) << content;
    if (auto size = f["size"].value<std::int64_t>()) fs::resize_file(path, static_cast<std::uintmax_t>(*size));  // sparse
  }
}

// Non-printable bytes in the program's messages: anything below 0x20 but tab and newline, and
// DEL. (UTF-8 multi-byte sequences are allowed: file names may hold them.)
bool printable(const std::string& s) {
  for (unsigned char c : s)
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) return false;
  return true;
}

// A word "nan", "inf" or "infinity" (any case), standing alone: how printf, JSON writers and CSV
// writers spell a non-finite number. (Not std::regex: GCC 12 warns inside it under -Werror.)
bool has_non_finite(const std::string& text) {
  auto letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t i = 0; i < text.size();) {
    if (!letter(text[i])) { ++i; continue; }
    std::size_t j = i;
    while (j < text.size() && letter(text[j])) ++j;
    std::string word = text.substr(i, j - i);
    for (auto& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (word == "nan" || word == "inf" || word == "infinity") return true;
    i = j;
  }
  return false;
}

std::vector<fs::path> temporaries(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (it->path().filename().string().find(".tmp.") != std::string::npos) out.push_back(it->path());
  }
  return out;
}

void restore_permissions(const fs::path& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
  }
}

std::size_t longest_line(const std::string& text) {
  std::size_t longest = 0, start = 0;
  for (std::size_t end = text.find('\n'); start < text.size(); end = text.find('\n', start)) {
    if (end == std::string::npos) end = text.size();
    longest = std::max(longest, end - start);
    start = end + 1;
  }
  return longest;
}

struct Outcome {
  int status = -1;
  std::string err;
};

Outcome run_case(const std::vector<std::string>& args, const fs::path& cwd, const std::map<std::string, std::string>& env,
                 const fs::path& scratch, std::int64_t seconds) {
  std::string command = "cd " + shell_quote(cwd.string()) + " && ";
  if (seconds > 0) command += "timeout -s KILL " + std::to_string(seconds) + " ";
  command += "env";
  for (const auto& [k, v] : env) command += " " + shell_quote(k + "=" + v);
  command += " " + shell_quote(ADJOIN_CLI);
  for (const auto& a : args) command += " " + shell_quote(a);
  const fs::path out = scratch / "stdout", err = scratch / "stderr";
  command += " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string()) + " </dev/null";
  const int raw = std::system(command.c_str());
  Outcome o;
  o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  o.err = adjoin::test::slurp(err);
  return o;
}

}  // namespace

TEST_CASE("the catalogue of bad and extreme inputs keeps the contract", "[bad_inputs][cli]") {
  const fs::path catalogue = fs::path(ADJOIN_SOURCE_DIR) / "tests" / "bad_inputs";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(catalogue))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(!files.empty());

  const fs::path root = fs::path(ADJOIN_TEST_TMP) / "bad_inputs";
  std::set<std::string> names;
  int index = 0;
  for (const auto& file : files) {
    const toml::table doc = toml::parse_file(file.string());
    const auto* cases = doc["case"].as_array();
    REQUIRE(cases);
    for (const auto& node : *cases) {
      const toml::table& c = *node.as_table();
      const std::string name = c["name"].value_or(std::string());
      INFO(file.filename().string() << ": " << name);
      REQUIRE(!name.empty());
      CHECK(names.insert(name).second);  // unique names, so a failure is easy to find

      const fs::path tmp = root / ("c" + std::to_string(index++));
      fs::create_directories(tmp);
      const fs::path scratch = root / ("s" + std::to_string(index));
      fs::create_directories(scratch);
      Placeholders p;
      p.values = {{"{tmp}", tmp.string()},
                  {"{records}", (fs::path(ADJOIN_SOURCE_DIR) / "records" / "real").string()},
                  {"{scenes}", (fs::path(ADJOIN_SOURCE_DIR) / "records" / "scenes").string()},
                  {"{source}", std::string(ADJOIN_SOURCE_DIR)},
                  {"{long}", std::string(100000, 'x')}};
      if (const auto* made = c["file"].as_array())
        for (const auto& f : *made) make_file(*f.as_table(), p);
      const fs::path cwd = p(c["cwd"].value_or(std::string("{tmp}")));
      fs::create_directories(cwd);
      std::map<std::string, std::string> env;
      if (const auto* e = c["env"].as_table())
        for (const auto& [k, v] : *e) env[std::string(k.str())] = p(*v.value<std::string>());

      std::map<std::string, std::string> before;  // same_as_before: contents to compare
      for (const auto& path : strings(c, "same_as_before", p)) before[path] = adjoin::test::slurp(path);

      const Outcome o = run_case(strings(c, "args", p), cwd, env, scratch, c["seconds"].value_or(std::int64_t{0}));
      INFO("stderr: " << o.err);
      const int expected = static_cast<int>(c["exit"].value_or(std::int64_t{-1}));
      CHECK(o.status == expected);
      CHECK((o.status == 0 || o.status == 2 || o.status == 3));
      if (o.status != 0) CHECK(o.err.rfind("error:", 0) == 0);
      CHECK(o.err.find("internal:") == std::string::npos);
      CHECK(printable(o.err));
      CHECK(longest_line(o.err) <= 1000);  // user input is quoted as short excerpts
      for (const auto& s : strings(c, "stderr", p)) CHECK_THAT(o.err, Catch::Contains(s));
      for (const auto& s : strings(c, "stderr_not", p)) CHECK_THAT(o.err, !Catch::Contains(s));
      for (const auto& path : strings(c, "absent", p)) {
        INFO("must not exist: " << path);
        CHECK(!fs::exists(path));
      }
      for (const auto& path : strings(c, "exists", p)) {
        INFO("must exist: " << path);
        CHECK(fs::exists(path));
      }
      for (const auto& path : strings(c, "finite", p)) {
        INFO("must exist and be finite: " << path);
        REQUIRE(fs::exists(path));
        CHECK(!has_non_finite(adjoin::test::slurp(path)));
      }
      for (const auto& [path, content] : before) {
        INFO("must be left as it was: " << path);
        CHECK(adjoin::test::slurp(path) == content);
      }
      for (const auto& t : temporaries(tmp)) {
        INFO("temporary file left: " << t.string());
        CHECK(false);
      }
      restore_permissions(tmp);
    }
  }
  INFO("cases in the catalogue: " << names.size());
  CHECK(names.size() >= 100);  // the catalogue only grows (the trust issue asked for at least 80)
}
