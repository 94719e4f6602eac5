#pragma once
// The adjoin program's commands register themselves: each src/cli/<command>.cpp defines one
// static Registration, so adding a command touches no other file.
//
// A command's `setup` adds its subcommand `name` (options, help) to the app and returns the
// function that runs it once parsed; main() sets up only the command the command line names
// (all of them when it names none: --help, --version, a typo), and checks that `name` is the
// subcommand's. Runners return an exit status or throw adjoin::InputError (exit 2) or
// adjoin::NumericalError (exit 3); main() turns those into "error: ..." on stderr.
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"

namespace adjoin::cli {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App& app)>;

struct Registration {
  Registration(int order, std::string name, Setup setup);  // lower order lists first in --help
};

struct RegisteredCommand {
  int order;
  std::string name;  // the subcommand's name, as `setup` adds it
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
