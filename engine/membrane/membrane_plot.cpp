#include "engine/membrane/membrane_plot.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>

namespace cablelab {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

std::string formatRow(std::initializer_list<double> values) {
  std::string line;
  char buffer[32];
  for (double v : values) {
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    if (!line.empty()) line += ',';
    line += buffer;
  }
  return line + '\n';
}

}  // namespace

MembranePlotData makeMembranePlotData(const MembraneGeometry& g, const MembraneParams& fitted,
                                      const std::vector<MembraneSample>& rows) {
  const Vec2 mid = 0.5 * (g.a + g.b);
  const Vec2 along = (g.b - g.a).normalized();
  // Reflection across the bisector flips the component along AB.
  auto reflect = [&](const Vec2& v) -> Vec2 { return v - 2.0 * v.dot(along) * along; };

  MembranePlotData data;
  for (const auto& row : rows) {
    MembraneQuiverRow q;
    q.p = row.p;
    q.measuredAngleDeg = row.angleDeg;
    q.modelAngleDeg = membraneForceAngleDeg(g, row.p);
    q.mirrorP = mid + reflect(row.p - mid);
    const double a = row.angleDeg / kDegPerRad;
    const Vec2 mirrored = reflect(Vec2(std::cos(a), std::sin(a)));
    q.mirrorAngleDeg = wrapAngleDeg(std::atan2(mirrored.y(), mirrored.x()) * kDegPerRad);
    data.quiver.push_back(q);
    data.scatter.push_back({row.fy, membraneForce(g, fitted, row.p).y()});
  }
  return data;
}

void writeQuiverCsv(std::ostream& out, const MembranePlotData& data) {
  out << "x,y,measured_angle_deg,model_angle_deg,mirror_x,mirror_y,mirror_angle_deg\n";
  for (const auto& q : data.quiver)
    out << formatRow({q.p.x(), q.p.y(), q.measuredAngleDeg, q.modelAngleDeg, q.mirrorP.x(),
                      q.mirrorP.y(), q.mirrorAngleDeg});
}

void writeScatterCsv(std::ostream& out, const MembranePlotData& data) {
  out << "measured_fy,model_fy\n";
  for (const auto& s : data.scatter) out << formatRow({s.measuredFy, s.modelFy});
}

}  // namespace cablelab
