#pragma once
// The adjoin program's commands register themselves: each src/cli/<command>.cpp defines one
// static Registration, so adding a command touches no other file.
//
// main() adds the subcommand `name` with its `description` to the app, and the command's
// `setup` gives it its options and returns the function that runs it once parsed. main() sets
// up only the command the command line names (all of them when it names none: --help,
// --version, a typo). Runners return an exit status or throw adjoin::InputError (exit 2) or
// adjoin::NumericalError (exit 3); main() turns those into "error: ..." on stderr.
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"

namespace adjoin::cli {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App* subcommand)>;

struct Registration {
  // Lower order lists first in --help.
  Registration(int order, std::string name, std::string description, Setup setup);
};

struct RegisteredCommand {
  int order;
  std::string name;  // the subcommand's name: `adjoin <name> ...`
  std::string description;
  Setup setup;
};
std::vector<RegisteredCommand>& registry();

// Draws a --plot figure after the command's own output is safely written. The plot's target
// was checked up front (plot_target); gnuplot missing or failing now is still the user's
// setup to fix, so exit status 2, and the message says the data output is kept
// ("error: --plot ...; <written>").
inline int draw_figure(const std::function<void()>& draw, const std::string& written) {
  try {
    draw();
  } catch (const InputError& e) {
    std::cerr << "error: --plot " << e.what() << "; " << written << " (kept)\n";
    return kExitInputError;
  }
  return 0;
}

}  // namespace adjoin::cli
