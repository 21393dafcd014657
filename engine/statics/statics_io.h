// JSON in and out for the statics problem (docs/cli.md, `cablelab statics`).
//
// Input:  {"cables": [{"a": [x, y], "b": [x, y], "k": k, "L": L}, ...], "p0": [x, y]}
//         ("p0" optional; unknown keys are rejected so that a typo is not silently ignored).
// Output: {"p": [x, y], "lengths": [...], "tensions": [...], "energy": E, "iterations": n,
//          "solve_us": t, "residual": r, "solver": "newton" | "socp", "converged": bool}
//         with every number printed so that it reads back to the same double.
#pragma once

#include <string>

#include "engine/statics/statics.h"

namespace cablelab {

/// Parses and validates (validateStatics) a problem; throws InputError(source, field, what)
/// naming the field, e.g. "cables[2].k", for bad JSON, a wrong type or size, or a bad value.
StaticsProblem parseStaticsJson(const std::string& text, const std::string& source);

/// Reads the file and parses it; a missing or unreadable file is an InputError too.
StaticsProblem loadStaticsFile(const std::string& path);

/// The result as one JSON object (no trailing newline).
std::string staticsResultToJson(const StaticsResult& result);

}  // namespace cablelab
