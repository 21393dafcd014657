#include "engine/mujoco/mujoco_world.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "engine/core/error.h"

namespace cablelab {

namespace {

const char* kSource = "mujoco";

// A plane point in MJCF's "x 0 z" form.
std::string xz(const Vec2& p) {
  std::ostringstream s;
  s << std::setprecision(17) << p.x() << " 0 " << p.y();
  return s.str();
}

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

void refuse(const std::string& field, const std::string& what) {
  throw InputError(kSource, field, what);
}

void writeBody(std::ostringstream& xml, const BodyDef& b, int index) {
  const std::string field = "bodies[" + std::to_string(index) + "]";
  if (b.type == BodyType::Kinematic)
    refuse(field + ".type", "kinematic bodies are not mapped" + gotValue("kinematic"));
  xml << "  <body name=\"" << b.name << "\" pos=\"" << xz(b.position) << "\" axisangle=\"0 -1 0 "
      << number(b.angle) << "\">\n";
  if (b.type == BodyType::Dynamic) {
    if (b.inertia <= 0)
      refuse(field + ".inertia", "needs an explicit inertia for MuJoCo" + gotValue(b.inertia));
    xml << "    <joint name=\"" << b.name << "_x\" type=\"slide\" axis=\"1 0 0\"/>\n"
        << "    <joint name=\"" << b.name << "_z\" type=\"slide\" axis=\"0 0 1\"/>\n";
    if (!b.fixedRotation)
      xml << "    <joint name=\"" << b.name << "_a\" type=\"hinge\" axis=\"0 -1 0\"/>\n";
    xml << "    <inertial pos=\"0 0 0\" mass=\"" << number(b.mass) << "\" diaginertia=\""
        << number(b.inertia) << ' ' << number(b.inertia) << ' ' << number(b.inertia) << "\"/>\n";
  }
  for (const ShapeDef& s : b.shapes) {
    if (s.kind == ShapeDef::Kind::Circle) {
      xml << "    <geom type=\"sphere\" size=\"" << number(s.radius) << "\" pos=\"" << xz(s.center)
          << '"';
    } else {
      Vec2 lo = s.vertices[0], hi = s.vertices[0];
      for (const Vec2& v : s.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      const Vec2 half = 0.5 * (hi - lo);
      xml << "    <geom type=\"box\" size=\"" << number(half.x()) << " 0.05 " << number(half.y())
          << "\" pos=\"" << xz(0.5 * (hi + lo)) << '"';
    }
    xml << " friction=\"" << number(s.friction) << " 0.005 0.0001\""
        << (s.sensor ? " contype=\"0\" conaffinity=\"0\"" : "") << "/>\n";
  }
  xml << "  </body>\n";
}

Vec2 worldOf(const SceneDef& scene, const std::string& body, const Vec2& local) {
  const int b = findBodyIndex(scene, body);
  if (b < 0) return local;
  return scene.bodies[b].position + rotate(local, scene.bodies[b].angle);
}

// A site for each cable point; world points go into the worldbody, others into their body.
struct Site {
  std::string name, body;
  Vec2 local;
};

std::vector<Site> cableSites(const SceneDef& scene, int c, double& length) {
  const CableDef& cable = scene.cables[c];
  const std::string field = "cables[" + std::to_string(c) + "]";
  if (cable.stiffness > 0) refuse(field + ".stiffness", "elastic cables are not mapped");
  std::vector<Site> sites;
  const std::string prefix = "c" + std::to_string(c) + "_";
  sites.push_back({prefix + "start", cable.start.body, cable.start.point});
  for (size_t j = 0; j < cable.pulleys.size(); ++j) {
    const PulleyDef& p = cable.pulleys[j];
    if (p.kind != PulleyDef::Kind::Point || p.side != WrapSide::Threaded)
      refuse(field + ".pulleys[" + std::to_string(j) + "]",
             "only threaded point pulleys are mapped (a tendon site is always in the path)");
    sites.push_back({prefix + "p" + std::to_string(j), p.body, p.point});
  }
  sites.push_back({prefix + "end", cable.end.body, cable.end.point});
  length = 0;
  for (size_t i = 0; i + 1 < sites.size(); ++i)
    length += (worldOf(scene, sites[i + 1].body, sites[i + 1].local) -
               worldOf(scene, sites[i].body, sites[i].local))
                  .norm();
  if (cable.restLength >= 0) length = cable.restLength;
  return sites;
}

}  // namespace

std::string sceneToMjcf(const SceneDef& scene) {
  if (!scene.joints.empty())
    refuse("joints", "joints are not mapped (got " + std::to_string(scene.joints.size()) + ")");
  std::vector<std::vector<Site>> sites;
  std::vector<double> lengths(scene.cables.size());
  for (size_t c = 0; c < scene.cables.size(); ++c)
    sites.push_back(cableSites(scene, static_cast<int>(c), lengths[c]));
  auto sitesOn = [&](const std::string& body) {
    std::ostringstream s;
    for (const auto& cable : sites)
      for (const Site& site : cable)
        if (site.body == body)
          s << "    <site name=\"" << site.name << "\" pos=\"" << xz(site.local) << "\"/>\n";
    return s.str();
  };

  std::ostringstream xml;
  xml << "<mujoco model=\"" << scene.name << "\">\n"
      << "<compiler angle=\"radian\"/>\n"
      << "<option timestep=\"" << number(scene.dt) << "\" gravity=\"" << xz(scene.gravity)
      << "\"/>\n"
      // Room for every tendon limit (the default 500 is full at a few hundred cables). MuJoCo
      // 2.2.2 allocates njmax x nv doubles, so no more than that plus a margin for contacts.
      << "<size njmax=\"" << 500 + scene.cables.size() << "\" nconmax=\"200\"/>\n"
      << "<worldbody>\n"
      << sitesOn("world");
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    std::ostringstream body;
    writeBody(body, scene.bodies[b], static_cast<int>(b));
    std::string text = body.str();
    text.insert(text.rfind("  </body>"), sitesOn(scene.bodies[b].name));
    xml << text;
  }
  xml << "</worldbody>\n<tendon>\n";
  for (size_t c = 0; c < scene.cables.size(); ++c) {
    xml << "  <spatial name=\"" << scene.cables[c].name << "\" limited=\"true\" range=\"0 "
        << number(lengths[c]) << "\">\n";
    for (const Site& s : sites[c]) xml << "    <site site=\"" << s.name << "\"/>\n";
    xml << "  </spatial>\n";
  }
  xml << "</tendon>\n</mujoco>\n";
  return xml.str();
}

struct MujocoWorld::Impl {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  std::vector<int> bodyIds;
  ~Impl() {
    if (data) mj_deleteData(data);
    if (model) mj_deleteModel(model);
  }
};

MujocoWorld::MujocoWorld(const SceneDef& scene) : impl_(std::make_unique<Impl>()) {
  const std::string xml = sceneToMjcf(scene);
  const std::string file = "scene.xml";
  auto vfs = std::make_unique<mjVFS>();  // about 2 MB: not on the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), file.c_str(), static_cast<int>(xml.size())) != 0)
    refuse("(model)", "cannot make the in-memory file");
  const int f = mj_findFileVFS(vfs.get(), file.c_str());
  std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs->filedata[f]));
  char error[1000] = "";
  impl_->model = mj_loadXML(file.c_str(), vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!impl_->model) refuse("(model)", std::string("MuJoCo refused the model: ") + error);
  impl_->data = mj_makeData(impl_->model);
  for (const BodyDef& b : scene.bodies) {
    impl_->bodyIds.push_back(mj_name2id(impl_->model, mjOBJ_BODY, b.name.c_str()));
    if (b.type != BodyType::Dynamic) continue;
    // Initial velocities: the slide joints' qvel (the hinge's is the angular velocity).
    const int jx = mj_name2id(impl_->model, mjOBJ_JOINT, (b.name + "_x").c_str());
    const int dof = impl_->model->jnt_dofadr[jx];
    impl_->data->qvel[dof] = b.velocity.x();
    impl_->data->qvel[dof + 1] = b.velocity.y();
    if (!b.fixedRotation) impl_->data->qvel[dof + 2] = b.angularVelocity;
  }
  mj_forward(impl_->model, impl_->data);
}

MujocoWorld::~MujocoWorld() = default;

void MujocoWorld::step() {
  mj_step(impl_->model, impl_->data);
}

double MujocoWorld::time() const {
  return impl_->data->time;
}

Vec2 MujocoWorld::bodyPosition(int i) const {
  const mjtNum* p = impl_->data->xpos + 3 * impl_->bodyIds[i];
  return Vec2(p[0], p[2]);
}

double MujocoWorld::cableLength(int i) const {
  return impl_->data->ten_length[i];
}

int MujocoWorld::dofs() const {
  return impl_->model->nv;
}

}  // namespace cablelab
