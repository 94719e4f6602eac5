#pragma once
// The adjoin program's commands register themselves: each src/cli/<command>.cpp defines one
// static Registration, so adding a command touches no other file.
//
// A command's `setup` adds its subcommand (options, help) to the app and returns the function
// that runs it once parsed. Runners return an exit status or throw adjoin::InputError (exit 2)
// or adjoin::NumericalError (exit 3); main() turns those into "error: ..." on stderr.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace adjoin::cli {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App& app)>;

struct Registration {
  Registration(int order, Setup setup);  // lower order lists first in --help
};

struct RegisteredCommand {
  int order;
  Setup setup;
};
std::vector<RegisteredCommand>& registry();

}  // namespace adjoin::cli
