// cablelab wrap FILE.json: the taut path from A to B around one convex polygon.
#include <algorithm>
#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/json_input.h"
#include "engine/wrap.h"

namespace cablelab::app {
namespace {

const bool registered = registerCommand("wrap", "Taut cable path from A to B around a convex polygon", [](CLI::App& sub) {
  auto file = std::make_shared<std::string>();
  sub.add_option("file", *file, "Input JSON {\"A\": [x, y], \"B\": [x, y], \"polygon\": [[x, y], ...], \"side\": \"left\"|\"right\"}")
      ->required();
  return [file] {
    const nlohmann::json in = readJsonFile(*file);
    if (!in.is_object()) throw InputError(*file, "(json)", "must be an object");
    for (const char* key : {"A", "B", "polygon", "side"})
      if (!in.contains(key)) throw InputError(*file, key, "is required");
    const Vec2 a = jsonVec2(in["A"], *file, "A");
    const Vec2 b = jsonVec2(in["B"], *file, "B");
    if (!in["polygon"].is_array() || in["polygon"].size() < 3) throw InputError(*file, "polygon", "needs at least 3 vertices");
    std::vector<Vec2> polygon;
    for (size_t i = 0; i < in["polygon"].size(); ++i)
      polygon.push_back(jsonVec2(in["polygon"][i], *file, "polygon[" + std::to_string(i) + "]"));
    if (!in["side"].is_string() || (in["side"] != "left" && in["side"] != "right"))
      throw InputError(*file, "side", "must be \"left\" or \"right\"");
    const WrapSide side = in["side"] == "left" ? WrapSide::Left : WrapSide::Right;

    // Accept either orientation; indices in the output refer to the input order.
    std::vector<int> order(polygon.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    if (!isConvexCCW(polygon)) {
      std::reverse(polygon.begin(), polygon.end());
      std::reverse(order.begin(), order.end());
      if (!isConvexCCW(polygon)) throw InputError(*file, "polygon", "is not convex (or has repeated or collinear vertices)");
    }
    if ((a - b).norm() == 0) throw InputError(*file, "B", "coincides with A");
    const auto chain = wrapChain(a, b, polygon, side);
    if (!chain) throw InputError(*file, "A", "A or B lies inside the polygon: no taut path goes round it");

    nlohmann::json path = nlohmann::json::array({{a.x(), a.y()}});
    nlohmann::json contacts = nlohmann::json::array();
    for (int v : *chain) {
      path.push_back({polygon[v].x(), polygon[v].y()});
      contacts.push_back(order[v]);
    }
    path.push_back({b.x(), b.y()});
    printJson(nlohmann::json{{"path", path}, {"length", chainLength(a, b, polygon, *chain)}, {"contact_vertices", contacts}}.dump());
    return 0;
  };
});

}  // namespace
}  // namespace cablelab::app
