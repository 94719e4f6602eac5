// The reference pages (docs/reference/) against the code they describe. Where the code has a
// table, the page holds a block generated from it between two markers
//
//     <!-- BEGIN generated: NAME (tests/test_docs_reference.cpp) -->
//     ...
//     <!-- END generated: NAME -->
//
// and the block must equal what the code gives today: every command and option of `adjoin`
// (from each command's --help, so an option added to the CLI and not to cli.md fails), every
// key of a two-block scene (known_scene_keys()) and of a building scene's structure (the
// building reader's own lists of accepted keys and types, asked by giving it an unknown one),
// the channels of a building run (structure::quantities()) and the building sweep's columns
// (building_sweep_channels()). The two-block sweep's columns (sweep_columns()) must each be
// named on the outputs page. `ADJOIN_UPDATE_DOCS=1 build/tests/test_docs_reference` rewrites
// the blocks from the code (then check the diff, and the prose around them).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "building_scene_error.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "adjoin/study/sweep.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;
using adjoin::test::run_cli;
using adjoin::test::slurp;

namespace {

const std::filesystem::path kReference = std::filesystem::path(ADJOIN_SOURCE_DIR) / "docs" / "reference";

// Checks the generated block NAME of a reference page; with ADJOIN_UPDATE_DOCS set, rewrites it first.
void check_generated(const std::string& page, const std::string& name, const std::string& expected) {
  const auto path = kReference / page;
  std::string text = slurp(path);
  const std::string begin = "<!-- BEGIN generated: " + name + " (tests/test_docs_reference.cpp) -->\n";
  const std::string end = "<!-- END generated: " + name + " -->";
  const auto b = text.find(begin);
  INFO(page << " must hold the block " << begin << "...\n" << end);
  REQUIRE(b != std::string::npos);
  const auto e = text.find(end, b);
  REQUIRE(e != std::string::npos);
  const auto from = b + begin.size();
  if (std::getenv("ADJOIN_UPDATE_DOCS") && text.substr(from, e - from) != expected) {
    text.replace(from, e - from, expected);
    std::ofstream(path, std::ios::binary) << text;
  }
  const std::string actual = slurp(path).substr(from, expected.size());
  INFO("docs/reference/" << page << " differs from the code; the block should read (ADJOIN_UPDATE_DOCS=1 "
       "build/tests/test_docs_reference rewrites it):\n" << expected);
  CHECK(actual == expected);
  CHECK(slurp(path).compare(from + expected.size(), end.size(), end) == 0);
}

// Text for a Markdown table cell or line: '|' would end the cell and "<name>" read as an HTML tag.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : c == '<' ? std::string("&lt;") : std::string(1, c);
  return out;
}

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : sep) + i;
  return out;
}

// ---- the command line, from --help ----

struct HelpEntry {
  std::string spec, text;  // "--out TEXT", "Output folder ..."
};

struct HelpPage {
  std::string description;
  std::vector<HelpEntry> positionals, options;
  std::vector<std::string> subcommands;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(' ') - b + 1);
}

// CLI11's help: the description, "Usage: ...", then sections "Positionals:", "Options:",
// "Subcommands:" of entries "  SPEC  TEXT" (a long SPEC puts TEXT on the next, indented line).
HelpPage parse_help(const std::string& out) {
  HelpPage page;
  std::istringstream in(out);
  std::string line, section;
  std::getline(in, page.description);
  std::vector<HelpEntry>* entries = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("Usage:", 0) == 0 || trim(line).empty()) continue;
    if (line[0] != ' ') {
      section = line;
      entries = section == "Positionals:" ? &page.positionals : section == "Options:" ? &page.options : nullptr;
      continue;
    }
    const bool starts_entry = line.size() > 2 && line[2] != ' ';
    if (section == "Subcommands:") {
      if (starts_entry) page.subcommands.push_back(trim(line.substr(0, line.find("  ", 2))));
      continue;
    }
    if (!entries) continue;
    if (starts_entry) {
      const auto gap = line.find("  ", 2);
      entries->push_back({trim(line.substr(0, gap)), gap == std::string::npos ? "" : trim(line.substr(gap))});
    } else if (!entries->empty()) {
      auto& text = entries->back().text;
      text += (text.empty() ? "" : " ") + trim(line);
    }
  }
  return page;
}

void describe_command(const std::string& path, std::string& md) {
  const auto r = run_cli(path + " --help");
  INFO("adjoin " << path << " --help: " << r.err);
  REQUIRE(r.status == 0);
  const HelpPage page = parse_help(r.out);
  md += "### `adjoin" + (path.empty() ? "" : " " + path) + "`\n\n" + cell(page.description) + "\n\n";
  std::vector<HelpEntry> entries = page.positionals;
  for (const auto& o : page.options)
    if (o.spec != "-h,--help") entries.push_back(o);
  if (!entries.empty()) {
    md += "| argument | meaning |\n|---|---|\n";
    for (const auto& e : entries) md += "| `" + e.spec + "` | " + cell(e.text) + " |\n";
    md += "\n";
  }
  if (!page.subcommands.empty()) {
    std::vector<std::string> names;
    for (const auto& s : page.subcommands) names.push_back("`" + s + "`");
    md += "Subcommands: " + join(names, ", ") + ".\n\n";
  }
  for (const auto& s : page.subcommands) describe_command(path.empty() ? s : path + " " + s, md);
}

// ---- the building reader's accepted keys, asked by giving it an unknown one ----

const std::string kBuilding = R"([model]
units = "SI"
[building.A]
storeys = 2
mass = 1e4
stiffness = 1e7
damping = { model = "modal", ratio = 0.05 }
[[building.A.device]]
type = "dashpot"
storeys = [1]
c = 1e4
[building.B]
storeys = 1
mass = 1e4
stiffness = 1e7
[[link]]
floors = [1, 1]
type = "friction"
slip_force = 1e3
[[contact]]
floors = [1, 1]
gap = 0.05
[ground]
source = "decaying-sine"
u0 = 0.01
omega = 5
k = 0.5
[solver]
h = 0.01
t_end = 1
)";

// The reader's message for kBuilding with `from` replaced by `to`.
std::string building_error(const std::string& from, const std::string& to) {
  return test::building_scene_error(kBuilding, from, to, "docs-keys.toml");
}

// The list after "expected one of " in the message, quotes dropped.
std::vector<std::string> expected_list(const std::string& message) {
  const std::string lead = "expected one of ";
  const auto at = message.find(lead);
  INFO(message);
  REQUIRE(at != std::string::npos);
  std::vector<std::string> items;
  std::istringstream in(message.substr(at + lead.size()));
  std::string item;
  while (std::getline(in, item, ',')) {
    item = trim(item);
    if (item.size() >= 2 && item.front() == '"') item = item.substr(1, item.size() - 2);
    items.push_back(item);
  }
  return items;
}

std::string code_list(const std::vector<std::string>& items) {
  std::vector<std::string> quoted;
  for (const auto& i : items) quoted.push_back("`" + i + "`");
  return join(quoted, ", ");
}

std::string building_keys_block() {
  std::string md;
  const auto keys = [&](const std::string& table, const std::string& from, const std::string& to) {
    md += "- " + table + ": " + code_list(expected_list(building_error(from, to))) + "\n";
  };
  keys("`building`", "[building.A]", "[building]\nzzz = 1\n[building.A]");
  keys("`building.X`", "storeys = 2", "storeys = 2\nzzz = 1");
  const auto damping = expected_list(building_error("model = \"modal\"", "model = \"zzz\""));
  keys("`building.X.damping` (`model` = " + code_list(damping) + ")", "ratio = 0.05 }", "ratio = 0.05, zzz = 1 }");
  const std::string device = "type = \"dashpot\"\nstoreys = [1]\nc = 1e4";
  for (const auto& type : expected_list(building_error(device, "type = \"zzz\"\nstoreys = [1]")))
    keys("`[[building.X.device]]` `type = \"" + type + "\"`", device, "type = \"" + type + "\"\nstoreys = [1]\nzzz = 1");
  const std::string link = "type = \"friction\"\nslip_force = 1e3";
  for (const auto& type : expected_list(building_error(link, "type = \"zzz\"")))
    keys("`[[link]]` `type = \"" + type + "\"`", link, "type = \"" + type + "\"\nzzz = 1");
  keys("`[[contact]]`", "gap = 0.05", "gap = 0.05\nzzz = 1");
  md += "- `[[contact]]` `model`: " + code_list(expected_list(building_error("gap = 0.05", "gap = 0.05\nmodel = \"zzz\""))) + "\n";
  keys("`model`", "units = \"SI\"", "units = \"SI\"\nzzz = 1");
  return md;
}

std::string scene_keys_block() {
  std::map<std::string, std::vector<std::string>> by_section;
  std::vector<std::string> order;
  for (const auto& key : known_scene_keys()) {
    const auto dot = key.find('.');
    const std::string section = dot == std::string::npos ? "" : key.substr(0, dot);
    if (!by_section.count(section)) order.push_back(section);
    by_section[section].push_back("`" + key + "`");
  }
  std::string md;
  for (const auto& s : order) md += "- " + (s.empty() ? std::string("top level") : "`[" + s + "]`") + ": " + join(by_section[s], ", ") + "\n";
  return md;
}

std::string channels_block() {
  using structure::ChannelScope;
  std::string md = "| channel | quantity | unit | peak | in timeseries.csv |\n|---|---|---|---|---|\n";
  for (const auto& q : structure::quantities()) {
    std::string name;
    switch (q.scope) {
      case ChannelScope::floor:
      case ChannelScope::storey: name = std::string("X.") + q.stem + "N" + q.suffix; break;
      case ChannelScope::building: name = std::string("X.") + q.stem; break;
      case ChannelScope::link: name = std::string("linkN.") + q.stem; break;
      case ChannelScope::contact: name = std::string("contactN.") + q.stem; break;
    }
    const char* peak = q.peak == structure::PeakRule::refined ? "refined between samples"
                       : q.peak == structure::PeakRule::sampled ? "largest sample"
                                                                : "none (the pair's `contacts` entry)";
    md += "| `" + name + "` | " + cell(q.meaning) + " | " + q.unit + " | " + peak + " | " + (q.timeseries ? "yes" : "no") + " |\n";
  }
  return md;
}

std::string sweep_channels_block() {
  std::string md = "| column | unit | meaning |\n|---|---|---|\n";
  for (const auto& c : building_sweep_channels()) md += "| `" + c.name + "` | " + c.unit + " | " + cell(c.meaning) + " |\n";
  return md;
}

}  // namespace

TEST_CASE("docs: the CLI reference lists every command and every option of adjoin --help", "[docs]") {
  std::string md;
  describe_command("", md);
  // The tree must have been read: the commands and options any reader looks for first.
  CHECK(md.find("### `adjoin run`") != std::string::npos);
  CHECK(md.find("### `adjoin record process`") != std::string::npos);
  CHECK(md.find("### `adjoin plot sweep`") != std::string::npos);
  CHECK(md.find("| `--allow-long` |") != std::string::npos);
  check_generated("cli.md", "commands", md);
}

TEST_CASE("docs: the scene key reference lists every key the two-block reader knows", "[docs]") {
  const std::string md = scene_keys_block();
  CHECK(md.find("`model.rod1.tau_x`") != std::string::npos);
  CHECK(md.find("`ground.match_ec8`") != std::string::npos);
  check_generated("scene-keys.md", "two-block keys", md);
}

TEST_CASE("docs: the scene key reference lists every key and type the building reader accepts", "[docs]") {
  const std::string md = building_keys_block();
  CHECK(md.find("`slip_ratio`") != std::string::npos);
  CHECK(md.find("`type = \"zener\"`") != std::string::npos);
  CHECK(md.find("`hertzdamp`") != std::string::npos);
  check_generated("scene-keys.md", "building keys", md);
}

TEST_CASE("docs: the channel reference lists every quantity of a building run", "[docs]") {
  const std::string md = channels_block();
  CHECK(md.find("`X.aN_abs`") != std::string::npos);
  check_generated("channels.md", "channels", md);
}

TEST_CASE("docs: the output reference lists every building sweep column of the registry", "[docs]") {
  check_generated("outputs.md", "building sweep columns", sweep_channels_block());
}

TEST_CASE("docs: the output reference names every column of a two-block and a building sweep", "[docs]") {
  const std::string page = slurp(kReference / "outputs.md");
  const auto examples = std::filesystem::path(ADJOIN_SOURCE_DIR) / "examples" / "sweeps";
  for (const char* file : {"slip-force.toml", "optimum-slip-force.toml", "demand.toml"}) {
    const SweepSpec spec = load_sweep(examples / file);
    std::vector<std::string> axes;
    for (const auto& a : spec.axes) axes.push_back(a.name);
    std::size_t checked = 0;
    for (const auto& c : sweep_columns(spec)) {
      if (std::find(axes.begin(), axes.end(), c.name) != axes.end()) continue;  // the user's own axis names
      std::string name = c.name;
      if (name.rfind("sa_", 0) == 0) name = "sa_T";  // sa_0.5: one column per im_periods entry
      // Building A's or B's column, link k's, contact pair k's: the registry's template.
      if (name.size() > 2 && (name[0] == 'A' || name[0] == 'B') && name[1] == '.') name = "X." + name.substr(2);
      for (const std::string stem : {"link", "contact"})
        if (name.rfind(stem, 0) == 0 && name.size() > stem.size() && std::isdigit(static_cast<unsigned char>(name[stem.size()])))
          name = stem + "N" + name.substr(name.find('.'));
      INFO(file << ": column " << c.name);
      CHECK(page.find("`" + name) != std::string::npos);
      ++checked;
    }
    CHECK(checked >= 10);
  }
}
