// `cablelab gui [SCENE] [options of ui/gui_options.h]`: hands off to the sibling executable
// cablelab-gui. The sandbox links libGL (SDL2 window) while this CLI links libOSMesa
// (snapshots); one binary linking both renders blank OSMesa images, so they are two programs.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/command.h"
#include "ui/gui_options.h"

namespace cablelab::app {
namespace {

std::filesystem::path siblingGui() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  return (error ? std::filesystem::path(".") : self.parent_path()) / "cablelab-gui";
}

const bool guiRegistered = registerCommand(
    "gui", "The interactive sandbox (SDL2 + Dear ImGui), run as the sibling cablelab-gui",
    [](CLI::App& sub) {
      // The same options as cablelab-gui (one definition), so that both --help list them all;
      // cablelab-gui checks them (bad input: exit 2 before any window when unattended).
      auto args = std::make_shared<ui::GuiArguments>();
      ui::addGuiOptions(sub, *args);
      return [args]() {
        const std::string gui = siblingGui().string();
        std::vector<std::string> line{gui};
        for (std::string& a : ui::guiCommandLine(*args)) line.push_back(std::move(a));
        std::vector<char*> argv;
        for (std::string& a : line) argv.push_back(a.data());
        argv.push_back(nullptr);
        std::cout.flush();
        execv(gui.c_str(), argv.data());
        std::cerr << "cablelab gui: cannot start " << gui << ": " << std::strerror(errno)
                  << " (was the project built with CABLELAB_BUILD_UI=ON?)\n";
        return 1;
      };
    });

}  // namespace
}  // namespace cablelab::app
