// The one way files are opened: input files read whole, JSON parsed, output files checked and
// opened, each failure an InputError in the style of engine/core/error.h:
//   scene.json: (file): cannot open: No such file or directory (got "scene.json")
//   scene.json: (file): is a directory, not a file (got "scene.json")
//   scene.json: (json): not valid JSON at line 3, column 7: syntax error ...
//   command line: --csv: cannot write the file: Permission denied (got "/out/t.csv")
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace cablelab {

/// The whole content of an input file; a missing, unreadable or directory path is an InputError.
std::string readInputFile(const std::string& path);

/// Parses JSON text; a syntax error is InputError(source, "(json)", ...) with line and column.
nlohmann::json parseJsonText(const std::string& text, const std::string& source);

/// readInputFile + parseJsonText.
nlohmann::json readJsonFile(const std::string& path);

/// Throws unless `path` can be written: not a directory, its folder exists and is writable.
/// Creates nothing; call it before a long run so a bad --png fails at once.
void requireWritable(const std::string& path, const std::string& option);

/// Opens `path` for writing (truncating), or throws naming `option` (e.g. "--csv").
std::ofstream openOutputFile(const std::string& path, const std::string& option);

/// Throws unless everything written to `out` reached the file.
void finishOutputFile(std::ofstream& out, const std::string& path, const std::string& option);

}  // namespace cablelab
