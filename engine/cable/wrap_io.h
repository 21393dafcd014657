// JSON in and out for `cablelab wrap` (docs/cli.md), shared by the CLI and the fuzzer.
//
// Input:  {"A": [x, y], "B": [x, y], "polygon": [[x, y], ...], "side": "left" | "right"}
//         (a convex polygon in either orientation).
// Output: {"path": [[x, y], ...], "length": l, "contact_vertices": [i, ...]} with the vertex
//         indices of the input order.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab {

struct WrapProblem {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  std::vector<Vec2> polygon;  ///< counter-clockwise (reversed from the input if needed)
  std::vector<int> order;     ///< polygon[i] is input vertex order[i]
  WrapSide side = WrapSide::Left;
};

struct WrapSolution {
  std::vector<Vec2> path;     ///< A, contact vertices, B
  double length = 0;          ///< m
  std::vector<int> contacts;  ///< input vertex indices, path order
};

/// Validates a parsed document; throws InputError(source, field, what) naming the field, also
/// for unknown keys.
WrapProblem parseWrapJson(const nlohmann::json& in, const std::string& source);
/// Parses text first (bad JSON is an InputError "(json)").
WrapProblem parseWrapText(const std::string& text, const std::string& source);
/// Reads the file (engine/core/file_input.h), then parseWrapText.
WrapProblem loadWrapFile(const std::string& path);

/// The taut path; throws InputError when A or B lies inside the polygon.
WrapSolution solveWrap(const WrapProblem& problem, const std::string& source);

nlohmann::json wrapSolutionToJson(const WrapSolution& solution);

}  // namespace cablelab
