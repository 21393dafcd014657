// JsonReader: the one way JSON input is read (scene files, statics and wrap input, fit results).
// It walks one JSON object, reads typed fields with defaults, remembers the path for messages
// ("cables[1].start.point[0]") and, when it goes out of scope, rejects every key it was never
// asked about, so a typo is an error rather than a silently ignored field. Errors are InputError
// in the style of engine/core/error.h.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "engine/core/math.h"

namespace cablelab {

class JsonReader {
 public:
  using json = nlohmann::json;

  /// @param j      must be an object, else InputError(source, path or "(root)", ...)
  /// @param source the file name, for messages
  /// @param path   where `j` sits in the file ("" for the root, "bodies[2]")
  JsonReader(const json& j, std::string source, std::string path = "");
  /// Rejects the keys no accessor asked about (unless an exception is already on its way).
  ~JsonReader() noexcept(false);
  JsonReader(const JsonReader&) = delete;
  JsonReader& operator=(const JsonReader&) = delete;
  JsonReader(JsonReader&&) = delete;  // returned and passed as prvalues only (C++17 elision)

  /// Declares every key this object may have and rejects any other at once (so a typo is
  /// reported before the field it misspells is found missing).
  void onlyKeys(std::initializer_list<const char*> keys);
  /// Accept keys no accessor asked about (for reading a few fields of another tool's output).
  void allowOtherKeys() { strict_ = false; }

  /// Whether `key` is present (and marks it as known).
  bool has(const std::string& key);
  double number(const std::string& key, double fallback);
  double requiredNumber(const std::string& key);
  /// A whole number within +/-1e9.
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key, const std::string& fallback);
  std::string requiredString(const std::string& key);
  Vec2 vec2(const std::string& key, const Vec2& fallback);
  Vec2 requiredVec2(const std::string& key);
  /// A list (empty when absent).
  const json& list(const std::string& key);
  const json& requiredList(const std::string& key);
  /// A list of [x, y] points.
  std::vector<Vec2> points(const std::string& key);
  /// The object at `key`, read with its own path.
  JsonReader child(const std::string& key);
  /// The i-th object of list `key`.
  JsonReader item(const std::string& key, size_t i);

  /// The path of `key` in this object, for messages ("bodies[2].mass"); "" is the object itself.
  std::string field(const std::string& key) const;
  const std::string& source() const { return source_; }
  /// InputError(source, field(key), what).
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  /// Value readers for list entries: `field` is the entry's full path.
  double numberValue(const json& v, const std::string& field) const;
  Vec2 vec2Value(const json& v, const std::string& field) const;

 private:
  const json& j_;
  std::string source_, path_;
  std::set<std::string> used_;
  bool strict_ = true;
};

/// A JSON value as it appears after "got" in messages: numbers in the one number format,
/// anything else as compact JSON, cut at 60 characters.
std::string describeJson(const nlohmann::json& v);

}  // namespace cablelab
