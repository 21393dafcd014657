// One main for all benchmark files (each file only registers its benchmarks).
//   cablelab_bench --write-scenes=DIR   writes the scale cases (engine/scenes/scale_scenes.h) as
//                                       scene files into DIR and exits (tests/data/bench/).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "engine/model/scene_json.h"
#include "engine/scenes/scale_scenes.h"

int main(int argc, char** argv) {
  const std::string flag = "--write-scenes=";
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]).rfind(flag, 0) == 0) {
      const std::string dir = std::string(argv[i]).substr(flag.size());
      for (const cablelab::ScaleCase& c : cablelab::scaleCases()) {
        const std::string path = dir + "/" + c.name + ".json";
        std::ofstream out(path);  // compact: atwood_1024 has 2048 bodies
        out << cablelab::sceneToJson(c.scene).dump() << "\n";
        if (!out) return std::fprintf(stderr, "cannot write %s\n", path.c_str()), 1;
        std::printf("wrote %s\n", path.c_str());
      }
      return 0;
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
