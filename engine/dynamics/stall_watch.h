// StallWatch: whether a servo has stalled (docs/servos.md, "Stalls"): it pushes at max_force and
// its joint stays nearly still for a while. A joint its servo brakes at max_force, or that its load
// pulls back against it (overpowered), moves: no stall. One per joint, fed once a World step.
// Private to engine/dynamics.
#pragma once

namespace cablelab {

struct StallWatch {
  /// s: a servo at max_force whose joint stays within kStillRange this long has stalled. Longer
  /// than a step at 30 Hz, so a joint turning round (braked, or pulled back) shows its motion;
  /// short against the stall's own time (docs/servos.md: within 0.2 s of max_force / (kp speed)).
  static constexpr double kWindow = 0.1;
  static constexpr double kStillRange = 1e-3;  ///< rad or m: the joint's range over the window
  static constexpr double kStillRate = 1e-3;   ///< rad/s or m/s: ... and its rate as it is said
  /// rad or m: a stalled joint this far outside the range it stalled in moves again: the stall
  /// ends (a new one is said anew). Wider than kStillRange, so a stalled drum's jiggle keeps it.
  static constexpr double kLeaveRange = 1e-2;
  static constexpr double kRelease = 0.9;  ///< of max_force: a stalled servo pushing less lets go

  double start = -1;         ///< s: the window's start (< 0: no window: not at max_force)
  double low = 0, high = 0;  ///< the joint's coordinate over the window (rad or m)
  double push = 0;           ///< the force's sign over it
  double last = 0;           ///< the coordinate at the end of the last step (rad or m)
  bool seen = false;         ///< last holds a coordinate
  bool stalled = false;      ///< the stall has been said and has not ended

  /// After a World step of dt ending at `time`: the servo's mean force over it (N or N m), its
  /// max_force, the joint's coordinate (rad or m) and rate (rad/s or m/s) at its end. True in the
  /// step a stall is found (once a stall); start then says from when.
  bool update(double force, double maxForce, double value, double rate, double time, double dt);
};

}  // namespace cablelab
