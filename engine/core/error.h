// InputError: the one exception type for bad user input (scene files, CLI values, data files).
// The CLI turns it into exit code 2 and one line on stderr: "<source>: <field>: <what is wrong>".
#pragma once

#include <stdexcept>
#include <string>

namespace cablelab {

class InputError : public std::runtime_error {
 public:
  /// @param source the file (or "--set", "<stdin>") the bad value came from
  /// @param field  a JSON-pointer-like path to the value, e.g. "bodies[2].mass"
  /// @param what   what is wrong, e.g. "must be positive (got -1)"
  InputError(std::string source, std::string field, std::string what)
      : std::runtime_error(source + ": " + field + ": " + what),
        source_(std::move(source)),
        field_(std::move(field)) {}

  const std::string& source() const { return source_; }
  const std::string& field() const { return field_; }

 private:
  std::string source_;
  std::string field_;
};

/// A simulation that cannot continue (NaN, degenerate geometry the guards cannot repair).
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cablelab
