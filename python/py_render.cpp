// render() and snapshot(): the sandbox's renderer, offscreen (OSMesa), from Python.
#include <cmath>
#include <cstring>
#include <vector>

#include "engine/core/error.h"
#include "python/bindings.h"
#include "python/py_world.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/offscreen.h"
#endif

namespace cablelab::python {

namespace {

std::pair<int, int> sizeOf(py::handle size, const std::string& source) {
  const auto v = toNumbers(size, 2, source, "size");
  if (v[0] != static_cast<int>(v[0]) || v[1] != static_cast<int>(v[1]) || v[0] < 16 || v[1] < 16 ||
      v[0] > 8192 || v[1] > 8192)
    throw InputError(source, "size",
                     "expected (width, height) with 16..8192 pixels per side (got (" +
                         formatNumber(v[0]) + ", " + formatNumber(v[1]) + "))");
  return {static_cast<int>(v[0]), static_cast<int>(v[1])};
}

/// The scene's view grown to take in every dynamic body and cable as they are now, with a margin
/// (what the sandbox's "fit view" shows): a scene without a "view" has a 4 m one at the origin.
ViewDef fitView(const World& world, double aspect) {
  const ViewDef& view = world.scene().view;
  const Vec2 half(0.5 * view.height * aspect, 0.5 * view.height);
  Vec2 lo = view.center - half, hi = view.center + half;
  std::vector<Vec2> points;
  std::vector<double> radii;
  for (int i = 0; i < world.bodyCount(); ++i) {
    const BodyDef& def = world.scene().bodies[i];
    if (def.type != BodyType::Dynamic) continue;  // grounds may be very wide
    const BodyState& b = world.body(i);
    const double c = std::cos(b.angle), s = std::sin(b.angle);
    for (const ShapeDef& shape : def.shapes) {
      if (shape.kind == ShapeDef::Kind::Circle)
        points.push_back(b.position + rotate(shape.center, c, s)), radii.push_back(shape.radius);
      for (const Vec2& v : shape.vertices)
        points.push_back(b.position + rotate(v, c, s)), radii.push_back(0);
    }
  }
  for (int i = 0; i < world.cableCount(); ++i)
    for (const WrapPoint& p : world.cable(i).path()) points.push_back(p.world), radii.push_back(0);
  const double margin = 0.04 * view.height;
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2 r = Vec2::Constant(radii[k] + margin);
    lo = lo.cwiseMin(points[k] - r);
    hi = hi.cwiseMax(points[k] + r);
  }
  return {0.5 * (lo + hi), std::max(hi.y() - lo.y(), (hi.x() - lo.x()) / aspect)};
}

/// A dict's keys as "keys center, size" (or "no keys").
std::string keysOf(const py::dict& d) {
  std::string out;
  for (auto [key, value] : d) out += (out.empty() ? "" : ", ") + py::str(key).cast<std::string>();
  return out.empty() ? "no keys" : "keys " + out;
}

/// render()'s view: None fits the scene (fitView), "scene" is the scene's own, else
/// (center, height) or {"center": [x, y], "height": h} (m).
ViewDef viewOf(const World& world, py::handle view, int width, int height,
               const std::string& source) {
  if (view.is_none()) return fitView(world, static_cast<double>(width) / height);
  if (py::isinstance<py::str>(view)) {
    if (view.cast<std::string>() == "scene") return world.scene().view;
    throw InputError(source, "view",
                     "must be None, \"scene\", (center, height) or a dict" + gotPython(view));
  }
  py::object center, tall;
  if (py::isinstance<py::dict>(view)) {
    const py::dict d = view.cast<py::dict>();
    for (auto [key, value] : d)
      if (py::str(key).cast<std::string>() != "center" &&
          py::str(key).cast<std::string>() != "height")
        throw InputError(source, "view." + py::str(key).cast<std::string>(),
                         "no such key (known: center, height)" + gotPython(key));
    if (!d.contains("center") || !d.contains("height"))
      throw InputError(source, "view",
                       "needs center [x, y] and height (m) (got " + keysOf(d) + ")");
    center = d["center"], tall = d["height"];
  } else {
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(view);
    if (!py::isinstance<py::sequence>(view) || py::len(seq) != 2)
      throw InputError(source, "view",
                       "must be None, \"scene\", (center, height) or a dict" + gotPython(view));
    center = seq[0], tall = seq[1];
  }
  ViewDef out;
  out.center = toVec2(center, source, "view.center");
  out.height = toNumbers(py::make_tuple(tall), 1, source, "view.height")[0];
  if (!(out.height > 0) || out.height > 1e9)
    throw InputError(source, "view.height", "must be positive (m)" + gotValue(out.height));
  return out;
}

#ifdef CABLELAB_HAVE_OFFSCREEN
ui::Image renderImage(const PyWorld& w, py::handle size, py::handle view, const char* source) {
  const auto [width, height] = sizeOf(size, source);
  return ui::renderSnapshot(
      *w.world, ui::Camera::fit(viewOf(*w.world, view, width, height, source), width, height));
}

// The GIL stays held: the renderer uses Dear ImGui's global context, one frame at a time.
py::array_t<std::uint8_t> renderCall(const PyWorld& w, py::handle size, py::handle view) {
  PyWorld::Busy busy(w);
  const ui::Image image = renderImage(w, size, view, "render");
  py::array_t<std::uint8_t> out({image.height, image.width, 4});
  std::memcpy(out.mutable_data(), image.rgba.data(), image.rgba.size());
  return out;
}

void snapshotCall(const PyWorld& w, py::handle path, py::handle size, py::handle view) {
  PyWorld::Busy busy(w);
  const std::string file = pathString(path, "snapshot", "path");
  const ui::Image image = renderImage(w, size, view, "snapshot");
  try {
    ui::writePng(image, file);
  } catch (const std::exception& e) {
    // writePng's message starts with the path: the value goes at the end, as everywhere.
    std::string what = e.what();
    if (what.rfind(file + ": ", 0) == 0) what = what.substr(file.size() + 2);
    throw InputError("snapshot", "path", what + gotValue(file));
  }
}
#else
py::array_t<std::uint8_t> renderCall(const PyWorld&, py::handle, py::handle) {
  throw InputError("render", "(build)", "this build has no offscreen renderer");
}
void snapshotCall(const PyWorld&, py::handle, py::handle, py::handle) {
  throw InputError("snapshot", "(build)", "this build has no offscreen renderer");
}
#endif

}  // namespace

void bindRender(py::module_& m) {
  using namespace pybind11::literals;
#ifdef CABLELAB_HAVE_OFFSCREEN
  m.attr("HAS_RENDERER") = true;
#else
  m.attr("HAS_RENDERER") = false;  // a build with -DCABLELAB_BUILD_UI=OFF
#endif
  m.def("render", &renderCall, "world"_a, "size"_a = py::make_tuple(800, 600),
        "view"_a = py::none(),
        R"doc(render(world, size=(800, 600), view=None) -> ndarray (height, width, 4) uint8

The world drawn by the sandbox's renderer (offscreen, OSMesa: no display needed), RGBA,
top row first; plt.imshow() shows it as it is. view, the camera: None fits the scene (its
"view" grown to take in every moving body and cable, as the sandbox's fit does); "scene":
the scene's own "view" exactly; (center, height) or {"center": [x, y], "height": h}: the
world point at the image centre and the height the image shows (m).)doc");
  m.def("snapshot", &snapshotCall, "world"_a, "path"_a, "size"_a = py::make_tuple(800, 600),
        "view"_a = py::none(),
        "snapshot(world, path, size=(800, 600), view=None): render() written to a PNG file.");
}

}  // namespace cablelab::python
