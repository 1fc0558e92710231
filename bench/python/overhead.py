"""The Python binding's overhead, measured side by side in one run (docs/performance.md):

1. one `rnea` call from Python on the 7-DOF sagittal human against Pinocchio's Python binding on the same
   model (the human exported as URDF by `mintorque figure`), and the per-state time of a batched call;
2. a plan through Python (`mintorque.plan`, wall time of the call) against the solve time the Rust library
   measures inside that same call (`solve_seconds`): the difference is what the binding adds (loading the
   task, sampling the motion, building the arrays and the summary).

Run: bash bench/python/run.sh   (makes target/python-venv with the wheel, numpy and Pinocchio's `pin`)
"""

import os
import subprocess
import sys
import tempfile
import timeit

import numpy as np

import mintorque

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def per_call(f, number):
    best = min(timeit.repeat(f, number=number, repeat=7))
    return best / number


def rnea_side_by_side():
    jack = mintorque.Model.human("sagittal", stature=1.83, mass=81.0)
    rng = np.random.default_rng(1)
    q, v, a = (rng.uniform(-1, 1, jack.nv) for _ in range(3))
    ours = per_call(lambda: jack.rnea(q, v, a), 20000)
    qb, vb, ab = (rng.uniform(-1, 1, (1000, jack.nv)) for _ in range(3))
    batched = per_call(lambda: jack.rnea(qb, vb, ab), 50) / 1000
    line = f"rnea, 7-DOF human: mintorque {ours * 1e6:.2f} µs per call, {batched * 1e6:.3f} µs per state batched"
    try:
        import pinocchio as pin
    except ImportError:
        print(line + "; Pinocchio not installed (pip install pin)")
        return
    with tempfile.TemporaryDirectory() as d:
        urdf = os.path.join(d, "jack.urdf")
        exe = os.path.join(ROOT, "target", "release", "mintorque")
        subprocess.run([exe, "figure", "--human", "sagittal", "--stature", "1.83", "--mass", "81", "--out", urdf], check=True, capture_output=True)
        # urdfdom (Pinocchio's parser) demands <limit velocity>, which mintorque's URDF export leaves out
        # (mintorque has no velocity limits): a dummy one, unused by rnea.
        import xml.etree.ElementTree as ET
        root = ET.parse(urdf).getroot()
        for lim in root.iter("limit"):
            lim.attrib.setdefault("velocity", "1e9")
        model = pin.buildModelFromXML(ET.tostring(root, encoding="unicode"))
    assert list(model.names)[1:] == jack.joint_names, list(model.names)
    data = model.createData()
    model.gravity.linear = np.array([0.0, 0.0, -9.81])
    tau_pin = pin.rnea(model, data, q, v, a)
    np.testing.assert_allclose(tau_pin, jack.rnea(q, v, a), rtol=1e-9, atol=1e-9)
    theirs = per_call(lambda: pin.rnea(model, data, q, v, a), 20000)
    print(line + f"; Pinocchio {pin.__version__} {theirs * 1e6:.2f} µs per call: ratio {ours / theirs:.2f}")


def plan_overhead(example, runs=5):
    path = os.path.join(ROOT, "examples", f"{example}.toml")
    mintorque.plan(path)  # warm the caches
    walls, solves = [], []
    for _ in range(runs):
        start = timeit.default_timer()
        r = mintorque.plan(path)
        walls.append(timeit.default_timer() - start)
        solves.append(r.solve_seconds)
    k = int(np.argmin(walls))
    print(f"plan {example}: {walls[k] * 1e3:.1f} ms through Python, of which the Rust solve {solves[k] * 1e3:.1f} ms: "
          f"overhead {100 * (walls[k] / solves[k] - 1):.1f} %")


if __name__ == "__main__":
    rnea_side_by_side()
    for example in sys.argv[1:] or ["arm_lift_earth", "weight_lift_earth", "push_up"]:
        plan_overhead(example)
