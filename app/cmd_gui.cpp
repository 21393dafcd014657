// `cablelab gui [SCENE] [--frames N] [--screenshot F.png]`: hands off to the sibling
// executable cablelab-gui. The sandbox links libGL (SDL2 window) while this CLI links libOSMesa
// (snapshots); one binary linking both renders blank OSMesa images, so they are two programs.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/command.h"

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
      auto scene = std::make_shared<std::string>();
      auto frames = std::make_shared<int>(0);
      auto screenshot = std::make_shared<std::string>();
      sub.add_option("scene", *scene, "built-in scene name or scene JSON file (default: hand)");
      sub.add_option("--frames", *frames, "quit after N frames and print {\"frames\", \"fps\"}")
          ->check(CLI::NonNegativeNumber);
      sub.add_option("--screenshot", *screenshot, "save the last frame as PNG");
      sub.allow_extras();  // further cablelab-gui options pass through (see cablelab-gui --help)
      return [=, &sub]() {
        const std::string gui = siblingGui().string();
        std::vector<std::string> args{gui};
        if (!scene->empty()) args.push_back(*scene);
        if (*frames > 0) args.insert(args.end(), {"--frames", std::to_string(*frames)});
        if (!screenshot->empty()) args.insert(args.end(), {"--screenshot", *screenshot});
        for (const std::string& extra : sub.remaining()) args.push_back(extra);
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
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
