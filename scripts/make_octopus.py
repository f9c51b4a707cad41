#!/usr/bin/env python3
"""Writes samples/octopus/octopus.scene.json: the procedural octopus swimming for 10 s.

The mantle is a rigid body (it is the octopus's head and body: stiff next to its arms) pushed
by jet pulses along its axis (+Y: an octopus jets mantle first) and slowed by the water's drag,
so it travels instead of bobbing in place. Each stroke has two phases:
  * the jet (JET of the PERIOD): the mantle contracts and water leaves the siphon; the arms are
    pulled in together behind the body (towards the axis and down);
  * the refill: the arms flare outwards (their web opening) while the body glides.
The arms' loads are world-axes line loads on three stretches of each arm, the outer stretches
later than the inner ones (a wave running root to tip), each arm a little later than the one
before it around the body (phase-lagged, not in lockstep), and a couple at each arm's tip that
curls it inwards at the peak of the pull (large_deflection: the arms curl past half a turn, as a
co-rotational chain). Partway through, arm 0 reaches for a point in the water the body swims
past (a reach target: wire IK every step), then lets go.

The second clip, "crawl", walks the octopus along the ground plane (across the camera's view)
in a two-group gait: the body settles onto its arms and glides forwards (keyed root motion)
while four arms (every other one around the body) hold their tips on footholds on the ground
(reach targets in world axes: wire IK every step) and the other four let go, swing forwards
under their own line loads (their tips brushing over the ground) and plant on footholds a
stride ahead; then the groups swap. The arms' reach is the small-deflection one (a lateral tip
force, exact sideways): their tips hang nearly straight down, so a foothold's height is out of
reach of a lateral force and the tips ride within a few cm of it (measured by
tests/samples/octopus_crawl_test.cpp).

Usage: scripts/make_octopus.py [OUT]   (default: samples/octopus/octopus.scene.json)
"""
import json
import math
import pathlib
import re
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent

DURATION = 10.0      # s
PERIOD = 1.25        # s per stroke (jet + refill)
JET = 0.4            # fraction of the stroke the jet pushes
JET_PEAK = 90.0      # N, the jet's peak thrust along +Y
DRAG_LINEAR = 30.0   # N s/m
DRAG_QUADRATIC = 60.0  # N s^2/m^2
DRAG_ANGULAR = 5.0   # N m s
ARMS = 8
ARM_LAG = 0.03       # s between neighbouring arms
WAVE_LAG = 0.12      # s between an arm's stretches, root to tip
STRETCHES = [(0.1, 0.4), (0.4, 0.7), (0.7, 1.0)]
PULL_IN = 20.0       # N/m, peak inward (and downward) load during the jet
FLARE = 16.0         # N/m, peak outward load during the refill
CURL = 18.0          # N m, peak tip couple of the pull (about 2.9 rad of curl on a 0.77 m arm)
CURL_LAG = 0.2       # s after the pull's inner stretch
REACH_ARM = 0
# Arm 0 at rest (the procedural rig's numbers: `wirerig rig` prints them): its tip, the tip's
# tangent, its spine's length.
ARM0_TIP = (0.593436, -0.495431, -0.245809)
ARM0_TIP_TANGENT = (0.155572, -0.985723, -0.0644042)
ARM0_LENGTH = 0.766195
# The reach: a point beside the body (riding with the mantle) that moves out and up and back,
# each position the tip of an exact elastica of the arm (reachable by a tip force, F L^2/EI).
REACH_KEYS = [(5.8, 0.0, 1.5), (6.4, 1.0, 1.5), (7.1, 1.0, 3.0), (7.9, 1.0, 2.0), (8.5, 0.0, 2.0)]
ARM_MATERIAL = "cartilage"  # the arms' spines: muscular hydrostats, stiffer than soft tissue
WIRE_MODES = 8       # the arms have inertia: they trail, lag and swing (playback.wires)
WIRE_DAMPING = 0.15
# The mantle's flesh jiggles on each jet pulse (profile wires with inertia): a loop of 1 m
# perimeter swings at MANTLE_FLESH_HZ, smaller ones faster.
MANTLE_FLESH_HZ = 1.5
MANTLE_FLESH_DAMPING = 0.2
KEYS_PER_STROKE = 8  # cubic keys per stroke for the arms' loads
JET_KEYS = 6         # linear keys over each jet pulse


def elastica_tip(alpha, steps=2000):
  """Tip (x, y) / L of a cantilever under a tip force perpendicular to its root, F L^2/EI =
  alpha: theta'' = -alpha cos(theta), theta(0) = 0, theta'(1) = 0, shot on theta'(0) by RK4."""
  def run(k0):
    h, state = 1.0 / steps, (0.0, k0, 0.0, 0.0)
    f = lambda s: (s[1], -alpha * math.cos(s[0]), math.cos(s[0]), math.sin(s[0]))
    for _ in range(steps):
      a = f(state)
      b = f([state[j] + h / 2 * a[j] for j in range(4)])
      c = f([state[j] + h / 2 * b[j] for j in range(4)])
      d = f([state[j] + h * c[j] for j in range(4)])
      state = [state[j] + h / 6 * (a[j] + 2 * b[j] + 2 * c[j] + d[j]) for j in range(4)]
    return state
  lo, hi = 0.0, 1.5 * alpha + 1.0
  for _ in range(60):
    mid = 0.5 * (lo + hi)
    lo, hi = (lo, mid) if run(mid)[1] > 0.0 else (mid, hi)
  state = run(0.5 * (lo + hi))
  return state[2], state[3]


def reach_target(alpha):
  """Arm 0's tip bent outwards (horizontally away from the body) by an elastica of alpha."""
  angle = 2.0 * math.pi * (REACH_ARM + 0.5) / ARMS
  out = (math.cos(angle), 0.0, -math.sin(angle))
  t = ARM0_TIP_TANGENT
  along = sum(out[k] * t[k] for k in range(3))
  e1 = [out[k] - along * t[k] for k in range(3)]
  norm = math.sqrt(sum(c * c for c in e1))
  x, y = elastica_tip(alpha)
  return [round(ARM0_TIP[k] + ARM0_LENGTH * ((x - 1.0) * t[k] + y * e1[k] / norm), 6)
          for k in range(3)]


def jet_thrust(t):
  """The jet's thrust at time t: a sin^2 pulse over the first JET of each stroke."""
  phase = (t % PERIOD) / PERIOD
  if phase >= JET:
    return 0.0
  return JET_PEAK * math.sin(math.pi * phase / JET) ** 2


def arm_drive(t):
  """-1 (pulled in) during the jet, +1 (flared) during the refill, smooth between."""
  phase = (t % PERIOD) / PERIOD
  return -math.cos(2.0 * math.pi * phase)


def key_times():
  count = int(round(DURATION / PERIOD * KEYS_PER_STROKE))
  return [DURATION * k / count for k in range(count + 1)]


def mantle_track():
  # Each stroke's pulse on JET_KEYS + 1 linear keys; zero between pulses.
  fine = []
  strokes = int(round(DURATION / PERIOD))
  for n in range(strokes):
    fine += [n * PERIOD + JET * PERIOD * k / JET_KEYS for k in range(JET_KEYS + 1)]
  fine.append(DURATION)
  return {
      "part": "mantle",
      "rigid_forces": [{
          "at": [0.0, 0.25, 0.0],
          "force": {"keys": [[round(t, 6), [0.0, round(jet_thrust(t), 4), 0.0], "linear"]
                             for t in fine]},
      }],
      "rigid_drag": {"linear": DRAG_LINEAR, "quadratic": DRAG_QUADRATIC,
                     "angular": DRAG_ANGULAR},
  }


def arm_track(i):
  angle = 2.0 * math.pi * (i + 0.5) / ARMS
  out = (math.cos(angle), 0.0, -math.sin(angle))
  loads = []
  for s, (a, b) in enumerate(STRETCHES):
    lag = i * ARM_LAG + s * WAVE_LAG
    keys = []
    for t in key_times():
      d = arm_drive(t - lag)
      radial = FLARE * d if d > 0 else PULL_IN * d
      down = PULL_IN * min(d, 0.0)  # pulled in: also down, behind the body
      force = [round(radial * out[0], 6), round(down, 6), round(radial * out[2], 6)]
      keys.append([round(t, 6), force, "cubic"])
    loads.append({"from": a, "to": b, "axes": "world", "force_per_length": {"keys": keys}})
  couple = []
  for t in key_times():
    pull = max(-arm_drive(t - i * ARM_LAG - CURL_LAG), 0.0) ** 2
    couple.append([round(t, 6), [round(-CURL * pull * out[0], 6), 0.0,
                                 round(-CURL * pull * out[2], 6)], "cubic"])
  track = {"part": f"tentacle_{i}", "boundary": "cantilever_free", "large_deflection": True,
           "line_loads": loads, "tip_couple": {"keys": couple}, "tip_couple_axes": "world"}
  if i == REACH_ARM:
    # The target moves along the elastica tips (every key reachable), F L^2/EI linear in time.
    target_keys = []
    for (t0, _, a0), (t1, _, a1) in zip(REACH_KEYS, REACH_KEYS[1:]):
      steps = max(1, int(round((t1 - t0) / 0.1)))
      target_keys += [[round(t0 + (t1 - t0) * k / steps, 6), reach_target(a0 + (a1 - a0) * k / steps),
                       "linear"] for k in range(steps)]
    target_keys.append([REACH_KEYS[-1][0], reach_target(REACH_KEYS[-1][2]), "linear"])
    track["reach"] = {"parent_frame": True, "target": {"keys": target_keys},
                      "weight": {"keys": [[t, w, "cubic"] for t, w, _ in REACH_KEYS]}}
  return track


# The crawl (clip "crawl"): positions in m, times in s.
CRAWL_DURATION = 10.0
GROUND = -0.62        # the ground plane's height (the scene's camera.ground)
FOOT_LIFT = 0.105     # the arm's spine tip over the ground at a foothold (the skin's tip beyond it)
SETTLE = 1.0          # the body lowers onto its arms (every arm planting) over [0, SETTLE]
DROP = 0.02           # how far the body lowers: its arms' skin then touches the ground
GAIT = 1.25           # s per gait cycle: each group holds for half of it, swings the other half
STRIDE = 0.2          # how far the body moves during half a cycle
SPLAY = 0.04          # a foothold's offset sideways (outwards, across the heading) from the rest tip
CAMERA_YAW = 1.2      # rad: the scene's camera looks along (-sin, 0, -cos) of it
# The crawl's heading: across the camera's view (so the contact sheet shows the path).
HEADING = (math.cos(CAMERA_YAW), 0.0, -math.sin(CAMERA_YAW))
LIFT_OFF = 0.25       # s over which a foot lets go of the ground
SWING_LOAD = 4.0      # N/m along the heading on a free arm: it swings forwards


def crawl_travel(t):
  """The body's travel along HEADING at time t: still while settling, then STRIDE per half
  cycle."""
  return max(t - SETTLE, 0.0) * 2.0 * STRIDE / GAIT


def crawl_body_y(t):
  """The body's height offset: lowered by DROP with a smooth ease over [0, SETTLE]."""
  u = min(t / SETTLE, 1.0)
  return -DROP * u * u * (3.0 - 2.0 * u)


def foothold(i, t):
  """Arm i's foothold on the ground: beside its rest tip's place (outwards in Z) when the body
  is where it is at time t. The arm reaches it by bending sideways (its tip hangs nearly
  straight down: the ground takes up DROP less the rest tips' height over it)."""
  angle = 2.0 * math.pi * (i + 0.5) / ARMS
  radius = math.hypot(ARM0_TIP[0], ARM0_TIP[2])
  tip = (radius * math.cos(angle), -radius * math.sin(angle))
  across = (-HEADING[2], HEADING[0])  # horizontal, perpendicular to the heading (x, z)
  side = SPLAY if tip[0] * across[0] + tip[1] * across[1] > 0.0 else -SPLAY
  travel = crawl_travel(t)
  return [round(tip[0] + travel * HEADING[0] + side * across[0], 6), round(GROUND + FOOT_LIFT, 6),
          round(tip[1] + travel * HEADING[2] + side * across[1], 6)]


def stances(i):
  """Arm i's stance intervals: every arm plants while settling; even arms swing second."""
  half = 0.5 * GAIT
  first = SETTLE + (half if i % 2 == 0 else 0.0)
  out = [(0.0, first)]
  t = first + half
  while t < CRAWL_DURATION:
    out.append((t, min(t + half, CRAWL_DURATION)))
    t += 2.0 * half
  return out


def crawl_arm_track(i):
  weight, target = [], []
  for n, (a, b) in enumerate(stances(i)):
    # The foothold is where the arm's tip lands when the body is at mid-stance's place minus
    # nothing: the body's place at the middle of the stance, so the arm sweeps from ahead to
    # behind of its neutral place.
    mid = 0.5 * (a + b) if n > 0 else SETTLE
    target.append([round(a, 6), foothold(i, mid), "step"])
    if n == 0:
      weight += [[0.0, 0.0, "cubic"], [round(0.8 * SETTLE, 6), 1.0, "linear"]]
    else:
      weight += [[round(a, 6), 1.0, "linear"]]
    if b < CRAWL_DURATION:
      weight += [[round(b, 6), 1.0, "cubic"], [round(b + LIFT_OFF, 6), 0.0, "cubic"]]
  load = [round(SWING_LOAD * HEADING[0], 6), 0.0, round(SWING_LOAD * HEADING[2], 6)]
  return {"part": f"tentacle_{i}", "boundary": "cantilever_free",
          "line_loads": [{"from": 0.3, "to": 1.0, "axes": "world",
                          "force_per_length": {"keys": [[0.0, load, "step"]]}}],
          "reach": {"target": {"keys": target}, "weight": {"keys": weight}}}


def crawl_mantle_track():
  steps = int(round(CRAWL_DURATION / 0.1))
  keys = []
  for k in range(steps + 1):
    t = 0.1 * k
    keys.append([round(t, 6), [round(crawl_travel(t) * HEADING[0], 6), round(crawl_body_y(t), 6),
                               round(crawl_travel(t) * HEADING[2], 6)], "linear"])
  return {"part": "mantle", "translation": {"keys": keys}}


def crawl_clip():
  return {"name": "crawl", "duration": CRAWL_DURATION, "loop": "once",
          "parts": [crawl_mantle_track()] + [crawl_arm_track(i) for i in range(ARMS)]}


def scene():
  return {
      "format": "wirerig.scene",
      "version": 1,
      "name": "octopus",
      "mesh": {"procedural": "octopus"},
      "rig": {"from": "procedural"},
      "skin_thickness": 0.005,
      "default_kind": "deformable",
      "parts": dict([("mantle", {"kind": "rigid"})] +
                    [(f"tentacle_{i}", {"spine": {"material": ARM_MATERIAL}}) for i in range(ARMS)]),
      "playback": {"preserve_volume": True,
                   "wires": {"modes": WIRE_MODES, "damping_ratio": WIRE_DAMPING},
                   "profile_wires": {"modes": 4, "damping_ratio": MANTLE_FLESH_DAMPING,
                                     "frequency": MANTLE_FLESH_HZ, "parts": ["mantle"]}},
      "clips": [{
          "name": "swim",
          "duration": DURATION,
          "loop": "once",
          "parts": [mantle_track()] + [arm_track(i) for i in range(ARMS)],
      }, crawl_clip()],
      "camera": {"target": [0.0, 1.5, 0.0], "yaw": CAMERA_YAW, "pitch": 0.1, "distance": 6.4, "ground": GROUND,
                 "fov": 0.8},
  }


def main():
  out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "samples/octopus/octopus.scene.json"
  text = json.dumps(scene(), indent=1)
  # One key per line: [time, value, "interpolation"] and [x, y, z] arrays collapsed.
  text = re.sub(r"\[\s+([^\[\]{}]*?)\s+\]", lambda m: "[" + " ".join(m.group(1).split()) + "]", text)
  text = re.sub(r"\[\s+([^\[\]{}]*?\[[^\[\]{}]*\][^\[\]{}]*?)\s+\]",
                lambda m: "[" + " ".join(m.group(1).split()) + "]", text)
  out.write_text(text + "\n")
  print(f"written: {out}")


if __name__ == "__main__":
  main()
