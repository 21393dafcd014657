#include "engine/core/file_input.h"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "engine/core/error.h"

namespace cablelab {
namespace fs = std::filesystem;

std::string readInputFile(const std::string& path) {
  std::error_code error;
  if (fs::is_directory(path, error))
    throw InputError(path, "(file)", "is a directory, not a file" + gotValue(path));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path, "(file)",
                     std::string("cannot open: ") + std::strerror(errno) + gotValue(path));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    throw InputError(path, "(file)",
                     std::string("cannot read: ") + std::strerror(errno) + gotValue(path));
  return text.str();
}

namespace {

bool endsAJsonToken(char c) {
  return std::isspace(static_cast<unsigned char>(c)) || std::strchr(",:[]{}", c) != nullptr;
}

// The text a syntax error stopped at, for its "(got ...)": the word the character at `byte` (1 is
// the first) belongs to or ends (`NaN`, `tru`), else that character alone (`}`).
std::string textAtSyntaxError(const std::string& text, size_t byte) {
  if (byte == 0 || byte > text.size()) return "";
  size_t at = byte - 1;
  if (endsAJsonToken(text[at]) && (at == 0 || endsAJsonToken(text[at - 1])))
    return std::string(1, text[at]);
  if (endsAJsonToken(text[at])) --at;
  size_t first = at, last = at + 1;
  while (first > 0 && !endsAJsonToken(text[first - 1])) --first;
  while (last < text.size() && !endsAJsonToken(text[last])) ++last;
  return text.substr(first, last - first);
}

}  // namespace

nlohmann::json parseJsonText(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.parse_error.101] parse error at line 1, column 2: what" -> "at ...: what"
    std::string what = e.what();
    if (const size_t id = what.find("] "); id != what.npos) what.erase(0, id + 2);
    if (what.rfind("parse error ", 0) == 0) what.erase(0, 12);
    // "number overflow parsing '1e999'": a number beyond double range, named with its text.
    const std::string overflow = "number overflow parsing '";
    if (what.rfind(overflow, 0) == 0 && what.size() > overflow.size() && what.back() == '\'')
      throw InputError(source, "(json)",
                       "a number beyond double range (got " +
                           what.substr(overflow.size(), what.size() - overflow.size() - 1) + ")");
    // "; last read: '...'" repeats the text before the error; the (got ...) below names it.
    const std::string lastRead = "; last read: '";
    if (const size_t from = what.find(lastRead); from != what.npos) {
      const size_t to = what.find("'; ", from + lastRead.size());
      what.erase(from, to == what.npos ? what.npos : to + 1 - from);
    }
    const auto* syntax = dynamic_cast<const nlohmann::json::parse_error*>(&e);
    const std::string got = syntax ? textAtSyntaxError(text, syntax->byte) : "";
    throw InputError(source, "(json)",
                     "not valid JSON " + what +
                         (got.empty() ? std::string(" (got the end of the text)") : gotValue(got)));
  }
}

nlohmann::json readJsonFile(const std::string& path) {
  return parseJsonText(readInputFile(path), path);
}

void requireWritable(const std::string& path, const std::string& option) {
  auto fail = [&](const std::string& why) {
    throw InputError(kCommandLine, option, "cannot write the file: " + why + gotValue(path));
  };
  if (path.empty()) fail("no file name");
  std::error_code error;
  if (fs::is_directory(path, error)) fail("it is a directory");
  const fs::path parent = fs::path(path).parent_path();
  const fs::path folder = parent.empty() ? fs::path(".") : parent;
  if (!fs::is_directory(folder, error)) fail("no folder " + folder.string());
  if (fs::exists(path, error) ? access(path.c_str(), W_OK) != 0
                              : access(folder.c_str(), W_OK | X_OK) != 0)
    fail(std::strerror(errno));
}

std::ofstream openOutputFile(const std::string& path, const std::string& option) {
  requireWritable(path, option);
  std::ofstream out(path, std::ios::binary);
  if (!out)
    throw InputError(
        kCommandLine, option,
        std::string("cannot write the file: ") + std::strerror(errno) + gotValue(path));
  return out;
}

void finishOutputFile(std::ofstream& out, const std::string& path, const std::string& option) {
  out.flush();
  if (!out)
    throw InputError(kCommandLine, option,
                     std::string("write failed: ") + std::strerror(errno) + gotValue(path));
}

}  // namespace cablelab
