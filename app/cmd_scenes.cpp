// cablelab scenes: one line per built-in scene, with its --set parameters.
#include <cstdio>
#include <filesystem>

#include "app/command.h"
#include "engine/core/error.h"
#include "engine/model/scene_json.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab::app {
namespace {

const bool scenesRegistered =
    registerCommand("scenes", "List the built-in scenes, one line each", [](CLI::App& sub) {
      auto verbose = std::make_shared<bool>(false);
      sub.add_flag("-v,--verbose", *verbose,
                   "Also list each scene's parameters with defaults and units");
      auto exportDir = std::make_shared<std::string>();
      sub.add_option("--export", *exportDir,
                     "Write every built-in scene (default parameters) as DIR/NAME.json");
      return [verbose, exportDir] {
        std::error_code error;
        if (!exportDir->empty() && !std::filesystem::is_directory(*exportDir, error))
          throw InputError(kCommandLine, "--export", "no such folder" + gotValue(*exportDir));
        if (!exportDir->empty())
          for (const SceneInfo& s : builtinScenes())
            saveSceneFile(makeScene(s.name), *exportDir + "/" + s.name + ".json");
        for (const SceneInfo& s : builtinScenes()) {
          std::string params;
          for (const SceneParam& p : s.params) params += (params.empty() ? "" : ",") + p.name;
          std::printf("%-10s %s [params: %s]\n", s.name.c_str(), s.description.c_str(),
                      params.c_str());
          if (*verbose)
            for (const SceneParam& p : s.params)
              std::printf("    %-10s = %-8g %s\n", p.name.c_str(), p.value, p.description.c_str());
        }
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
