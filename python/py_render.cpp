// render() and snapshot(): the sandbox's renderer, offscreen (OSMesa), from Python.
#include <cstring>

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
    throw InputError(source, "size", "expected (width, height) with 16..8192 pixels per side");
  return {static_cast<int>(v[0]), static_cast<int>(v[1])};
}

#ifdef CABLELAB_HAVE_OFFSCREEN
// The GIL stays held: the renderer uses Dear ImGui's global context, one frame at a time.
py::array_t<std::uint8_t> renderCall(const PyWorld& w, py::handle size) {
  PyWorld::Busy busy(w);
  const auto [width, height] = sizeOf(size, "render");
  const ui::Image image = ui::renderSnapshot(*w.world, width, height);
  py::array_t<std::uint8_t> out({image.height, image.width, 4});
  std::memcpy(out.mutable_data(), image.rgba.data(), image.rgba.size());
  return out;
}

void snapshotCall(const PyWorld& w, py::handle path, py::handle size) {
  PyWorld::Busy busy(w);
  const std::string file = pathString(path, "snapshot", "path");
  const auto [width, height] = sizeOf(size, "snapshot");
  const ui::Image image = ui::renderSnapshot(*w.world, width, height);
  try {
    ui::writePng(image, file);
  } catch (const std::exception& e) {
    throw InputError(file, "path", e.what());
  }
}
#else
py::array_t<std::uint8_t> renderCall(const PyWorld&, py::handle) {
  throw InputError("render", "(build)", "this build has no offscreen renderer");
}
void snapshotCall(const PyWorld&, py::handle, py::handle) {
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
        R"doc(render(world, size=(800, 600)) -> ndarray (height, width, 4) uint8

The world drawn by the sandbox's renderer (offscreen, OSMesa: no display needed), RGBA,
top row first, with the scene's default view; plt.imshow() shows it as it is.)doc");
  m.def("snapshot", &snapshotCall, "world"_a, "path"_a, "size"_a = py::make_tuple(800, 600),
        "snapshot(world, path, size=(800, 600)): render() written to a PNG file, as `cablelab "
        "snapshot`.");
}

}  // namespace cablelab::python
