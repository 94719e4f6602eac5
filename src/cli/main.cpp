// adjoin: the command-line program. Parses the command line, dispatches to a command and maps
// failures to exit statuses: 0 success, 2 bad input, 3 numerical failure (and, for the
// exceptions nobody foresaw, 3 with "internal": the contract has no other status).
#include <algorithm>
#include <exception>
#include <new>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/text_file.hpp"
#include "command.hpp"

namespace adjoin::cli {

std::vector<RegisteredCommand>& registry() {
  static std::vector<RegisteredCommand> commands;
  return commands;
}

Registration::Registration(int order, std::string name, std::string description, Setup setup) {
  registry().push_back(RegisteredCommand{order, std::move(name), std::move(description), std::move(setup)});
}

namespace {

// The commands to set up, in --help's order: only the one the first argument names (adding
// every command's options and help texts costs more instructions than starting a short run's
// process otherwise does), or all of them when it names none (`adjoin --help`, `--version`, a
// misspelt command), so that the help lists everything and CLI11's messages are unchanged.
std::vector<RegisteredCommand> commands_to_set_up(int argc, char** argv) {
  std::vector<RegisteredCommand> commands = registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  if (argc < 2) return commands;
  const std::string first = argv[1];
  const auto named = std::find_if(commands.begin(), commands.end(), [&](const auto& c) { return c.name == first; });
  if (named == commands.end()) return commands;
  return {*named};
}

// An option given an empty value (--ductility '', --delimiter '') would read as one not given,
// as the commands take "" for "absent": refused, naming the option. (--title '' asks for no
// title.)
void refuse_empty_values(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) {
    for (const CLI::Option* o : sub->get_options()) {
      if (o->get_type_size() == 0 || o->get_name() == "--title") continue;  // flags take no value
      const std::string name = o->get_name().empty() ? o->get_name(true) : o->get_name();  // --option, or a positional's name
      for (const std::string& value : o->results())
        if (value.empty()) throw InputError(name + ": an empty value; give one, or leave the option out");
    }
    refuse_empty_values(*sub);
  }
}

// CLI11's own messages quote the offending argument whole: a word longer than `longest`
// characters is cut to an excerpt. (Our messages quote user text as excerpts where they build
// it; a path or value longer than any real one (PATH_MAX is 4096) is cut here as well.)
std::string shortened(const std::string& message, std::size_t longest = 80) {
  std::string out, word;
  const auto flush = [&] {
    out += word.size() > longest ? word.substr(0, 60) + "..." : word;
    word.clear();
  };
  for (char c : message) {
    if (c == ' ') {
      flush();
      out += c;
    } else {
      word += c;
    }
  }
  flush();
  return out;
}

}  // namespace

}  // namespace adjoin::cli

int main(int argc, char** argv) {
  using namespace adjoin;
  CLI::App app{"adjoin: earthquake response of two adjacent structures joined by a friction damper "
               "and held by fractional viscoelastic rods"};
  app.set_version_flag("--version", std::string("adjoin ") + ADJOIN_VERSION);
  app.require_subcommand(1);

  std::vector<std::pair<CLI::App*, cli::Runner>> runners;
  for (auto& command : cli::commands_to_set_up(argc, argv)) {
    CLI::App* sub = app.add_subcommand(command.name, command.description);
    runners.emplace_back(sub, command.setup(sub));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << printable_message(cli::shortened(e.what())) << " (see adjoin --help)\n";
    return kExitInputError;
  }

  try {
    cli::refuse_empty_values(app);
    for (auto& [sub, runner] : runners)
      if (sub->parsed()) return runner();
    return 0;
  } catch (const InputError& e) {
    std::cerr << "error: " << printable_message(cli::shortened(e.what(), 4096)) << "\n";
    return kExitInputError;
  } catch (const NumericalError& e) {
    std::cerr << "error: numerical failure: " << printable_message(cli::shortened(e.what(), 4096)) << "\n";
    return kExitNumericalError;
  } catch (const std::bad_alloc&) {
    // Inputs are sized up front (records, runs, sweeps refuse what would not fit); reaching
    // this means an estimate missed a case.
    std::cerr << "error: numerical failure: out of memory; reduce the problem's size (steps, samples, runs)\n";
    return kExitNumericalError;
  } catch (const std::exception& e) {
    // A bug, not the user's fault; still within the documented exit statuses.
    std::cerr << "error: internal: " << printable_message(e.what()) << " (please report this)\n";
    return kExitNumericalError;
  }
}
