"""cablelab: cable-driven soft robots on Box2D, scripted from Python with numpy.

The same engine as the `cablelab` command-line tool, in-process (no process start per run):

    import cablelab
    w = cablelab.World.load("pulley")          # a built-in scene or a scene JSON file
    for _ in range(120): w.step()              # the scene's dt and sub-steps
    print(w.cable_tensions(), w.body_states()) # N; one row x y theta vx vy omega per body

Units: metres, kilograms, seconds, radians, newtons (angles in degrees only where a name
says _deg). Arrays are numpy float64.

Simulation   World (load, from_dict, step, run, state as arrays, forces, servos, cables)
State        World.get_state / set_state / copy, WorldState; World and the value classes
             pickle (processes, Dask)
Sensors      cable_span_tensions, cable_corner_tensions, cable_jacobian, cable_jdot_v,
             joint_values / rates / forces, contact_forces; set_body_states,
             set_joint_values
Tools        statics, wrap, fit, membrane_data, membrane_model, scenes
The hand     HandModel, ControllerParams, HandController, hand_joints, place_hand,
             track, reach (`cablelab track` and `reach`; the GIL is released while they
             run), HandGrasp and GraspOptions (the grasp sequence, to step the hand under
             the controller or a law written in Python)
Many runs    rollout (N Worlds stepped on a thread pool, recorded as (N, T, ...) arrays),
             sweep (a task over a parameter grid on Dask: a LocalCluster or any Client)
Pictures     render (numpy RGBA image), snapshot (PNG); offscreen, no display needed
             (HAS_RENDERER is False in a build without the UI)
Errors       InputError (a ValueError; str(e) is the CLI's one-line message
             'SOURCE: FIELD: what is wrong (got VALUE)', with e.source and e.field;
             InputTypeError, for a value of the wrong type, is also a TypeError),
             SimulationError (a RuntimeError), SweepError (tasks of a
             sweep that raised, with their parameters)
"""

import sys as _sys

from ._version import __version__

try:
    import numpy as _numpy  # noqa: F401  (_core hands out numpy arrays)
except ImportError as _error:
    raise ImportError(
        f"cablelab needs numpy, which this Python cannot import: {_sys.executable} "
        f"(Python {_sys.version.split()[0]}). Install it for this interpreter (Debian: "
        f"apt-get install python3-numpy; a venv: python3 -m venv --system-site-packages), "
        f"or run Debian's /usr/bin/python3.") from _error

from . import _core
from ._sweep import SweepError, sweep
from ._core import (
    HAS_RENDERER,
    HAND_BOX,
    HAND_CABLES,
    HAND_JOINT_NAMES,
    PID_KI,
    ControllerParams,
    GraspOptions,
    HandController,
    HandGrasp,
    HandModel,
    InputError,
    InputTypeError,
    SimulationError,
    World,
    WorldState,
    fit,
    hand_joints,
    membrane_data,
    membrane_model,
    place_hand,
    reach,
    render,
    rollout,
    scenes,
    snapshot,
    statics,
    track,
    wrap,
)

__all__ = [
    "World", "WorldState", "statics", "wrap", "fit", "membrane_data", "membrane_model", "scenes",
    "HandModel", "ControllerParams", "HandController", "HandGrasp", "GraspOptions",
    "hand_joints", "place_hand",
    "track", "reach", "rollout", "sweep", "SweepError", "render", "snapshot",
    "InputError", "InputTypeError", "SimulationError",
    "HAND_JOINT_NAMES", "HAND_BOX", "HAND_CABLES", "PID_KI", "HAS_RENDERER",
]

# Show the public names as cablelab.X (not cablelab._core.X) in help() and reprs.
for _name in __all__:
    _obj = globals()[_name]
    if hasattr(_obj, "__module__") and not isinstance(_obj, (str, tuple, float, bool)):
        try:
            _obj.__module__ = "cablelab"
        except (AttributeError, TypeError):
            pass
from ._keywords import name_keywords as _name_keywords

_name_keywords(_sys.modules[__name__], __all__)
del _name, _obj, _sys, _name_keywords
