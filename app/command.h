// Subcommand registry: each app/cmd_*.cpp registers itself, main() never lists them.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace cablelab::app {

/// Declares the subcommand's options on `sub` and returns the function that runs it
/// (returning the process exit code). Throw cablelab::InputError for bad input.
using CommandSetup = std::function<std::function<int()>(CLI::App& sub)>;

struct Command {
  std::string name;
  std::string description;
  CommandSetup setup;
};

/// Registers a subcommand; call from a namespace-scope initializer in the command's file.
bool registerCommand(std::string name, std::string description, CommandSetup setup);

/// All registered commands, sorted by name.
const std::vector<Command>& commands();

/// Writes `json` (already serialised) to stdout followed by a newline.
void printJson(const std::string& json);

}  // namespace cablelab::app
