// The worlds that measure how the engine scales (tests/bench/mujoco_bench.cpp, `cablelab bench`):
// built here, saved under tests/data/bench/ (a test checks the files are these scenes), and
// stepped by cablelab and by MuJoCo from the same SceneDef.
#pragma once

#include <string>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab {

/// `n` independent Atwood machines side by side, 2 m apart: two 1 kg discs hung over two world
/// pulleys 0.5 m apart by one rigid cable, both swinging sideways at 0.2 m/s. Equal masses, so
/// nothing runs into a pulley however long it is stepped.
SceneDef makeAtwoodMachines(int n);

/// One rigid cable from a world anchor down and up over `pulleys` point pulleys: world pulleys
/// 1 m apart alternating with a point on top of each of pulleys / 2 hanging 1 kg discs (a block
/// and tackle), the discs moving up and down in alternation at 0.1 m/s. `pulleys` must be even.
SceneDef makePulleyChain(int pulleys);

/// One rope of `n` 1 kg discs, each hung 0.6 m below the one above by one rigid cable between
/// their centres, the first from a world anchor: one island of n cables whose rows share bodies
/// (a chain: K tridiagonal). Every disc moves sideways at 0.2 m/s (the whole rope swings).
/// Links are longer than kFloorWatch, so the cables get no floor rows.
SceneDef makeHangingChain(int n);

/// A curtain: `rows` x `cols` 1 kg discs 0.6 m apart, each joined to its right and lower
/// neighbours by rigid cables and the top row hung from world anchors: one island of
/// rows (2 cols - 1) cables on a 2-D mesh. The discs swing sideways at 0.2 m/s.
SceneDef makeCableNet(int rows, int cols);

/// A benchmark case: a name ("atwood_256", "pulleys_64") and its scene.
struct ScaleCase {
  std::string name;
  SceneDef scene;
};

/// The cases of issue 11's scale table: atwood_1, _16, _256, _1024 and pulleys_64.
std::vector<ScaleCase> scaleCases();

/// One big island each: chain_16, _64, _256, _1024 (makeHangingChain) and net_4x4 .. net_32x32.
std::vector<ScaleCase> bigIslandCases();

}  // namespace cablelab
