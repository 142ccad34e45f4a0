#!/usr/bin/env python3
"""Writes assets/clips/walk.bvh: a looped adult walk built from smooth periodic
curves that follow normative sagittal joint angles (Perry's gait phases).

Python 3 standard library only. The joint names are CMU-style (Hips, LeftUpLeg,
LeftLeg, LeftFoot, LeftToeBase, Spine, Spine1, Neck, Head, LeftShoulder,
LeftArm, LeftForeArm, LeftHand, ...), lengths are centimetres, +Y is up, the
walker faces +Z and its left is +X.

The joint angles are prescribed, but for the hip of a standing leg: the root
moves forward at a constant speed and each stance hip is solved so that its
sole's lowest point stays where it landed (the speed is the one that takes
the hip from its heel-strike to its toe-off flexion). Each frame the root is
raised so that the lowest point of either sole touches the ground (y = 0).

Usage: python3 tools/make_walk_bvh.py [OUTPUT]   (default assets/clips/walk.bvh)
"""

import math
import os
import sys

FPS = 60
CYCLE_S = 1.1
CYCLES = 3
FRAMES_PER_CYCLE = round(CYCLE_S * FPS)
# Phase of toe-off (0 = heel strike): a foot stands for this part of the cycle.
TOE_OFF = 0.6

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


def periodic_spline(keys, p):
    """A smooth periodic curve through `keys`, values at evenly spaced phases
    from 0 (a uniform Catmull-Rom spline closed on itself)."""
    n = len(keys)
    x = (p % 1.0) * n
    k = int(x) % n
    u = x - int(x)
    p0, p1, p2, p3 = (keys[(k + d) % n] for d in (-1, 0, 1, 2))
    return 0.5 * (
        2.0 * p1
        + (p2 - p0) * u
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u * u
        + (3.0 * p1 - p0 - 3.0 * p2 + p3) * u * u * u
    )


# Sagittal angles of one leg in degrees at phases 0, 0.1, ..., 0.9 (0 = its
# heel strike, toe-off at about 0.6), after Perry's normative curves.
# Hip flexion relative to the pelvis: +30 at heel strike, -10 at toe-off.
HIP_FLEXION = [27.0, 26.0, 20.0, 10.0, 0.0, -9.0, -10.0, 12.0, 27.0, 30.0]
# Knee flexion: 5 at heel strike, loading response, near 0 mid-stance, 62 in swing.
KNEE_FLEXION = [5.0, 17.0, 15.0, 7.0, 4.0, 11.0, 38.0, 63.0, 58.0, 30.0]
# Ankle dorsiflexion (toe up): foot flat, tibia advance, push-off, swing.
ANKLE_DORSIFLEXION = [0.0, -5.0, 2.0, 6.0, 9.0, 5.0, -14.0, 0.0, 10.0, 7.0]
# Toes bent up at push-off (the ball stays on the ground).
TOE_EXTENSION = [0.0, 0.0, 0.0, 0.0, 5.0, 18.0, 10.0, 0.0, 0.0, 0.0]
# Shoulder flexion (arm forward) at the phases of the same side's leg: back
# as that leg lands, forward as it pushes off.
SHOULDER_FLEXION = [-15.0, -12.0, -5.0, 5.0, 14.0, 18.0, 14.0, 5.0, -5.0, -12.0]
# Elbow flexion at the same phases: most bent as the arm swings forward.
ELBOW_FLEXION = [12.0, 13.0, 16.0, 22.0, 28.0, 30.0, 28.0, 22.0, 16.0, 13.0]
# Forward (anterior) tilt of the pelvis, degrees.
PELVIS_TILT = 4.0


def prescribed_angles(p):
    """Each joint's (z, x, y) Euler angles in degrees at walk phase `p`
    (0 = left heel strike) from the normative curves; positive x turns a
    hanging bone backward."""
    q = (p + 0.5) % 1.0
    two_pi = 2.0 * math.pi
    pelvis_yaw = -6.0 * math.cos(two_pi * p)
    pelvis_list = 3.0 * math.cos(two_pi * (p - 0.2))
    a = {name: (0.0, 0.0, 0.0) for name, _, _ in JOINTS}
    a["Hips"] = (pelvis_list, PELVIS_TILT, pelvis_yaw)
    for side, phase in (("Left", p), ("Right", q)):
        a[side + "UpLeg"] = (0.0, -periodic_spline(HIP_FLEXION, phase), 0.0)
        a[side + "Leg"] = (0.0, periodic_spline(KNEE_FLEXION, phase), 0.0)
        a[side + "Foot"] = (0.0, -periodic_spline(ANKLE_DORSIFLEXION, phase), 0.0)
        a[side + "ToeBase"] = (0.0, -periodic_spline(TOE_EXTENSION, phase), 0.0)
        # The arm swings with the opposite leg: back as its own leg lands.
        a[side + "Arm"] = (0.0, -periodic_spline(SHOULDER_FLEXION, phase), 0.0)
        a[side + "ForeArm"] = (0.0, -periodic_spline(ELBOW_FLEXION, phase), 0.0)
    a["Spine"] = (-0.6 * pelvis_list, -PELVIS_TILT, -1.6 * pelvis_yaw)
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


def globals_of(a):
    """Each joint's (rotation, position) for the angles `a`, root at the origin."""
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


# Forward distance of each sole point (heel, ball, toe tip) from the heel on a flat foot.
FLAT_FROM_HEEL = (0.0, 18.0, 24.0)


def lowest_z(a, side):
    """Where the heel of a sole would be (forward, relative to the root) if the
    sole lay flat on the ground under its lowest point."""
    points = sole_points(globals_of(a), side)
    k = min(range(len(points)), key=lambda i: points[i][1])
    return points[k][2] - FLAT_FROM_HEEL[k]


def with_hip(a, side, flexion):
    """The angles `a` with one hip's flexion replaced."""
    b = dict(a)
    b[side + "UpLeg"] = (0.0, -flexion, 0.0)
    return b


def stance_speed():
    """cm/s the root moves so that the stance hip, solved to keep the sole in
    place, reaches its prescribed toe-off flexion at toe-off (bisection)."""
    a = prescribed_angles(TOE_OFF)
    wanted = periodic_spline(HIP_FLEXION, TOE_OFF)
    lo, hi = 30.0, 300.0
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        if solve_hip(a, "Left", TOE_OFF, mid) > wanted:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def solve_hip(a, side, phase, speed):
    """The stance hip flexion that keeps the sole, rolling from heel to toe
    about its lowest point, where it landed while the root moves forward at
    `speed` (bisection)."""
    target = lowest_z(prescribed_angles(0.0), "Left") - speed * phase * CYCLE_S
    lo, hi = -45.0, 60.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if lowest_z(with_hip(a, side, mid), side) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def angles(p, speed):
    """The walk's angles at phase `p`: the prescribed curves, each stance hip
    solved so its planted sole does not slide under a root moving at `speed`."""
    a = prescribed_angles(p)
    for side, phase in (("Left", p % 1.0), ("Right", (p + 0.5) % 1.0)):
        if phase <= TOE_OFF:
            a = with_hip(a, side, solve_hip(a, side, phase, speed))
    return a


def globals_at(p, speed):
    """Each joint's (rotation, position) at phase `p`, root at the origin."""
    return globals_of(angles(p, speed))


def root_height(g):
    """How high the root must be for the lowest sole point to touch y = 0."""
    lowest = min(pt[1] for side in ("Left", "Right") for pt in sole_points(g, side))
    return -lowest


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
        a = angles(p, speed)
        height = root_height(globals_of(a))
        values = [0.0, height, speed * t]
        for name, _, _ in JOINTS:
            values.extend(a[name])
        lines.append(" ".join(f"{v:.4f}" for v in values))
    return lines


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "assets", "clips", "walk.bvh")
    out = sys.argv[1] if len(sys.argv) > 1 else default
    speed = stance_speed()
    text = "\n".join(hierarchy_lines() + motion_lines(speed)) + "\n"
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    tmp = out + ".tmp"
    with open(tmp, "w", encoding="ascii") as f:
        f.write(text)
    os.replace(tmp, out)
    print(
        f"wrote {out}: {CYCLES} cycles of {CYCLE_S} s at {FPS} fps, "
        f"{speed / 100.0:.2f} m/s, stride {speed * CYCLE_S / 100.0:.2f} m"
    )


if __name__ == "__main__":
    main()
