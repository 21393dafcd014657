// Tests for engine/membrane/membrane_plot.h: the mirror image and the modelled values.
#include "engine/membrane/membrane_plot.h"

#include <gtest/gtest.h>

#include <sstream>

namespace cablelab {
namespace {

TEST(MembranePlot, MirrorsAcrossTheBisectorAndEvaluatesTheFit) {
  const MembraneGeometry g{Vec2(0.0, 1.0), Vec2(0.4, 1.0)};  // bisector x = 0.2
  const MembraneParams m{30.0, 0.5};
  const std::vector<MembraneSample> rows = {{Vec2(0.1, 0.9), 4.0, 70.0},
                                            {Vec2(0.3, 1.1), -4.0, -100.0}};
  const MembranePlotData data = makeMembranePlotData(g, m, rows);
  ASSERT_EQ(data.quiver.size(), 2u);
  EXPECT_NEAR(data.quiver[0].mirrorP.x(), 0.3, 1e-15);
  EXPECT_NEAR(data.quiver[0].mirrorP.y(), 0.9, 1e-15);
  EXPECT_NEAR(data.quiver[0].mirrorAngleDeg, 110.0, 1e-12);
  EXPECT_NEAR(data.quiver[1].mirrorAngleDeg, -80.0, 1e-12);
  EXPECT_EQ(data.quiver[0].modelAngleDeg, membraneForceAngleDeg(g, rows[0].p));
  EXPECT_EQ(data.scatter[1].measuredFy, -4.0);
  EXPECT_EQ(data.scatter[1].modelFy, membraneForce(g, m, rows[1].p).y());

  std::ostringstream quiver, scatter;
  writeQuiverCsv(quiver, data);
  writeScatterCsv(scatter, data);
  EXPECT_EQ(quiver.str().substr(0, quiver.str().find('\n')),
            "x,y,measured_angle_deg,model_angle_deg,mirror_x,mirror_y,mirror_angle_deg");
  EXPECT_EQ(scatter.str().substr(0, 23), "measured_fy,model_fy\n4,");
}

}  // namespace
}  // namespace cablelab
