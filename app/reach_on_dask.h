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

/// Fills r's targets (from reachGrid) with their verdicts computed on the scheduler's workers,
/// and r.threads with the workers' thread count. An unreachable scheduler is an InputError on
/// --scheduler; a missing Python module or failing tasks a std::runtime_error.
void evaluateReachOnDask(const std::string& address, const ReachOptions& options, ReachResult& r,
                         Progress& progress);

}  // namespace cablelab::app
