#include "ui/window.h"

#include <GL/gl.h>
#include <backends/imgui_impl_opengl2.h>
#include <backends/imgui_impl_sdl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cablelab::ui {

Window::Window(const std::string& title, int width, int height, bool vsync) {
  if (SDL_Init(SDL_INIT_VIDEO | SDL_INIT_TIMER) != 0)
    throw std::runtime_error(std::string("SDL_Init failed: ") + SDL_GetError());
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 2);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);
  if (width <= 0 || height <= 0) {  // fit the display the window opens on
    SDL_Rect usable{0, 0, 1280, 720};
    if (SDL_GetDisplayUsableBounds(0, &usable) != 0) SDL_GetDisplayBounds(0, &usable);
    width = std::max(std::min(640, usable.w), static_cast<int>(0.9 * usable.w));
    height = std::max(std::min(480, usable.h), static_cast<int>(0.9 * usable.h));
  }
  window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width,
                             height, SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE);
  if (!window_) {
    const std::string error = SDL_GetError();
    SDL_Quit();
    throw std::runtime_error("cannot open a window (is DISPLAY set?): " + error);
  }
  gl_ = SDL_GL_CreateContext(window_);
  if (!gl_) {
    const std::string error = SDL_GetError();
    SDL_DestroyWindow(window_);
    SDL_Quit();
    throw std::runtime_error("cannot create an OpenGL 2.1 context: " + error);
  }
  SDL_GL_MakeCurrent(window_, gl_);
  SDL_GL_SetSwapInterval(vsync ? 1 : 0);  // -1 under Xvfb: harmless, frames are not capped
  SDL_GetWindowSize(window_, &width_, &height_);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's directory
  ImGui::StyleColorsLight();
  ImGui_ImplSDL2_InitForOpenGL(window_, gl_);
  ImGui_ImplOpenGL2_Init();
}

void Window::setUiScale(float scale) {
  scale = std::clamp(scale, 0.5f, 4.0f);
  if (scale == uiScale_) return;
  uiScale_ = scale;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  ImFontConfig font;
  font.SizePixels = std::round(13.0f * scale);
  io.Fonts->AddFontDefault(&font);
  ImGui_ImplOpenGL2_DestroyFontsTexture();
  ImGui_ImplOpenGL2_CreateFontsTexture();
  ImGuiStyle style;
  ImGui::StyleColorsLight(&style);
  style.ScaleAllSizes(scale);
  ImGui::GetStyle() = style;
}

float Window::suggestedUiScale() const {
  SDL_Rect bounds{0, 0, 1280, 720};
  if (SDL_GetDisplayBounds(SDL_GetWindowDisplayIndex(window_), &bounds) != 0) return 1;
  return std::clamp(std::round(bounds.h / 1080.0f * 4) / 4, 1.0f, 3.0f);
}

Window::~Window() {
  ImGui_ImplOpenGL2_Shutdown();
  ImGui_ImplSDL2_Shutdown();
  ImGui::DestroyContext();
  SDL_GL_DeleteContext(gl_);
  SDL_DestroyWindow(window_);
  SDL_Quit();
}

bool Window::pollEvents(const std::function<void(const SDL_Event&)>& handler) {
  SDL_Event event;
  while (SDL_PollEvent(&event)) {
    ImGui_ImplSDL2_ProcessEvent(&event);
    if (event.type == SDL_QUIT) closed_ = true;
    if (event.type == SDL_WINDOWEVENT && event.window.event == SDL_WINDOWEVENT_CLOSE &&
        event.window.windowID == SDL_GetWindowID(window_))
      closed_ = true;
    if (event.type == SDL_WINDOWEVENT && event.window.event == SDL_WINDOWEVENT_SIZE_CHANGED)
      SDL_GetWindowSize(window_, &width_, &height_);
    handler(event);
  }
  return !closed_;
}

void Window::beginFrame() {
  ImGui_ImplOpenGL2_NewFrame();
  ImGui_ImplSDL2_NewFrame();
  ImGui::NewFrame();
  glViewport(0, 0, width_, height_);
}

void Window::endFrame(Image* capture) {
  ImGui::Render();
  ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
  if (capture) {
    capture->width = width_;
    capture->height = height_;
    capture->rgba.assign(static_cast<size_t>(width_) * height_ * 4, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, capture->rgba.data());
    flipRows(*capture);  // GL reads the bottom row first
    for (size_t i = 3; i < capture->rgba.size(); i += 4) capture->rgba[i] = 255;
  }
  SDL_GL_SwapWindow(window_);
}

}  // namespace cablelab::ui
