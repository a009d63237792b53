#!/usr/bin/env python3
"""truth_error.py SESSION NOMINAL_ROBOT REPORT_JSON: a session calibrated from a
sim world against the world's hidden truth (SESSION/truth/, written by the sim
controller or `hexcal sim-camera`). Prints the mean error of the 42 parameters,
nominal and calibrated, and the held-out RMS before and after; fails unless the
calibration is at least 2 times closer to the truth and 3 times better on the
held-out poses.

The truth is moved into the registered frames, a -> G a, b -> H b with
G = X X*^-1 and H = Y Y*^-1 (core/registration.h, ExpressInFrames), and
compared with the calibrated and the nominal parameters: all 42, robot unit.
"""
import json, os, re, sys
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rigid import apply, comp, inv, pose
s, preset = sys.argv[1], sys.argv[2]
def frames(path):
    text = open(path).read()
    get = lambda key: pose([float(x) for x in re.search(key + r": \[([^\]]*)\]", text).group(1).split(",")])
    return get("base_from_camera"), get("platform_from_target")
def legs(path):
    text = open(path).read().split("limits:")[0]
    out = []
    for m in re.finditer(r"a: \[([^\]]*)\], b: \[([^\]]*)\], l: ([-0-9.e+]+)", text):
        out.append(([float(x) for x in m.group(1).split(",")], [float(x) for x in m.group(2).split(",")], float(m.group(3))))
    assert len(out) == 6, path
    return out
x_true, y_true = frames(s + "/truth/frames.yaml")
x_reg, y_reg = frames(s + "/session.yaml")
g, h = comp(x_reg, inv(x_true)), comp(y_reg, inv(y_true))
truth = [(apply(g, a), apply(h, b), l) for a, b, l in legs(s + "/truth/robot.yaml")]
def flat(robot): return [v for a, b, l in robot for v in a + b + [l]]
t = flat(truth)
def error(robot): return sum(abs(u - v) for u, v in zip(flat(robot), t)) / len(t)
nominal, calibrated = error(legs(preset)), error(legs(s + "/results/calibrated.yaml"))
print("parameter error against the truth in the registered frames, mean of 42: nominal %.5f, calibrated %.5f" % (nominal, calibrated))
assert calibrated * 2 < nominal, (nominal, calibrated)
v = json.load(open(sys.argv[3]))["validation"]
print("held-out position RMS (cm): before %.5f, after %.5f; orientation RMS (deg): before %.4f, after %.4f" %
      (v["before"]["position_rms"], v["after"]["position_rms"], v["before"]["orientation_rms"],
       v["after"]["orientation_rms"]))
assert v["after"]["position_rms"] * 3 < v["before"]["position_rms"], v
