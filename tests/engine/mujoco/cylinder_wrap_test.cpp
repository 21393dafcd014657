// The length over a circle pulley against MuJoCo 2.2.2's cylinder wrap on the same geometry: a
// spatial tendon from a site over a cylinder (a sidesite choosing the side) to a site, in the
// plane, against cableKinematics on anchor -> circle -> anchor (docs/wheels.md). They agree to
// round-off (below 1e-14 relative on this seed): the test allows 1e-12.
#ifdef CABLELAB_HAVE_MUJOCO
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "engine/cable/cable.h"
#include "engine/cable/circle_wrap.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

// Everything in MuJoCo's (x, y) plane at z = 0, the cylinder's axis along z: the cylinder wrap is
// then the planar circle wrap. MuJoCo places world sites and geoms when the model compiles (not in
// mj_forward), so each configuration is its own model.
std::string wrapModel(const Vec2& a, const Vec2& b, const Vec2& side, const Vec2& c, double r) {
  auto pos = [](const Vec2& p) {
    char text[80];
    std::snprintf(text, sizeof text, "%.17g %.17g 0", p.x(), p.y());
    return std::string(text);
  };
  char radius[40];
  std::snprintf(radius, sizeof radius, "%.17g", r);
  return "<mujoco><worldbody>"
         "<site name='a' pos='" +
         pos(a) + "'/><site name='b' pos='" + pos(b) +
         "'/>"
         "<site name='side' pos='" +
         pos(side) +
         "'/>"
         "<geom name='wheel' type='cylinder' size='" +
         radius + " 0.1' pos='" + pos(c) +
         "' contype='0' conaffinity='0'/></worldbody>"
         "<tendon><spatial name='cable'><site site='a'/><geom geom='wheel' sidesite='side'/>"
         "<site site='b'/></spatial></tendon></mujoco>";
}

struct Mujoco {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  explicit Mujoco(const std::string& xml) {
    const std::string file = "wrap.xml";
    auto vfs = std::make_unique<mjVFS>();  // about 2 MB: not on the stack
    mj_defaultVFS(vfs.get());
    if (mj_makeEmptyFileVFS(vfs.get(), file.c_str(), static_cast<int>(xml.size())) == 0) {
      const int f = mj_findFileVFS(vfs.get(), file.c_str());
      std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs->filedata[f]));
      char error[1000] = "";
      model = mj_loadXML(file.c_str(), vfs.get(), error, sizeof error);
      if (!model) ADD_FAILURE() << "MuJoCo refused the model: " << error;
    }
    mj_deleteVFS(vfs.get());
    if (!model) return;
    data = mj_makeData(model);
    mj_forward(model, data);
  }
  ~Mujoco() {
    if (data) mj_deleteData(data);
    if (model) mj_deleteModel(model);
  }
};

// The segment a-b passes closer than r to c: the wrap on either side is taut, below half a turn.
bool segmentCuts(const Vec2& a, const Vec2& b, const Vec2& c, double r) {
  const Vec2 d = b - a;
  const double t = std::clamp((c - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - c).norm() < r;
}

TEST(CylinderWrap, LengthMatchesMujocosCylinderWrapOnBothSides) {
  test::Random rng(12);
  int checked[2] = {0, 0};
  for (int trial = 0; trial < 2000 && std::min(checked[0], checked[1]) < 60; ++trial) {
    const Vec2 c = rng.point(-1, 1);
    const double r = rng.uniform(0.05, 1.0);
    const Vec2 a = c + rng.uniform(1.1 * r, 4) * rotate(Vec2(1, 0), rng.uniform(-M_PI, M_PI));
    const Vec2 b = c + rng.uniform(1.1 * r, 4) * rotate(Vec2(1, 0), rng.uniform(-M_PI, M_PI));
    if (!segmentCuts(a, b, c, r)) continue;
    const int left = rng.integer(0, 1);
    const double rho = left ? r : -r;
    // The cable touches the circle at c + rho n (n the left normal of its direction): the
    // sidesite sits out on that side of the centre, seen from the line a -> b.
    const Vec2 n = perp(b - a).normalized();
    const Mujoco mj(wrapModel(a, b, c + 2 * rho * n, c, r));
    ASSERT_NE(mj.data, nullptr);

    WrapPoint circle{WrapPoint::Kind::Circle, -1, c};
    circle.radius = rho;
    circle.arc = M_PI / 2;  // start on the wrapped branch, below half a turn
    std::vector<WrapPoint> path = {
        {WrapPoint::Kind::Anchor, -1, a}, circle, {WrapPoint::Kind::Anchor, -1, b}};
    const double length = cableKinematics(path, {}).length;
    ASSERT_GT(path[1].arc, 0) << "trial " << trial;
    ASSERT_LT(path[1].arc, M_PI) << "trial " << trial;

    // MuJoCo's path: site, two tangent points on the wheel, site.
    ASSERT_EQ(mj.data->ten_wrapnum[0], 4) << "trial " << trial << ": MuJoCo did not wrap";
    const mjtNum* x = mj.data->wrap_xpos + 3 * mj.data->ten_wrapadr[0];
    EXPECT_NEAR(mj.data->ten_length[0], length, 1e-12 * length) << "trial " << trial;
    // The same tangent points (the arc on the same side, not only the same length).
    const Vec2 touchIn = circleTangent(a, 0, c, rho).to(c, rho);
    const Vec2 touchOut = circleTangent(c, rho, b, 0).from(c, rho);
    EXPECT_LT((Vec2(x[3], x[4]) - touchIn).norm(), 1e-12) << "trial " << trial;
    EXPECT_LT((Vec2(x[6], x[7]) - touchOut).norm(), 1e-12) << "trial " << trial;
    EXPECT_EQ(x[5], 0);
    ++checked[left];
  }
  EXPECT_GE(checked[0], 50);
  EXPECT_GE(checked[1], 50);
}

}  // namespace
}  // namespace cablelab
#endif
