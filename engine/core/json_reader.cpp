#include "engine/core/json_reader.h"

#include <cmath>
#include <exception>

#include "engine/core/error.h"

namespace cablelab {

std::string describeJson(const nlohmann::json& v) {
  if (v.is_number()) return formatNumber(v.get<double>());
  std::string text = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

namespace {
std::string got(const nlohmann::json& v) {
  return " (got " + describeJson(v) + ")";
}
}  // namespace

JsonReader::JsonReader(const json& j, std::string source, std::string path)
    : j_(j), source_(std::move(source)), path_(std::move(path)) {
  if (!j_.is_object())
    throw InputError(source_, path_.empty() ? "(root)" : path_, "must be an object" + got(j_));
}

JsonReader::~JsonReader() noexcept(false) {
  if (!strict_ || std::uncaught_exceptions() > 0) return;
  for (const auto& [key, value] : j_.items())
    if (!used_.count(key)) fail(key, "unknown key");
}

std::string JsonReader::field(const std::string& key) const {
  if (key.empty()) return path_.empty() ? "(root)" : path_;
  return path_.empty() ? key : path_ + "." + key;
}

void JsonReader::fail(const std::string& key, const std::string& what) const {
  throw InputError(source_, field(key), what);
}

void JsonReader::onlyKeys(std::initializer_list<const char*> keys) {
  for (const char* k : keys) used_.insert(k);
  for (const auto& [key, value] : j_.items())
    if (!used_.count(key)) fail(key, "unknown key");
}

bool JsonReader::has(const std::string& key) {
  used_.insert(key);
  return j_.contains(key);
}

double JsonReader::numberValue(const json& v, const std::string& f) const {
  if (!v.is_number()) throw InputError(source_, f, "must be a number" + got(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw InputError(source_, f, "must be finite" + got(v));
  return d;
}

Vec2 JsonReader::vec2Value(const json& v, const std::string& f) const {
  if (!v.is_array() || v.size() != 2) throw InputError(source_, f, "must be [x, y]" + got(v));
  return Vec2(numberValue(v[0], f + "[0]"), numberValue(v[1], f + "[1]"));
}

double JsonReader::number(const std::string& key, double fallback) {
  return has(key) ? numberValue(j_.at(key), field(key)) : fallback;
}

double JsonReader::requiredNumber(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return number(key, 0);
}

int JsonReader::integer(const std::string& key, int fallback) {
  const double v = number(key, fallback);
  if (v != std::floor(v) || std::abs(v) > 1e9) fail(key, "must be a whole number" + gotValue(v));
  return static_cast<int>(v);
}

bool JsonReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  if (!j_.at(key).is_boolean()) fail(key, "must be true or false" + got(j_.at(key)));
  return j_.at(key).get<bool>();
}

std::string JsonReader::string(const std::string& key, const std::string& fallback) {
  if (!has(key)) return fallback;
  if (!j_.at(key).is_string()) fail(key, "must be a string" + got(j_.at(key)));
  return j_.at(key).get<std::string>();
}

std::string JsonReader::requiredString(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return string(key, "");
}

Vec2 JsonReader::vec2(const std::string& key, const Vec2& fallback) {
  return has(key) ? vec2Value(j_.at(key), field(key)) : fallback;
}

Vec2 JsonReader::requiredVec2(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return vec2(key, Vec2::Zero());
}

const nlohmann::json& JsonReader::list(const std::string& key) {
  static const json empty = json::array();
  if (!has(key)) return empty;
  if (!j_.at(key).is_array()) fail(key, "must be a list" + got(j_.at(key)));
  return j_.at(key);
}

const nlohmann::json& JsonReader::requiredList(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return list(key);
}

std::vector<Vec2> JsonReader::points(const std::string& key) {
  std::vector<Vec2> out;
  const json& l = list(key);
  for (size_t i = 0; i < l.size(); ++i)
    out.push_back(vec2Value(l[i], field(key) + "[" + std::to_string(i) + "]"));
  return out;
}

JsonReader JsonReader::child(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return JsonReader(j_.at(key), source_, field(key));
}

JsonReader JsonReader::item(const std::string& key, size_t i) {
  const json& l = list(key);
  return JsonReader(l.at(i), source_, field(key) + "[" + std::to_string(i) + "]");
}

}  // namespace cablelab
