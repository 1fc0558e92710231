"""MuJoCo's inverse dynamics of MJCF models, for tests/mjcf.rs.

usage: reference.py OUT.json MODEL.xml...

For each model: its joints (name, or joint{id} when unnamed; type; qpos and dof addresses), the mass of
the bodies that can move, gravity, and for seeded random states (qpos, qvel, qacc) MuJoCo's
qfrc_inverse = M(q)·qacc + bias(q, qvel) − passive(q, qvel), with every constraint (contacts, limits,
equalities, friction loss) disabled. Passive forces (springs, dampers) stay on: the test subtracts ours.
"""

import json
import sys

import mujoco
import numpy as np

TYPES = {0: "free", 1: "ball", 2: "slide", 3: "hinge"}
STATES = 8


def random_qpos(m, rng):
    """A configuration: hinges in (−π, π), slides in (−0.3, 0.3) m, free positions in (−1, 1) m, random
    unit quaternions."""
    q = np.zeros(m.nq)
    for j in range(m.njnt):
        a, t = m.jnt_qposadr[j], m.jnt_type[j]
        if t == 0:
            q[a : a + 3] = rng.uniform(-1, 1, 3)
            a += 3
        if t in (0, 1):
            quat = rng.normal(size=4)
            q[a : a + 4] = quat / np.linalg.norm(quat)
        else:
            q[a] = rng.uniform(-np.pi, np.pi) if t == 3 else rng.uniform(-0.3, 0.3)
    return q


def model_reference(path, rng):
    m = mujoco.MjModel.from_xml_path(path)
    m.opt.disableflags |= (
        mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
        | mujoco.mjtDisableBit.mjDSBL_CONTACT
        | mujoco.mjtDisableBit.mjDSBL_LIMIT
        | mujoco.mjtDisableBit.mjDSBL_EQUALITY
        | mujoco.mjtDisableBit.mjDSBL_FRICTIONLOSS
    )
    d = mujoco.MjData(m)
    joints = [
        {
            "name": m.joint(j).name or f"joint{j}",
            "type": TYPES[int(m.jnt_type[j])],
            "qposadr": int(m.jnt_qposadr[j]),
            "dofadr": int(m.jnt_dofadr[j]),
        }
        for j in range(m.njnt)
    ]
    states = []
    for s in range(STATES):
        # State 0: MuJoCo's rest pose, at rest (gravity and springs only).
        qpos = m.qpos0.copy() if s == 0 else random_qpos(m, rng)
        qvel = np.zeros(m.nv) if s == 0 else rng.normal(size=m.nv)
        qacc = np.zeros(m.nv) if s == 0 else rng.normal(size=m.nv)
        d.qpos[:], d.qvel[:], d.qacc[:] = qpos, qvel, qacc
        mujoco.mj_inverse(m, d)
        states.append(
            {
                "qpos": qpos.tolist(),
                "qvel": qvel.tolist(),
                "qacc": qacc.tolist(),
                "qfrc_inverse": d.qfrc_inverse.tolist(),
                "qfrc_passive": d.qfrc_passive.tolist(),
            }
        )
    moving = [b for b in range(m.nbody) if m.body_weldid[b] != 0]
    return {
        "file": path,
        "mujoco": mujoco.__version__,
        "nq": int(m.nq),
        "nv": int(m.nv),
        "gravity": m.opt.gravity.tolist(),
        "moving_mass": float(sum(m.body_mass[b] for b in moving)),
        "joints": joints,
        "states": states,
    }


def main():
    out, paths = sys.argv[1], sys.argv[2:]
    rng = np.random.default_rng(20011)
    doc = {"models": [model_reference(p, rng) for p in paths]}
    with open(out, "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
