#include "ui/plot.h"

#include <GL/gl.h>
#include <imgui.h>

#include "ui/offscreen_context.h"
#include "ui/plot_draw.h"

namespace cablelab::ui {

Image renderPlot(const Plot& plot, int width, int height) {
  checkPlot(plot, width, height);
  OffscreenContext context(width, height);
  return context.render([&](ImDrawList* draw) {
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    drawPlot(draw, plot, width, height);
  });
}

void writePlotPng(const Plot& plot, const std::string& path, int width, int height) {
  writePng(renderPlot(plot, width, height), path);
}

}  // namespace cablelab::ui
