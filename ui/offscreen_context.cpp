#include "ui/offscreen_context.h"

#include <GL/osmesa.h>
#include <backends/imgui_impl_opengl2.h>
#include <imgui.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace cablelab::ui {

struct OffscreenContext::Impl {
  int width = 0, height = 0;
  OSMesaContext gl = nullptr;
  std::vector<unsigned char> buffer;
  ImGuiContext* imgui = nullptr;
  bool backend = false;
};

namespace {

/// Makes `context` current for ImGui for one scope and restores the previous one.
class ImGuiScope {
 public:
  explicit ImGuiScope(ImGuiContext* context) : previous_(ImGui::GetCurrentContext()) {
    ImGui::SetCurrentContext(context);
  }
  ~ImGuiScope() { ImGui::SetCurrentContext(previous_); }

 private:
  ImGuiContext* previous_;
};

void makeCurrent(OSMesaContext gl, std::vector<unsigned char>& buffer, int width, int height) {
  if (!OSMesaMakeCurrent(gl, buffer.data(), GL_UNSIGNED_BYTE, width, height))
    throw std::runtime_error("OSMesaMakeCurrent failed");
}

}  // namespace

OffscreenContext::OffscreenContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw std::runtime_error("offscreen size must be 1..16384 pixels per side (got " +
                             std::to_string(width) + "x" + std::to_string(height) + ")");
  impl_->width = width;
  impl_->height = height;
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            0};
  impl_->gl = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!impl_->gl) throw std::runtime_error("OSMesaCreateContextAttribs failed (no OSMesa?)");
  impl_->buffer.assign(static_cast<size_t>(width) * height * 4, 0);
  makeCurrent(impl_->gl, impl_->buffer, impl_->width, impl_->height);

  ImGuiContext* previous = ImGui::GetCurrentContext();
  impl_->imgui = ImGui::CreateContext();
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  impl_->backend = ImGui_ImplOpenGL2_Init();
  ImGui::SetCurrentContext(previous);
  if (!impl_->backend) throw std::runtime_error("ImGui OpenGL2 backend failed on OSMesa");
}

OffscreenContext::~OffscreenContext() {
  if (impl_->imgui) {
    ImGuiScope scope(impl_->imgui);
    if (impl_->gl)
      OSMesaMakeCurrent(impl_->gl, impl_->buffer.data(), GL_UNSIGNED_BYTE, impl_->width,
                        impl_->height);
    if (impl_->backend) ImGui_ImplOpenGL2_Shutdown();
    ImGui::DestroyContext(impl_->imgui);
  }
  if (impl_->gl) OSMesaDestroyContext(impl_->gl);
}

int OffscreenContext::width() const {
  return impl_->width;
}
int OffscreenContext::height() const {
  return impl_->height;
}

Image OffscreenContext::render(const std::function<void(ImDrawList*)>& draw) {
  makeCurrent(impl_->gl, impl_->buffer, impl_->width, impl_->height);
  ImGuiScope scope(impl_->imgui);
  ImGui_ImplOpenGL2_NewFrame();
  ImGui::NewFrame();
  glViewport(0, 0, impl_->width, impl_->height);
  draw(ImGui::GetBackgroundDrawList());
  ImGui::Render();
  ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
  glFinish();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw std::runtime_error("OpenGL error " + std::to_string(error) + " in offscreen frame");

  Image image;
  image.width = impl_->width;
  image.height = impl_->height;
  image.rgba = impl_->buffer;  // OSMesa stores the bottom row first
  flipRows(image);
  for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;  // opaque PNGs
  return image;
}

}  // namespace cablelab::ui
