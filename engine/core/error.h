// InputError: the one exception type for bad user input (scene files, CLI values, data files).
// The CLI turns it into exit code 2 and one line on stderr, always in the same style:
//   SOURCE: FIELD: what is wrong (got VALUE)
// SOURCE is the file, or "command line"; FIELD the JSON path ("bodies[2].mass"), the option
// ("--dt"), "(file)" for the file as a whole or "(json)" for its syntax. VALUE is written by
// gotValue(): numbers as the shortest text that reads back as the same double, text quoted.
#pragma once

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

namespace cablelab {

/// The one number format of messages: shortest round-trip text ("-1", "0.1", "1e+300", "nan").
inline std::string formatNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  const auto [end, error] = std::to_chars(buf, buf + sizeof buf, v);
  return error == std::errc() ? std::string(buf, end) : std::string("?");
}

/// Text as it appears in a message: quoted, control characters escaped, at most 60 characters.
inline std::string quoteText(std::string_view text) {
  std::string out = "\"";
  for (size_t i = 0; i < text.size(); ++i) {
    if (i == 57 && text.size() > 60) return out + "...\"";
    const char c = text[i];
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      out += c == '\n' ? "\\n" : c == '\t' ? "\\t" : "?";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

/// " (got VALUE)", to end a message.
inline std::string gotValue(double v) {
  return " (got " + formatNumber(v) + ")";
}
inline std::string gotValue(std::string_view text) {
  return " (got " + quoteText(text) + ")";
}
inline std::string gotValue(const char* text) {
  return gotValue(std::string_view(text));
}
inline std::string gotValue(const std::string& text) {
  return gotValue(std::string_view(text));
}

class InputError : public std::runtime_error {
 public:
  /// @param source the file, or "command line", the bad value came from
  /// @param field  a JSON path to the value ("bodies[2].mass") or the option ("--dt")
  /// @param what   what is wrong, e.g. "must be positive" + gotValue(-1)
  InputError(std::string source, std::string field, std::string what)
      : std::runtime_error(oneLine(source + ": " + field + ": " + what)),
        source_(std::move(source)),
        field_(std::move(field)),
        detail_(std::move(what)) {}

  const std::string& source() const { return source_; }
  const std::string& field() const { return field_; }
  /// What is wrong, without source and field.
  const std::string& detail() const { return detail_; }

 private:
  // Messages are one line on stderr, whatever a library's text contained.
  static std::string oneLine(std::string s) {
    for (char& c : s)
      if (c == '\n' || c == '\r') c = ' ';
    return s;
  }
  std::string source_;
  std::string field_;
  std::string detail_;
};

/// The SOURCE of every command-line value.
inline const char* const kCommandLine = "command line";

/// A simulation that cannot continue (NaN, degenerate geometry the guards cannot repair).
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cablelab
