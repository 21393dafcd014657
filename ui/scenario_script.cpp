#include "ui/scenario_script.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/authoring.h"
#include "ui/build_scenarios.h"
#include "ui/controller_panel.h"
#include "ui/report_json.h"
#include "ui/synthetic_events.h"
#include "ui/tension_scale.h"
#include "ui/timeline_scenarios.h"

namespace cablelab::ui {
namespace {

/// The body at the end of a rigid cable that the mouse can grab, -1 if none.
int rigidCableBody(const World& world, int* cable) {
  for (int i = 0; i < world.cableCount(); ++i) {
    if (world.cable(i).elastic()) continue;
    for (const std::string& name :
         {world.cable(i).def().end.body, world.cable(i).def().start.body}) {
      const int b = world.findBody(name);
      if (b >= 0 && world.scene().bodies[b].type == BodyType::Dynamic) {
        *cable = i;
        return b;
      }
    }
  }
  return -1;
}

/// The Inspector's span table as it was shown, with the engine's span tensions of the moment.
std::string spansJson(const Sandbox& sandbox) {
  const SpanTable& t = sandbox.shownSpans;
  std::string out = "{\"spans\": [";
  for (size_t k = 0; k < t.spans.size(); ++k)
    out += std::string(k ? ", " : "") + "{\"tension\": " + jsonNumber(t.spans[k].tension) +
           ", \"text\": " + jsonQuoted(t.spans[k].text) + "}";
  out += "], \"wheels\": [";
  for (size_t k = 0; k < t.wheels.size(); ++k) {
    const WheelRow& w = t.wheels[k];
    out += std::string(k ? ", " : "") + "{\"mu\": " + jsonNumber(w.mu) +
           ", \"theta\": " + jsonNumber(w.wrapAngle) + ", \"ratio\": " + jsonNumber(w.ratio) +
           ", \"state\": " + jsonQuoted(w.state) + ", \"text\": " + jsonQuoted(w.text) + "}";
  }
  out += "], \"engine\": [";
  const World& world = *sandbox.world();
  const Cable& c = world.cable(std::clamp(sandbox.selectedCable, 0, world.cableCount() - 1));
  for (int k = 0; k < c.spanCount(); ++k)
    out += std::string(k ? ", " : "") + jsonNumber(c.spanTension(k));
  return out + "], \"overflow\": " + jsonNumber(sandbox.panelOverflow[1]) + "}";
}

/// The world point in the free area's fraction (fx, fy) from its top-left corner, as pixels.
Vec2 freePoint(const Sandbox& sandbox, double fx, double fy) {
  const PanelRect f = sandbox.freeArea();
  return Vec2(f.x + fx * f.width, f.y + fy * f.height);
}

}  // namespace

const std::vector<std::string>& ScenarioScript::names() {
  static const std::vector<std::string> n = [] {
    std::vector<std::string> all = {"describe", "reset-scale",  "rigid-drag", "drop-box",
                                    "author",   "capstan-slip", "pose-drag",  "pose-payout"};
    for (const BuildScenario& b : buildScenarios()) all.push_back(b.name);
    for (const std::string& t : TimelineScenario::names()) all.push_back(t);
    for (const std::string& name : LectureScript::names()) all.push_back(name);
    all.push_back(TurnTargetScenario::kName);
    all.push_back(LawTargetScenario::kMpc);
    all.push_back(LawTargetScenario::kPid);
    return all;
  }();
  return n;
}

ScenarioScript::ScenarioScript(std::string name, Uint32 windowId, std::string out)
    : name_(std::move(name)), out_(std::move(out)), windowId_(windowId) {
  const auto& timeline = TimelineScenario::names();
  if (std::find(timeline.begin(), timeline.end(), name_) != timeline.end())
    timeline_ = std::make_shared<TimelineScenario>(name_, windowId_, out_);
  const auto& lecture = LectureScript::names();
  if (std::find(lecture.begin(), lecture.end(), name_) != lecture.end())
    lecture_ = std::make_unique<LectureScript>(name_, windowId_, out_);
  if (name_ == TurnTargetScenario::kName)
    turnTarget_ = std::make_unique<TurnTargetScenario>(windowId_);
  if (name_ == LawTargetScenario::kMpc || name_ == LawTargetScenario::kPid)
    lawTarget_ = std::make_unique<LawTargetScenario>(windowId_, name_ == LawTargetScenario::kMpc);
}

void ScenarioScript::mouse(Uint32 type, const Vec2& screen, Uint8 button) {
  pushMouseEvent(windowId_, type, screen, button);
}

void ScenarioScript::key(SDL_Keycode k) {
  pushKeyPress(windowId_, k);
}

bool ScenarioScript::beforeFrame(Sandbox& sandbox, int frame) {
  if (!sandbox.world()) {
    report_ = "{\"scenario\": " + jsonQuoted(name_) + ", \"failure\": \"no scene\"}";
    return false;
  }
  if (lecture_) {
    const bool more = lecture_->beforeFrame(sandbox, frame);
    report_ = lecture_->report();
    return more;
  }
  if (turnTarget_) return turnTarget_->beforeFrame(sandbox, frame, report_);
  if (lawTarget_) return lawTarget_->beforeFrame(sandbox, frame, report_);
  if (name_ == "describe") return describe(sandbox, frame);
  if (name_ == "reset-scale") return resetScale(sandbox, frame);
  if (name_ == "rigid-drag") return rigidDrag(sandbox, frame);
  if (name_ == "drop-box") return dropBox(sandbox, frame);
  if (name_ == "author") return author(sandbox, frame);
  if (name_ == "capstan-slip") return capstanSlip(sandbox, frame);
  if (name_ == "pose-drag" || name_ == "pose-payout") return poseDrag(sandbox, frame);
  if (name_.rfind("build-", 0) == 0) return build(sandbox, frame);
  if (timeline_) return timeline_->beforeFrame(sandbox, frame, report_);
  report_ = "{\"scenario\": " + jsonQuoted(name_) + ", \"failure\": \"unknown scenario\"}";
  return false;
}

bool ScenarioScript::describe(Sandbox& sandbox, int frame) {
  if (frame < 3) return true;  // the panel has been drawn
  report_ = "{\"scenario\": \"describe\", \"title\": " + jsonQuoted(sandbox.shownTitle) +
            ", \"description\": " + jsonQuoted(sandbox.shownDescription) +
            ", \"scene_description\": " + jsonQuoted(sandbox.scene.description) + "}";
  return false;
}

bool ScenarioScript::resetScale(Sandbox& sandbox, int frame) {
  World& world = *sandbox.world();
  if (frame == 2) {
    figures_[0] = sandbox.tensionScale;
    int cable = -1;
    body_ = rigidCableBody(world, &cable);
    if (body_ < 0) body_ = sandbox.bodyAt(world.body(0).position);
    if (body_ >= 0) {
      from_ = sandbox.camera.toScreen(world.body(body_).position);
      to_ = from_ + Vec2(0, 250);  // pull down hard: the tension rises
      mouse(SDL_MOUSEMOTION, from_);
      mouse(SDL_MOUSEBUTTONDOWN, from_);
    }
  } else if (frame > 2 && frame <= 40) {
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * std::min(1.0, (frame - 2) / 20.0));
    for (int i = 0; i < world.cableCount(); ++i)
      largest_ = std::max(largest_, world.cable(i).tension());
  } else if (frame == 41) {
    mouse(SDL_MOUSEBUTTONUP, to_);
    figures_[1] = sandbox.tensionScale;
  } else if (frame == 45) {
    key(SDLK_r);
  } else if (frame == 50) {
    figures_[2] = sandbox.tensionScale;
    report_ = "{\"scenario\": \"reset-scale\", \"before\": " + jsonNumber(figures_[0]) +
              ", \"after_drag\": " + jsonNumber(figures_[1]) +
              ", \"after_reset\": " + jsonNumber(figures_[2]) +
              ", \"expected\": " + jsonNumber(loadTensionScale(sandbox.scene)) +
              ", \"largest_tension\": " + jsonNumber(largest_) +
              ", \"time_after_reset\": " + jsonNumber(world.time()) + "}";
    return false;
  }
  return true;
}

bool ScenarioScript::rigidDrag(Sandbox& sandbox, int frame) {
  World& world = *sandbox.world();
  if (frame == 2) {
    body_ = rigidCableBody(world, &cable_);
    if (body_ < 0) {
      report_ = "{\"scenario\": \"rigid-drag\", \"failure\": \"no body on a rigid cable\"}";
      return false;
    }
    // Away from the cable's other end: the drag pulls the cable taut and tries to stretch it.
    const Vec2 p = world.body(body_).position;
    const Vec2 anchor = world.cable(cable_).path().front().world;
    const Vec2 away = (p - anchor).normalized();
    from_ = sandbox.camera.toScreen(p);
    to_ = sandbox.camera.toScreen(p + 3.0 * away);
    mouse(SDL_MOUSEMOTION, from_);
    mouse(SDL_MOUSEBUTTONDOWN, from_);
  } else if (frame > 2 && frame <= 150) {
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * std::min(1.0, (frame - 2) / 30.0));
    for (int i = 0; i < world.cableCount(); ++i) {
      const Cable& c = world.cable(i);
      if (!c.elastic() && !c.slack()) largest_ = std::max(largest_, c.length() - c.restLength());
    }
    figures_[0] = std::max(figures_[0], sandbox.drag.force.norm());
    figures_[1] += sandbox.drag.limited ? 1 : 0;
  } else if (frame == 151) {
    mouse(SDL_MOUSEBUTTONUP, to_);
    report_ =
        "{\"scenario\": \"rigid-drag\", \"body\": " + jsonQuoted(world.scene().bodies[body_].name) +
        ", \"largest_stretch\": " + jsonNumber(largest_) +
        ", \"largest_drag_force\": " + jsonNumber(figures_[0]) +
        ", \"drag_limit\": " + jsonNumber(sandbox.dragLimit(body_)) +
        ", \"frames_at_limit\": " + jsonNumber(figures_[1]) +
        ", \"banner\": " + jsonQuoted(sandbox.banner) + "}";
    return false;
  }
  return true;
}

bool ScenarioScript::poseDrag(Sandbox& sandbox, int frame) {
  constexpr int kDragFrames = 30;
  World& world = *sandbox.world();
  const bool payOut = name_ == "pose-payout";
  // figures_: 0 largest stretch while paused, 1 stretch at Play, 2 energy posed, 3 time of Play,
  // 4 top speed after Play, 5 paused when the drag began (1) or not (0).
  if (frame == 2) {
    key(SDLK_SPACE);
  } else if (frame == 4) {
    figures_[5] = sandbox.paused ? 1 : 0;
    body_ = rigidCableBody(world, &cable_);
    if (body_ < 0) {
      report_ = "{\"scenario\": \"pose-drag\", \"failure\": \"no body on a rigid cable\"}";
      return false;
    }
    // 1 m out along the cable's last segment: the pull a rigid cable resists most directly.
    const auto& path = world.cable(cable_).path();
    const bool atEnd = world.findBody(world.cable(cable_).def().end.body) == body_;
    const Vec2 last = atEnd ? path.back().world : path.front().world;
    const Vec2 before = atEnd ? path[path.size() - 2].world : path[1].world;
    to_ = sandbox.camera.toScreen(last + (last - before).normalized());
    from_ = sandbox.camera.toScreen(last);
    start_ = world.body(body_).position;
    restBefore_ = world.cable(cable_).restLength();
    figures_[0] = -INFINITY;
    mouse(SDL_MOUSEMOTION, from_);
    mouse(SDL_MOUSEBUTTONDOWN, from_);
  } else if (frame > 4 && frame <= 4 + kDragFrames) {
    if (payOut) SDL_SetModState(KMOD_LSHIFT);  // held while the motion events are handled
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * ((frame - 4.0) / kDragFrames));
    figures_[0] = std::max(figures_[0], world.longestRigidStretch());
  } else if (frame == 5 + kDragFrames) {
    SDL_SetModState(KMOD_NONE);
    figures_[0] = std::max(figures_[0], world.longestRigidStretch());
    said_ = sandbox.message;
    end_ = world.body(body_).position;
    mouse(SDL_MOUSEBUTTONUP, to_);
  } else if (frame == 6 + kDragFrames) {
    figures_[1] = world.longestRigidStretch();
    figures_[2] = world.energy();
    figures_[3] = world.time();
    key(SDLK_SPACE);
  } else if (frame > 6 + kDragFrames) {
    figures_[4] = std::max(figures_[4], world.body(body_).velocity.norm());
    if (world.time() < figures_[3] + 0.1 - 1e-9) return true;
    report_ = "{\"scenario\": " + jsonQuoted(name_) +
              ", \"body\": " + jsonQuoted(world.scene().bodies[body_].name) +
              ", \"paused\": " + (figures_[5] > 0 ? "true" : "false") +
              ", \"largest_paused_stretch\": " + jsonNumber(figures_[0]) +
              ", \"stretch_at_play\": " + jsonNumber(figures_[1]) +
              ", \"moved\": " + jsonNumber((end_ - start_).norm()) +
              ", \"energy_posed\": " + jsonNumber(figures_[2]) +
              ", \"energy_after\": " + jsonNumber(world.energy()) +
              ", \"seconds_run\": " + jsonNumber(world.time() - figures_[3]) +
              ", \"fastest_after_play\": " + jsonNumber(figures_[4]) +
              ", \"rest_before\": " + jsonNumber(restBefore_) +
              ", \"rest_after\": " + jsonNumber(world.cable(cable_).restLength()) +
              ", \"status\": " + jsonQuoted(said_) + ", \"banner\": " + jsonQuoted(sandbox.banner) +
              "}";
    return false;
  }
  return true;
}

bool ScenarioScript::dropBox(Sandbox& sandbox, int frame) {
  World& world = *sandbox.world();
  const int box = world.findBody("box");
  if (box < 0) {
    report_ = "{\"scenario\": \"drop-box\", \"failure\": \"no body called box\"}";
    return false;
  }
  if (!sandbox.banner.empty()) bannerSeen_ = sandbox.banner;
  if (frame == 2) {
    sandbox.dragWeights = 20;  // strong enough to pull the box out of the membranes
    figures_[0] = 0;
    from_ = sandbox.camera.toScreen(world.body(box).position);
    to_ = sandbox.camera.toScreen(world.body(box).position + Vec2(1.5, 0.0));
    mouse(SDL_MOUSEMOTION, from_);
    mouse(SDL_MOUSEBUTTONDOWN, from_);
    report_ = std::string("{\"scenario\": \"drop-box\", \"state_before\": ") +
              jsonQuoted(handGraspState(sandbox)) + "}";
  } else if (frame > 2 && frame <= 120) {
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * std::min(1.0, (frame - 2) / 60.0));
  } else if (frame == 121) {
    mouse(SDL_MOUSEBUTTONUP, to_);
  } else if (frame == 180) {
    report_.pop_back();
    report_ += ", \"banner_seen\": " + jsonQuoted(bannerSeen_) +
               ", \"state_after\": " + jsonQuoted(handGraspState(sandbox)) + ", \"box\": [" +
               jsonNumber(world.body(box).position.x()) + ", " +
               jsonNumber(world.body(box).position.y()) + "]}";
    return false;
  }
  return true;
}

bool ScenarioScript::capstanSlip(Sandbox& sandbox, int frame) {
  if (sandbox.world()->cableCount() == 0) {
    report_ = "{\"scenario\": \"capstan-slip\", \"failure\": \"no cable\"}";
    return false;
  }
  if (frame == 60) {  // 1 s with the scene's own masses: the rope holds
    report_ = "{\"scenario\": \"capstan-slip\", \"holding\": " + spansJson(sandbox);
    // The Scene panel's slider, as a user sets it: a load past e^(mu theta) m_hold.
    auto parameters = sandbox.parameters;
    std::erase_if(parameters, [](const auto& p) { return p.first == "m_load"; });
    parameters.emplace_back("m_load", 6.0);
    sandbox.rebuild(parameters);
  } else if (frame == 120) {  // 1 s later: slipping (the hold reaches its pulley after 1.2 s)
    report_ += ", \"slipping\": " + spansJson(sandbox) + "}";
    return false;
  }
  return true;
}

bool ScenarioScript::author(Sandbox& sandbox, int frame) {
  // New scene, then: a box (dynamic) low in the middle, a point pulley above it, a cable from
  // a world anchor left-up, over the pulley, down to the box.
  Authoring& a = *sandbox.authoring;
  auto click = [&](double fx, double fy) {
    const Vec2 p = freePoint(sandbox, fx, fy);
    mouse(SDL_MOUSEMOTION, p);
    mouse(SDL_MOUSEBUTTONDOWN, p);
    mouse(SDL_MOUSEBUTTONUP, p);
  };
  switch (frame) {
    case 2:
      newScene(sandbox);
      sandbox.paused = true;
      break;
    case 5:
      a.tool = Authoring::Tool::Box;
      click(0.6, 0.6);
      break;
    case 8:
      a.tool = Authoring::Tool::PointPulley;
      click(0.6, 0.25);
      break;
    case 11:
      a.tool = Authoring::Tool::Cable;
      click(0.25, 0.25);
      break;  // start: world anchor
    case 13:
      click(0.6, 0.25);
      break;  // over the pulley
    case 15:
      click(0.6, 0.6);
      break;  // end: on the box
    case 18: {
      a.tool = Authoring::Tool::None;
      std::string error;
      try {
        saveScene(sandbox, out_);
      } catch (const std::exception& e) {
        error = e.what();
      }
      const SceneDef& s = sandbox.scene;
      report_ = "{\"scenario\": \"author\", \"bodies\": " + jsonNumber(s.bodies.size()) +
                ", \"cables\": " + jsonNumber(s.cables.size()) + ", \"pulleys\": " +
                jsonNumber(s.cables.empty() ? 0 : s.cables.front().pulleys.size()) +
                ", \"undo\": " + jsonNumber(a.undo.size()) + ", \"file\": " + jsonQuoted(out_) +
                ", \"error\": " + jsonQuoted(error + sandbox.error) + "}";
      return false;
    }
    default:
      break;
  }
  return true;
}

// One step every 3 frames (a click's events are handled in the frame they are pushed); modifier
// keys are held for one frame through SDL's modifier state, which the handlers read.
bool ScenarioScript::build(Sandbox& sandbox, int frame) {
  const BuildScenario* it = findBuildScenario(name_);
  SDL_SetModState(KMOD_NONE);
  if (frame == 2) {
    newScene(sandbox);
    sandbox.paused = true;
  }
  if (frame < 6 || frame % 3 != 0) return true;
  if (step_ < it->steps.size()) {
    playBuildStep(sandbox, windowId_, it->steps[step_++]);
    return true;
  }
  const World& world = *sandbox.world();
  if (!playing_) {  // built: save, report, then Space plays the scene as saved
    std::string saveError;
    try {
      saveScene(sandbox, out_);
    } catch (const std::exception& e) {
      saveError = e.what();
    }
    const SceneDef& scene = sandbox.scene;
    int wraps = 0;
    for (int i = 0; i < world.cableCount(); ++i) wraps += world.cable(i).wraps();
    report_ =
        "{\"scenario\": " + jsonQuoted(name_) + ", \"bodies\": " + jsonNumber(scene.bodies.size()) +
        ", \"cables\": " + jsonNumber(scene.cables.size()) +
        ", \"joints\": " + jsonNumber(scene.joints.size()) + ", \"wraps\": " + jsonNumber(wraps) +
        ", \"undo\": " + jsonNumber(sandbox.authoring->undo.size()) +
        ", \"redo\": " + jsonNumber(sandbox.authoring->redo.size()) +
        ", \"error\": " + jsonQuoted(sandbox.error) + ", \"save_error\": " + jsonQuoted(saveError) +
        ", \"file\": " + jsonQuoted(out_) +
        ", \"plots_open\": " + (sandbox.plotsSectionOpen ? "true" : "false") +
        ", \"build_open\": " + (sandbox.buildSectionOpen ? "true" : "false") +
        ", \"panel_overflow\": [" + jsonNumber(sandbox.panelOverflow[0]) + ", " +
        jsonNumber(sandbox.panelOverflow[1]) + "]";
    playing_ = true;
    playFrom_ = world.time();
    key(SDLK_SPACE);
    return true;
  }
  // One step a frame (scripted runs step at a fixed rate): the poses after kBuildPlaySteps.
  const long steps = std::lround((world.time() - playFrom_) / sandbox.dt);
  if (steps < kBuildPlaySteps && !sandbox.paused) return true;
  std::string poses;
  for (int b = 0; b < world.bodyCount(); ++b) {
    const BodyState& s = world.body(b);
    poses += std::string(b ? ", " : "") + "{\"name\": " + jsonQuoted(world.scene().bodies[b].name) +
             ", \"x\": " + jsonNumber(s.position.x()) + ", \"y\": " + jsonNumber(s.position.y()) +
             ", \"theta\": " + jsonNumber(s.angle) + "}";
  }
  report_ += ", \"played_steps\": " + jsonNumber(steps) + ", \"poses\": [" + poses + "]}";
  return false;
}

}  // namespace cablelab::ui
