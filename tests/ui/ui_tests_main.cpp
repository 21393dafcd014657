// ui_tests main: registers one Golden.<scene> test per built-in scene (from the registry, after
// static initialisation), then runs every test.
#include <gtest/gtest.h>

#include "ui/scene_catalog.h"

namespace cablelab::ui {
void checkGolden(const std::string& scene);
}

namespace {

class GoldenTest : public testing::Test {
 public:
  explicit GoldenTest(std::string scene) : scene_(std::move(scene)) {}
  void TestBody() override { cablelab::ui::checkGolden(scene_); }

 private:
  std::string scene_;
};

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  for (const auto& entry : cablelab::ui::builtinSceneList())
    testing::RegisterTest("Golden", entry.name.c_str(), nullptr, nullptr, __FILE__, __LINE__,
                          [name = entry.name]() -> GoldenTest* { return new GoldenTest(name); });
  return RUN_ALL_TESTS();
}
