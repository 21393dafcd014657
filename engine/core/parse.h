// The one way text becomes numbers: finite decimals, lists "a,b,c", whole numbers and "WxH"
// sizes, for command-line options, scene parameters and CSV fields. Errors are InputError in
// the style of engine/core/error.h, naming SOURCE and FIELD.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cablelab {

/// The whole of `text` as one finite decimal number ("1e-3", "+2", "-0.5"), else nullopt:
/// no surrounding spaces, no hex, no "inf" or "nan", nothing after the number.
std::optional<double> parseFiniteNumber(std::string_view text);

/// parseFiniteNumber, or InputError(source, field, "must be a finite number (got "text")").
double parseNumber(std::string_view text, const std::string& source, const std::string& field);

/// A whole number in [lo, hi] ("12", "1e3"), else InputError.
long parseWholeNumber(std::string_view text, const std::string& source, const std::string& field,
                      long lo, long hi);

/// "a,b,c" as exactly `count` finite numbers; `shape` names them in the message ("X,Y").
std::vector<double> parseNumberList(std::string_view text, size_t count, const std::string& source,
                                    const std::string& field, const std::string& shape);

/// Image or window size in pixels (or any "WxH" pair of whole numbers).
struct PixelSize {
  int width = 0;
  int height = 0;
};

/// "WxH" (or "WXH"), each side a whole number in [minSide, maxSide].
PixelSize parsePixelSize(std::string_view text, const std::string& source, const std::string& field,
                         int minSide, int maxSide);

/// Throws InputError(source, field, "must be a number in [lo, hi] (got v)") unless v is finite
/// and lo <= v <= hi.
void requireInRange(double v, const std::string& source, const std::string& field, double lo,
                    double hi);

class InputError;

/// A command-line parser's message (CLI11's, as in "Could not convert: --time = abc") as the
/// InputError "command line: --time: cannot convert (got "abc")", naming the option when the
/// message does; otherwise the FIELD is "(arguments)". `help` ends the message ("see ... --help").
InputError commandLineError(const std::string& message, const std::string& help);

}  // namespace cablelab
