"""Random busy scenes for issue 36's energy items (tests/engine/dynamics/busy_knocks_test.cpp):
six parts 12 m apart, each one of: an elastic rope from a world point over a polygon spinning on
its pivot to a bob (and on over a point pulley), an Atwood machine over two point pulleys or a
circle (rigid or elastic), a bob thrown on an elastic rope at its point pulley, a free polygon
spinning in a rope loop. Bodies are thrown at their pulleys; every shape is a sensor with
restitution e (nothing touches but the ropes' knocks). No damping, no friction.

    python3 busy_knocks.py SEED E > scene.json    (SEED an integer, E the restitution)"""
import json, math, random, sys


def poly(rng, r):
    n = rng.randint(3, 6)
    a0 = rng.uniform(0, 2 * math.pi)
    return [[r * math.cos(a0 + 2 * math.pi * i / n), r * math.sin(a0 + 2 * math.pi * i / n)] for i in range(n)]


def bob(name, pos, m, e, vel=(0, 0)):
    return {"name": name, "position": list(pos), "mass": m, "fixed_rotation": True,
            "velocity": list(vel),
            "shapes": [{"type": "circle", "radius": 0.03, "sensor": True, "restitution": e}]}


kind_log = []


def part_kind(seed, e, p):
    scene(seed, e)
    return kind_log[p]


def scene(seed, e):
    rng = random.Random(seed)
    kind_log.clear()
    bodies, joints, cables = [], [], []
    kinds = ["poly_bungee", "poly_bungee_point", "atwood_point", "atwood_circle", "bungee_point",
             "free_poly_loop"]
    nparts = 6
    for p in range(nparts):
        kind = rng.choice(kinds)
        kind_log.append(kind)
        ox = 12.0 * p
        pre = f"p{p}."
        k = rng.uniform(200, 3000)
        if kind.startswith("poly_bungee"):
            r = rng.uniform(0.2, 0.5)
            bodies.append({"name": pre + "poly", "position": [ox, 0], "mass": rng.uniform(0.5, 3),
                           "angular_velocity": rng.uniform(-6, 6), "inertia": 0.5 * r * r,
                           "shapes": [{"type": "polygon", "vertices": poly(rng, r), "sensor": True,
                                       "restitution": e}]})
            joints.append({"type": "revolute", "body_b": pre + "poly", "anchor": [ox, 0]})
            bx, by = ox + rng.uniform(-1.5, 1.5), -rng.uniform(0.8, 2.0)
            v = (rng.uniform(-4, 4), rng.uniform(-2, 8))
            bodies.append(bob(pre + "bob", (bx, by), rng.uniform(0.3, 2), e, v))
            pulleys = [{"type": "polygon", "body": pre + "poly", "side": rng.choice(["left", "right"])}]
            start = [ox + rng.choice([-1, 1]) * rng.uniform(1.0, 2.0), rng.uniform(0.3, 1.2)]
            if kind == "poly_bungee_point":
                pulleys.append({"type": "point", "point": [ox + rng.uniform(-0.8, 0.8), -0.8]})
            cables.append({"name": pre + "rope", "start": {"point": start},
                           "end": {"body": pre + "bob"}, "pulleys": pulleys, "stiffness": k,
                           "rest_length": None})
        elif kind in ("atwood_point", "atwood_circle"):
            m1, m2 = rng.uniform(0.5, 2), rng.uniform(0.5, 2)
            d = rng.uniform(0.4, 1.0)
            y1, y2 = -rng.uniform(0.6, 1.5), -rng.uniform(0.6, 1.5)
            v1 = rng.uniform(1, 8)
            bodies.append(bob(pre + "a", (ox - d, y1), m1, e, (0, v1)))
            bodies.append(bob(pre + "b", (ox + d, y2), m2, e, (0, -v1)))
            if kind == "atwood_point":
                pulleys = [{"type": "point", "point": [ox - d, 0]}, {"type": "point", "point": [ox + d, 0]}]
            else:
                pulleys = [{"type": "circle", "point": [ox, 0], "radius": d, "side": "left", "turns": 0.5}]
            stiff = rng.choice([0.0, k])
            cables.append({"name": pre + "rope", "start": {"body": pre + "a"}, "end": {"body": pre + "b"},
                           "pulleys": pulleys, "stiffness": stiff, "rest_length": None})
        elif kind == "bungee_point":
            bx, by = ox + rng.uniform(-0.5, 0.5), -rng.uniform(0.8, 2.0)
            bodies.append(bob(pre + "bob", (bx, by), rng.uniform(0.3, 2), e,
                              (rng.uniform(-2, 2), rng.uniform(2, 9))))
            cables.append({"name": pre + "rope", "start": {"point": [ox - 1.0, 0.5]},
                           "end": {"body": pre + "bob"},
                           "pulleys": [{"type": "point", "point": [ox, 0]}], "stiffness": k,
                           "rest_length": None})
        else:  # free polygon hanging in a rope loop
            r = rng.uniform(0.2, 0.4)
            bodies.append({"name": pre + "poly", "position": [ox, 0.6], "mass": rng.uniform(0.5, 3),
                           "angular_velocity": rng.uniform(-4, 4), "inertia": 0.5 * r * r,
                           "velocity": [rng.uniform(-1, 1), rng.uniform(-1, 3)],
                           "shapes": [{"type": "polygon", "vertices": poly(rng, r), "sensor": True,
                                       "restitution": e}]})
            stiff = rng.choice([0.0, k])
            cables.append({"name": pre + "rope", "start": {"point": [ox - 1.2, 0.5]},
                           "end": {"point": [ox + 1.2, 0.5]},
                           "pulleys": [{"type": "polygon", "body": pre + "poly", "side": "right"}],
                           "stiffness": stiff, "rest_length": None})
    for c in cables:
        if c["rest_length"] is None:
            del c["rest_length"]
    return {"name": f"busy_knocks_{seed}", "bodies": bodies, "joints": joints, "cables": cables}


if __name__ == "__main__":
    seed, e = int(sys.argv[1]), float(sys.argv[2])
    print(json.dumps(scene(seed, e), indent=1))
