#include "engine/core/file_input.h"

#include <unistd.h>

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

nlohmann::json parseJsonText(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax errors, numbers beyond double range
    // "[json.exception.parse_error.101] parse error at line 1, column 2: what" -> "at ...: what"
    std::string what = e.what();
    if (const size_t id = what.find("] ");
        what.rfind("[json.exception.", 0) == 0 && id != what.npos)
      what.erase(0, id + 2);
    if (what.rfind("parse error ", 0) == 0) what.erase(0, 12);
    // "number overflow parsing '1e999'": a number beyond double range, named with its text.
    const std::string overflow = "number overflow parsing '";
    if (what.rfind(overflow, 0) == 0 && what.size() > overflow.size() && what.back() == '\'')
      throw InputError(source, "(json)",
                       "a number beyond double range (got " +
                           what.substr(overflow.size(), what.size() - overflow.size() - 1) + ")");
    throw InputError(source, "(json)", "not valid JSON " + what);
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
