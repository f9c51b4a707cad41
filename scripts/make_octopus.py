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
                   "wires": {"modes": WIRE_MODES, "damping_ratio": WIRE_DAMPING}},
      "clips": [{
          "name": "swim",
          "duration": DURATION,
          "loop": "once",
          "parts": [mantle_track()] + [arm_track(i) for i in range(ARMS)],
      }],
      "camera": {"target": [0.0, 1.5, 0.0], "yaw": 1.2, "pitch": 0.1, "distance": 6.4, "ground": -0.62,
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
