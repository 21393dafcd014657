// engine/core/json_reader.h and engine/core/file_input.h: typed fields with paths in messages,
// unknown keys rejected, files opened the one way.
#include "engine/core/json_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using nlohmann::json;

using test::messageOf;

TEST(JsonReader, ReadsTypedFieldsWithDefaults) {
  const json j = json::parse(R"({"n": 2.5, "i": 3, "b": true, "s": "x", "v": [1, 2],
                                 "l": [[0, 0], [1, 0]], "o": {"k": 4}})");
  JsonReader r(j, "f.json");
  EXPECT_EQ(r.number("n", 0), 2.5);
  EXPECT_EQ(r.number("absent", 7), 7);
  EXPECT_EQ(r.integer("i", 0), 3);
  EXPECT_TRUE(r.boolean("b", false));
  EXPECT_EQ(r.string("s", ""), "x");
  EXPECT_EQ(r.vec2("v", Vec2::Zero()), Vec2(1, 2));
  EXPECT_EQ(r.points("l").size(), 2u);
  EXPECT_EQ(r.child("o").requiredNumber("k"), 4);
}

TEST(JsonReader, MessagesNameThePathAndTheValue) {
  const json j = json::parse(R"({"bodies": [{"mass": "1", "v": [1, 2, 3], "p": [1, null]}],
                                 "x": 1e308, "n": 1.5, "o": 3})");
  auto body = [&](const std::function<void(JsonReader&)>& f) {
    return messageOf([&] {
      JsonReader r(j, "f.json");
      r.allowOtherKeys();
      JsonReader b = r.item("bodies", 0);
      b.allowOtherKeys();
      f(b);
    });
  };
  EXPECT_EQ(body([](JsonReader& b) { b.number("mass", 0); }),
            "f.json: bodies[0].mass: must be a number (got \"1\")");
  EXPECT_EQ(body([](JsonReader& b) { b.vec2("v", Vec2::Zero()); }),
            "f.json: bodies[0].v: must be [x, y] (got [1,2,3])");
  EXPECT_EQ(body([](JsonReader& b) { b.vec2("p", Vec2::Zero()); }),
            "f.json: bodies[0].p[1]: must be a number (got null)");
  EXPECT_EQ(body([](JsonReader& b) { b.requiredString("name"); }),
            "f.json: bodies[0].name: is required");
  EXPECT_EQ(messageOf([&] {
              JsonReader r(j, "f.json");
              r.allowOtherKeys();
              r.integer("n", 0);
            }),
            "f.json: n: must be a whole number (got 1.5)");
  EXPECT_EQ(messageOf([&] {
              JsonReader r(j, "f.json");
              r.allowOtherKeys();
              r.child("o");
            }),
            "f.json: o: must be an object (got 3)");
  EXPECT_EQ(messageOf([] { JsonReader r(json::array(), "f.json"); }),
            "f.json: (root): must be an object (got [])");
}

TEST(JsonReader, RejectsKeysNobodyAskedFor) {
  const json j = json::parse(R"({"a": 1, "typo": 2, "inner": {"k": 1, "kk": 2}})");
  EXPECT_EQ(messageOf([&] {
              JsonReader r(j, "f.json");
              r.number("a", 0);
              r.has("inner");
            }),
            "f.json: typo: unknown key");
  EXPECT_EQ(messageOf([&] {
              JsonReader r(j, "f.json");
              r.allowOtherKeys();
              r.child("inner").number("k", 0);
            }),
            "f.json: inner.kk: unknown key");
  // The first error wins: a bad value is reported, not the unknown keys after it.
  EXPECT_EQ(messageOf([&] {
              JsonReader r(j, "f.json");
              r.string("a", "");
            }),
            "f.json: a: must be a string (got 1)");
}

TEST(FileInput, MissingDirectoryAndBadJsonSayWhatIsWrong) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("cablelab_file_input_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string bad = (dir / "bad.json").string();
  std::ofstream(bad) << "{\"a\": 1,\n \"b\": }";
  EXPECT_EQ(messageOf([] { readInputFile("/no/such/file.json"); }),
            "/no/such/file.json: (file): cannot open: No such file or directory (got "
            "\"/no/such/file.json\")");
  EXPECT_EQ(messageOf([&] { readInputFile(dir.string()); }),
            dir.string() + ": (file): is a directory, not a file" + gotValue(dir.string()));
  const std::string m = messageOf([&] { readJsonFile(bad); });
  EXPECT_EQ(m.rfind(bad + ": (json): not valid JSON at line 2, column 7: ", 0), 0u) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  fs::remove_all(dir);
}

TEST(FileInput, BadJsonEndsWithTheTextWhereItStopped) {
  const auto parsed = [](const std::string& text) {
    return messageOf([&] { parseJsonText(text, "s.json"); });
  };
  const std::string at = "s.json: (json): not valid JSON at line 1, column ";
  // JSON has no NaN or Infinity: the word the parser stopped in is quoted whole.
  EXPECT_EQ(parsed("{\"mass\": NaN}"),
            at + "10: syntax error while parsing value - invalid literal (got \"NaN\")");
  EXPECT_EQ(parsed("{\"a\": Infinity, \"b\": 1}"),
            at + "7: syntax error while parsing value - invalid literal (got \"Infinity\")");
  EXPECT_EQ(parsed("{\"a\": tru}"),
            at + "10: syntax error while parsing value - invalid literal (got \"tru\")");
  EXPECT_EQ(parsed("{\"a\": 1,}"), at + "9: syntax error while parsing object key - unexpected "
                                        "'}'; expected string literal (got \"}\")");
  EXPECT_EQ(parsed("[1, 2"), at + "6: syntax error while parsing array - unexpected end of "
                                  "input; expected ']' (got the end of the text)");
  EXPECT_EQ(parsed("{\"a\": 1e999}"), "s.json: (json): a number beyond double range (got 1e999)");
}

TEST(FileInput, OutputsAreCheckedBeforeAnythingIsWritten) {
  namespace fs = std::filesystem;
  EXPECT_EQ(messageOf([] { requireWritable("/no/such/dir/x.png", "--png"); }),
            "command line: --png: cannot write the file: no folder /no/such/dir (got "
            "\"/no/such/dir/x.png\")");
  const std::string tmp = fs::temp_directory_path().string();
  EXPECT_EQ(messageOf([&] { requireWritable(tmp, "--out"); }),
            "command line: --out: cannot write the file: it is a directory (got \"" + tmp + "\")");
  const fs::path ok = fs::temp_directory_path() / ("cablelab_out_" + std::to_string(getpid()));
  requireWritable(ok.string(), "--csv");
  EXPECT_FALSE(fs::exists(ok)) << "the check creates nothing";
  {
    std::ofstream out = openOutputFile(ok.string(), "--csv");
    out << "t\n";
    finishOutputFile(out, ok.string(), "--csv");
  }
  EXPECT_EQ(readInputFile(ok.string()), "t\n");
  fs::remove(ok);
}

}  // namespace
}  // namespace cablelab
