#include "engine/core/parse.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <regex>

#include "engine/core/error.h"

namespace cablelab {

std::optional<double> parseFiniteNumber(std::string_view text) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  // from_chars takes no leading plus; a sign after it ("+-1") must still fail.
  if (begin != end && *begin == '+' && end - begin > 1 && begin[1] != '-') ++begin;
  double value = 0;
  const auto [stop, error] = std::from_chars(begin, end, value, std::chars_format::general);
  if (begin == end || error != std::errc() || stop != end || !std::isfinite(value))
    return std::nullopt;
  return value;
}

double parseNumber(std::string_view text, const std::string& source, const std::string& field) {
  const auto v = parseFiniteNumber(text);
  if (!v) throw InputError(source, field, "must be a finite number" + gotValue(text));
  return *v;
}

void requireInRange(double v, const std::string& source, const std::string& field, double lo,
                    double hi) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw InputError(
        source, field,
        "must be a number in [" + formatNumber(lo) + ", " + formatNumber(hi) + "]" + gotValue(v));
}

long parseWholeNumber(std::string_view text, const std::string& source, const std::string& field,
                      long lo, long hi) {
  const auto v = parseFiniteNumber(text);
  if (!v || *v != std::floor(*v) || *v < static_cast<double>(lo) || *v > static_cast<double>(hi))
    throw InputError(source, field,
                     "must be a whole number in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]" + gotValue(text));
  return static_cast<long>(*v);
}

std::vector<double> parseNumberList(std::string_view text, size_t count, const std::string& source,
                                    const std::string& field, const std::string& shape) {
  std::vector<double> values;
  bool ok = true;
  size_t start = 0;
  while (ok) {
    const size_t comma = text.find(',', start);
    const auto v =
        parseFiniteNumber(text.substr(start, comma == text.npos ? comma : comma - start));
    if (v) values.push_back(*v);
    ok = v.has_value();
    if (comma == text.npos) break;
    start = comma + 1;
  }
  if (!ok || values.size() != count)
    throw InputError(
        source, field,
        "must be " + shape + ", " + std::to_string(count) + " finite numbers" + gotValue(text));
  return values;
}

PixelSize parsePixelSize(std::string_view text, const std::string& source, const std::string& field,
                         int minSide, int maxSide) {
  size_t x = text.find_first_of("xX");
  if (x == text.npos) x = text.size();  // no 'x': the height below is empty, so it fails
  const auto w = parseFiniteNumber(text.substr(0, x));
  const auto h = parseFiniteNumber(text.substr(std::min(x + 1, text.size())));
  auto side = [&](const std::optional<double>& v) {
    return v && *v == std::floor(*v) && *v >= minSide && *v <= maxSide;
  };
  if (!side(w) || !side(h))
    throw InputError(source, field,
                     "must be WxH, each a whole number in [" + std::to_string(minSide) + ", " +
                         std::to_string(maxSide) + "]" + gotValue(text));
  return {static_cast<int>(*w), static_cast<int>(*h)};
}

InputError commandLineError(const std::string& message, const std::string& help) {
  static const std::regex notAllowed(R"(^The value (.*) is not an allowed value for (\S+)$)");
  static const std::regex noConversion(R"(^Could not convert: (\S+) = (.*)$)");
  static const std::regex required(R"(^(\S+) is required$)");
  static const std::regex named(R"(^(-{1,2}[A-Za-z0-9][\w-]*): (.*)$)");
  static const std::regex extra(R"(^The following arguments? (?:was|were) not expected: (.*)$)");
  const std::string tail = help.empty() ? "" : " (" + help + ")";
  std::smatch m;
  if (std::regex_match(message, m, notAllowed))
    return InputError(kCommandLine, m[2], "not an allowed value" + gotValue(m[1].str()) + tail);
  if (std::regex_match(message, m, noConversion))
    return InputError(kCommandLine, m[1], "cannot convert the value" + gotValue(m[2].str()) + tail);
  if (std::regex_match(message, m, required))
    return InputError(kCommandLine, m[1], "is required (got nothing)" + tail);
  if (std::regex_match(message, m, extra))
    return InputError(kCommandLine, "(arguments)",
                      "unknown option or one argument too many" + gotValue(m[1].str()) + tail);
  if (message == "A subcommand is required")
    return InputError(kCommandLine, "(arguments)", "a subcommand is required (got nothing)" + tail);
  if (std::regex_match(message, m, named)) return InputError(kCommandLine, m[1], m[2].str() + tail);
  return InputError(kCommandLine, "(arguments)",
                    (message.empty() ? "bad command line" : message) + tail);
}

}  // namespace cablelab
