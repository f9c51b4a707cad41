#!/usr/bin/env python3
"""Writes samples/walk/walk.scene.json: human.zae walking for 10 s on its bone chain.

The gait is planned in the sagittal plane (z forward, y up) and keyed as joint angles:
  * the pelvis travels forward at the speed that keeps each stance foot planted
    (stride / stance time), bobs and turns a little;
  * each ankle follows its foot path (planted during stance, lifted on an arc during swing,
    the right leg half a cycle behind the left); hip and knee angles come from two-bone
    inverse kinematics of the thigh and shin lengths of samples/rigs/human.description.json;
  * the foot stays flat while the ankle's limits allow (the heel rises at toe-off);
  * the arms hang by the body and swing against the legs, elbows bent past 60 degrees.
Joint-angle signs follow runtime/joint.h on the description's axes: a positive X angle turns
a leg or an arm backwards (the thigh's, shin's and foot's X axes are all about world +X), so
hip flexion is negative, knee flexion positive, a toes-down ankle positive.

Usage: scripts/make_walk.py [OUT]   (default: samples/walk/walk.scene.json)
"""
import json
import math
import pathlib
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent
DESCRIPTION = REPO / "samples/rigs/human.description.json"

DURATION = 10.0     # s
PERIOD = 1.0        # s per gait cycle (two steps)
STANCE = 0.6        # fraction of the cycle a foot is on the ground
STRIDE = 0.45       # m: how far the foot moves relative to the hip over a stance
LIFT = 0.10         # m: the swing foot's highest lift
HEEL_DOWN = 0.4     # the fraction of the swing over which the toe-off's heel rise goes back down
DROP = 0.025        # m: the pelvis lowered from rest (mean), so the leg reaches without locking
BOB = 0.012         # m: the pelvis's rise and fall, twice per cycle
YAW = 0.05          # rad: the pelvis's turn each way
ARM_SWING = 22.0    # degrees each way
ELBOW = (62.0, 14.0)  # degrees: mean and swing of the elbows' flexion
KEYS_PER_CYCLE = 20
TRACKING_HZ = 8.0       # the joints' PD tracking: natural frequency
TRACKING_DAMPING = 0.7  # and damping ratio (below 1: overshoot, follow-through)
GRAVITY = 9.81          # m/s^2, on the limbs (the pelvis is keyed)
# The flesh of the trunk, thighs, shins and upper arms jiggles on the steps (profile wires with
# inertia): a loop of 1 m perimeter swings at FLESH_HZ, smaller ones faster. Hands, feet, neck
# and head are left out: their loops wrap thin features (fingers, toes) or bone.
FLESH_HZ = 3.0
FLESH_DAMPING = 0.3
FLESH_PARTS = ["pelvis", "spine_1", "spine_2", "chest", "upper_arm_l", "upper_arm_r",
               "thigh_l", "thigh_r", "shin_l", "shin_r"]


def load_parts():
    description = json.loads(DESCRIPTION.read_text())
    return {p["name"]: p for p in description["parts"]}


def sagittal(v):
    """(forward z, up y) of a 3-vector."""
    return v[2], v[1]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def length(v):
    return math.sqrt(sum(x * x for x in v))


def forward_angle(direction):
    """Angle of a downward-pointing direction forward of straight down (rad), sagittal."""
    z, y = sagittal(direction)
    return math.atan2(z, -y)


def leg_geometry(parts, side):
    thigh = parts["thigh_" + side]["central_curve"]
    shin = parts["shin_" + side]["central_curve"]
    foot = parts["foot_" + side]["central_curve"]
    hip, knee, ankle = thigh[0], thigh[-1], shin[-1]
    return {
        "hip": hip,
        "ankle_height": ankle[1],
        "thigh": length(sub(knee, hip)),
        "shin": length(sub(ankle, knee)),
        "thigh_rest": forward_angle(sub(knee, hip)),
        "shin_rest": forward_angle(sub(ankle, knee)),
        # the toe tip from the ankle: (forward, down) m
        "toe": (foot[-1][2] - ankle[2], ankle[1] - foot[-1][1]),
    }


def smooth(s):
    return 0.5 - 0.5 * math.cos(math.pi * s)


def foot_path(phase):
    """Ankle offset from its hip: (forward m, lift m), for phase in [0, 1)."""
    if phase < STANCE:
        return STRIDE / 2 - STRIDE * phase / STANCE, 0.0
    s = (phase - STANCE) / (1.0 - STANCE)
    return -STRIDE / 2 + STRIDE * smooth(s), LIFT * math.sin(math.pi * s)


def pelvis_bob(t):
    return BOB * math.cos(4.0 * math.pi * t / PERIOD)


def two_bone(leg, forward, down):
    """Thigh and shin forward angles (rad) putting the ankle `forward` ahead of and `down` below
    the hip, the knee ahead of the hip-ankle line."""
    d = min(math.hypot(forward, down), leg["thigh"] + leg["shin"] - 1e-4)
    line = math.atan2(forward, down)
    at_hip = math.acos((leg["thigh"] ** 2 + d * d - leg["shin"] ** 2) / (2 * leg["thigh"] * d))
    at_ankle = math.acos((leg["shin"] ** 2 + d * d - leg["thigh"] ** 2) / (2 * leg["shin"] * d))
    return line + at_hip, line - at_ankle


def leg_angles(leg, t, phase):
    """(hip, knee, ankle) X angles in degrees. The foot is kept flat; where the ankle's
    dorsiflexion limit forbids that (late stance), the foot pivots on its toes: the heel rises
    and the ankle with it, so the toes stay on the ground. In the swing the heel comes back
    down smoothly from where toe-off left it (no jump of the knee at the stance's end)."""
    if phase >= STANCE:
        s = (phase - STANCE) / (1.0 - STANCE)
        toe_off = leg_pose(leg, t, -STRIDE / 2, 0.0, None)[3]
        fixed = toe_off * (1.0 - smooth(min(1.0, s / HEEL_DOWN)))
        return leg_pose(leg, t, *foot_path(phase), fixed)[:3]
    return leg_pose(leg, t, *foot_path(phase), None)[:3]


def leg_pose(leg, t, forward, lift, fixed_pitch):
    """(hip, knee, ankle, pitch): the ankle `forward` of its hip and lifted by `lift` with the
    foot pitched toes-down by `fixed_pitch` (rad), or, when that is None, by what planting it
    on its toes takes (found by iteration from a flat foot)."""
    hip_height = leg["hip"][1] - DROP + pelvis_bob(t)
    toe_forward, toe_down = leg["toe"]
    pitch = 0.0 if fixed_pitch is None else fixed_pitch  # rad, toes down
    for _ in range(8 if fixed_pitch is None else 1):
        # The ankle where the toes stay where a flat foot would put them.
        ankle_forward = forward + toe_forward - (toe_forward * math.cos(pitch) - toe_down * math.sin(pitch))
        ankle_lift = lift - toe_down + (toe_forward * math.sin(pitch) + toe_down * math.cos(pitch))
        down = hip_height - (leg["ankle_height"] + ankle_lift)
        thigh, shin = two_bone(leg, ankle_forward, down)
        hip_x = -math.degrees(thigh - leg["thigh_rest"])
        knee_x = math.degrees((thigh - shin) - (leg["thigh_rest"] - leg["shin_rest"]))
        ankle_x = min(max(-(hip_x + knee_x) + math.degrees(pitch), -20.0), 45.0)
        if fixed_pitch is None:
            pitch = max(0.0, math.radians(hip_x + knee_x + ankle_x))
    return hip_x, knee_x, ankle_x, pitch


def key(t, value):
    return [round(t, 4), [round(v, 3) for v in value], "cubic"]


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "samples/walk/walk.scene.json"
    parts = load_parts()
    legs = {side: leg_geometry(parts, side) for side in ("l", "r")}
    speed = STRIDE / (STANCE * PERIOD)
    times = [i * PERIOD / KEYS_PER_CYCLE for i in range(int(DURATION / PERIOD * KEYS_PER_CYCLE) + 1)]
    tracks = {name: [] for name in ("pelvis_rotation", "pelvis_translation", "spine_2", "chest",
                                    "thigh_l", "shin_l", "foot_l", "thigh_r", "shin_r", "foot_r",
                                    "upper_arm_l", "forearm_l", "upper_arm_r", "forearm_r")}
    for t in times:
        cycle = t / PERIOD
        swing = math.sin(2.0 * math.pi * cycle)  # +: the left leg forward
        tracks["pelvis_translation"].append(key(t, [0.0, -DROP + pelvis_bob(t), speed * t]))
        tracks["pelvis_rotation"].append(key(t, [0.0, YAW * swing, 0.0]))
        tracks["spine_2"].append(key(t, [3.0, 0.0, -3.0 * swing]))
        tracks["chest"].append(key(t, [2.0, 0.0, -3.0 * swing]))
        for side, offset in (("l", 0.0), ("r", 0.5)):
            # t = 0: mid-stance on the left; rounded so a key on the stance's end is the same
            # phase in every cycle
            phase = round((cycle + offset + STANCE / 2) % 1.0, 9) % 1.0
            hip, knee, ankle = leg_angles(legs[side], t, phase)
            tracks["thigh_" + side].append(key(t, [hip, 0.0, 0.0]))
            tracks["shin_" + side].append(key(t, [knee, 0.0, 0.0]))
            tracks["foot_" + side].append(key(t, [ankle, 0.0, 0.0]))
        # Arms against the legs: the left arm forward (negative X) with the right leg.
        for side, sign, adduct in (("l", 1.0, -30.0), ("r", -1.0, 30.0)):
            arm = sign * ARM_SWING * swing
            tracks["upper_arm_" + side].append(key(t, [arm, adduct, 0.0]))
            elbow = ELBOW[0] - sign * ELBOW[1] * swing
            tracks["forearm_" + side].append(key(t, [elbow, 0.0, 0.0]))

    def joint(part, name=None):
        return {"part": part, "joint_angles": {"keys": tracks[name or part]}}

    scene = {
        "format": "wirerig.scene",
        "version": 1,
        "name": "walk",
        "mesh": {"file": "../../.cache/assets/assimp/Collada/human.zae"},
        "rig": {"description": "../rigs/human.description.json"},
        "default_kind": "rigid",
        # The keyed poses are targets: the chain's rigid-body dynamics tracks them (PD at
        # TRACKING_HZ, damping ratio TRACKING_DAMPING) under the pelvis's own accelerations, so
        # the limbs lag and follow through, and hang under gravity (the pelvis follows its
        # keys: the model has no ground contact to carry the body's weight).
        "playback": {"tracking": {"frequency": TRACKING_HZ, "damping_ratio": TRACKING_DAMPING,
                                  "gravity": [0.0, -GRAVITY, 0.0]},
                     "profile_wires": {"modes": 4, "damping_ratio": FLESH_DAMPING,
                                       "frequency": FLESH_HZ, "parts": FLESH_PARTS}},
        "camera": {"target": [0.0, 0.85, 0.0], "yaw": 1.2, "pitch": 0.12, "distance": 3.2,
                   "fov": 0.7, "follow": "pelvis"},
        "clips": [{
            "name": "walk",
            "duration": DURATION,
            "loop": "once",
            "parts": [
                {"part": "pelvis", "rotation": {"keys": tracks["pelvis_rotation"]},
                 "translation": {"keys": tracks["pelvis_translation"]}},
                joint("spine_2"), joint("chest"),
                joint("thigh_l"), joint("shin_l"), joint("foot_l"),
                joint("thigh_r"), joint("shin_r"), joint("foot_r"),
                joint("upper_arm_l"), joint("forearm_l"), joint("upper_arm_r"), joint("forearm_r"),
            ],
        }],
    }
    out.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(scene, indent=1)
    out.write_text(text + "\n")
    print(f"written: {out} (speed {speed:.3f} m/s, {len(times)} keys per track)")


if __name__ == "__main__":
    main()
