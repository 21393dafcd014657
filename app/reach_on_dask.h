// `cablelab reach --scheduler ADDRESS`: the reach grid's targets evaluated on a Dask cluster.
// The CLI starts `python3 -m cablelab._reach_on_dask` (python/cablelab/_reach_on_dask.py), which
// runs the grid's rows as cablelab.sweep tasks on the scheduler's workers with the engine's own
// per-target code and streams the verdicts back as JSON lines; the sets, areas, JSON and CSV are
// then made here exactly as for the run on local threads (docs/cli.md, "reach on Dask").
#pragma once

#include <string>

#include "app/progress.h"
#include "engine/hand/hand_reach.h"

namespace cablelab::app {

/// runReach's result (HandModel{}, the CLI's hand) with the targets evaluated on the workers of
/// the Dask scheduler at `address`; threads: the workers' thread count; progress: rows done. An
/// unreachable scheduler is an InputError on --scheduler; a missing Python module or failing
/// tasks a std::runtime_error.
ReachResult runReachOnDask(const std::string& address, const ReachOptions& options,
                           Progress& progress);

}  // namespace cablelab::app
