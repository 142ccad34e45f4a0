#!/usr/bin/env python3
"""Writes assets/clips/walk.bvh: a looped adult walk built from smooth periodic
curves that follow normative sagittal joint angles (Perry's gait phases).

Python 3 standard library only. The joint names are CMU-style (Hips, LeftUpLeg,
LeftLeg, LeftFoot, LeftToeBase, Spine, Spine1, Neck, Head, LeftShoulder,
LeftArm, LeftForeArm, LeftHand, ...), lengths are centimetres, +Y is up, the
walker faces +Z and its left is +X.

The joint angles are prescribed; the root follows from them: each frame it is
raised so that the lowest point of either sole touches the ground (y = 0), and
it moves forward at the constant speed that keeps the stance sole in place on
average. The script prints that speed and the largest slide of a stance sole.

Usage: python3 tools/make_walk_bvh.py [OUTPUT]   (default assets/clips/walk.bvh)
"""

import math
import os
import sys

FPS = 60
CYCLE_S = 1.1
CYCLES = 3
FRAMES_PER_CYCLE = round(CYCLE_S * FPS)
# Stance of a normal walk: heel strike at phase 0, toe-off at about 0.6.
# The left foot lies flat between these phases.
STANCE_WINDOW = (0.1, 0.4)

# The hierarchy: (name, parent, offset in cm, has rotation channels).
# End sites are (name None, parent, offset).
JOINTS = [
    ("Hips", None, (0.0, 0.0, 0.0)),
    ("LeftUpLeg", "Hips", (9.0, -6.0, 0.0)),
    ("LeftLeg", "LeftUpLeg", (0.0, -43.0, 0.0)),
    ("LeftFoot", "LeftLeg", (0.0, -42.0, 0.0)),
    ("LeftToeBase", "LeftFoot", (0.0, -6.0, 13.0)),
    ("RightUpLeg", "Hips", (-9.0, -6.0, 0.0)),
    ("RightLeg", "RightUpLeg", (0.0, -43.0, 0.0)),
    ("RightFoot", "RightLeg", (0.0, -42.0, 0.0)),
    ("RightToeBase", "RightFoot", (0.0, -6.0, 13.0)),
    ("Spine", "Hips", (0.0, 10.0, 0.0)),
    ("Spine1", "Spine", (0.0, 15.0, 0.0)),
    ("Neck", "Spine1", (0.0, 22.0, -1.0)),
    ("Head", "Neck", (0.0, 10.0, 0.0)),
    ("LeftShoulder", "Spine1", (3.0, 18.0, 0.0)),
    ("LeftArm", "LeftShoulder", (15.0, 0.0, 0.0)),
    ("LeftForeArm", "LeftArm", (0.0, -29.0, 0.0)),
    ("LeftHand", "LeftForeArm", (0.0, -26.0, 0.0)),
    ("RightShoulder", "Spine1", (-3.0, 18.0, 0.0)),
    ("RightArm", "RightShoulder", (-15.0, 0.0, 0.0)),
    ("RightForeArm", "RightArm", (0.0, -29.0, 0.0)),
    ("RightHand", "RightForeArm", (0.0, -26.0, 0.0)),
]
END_SITES = {
    "LeftToeBase": (0.0, -1.0, 6.0),
    "RightToeBase": (0.0, -1.0, 6.0),
    "Head": (0.0, 15.0, 0.0),
    "LeftHand": (0.0, -18.0, 0.0),
    "RightHand": (0.0, -18.0, 0.0),
}
# Points of each sole relative to the ankle (LeftFoot) in the foot's frame:
# heel and ball (under the toe joint); the toe tip relative to the toe joint.
SOLE_POINTS = [(0.0, -7.0, -5.0), (0.0, -7.0, 13.0)]
TOE_TIP = (0.0, -1.0, 6.0)


def bump(p, centre, width):
    """A periodic Gaussian bump of unit height at phase `centre`."""
    d = (p - centre + 0.5) % 1.0 - 0.5
    return math.exp(-0.5 * (d / width) ** 2)


def hip_flexion(p):
    """Thigh forward of the vertical, degrees: +30 at heel strike, -10 at toe-off."""
    return 10.0 + 20.0 * math.cos(2.0 * math.pi * (p - 0.05))


def knee_flexion(p):
    """Degrees: 5 at heel strike, 18 at loading, near 0 mid-stance, 62 in swing."""
    return 3.0 + 15.0 * bump(p, 0.15, 0.07) + 59.0 * bump(p, 0.72, 0.11)


def ankle_dorsiflexion(p):
    """Degrees, positive toe up: foot flat, tibia advance, push-off, swing."""
    return (
        -7.0 * bump(p, 0.06, 0.04)
        + 10.0 * bump(p, 0.43, 0.1)
        - 17.0 * bump(p, 0.62, 0.05)
        + 3.0 * bump(p, 0.85, 0.1)
    )


def toe_extension(p):
    """Degrees the toes bend up at push-off (the ball stays on the ground)."""
    return 25.0 * bump(p, 0.58, 0.05)


def shoulder_flexion(p):
    """Left arm forward of the vertical, degrees: back at left heel strike."""
    return 3.0 - 17.0 * math.cos(2.0 * math.pi * (p - 0.02))


def elbow_flexion(p):
    """Degrees: most bent as the arm swings forward."""
    return 20.0 - 10.0 * math.cos(2.0 * math.pi * (p - 0.02))


def angles(p):
    """Each joint's (z, x, y) Euler angles in degrees at walk phase `p`
    (0 = left heel strike); positive x turns a hanging bone backward."""
    q = (p + 0.5) % 1.0
    two_pi = 2.0 * math.pi
    pelvis_yaw = -5.0 * math.cos(two_pi * p)
    pelvis_list = 4.0 * math.cos(two_pi * (p - 0.2))
    a = {name: (0.0, 0.0, 0.0) for name, _, _ in JOINTS}
    a["Hips"] = (pelvis_list, 0.0, pelvis_yaw)
    for side, phase in (("Left", p), ("Right", q)):
        a[side + "UpLeg"] = (0.0, -hip_flexion(phase), 0.0)
        a[side + "Leg"] = (0.0, knee_flexion(phase), 0.0)
        a[side + "Foot"] = (0.0, -ankle_dorsiflexion(phase), 0.0)
        a[side + "ToeBase"] = (0.0, -toe_extension(phase), 0.0)
        a[side + "Arm"] = (0.0, -shoulder_flexion(phase), 0.0)
        a[side + "ForeArm"] = (0.0, -elbow_flexion(phase), 0.0)
    a["Spine"] = (-0.6 * pelvis_list, 0.0, -1.6 * pelvis_yaw)
    a["Spine1"] = (-0.2 * pelvis_list, 0.0, -0.4 * pelvis_yaw)
    a["Neck"] = (0.2 * pelvis_list, 0.0, 0.6 * pelvis_yaw)
    return a


def rot(axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    if axis == "x":
        return [[1, 0, 0], [0, c, -s], [0, s, c]]
    if axis == "y":
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(m, v):
    return tuple(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def zxy(z, x, y):
    """The rotation of channels `Zrotation Xrotation Yrotation`: Rz * Rx * Ry."""
    return mul(mul(rot("z", z), rot("x", x)), rot("y", y))


def globals_at(p):
    """Each joint's (rotation, position) with the root at the origin."""
    a = angles(p)
    out = {}
    for name, parent, offset in JOINTS:
        local = zxy(*a[name])
        if parent is None:
            out[name] = (local, offset)
        else:
            prot, ppos = out[parent]
            out[name] = (mul(prot, local), add(ppos, apply(prot, offset)))
    return out


def sole_points(g, side):
    """World points of one sole (root at the origin): heel, ball, toe tip."""
    frot, fpos = g[side + "Foot"]
    points = [add(fpos, apply(frot, s)) for s in SOLE_POINTS]
    trot, tpos = g[side + "ToeBase"]
    points.append(add(tpos, apply(trot, TOE_TIP)))
    return points


def root_height(g):
    """How high the root must be for the lowest sole point to touch y = 0."""
    lowest = min(pt[1] for side in ("Left", "Right") for pt in sole_points(g, side))
    return -lowest


def stance_contact_z(p):
    """The left sole's centre (between heel and ball), z relative to the root."""
    heel, ball, _ = sole_points(globals_at(p), "Left")
    return 0.5 * (heel[2] + ball[2])


def walking_speed():
    """cm/s that keeps the flat left sole in place on average."""
    a, b = STANCE_WINDOW
    return (stance_contact_z(a) - stance_contact_z(b)) / ((b - a) * CYCLE_S)


def largest_slide(speed):
    """The most the flat left sole's centre moves, cm."""
    a, b = STANCE_WINDOW
    steps = 40
    zs = []
    for k in range(steps + 1):
        p = a + (b - a) * k / steps
        zs.append(stance_contact_z(p) + speed * p * CYCLE_S)
    return max(zs) - min(zs)


def hierarchy_lines():
    lines = ["HIERARCHY"]
    children = {}
    for name, parent, _ in JOINTS:
        children.setdefault(parent, []).append(name)
    offsets = {name: off for name, _, off in JOINTS}

    def write(name, depth):
        pad = "  " * depth
        keyword = "ROOT" if depth == 0 else "JOINT"
        lines.append(f"{pad}{keyword} {name}")
        lines.append(pad + "{")
        ox, oy, oz = offsets[name]
        lines.append(f"{pad}  OFFSET {ox:.2f} {oy:.2f} {oz:.2f}")
        if depth == 0:
            lines.append(
                f"{pad}  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
            )
        else:
            lines.append(f"{pad}  CHANNELS 3 Zrotation Xrotation Yrotation")
        for child in children.get(name, []):
            write(child, depth + 1)
        if name in END_SITES:
            ex, ey, ez = END_SITES[name]
            lines.append(f"{pad}  End Site")
            lines.append(pad + "  {")
            lines.append(f"{pad}    OFFSET {ex:.2f} {ey:.2f} {ez:.2f}")
            lines.append(pad + "  }")
        lines.append(pad + "}")

    write("Hips", 0)
    return lines


def motion_lines(speed):
    frames = FRAMES_PER_CYCLE * CYCLES + 1
    lines = ["MOTION", f"Frames: {frames}", f"Frame Time: {1.0 / FPS:.6f}"]
    for f in range(frames):
        t = f / FPS
        p = (t / CYCLE_S) % 1.0
        a = angles(p)
        height = root_height(globals_at(p))
        values = [0.0, height, speed * t]
        for name, _, _ in JOINTS:
            values.extend(a[name])
        lines.append(" ".join(f"{v:.4f}" for v in values))
    return lines


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "assets", "clips", "walk.bvh")
    out = sys.argv[1] if len(sys.argv) > 1 else default
    speed = walking_speed()
    text = "\n".join(hierarchy_lines() + motion_lines(speed)) + "\n"
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    tmp = out + ".tmp"
    with open(tmp, "w", encoding="ascii") as f:
        f.write(text)
    os.replace(tmp, out)
    print(
        f"wrote {out}: {CYCLES} cycles of {CYCLE_S} s at {FPS} fps, "
        f"{speed / 100.0:.2f} m/s, stride {speed * CYCLE_S / 100.0:.2f} m, "
        f"flat sole slides at most {largest_slide(speed):.1f} cm"
    )


if __name__ == "__main__":
    main()
