// cablelab: the command-line entry point. Subcommands register themselves (see command.h).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>

#include "app/command.h"
#include "engine/core/error.h"
#include "engine/core/parse.h"

namespace cablelab::app {

static std::vector<Command>& registry() {
  static std::vector<Command> all;
  return all;
}

bool registerCommand(std::string name, std::string description, CommandSetup setup) {
  registry().push_back({std::move(name), std::move(description), std::move(setup)});
  return true;
}

const std::vector<Command>& commands() {
  auto& all = registry();
  std::sort(all.begin(), all.end(),
            [](const Command& a, const Command& b) { return a.name < b.name; });
  return all;
}

void printJson(const std::string& json) {
  std::fwrite(json.data(), 1, json.size(), stdout);
  std::fputc('\n', stdout);
  std::fflush(stdout);
}

}  // namespace cablelab::app

int main(int argc, char** argv) {
  using namespace cablelab;
  CLI::App cli{"cablelab: cable-driven soft robots on Box2D"};
  cli.require_subcommand(1);
  std::map<CLI::App*, std::function<int()>> runners;
  for (const auto& command : app::commands()) {
    CLI::App* sub = cli.add_subcommand(command.name, command.description);
    runners[sub] = command.setup(*sub);
  }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string help = "see cablelab --help";
    bool inCommand = false;
    for (const auto& [sub, run] : runners)
      if (sub->parsed()) help = "see cablelab " + sub->get_name() + " --help", inCommand = true;
    // A first word that is no command: CLI11 says only "A subcommand is required".
    if (!inCommand && argc > 1 && argv[1][0] != '-') {
      std::string known;
      for (const auto& command : app::commands())
        known += (known.empty() ? "" : ", ") + std::string(command.name);
      std::cerr << InputError(kCommandLine, "COMMAND",
                              "no such command (known: " + known + ")" + gotValue(argv[1]))
                       .what()
                << "\n";
      return 2;
    }
    std::cerr << commandLineError(e.what(), help).what() << "\n";
    return 2;
  }
  try {
    for (auto& [sub, run] : runners)
      if (sub->parsed()) return run();
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const SimulationError& e) {
    std::cerr << "simulation stopped: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "cablelab: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
