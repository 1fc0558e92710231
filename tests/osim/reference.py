#!/usr/bin/env python3
"""OpenSim's inverse dynamics of .osim models, for tests/osim.rs (OpenSim 4.6 from PyPI: scripts/opensim-venv.sh).

  reference.py build DIR        writes the test models (built with the OpenSim API) into DIR
  reference.py reference FILE…  for each model file, OpenSim's generalized forces at seeded random states,
                                as JSON on stdout
  reference.py mot MODEL MOT    OpenSim's reading of a motion on a model: the columns that are no coordinate,
                                and the first and last rows in SI (degrees converted by the coordinates' types)

States are given as coordinate values q (rad or m), their rates q' and second derivatives q'' (the
coordinates' own time derivatives). OpenSim's ball and free joints use angular velocities as speeds u, so
u = N^-1 q', u' = N^-1 (q'' - N' u) (N' u by central differences of N along q'), and the forces conjugate to
q' are tau_q = N^-T tau_u. Gravity is the model's.
"""
import json
import math
import os
import sys

import numpy as np
import opensim as osim

osim.Logger.setLevelString("error")  # stdout carries the JSON only
osim.Logger.removeFileSink()  # and no opensim.log is left behind

STATES = 6


def v3(*x):
    return osim.Vec3(*x)


def add_body(m, name, mass, com, moments, products):
    b = osim.Body(name, mass, v3(*com), osim.Inertia(v3(*moments), v3(*products)))
    m.addBody(b)
    return b


def axis(st, k, coordinate, direction, function):
    """Sets TransformAxis k (0-2 rotations, 3-5 translations) of a SpatialTransform."""
    ta = st.updTransformAxis(k)
    names = osim.ArrayStr()
    if coordinate:
        names.append(coordinate)
    ta.setCoordinateNames(names)
    ta.setAxis(v3(*direction))
    ta.set_function(function)


def spline(xs, f):
    s = osim.SimmSpline()
    for x in xs:
        s.addPoint(x, f(x))
    return s


def set_range(m, name, lo, hi):
    c = m.updCoordinateSet().get(name)
    c.setRangeMin(lo)
    c.setRangeMax(hi)


def skeleton():
    """Every joint type, uncoupled: Free root, Ball, Pin, Universal, Slider, Gimbal, Planar, Weld, Custom."""
    m = osim.Model()
    m.setName("skeleton")
    m.setGravity(v3(0, -9.80665, 0))
    g = m.getGround()
    pelvis = add_body(m, "pelvis", 11.0, (-0.07, 0.01, 0.0), (0.10, 0.09, 0.06), (0.004, -0.003, 0.002))
    torso = add_body(m, "torso", 26.0, (-0.03, 0.32, 0.0), (1.4, 0.7, 1.3), (0.01, 0.0, -0.02))
    head = add_body(m, "head", 5.0, (0.02, 0.1, 0.0), (0.03, 0.02, 0.03), (0.0, 0.0, 0.0))
    humerus = add_body(m, "humerus_r", 2.0, (0.0, -0.16, 0.0), (0.013, 0.004, 0.014), (0.0, 0.0, 0.0))
    ulna = add_body(m, "ulna_r", 1.2, (0.12, 0.0, 0.01), (0.001, 0.006, 0.006), (0.0002, 0.0, 0.0))
    hand = add_body(m, "hand_r", 0.45, (0.0, -0.07, 0.0), (0.0009, 0.0005, 0.0012), (0.0, 0.0, 0.0))
    femur_r = add_body(m, "femur_r", 9.0, (0.0, -0.17, 0.0), (0.13, 0.03, 0.14), (0.0, 0.0, 0.0))
    tibia_r = add_body(m, "tibia_r", 3.6, (0.0, -0.18, 0.0), (0.05, 0.005, 0.05), (0.0, 0.0, 0.0))
    foot_r = add_body(m, "calcn_r", 1.2, (0.09, 0.03, 0.0), (0.0013, 0.0036, 0.0038), (0.0, 0.0, 0.0))
    femur_l = add_body(m, "femur_l", 9.0, (0.0, -0.17, 0.0), (0.13, 0.03, 0.14), (0.0, 0.0, 0.0))
    tibia_l = add_body(m, "tibia_l", 3.6, (0.0, -0.18, 0.0), (0.05, 0.005, 0.05), (0.0, 0.0, 0.0))
    foot_l = add_body(m, "calcn_l", 1.2, (0.09, 0.03, 0.0), (0.0013, 0.0036, 0.0038), (0.0, 0.0, 0.0))
    J = []
    J.append(osim.FreeJoint("ground_pelvis", g, v3(0, 0.95, 0), v3(0, 0, 0), pelvis, v3(0, 0, 0), v3(0, 0, 0)))
    J.append(osim.BallJoint("back", pelvis, v3(-0.1, 0.08, 0), v3(0.1, -0.2, 0.3), torso, v3(0.03, -0.02, 0.01), v3(0, 0, 0.1)))
    J.append(osim.PinJoint("neck", torso, v3(0, 0.45, 0), v3(0, 0, 0.2), head, v3(0, 0, 0), v3(0, 0, 0)))
    J.append(osim.UniversalJoint("shoulder_r", torso, v3(0, 0.4, 0.17), v3(0.3, 0, 0), humerus, v3(0, 0, 0), v3(0, 0, 0)))
    J.append(osim.SliderJoint("elbow_r", humerus, v3(0, -0.3, 0), v3(0, 0, -1.4), ulna, v3(0, 0, 0), v3(0, 0, 0)))
    J.append(osim.GimbalJoint("wrist_r", ulna, v3(0.25, 0, 0), v3(0, 0, 1.5), hand, v3(0, 0.01, 0), v3(0.2, 0, 0)))
    st = osim.SpatialTransform()
    axis(st, 0, "hip_flexion_r", (0, 0, 1), osim.LinearFunction(1, 0))
    axis(st, 1, "hip_adduction_r", (1, 0, 0), osim.LinearFunction(1, 0))
    axis(st, 2, "hip_rotation_r", (0, 1, 0), osim.LinearFunction(1, 0))
    axis(st, 3, None, (1, 0, 0), osim.Constant(0.01))
    axis(st, 4, None, (0, 1, 0), osim.Constant(0))
    axis(st, 5, None, (0, 0, 1), osim.Constant(-0.005))
    J.append(osim.CustomJoint("hip_r", pelvis, v3(-0.07, -0.07, 0.08), v3(0, 0, 0), femur_r, v3(0, 0, 0), v3(0, 0, 0), st))
    J.append(osim.PinJoint("knee_r", femur_r, v3(0, -0.4, 0), v3(0, 0, 0), tibia_r, v3(0, 0, 0), v3(0, 0, 0)))
    J.append(osim.PlanarJoint("ankle_r", tibia_r, v3(0, -0.43, 0), v3(0, 0.1, 0), foot_r, v3(0, 0, 0), v3(0, 0, 0)))
    st = osim.SpatialTransform()
    axis(st, 0, "hip_flexion_l", (0, 0, 1), osim.LinearFunction(1, 0))
    n = math.sqrt(0.1**2 + 0.9**2 + 0.2**2)
    axis(st, 1, "hip_rotation_l", (0.1 / n, 0.9 / n, 0.2 / n), osim.LinearFunction(1, 0))
    # A constant last rotation (one before a moving rotation: see constant_rotation()).
    axis(st, 2, None, (1, 0, 0), osim.Constant(0.2))
    axis(st, 3, None, (1, 0, 0), osim.Constant(0))
    axis(st, 4, None, (0, 1, 0), osim.Constant(0))
    axis(st, 5, None, (0, 0, 1), osim.Constant(0))
    J.append(osim.CustomJoint("hip_l", pelvis, v3(-0.07, -0.07, -0.08), v3(0, 0.1, 0), femur_l, v3(0, 0, 0), v3(0, 0, 0), st))
    J.append(osim.PinJoint("knee_l", femur_l, v3(0, -0.4, 0), v3(0, 0, 0), tibia_l, v3(0, 0, 0), v3(0, 0, 0)))
    J.append(osim.WeldJoint("ankle_l", tibia_l, v3(0, -0.43, 0), v3(0, 0, 0), foot_l, v3(0, 0, 0), v3(0, 0, 0)))
    for j in J:
        m.addJoint(j)
    m.addMarker(osim.Marker("R.ASIS", pelvis, v3(0.01, 0.0, 0.12)))
    m.addMarker(osim.Marker("R.HEEL", foot_r, v3(-0.01, 0.01, 0.0)))
    m.finalizeConnections()
    return m


def coupled_legs():
    """A gait-style pelvis and two legs whose knees translate with flexion (SimmSpline, MultiplierFunction), an
    ankle coupled through a polynomial and a linear function, a knee driven through a sign flip."""
    m = osim.Model()
    m.setName("coupled_legs")
    m.setGravity(v3(0, -9.80665, 0))
    g = m.getGround()
    pelvis = add_body(m, "pelvis", 11.0, (-0.07, 0.0, 0.0), (0.10, 0.09, 0.06), (0.0, 0.0, 0.0))
    torso = add_body(m, "torso", 26.0, (-0.03, 0.32, 0.0), (1.4, 0.7, 1.3), (0.0, 0.0, 0.0))
    legs = {}
    for side in "rl":
        legs[side] = (
            add_body(m, f"femur_{side}", 9.0, (0.0, -0.17, 0.0), (0.13, 0.03, 0.14), (0.0, 0.0, 0.0)),
            add_body(m, f"tibia_{side}", 3.6, (0.0, -0.18, 0.0), (0.05, 0.005, 0.05), (0.0, 0.0, 0.0)),
            add_body(m, f"calcn_{side}", 1.2, (0.09, 0.03, 0.0), (0.0013, 0.0036, 0.0038), (0.0, 0.0, 0.0)),
        )
    st = osim.SpatialTransform()
    axis(st, 0, "pelvis_tilt", (0, 0, 1), osim.LinearFunction(1, 0))
    axis(st, 1, "pelvis_list", (1, 0, 0), osim.LinearFunction(1, 0))
    axis(st, 2, "pelvis_rotation", (0, 1, 0), osim.LinearFunction(1, 0))
    axis(st, 3, "pelvis_tx", (1, 0, 0), osim.LinearFunction(1, 0))
    axis(st, 4, "pelvis_ty", (0, 1, 0), osim.LinearFunction(1, 0))
    axis(st, 5, "pelvis_tz", (0, 0, 1), osim.LinearFunction(1, 0))
    joints = [osim.CustomJoint("ground_pelvis", g, v3(0, 0, 0), v3(0, 0, 0), pelvis, v3(0, 0, 0), v3(0, 0, 0), st)]
    joints.append(osim.GimbalJoint("back", pelvis, v3(-0.1, 0.08, 0), v3(0, 0, 0), torso, v3(0, 0, 0), v3(0, 0, 0)))
    knee_x = [-2.0944, -1.7453, -1.3963, -1.0472, -0.6981, -0.3491, -0.1745, 0.0, 0.1745]
    for side, sign in (("r", 1.0), ("l", -1.0)):
        femur, tibia, calcn = legs[side]
        joints.append(osim.BallJoint(f"hip_{side}", pelvis, v3(-0.07, -0.07, 0.08 * sign), v3(0, 0, 0), femur, v3(0, 0, 0), v3(0, 0, 0)))
        st = osim.SpatialTransform()
        # r: the coordinate itself; l: through a sign flip (coupled).
        axis(st, 0, f"knee_angle_{side}", (0, 0, 1), osim.LinearFunction(1.0 if side == "r" else -1.0, 0))
        axis(st, 1, None, (1, 0, 0), osim.Constant(0))
        axis(st, 2, None, (0, 1, 0), osim.Constant(0))
        axis(st, 3, f"knee_angle_{side}", (1, 0, 0), spline(knee_x, lambda q: 0.004 * math.sin(1.7 * q) - 0.002 * q * q))
        inner = spline(knee_x, lambda q: -0.395 + 0.006 * math.cos(1.3 * q) + 0.001 * q)
        # The MultiplierFunction takes ownership of its function: Python must not delete it too.
        inner.thisown = False
        axis(st, 4, f"knee_angle_{side}", (0, 1, 0), osim.MultiplierFunction(inner, 1.03))
        axis(st, 5, None, (0, 0, 1), osim.Constant(0))
        joints.append(osim.CustomJoint(f"knee_{side}", femur, v3(0, 0, 0), v3(0, 0, 0), tibia, v3(0, 0, 0), v3(0, 0, 0), st))
        st = osim.SpatialTransform()
        axis(st, 0, f"ankle_angle_{side}", (0.1, -0.17, 0.98), osim.LinearFunction(1, 0))
        axis(st, 1, f"ankle_angle_{side}", (1, 0, 0), osim.PolynomialFunction(osim.Vector([0.3, -0.2, 0.4, 0.05])))
        axis(st, 2, None, (0, 1, 0), osim.Constant(0))
        axis(st, 3, f"ankle_angle_{side}", (1, 0, 0), osim.LinearFunction(0.02, 0.01))
        axis(st, 4, None, (0, 1, 0), osim.Constant(0))
        axis(st, 5, None, (0, 0, 1), osim.Constant(0))
        joints.append(osim.CustomJoint(f"ankle_{side}", tibia, v3(0, -0.43, 0), v3(0, 0, 0), calcn, v3(0.01, 0.02, 0), v3(0, 0, 0.05), st))
    for j in joints:
        m.addJoint(j)
    m.addForce(osim.CoordinateActuator("knee_angle_r"))
    m.addContactGeometry(osim.ContactSphere(0.03, v3(0.1, -0.02, 0), legs["r"][2], "heel_r"))
    m.finalizeConnections()
    set_range(m, "knee_angle_r", -2.0, 0.1)
    set_range(m, "knee_angle_l", -2.0, 0.1)
    set_range(m, "pelvis_tx", -1.0, 1.0)
    set_range(m, "pelvis_ty", 0.0, 1.2)
    return m


def constant_rotation():
    """A CustomJoint with a constant rotation before a moving one: Simbody's FunctionBased mobilizer leaves the
    constant out of its velocity map H (buildH evaluates only functions with coordinates), so OpenSim's
    velocities there are not the derivatives of its positions."""
    m = osim.Model()
    m.setName("constant_rotation")
    m.setGravity(v3(0, -9.80665, 0))
    link1 = add_body(m, "link1", 2.0, (0.1, -0.2, 0.05), (0.03, 0.01, 0.02), (0.0, 0.0, 0.0))
    link2 = add_body(m, "link2", 1.0, (0.0, -0.15, 0.0), (0.01, 0.002, 0.01), (0.0, 0.0, 0.0))
    st = osim.SpatialTransform()
    axis(st, 0, "a", (0, 0, 1), osim.LinearFunction(1, 0))
    axis(st, 1, None, (1, 0, 0), osim.Constant(0.6))
    axis(st, 2, "b", (0, 1, 0), osim.LinearFunction(1, 0))
    axis(st, 3, None, (1, 0, 0), osim.Constant(0))
    axis(st, 4, None, (0, 1, 0), osim.Constant(0))
    axis(st, 5, None, (0, 0, 1), osim.Constant(0))
    m.addJoint(osim.CustomJoint("j1", m.getGround(), v3(0, 1, 0), v3(0, 0, 0), link1, v3(0, 0, 0), v3(0, 0, 0), st))
    m.addJoint(osim.PinJoint("j2", link1, v3(0, -0.4, 0), v3(0, 0, 0), link2, v3(0, 0, 0), v3(0, 0, 0)))
    m.finalizeConnections()
    return m


def multi_rotation():
    """One coordinate driving all three rotations of a CustomJoint (rotation1 itself, rotation2 and rotation3
    through splines, like a walker knee): Simbody's FunctionBased buildHdot takes the angular velocity "after
    the first rotation" as that of the first mobility, which here carries all three, so OpenSim's
    velocity-product terms are off (its velocities are right)."""
    m = osim.Model()
    m.setName("multi_rotation")
    m.setGravity(v3(0, -9.80665, 0))
    thigh = add_body(m, "thigh", 8.0, (0.0, -0.2, 0.0), (0.12, 0.03, 0.12), (0.0, 0.0, 0.0))
    shank = add_body(m, "shank", 3.5, (0.02, -0.2, 0.01), (0.05, 0.006, 0.05), (0.0, 0.0, 0.0))
    m.addJoint(osim.PinJoint("hip", m.getGround(), v3(0, 1, 0), v3(0, 0, 0), thigh, v3(0, 0, 0), v3(0, 0, 0)))
    xs = [-2.0 + 0.25 * k for k in range(11)]
    st = osim.SpatialTransform()
    axis(st, 0, "knee", (0, 0, 1), osim.LinearFunction(1, 0))
    axis(st, 1, "knee", (1, 0, 0), spline(xs, lambda q: 0.3 * math.sin(q)))
    axis(st, 2, "knee", (0, 1, 0), spline(xs, lambda q: 0.25 * q + 0.05 * q * q))
    axis(st, 3, "knee", (1, 0, 0), spline(xs, lambda q: 0.01 * q))
    axis(st, 4, None, (0, 1, 0), osim.Constant(-0.4))
    axis(st, 5, None, (0, 0, 1), osim.Constant(0))
    m.addJoint(osim.CustomJoint("knee", thigh, v3(0, 0, 0), v3(0, 0, 0), shank, v3(0, 0, 0), v3(0, 0, 0), st))
    m.finalizeConnections()
    set_range(m, "knee", -1.9, 0.4)
    return m


def rotations(st, names, axes):
    """A SpatialTransform's three rotations: coordinate `names[k]` (None: a constant 0) about `axes[k]`."""
    for k, (name, direction) in enumerate(zip(names, axes)):
        axis(st, k, name, direction, osim.LinearFunction(1, 0) if name else osim.Constant(0))


def custom(name, parent, loc_p, rot_p, child, loc_c, rot_c, names, axes, translations=None):
    """A CustomJoint turning about `axes` by `names` and translating by `translations` (three functions of
    coordinates, each (coordinate, function); None: no translation)."""
    st = osim.SpatialTransform()
    rotations(st, names, axes)
    for k, tr in enumerate(translations or [None, None, None]):
        if tr is None:
            axis(st, 3 + k, None, [(1, 0, 0), (0, 1, 0), (0, 0, 1)][k], osim.Constant(0))
        else:
            axis(st, 3 + k, tr[0], [(1, 0, 0), (0, 1, 0), (0, 0, 1)][k], tr[1])
    return osim.CustomJoint(name, parent, v3(*loc_p), v3(*rot_p), child, v3(*loc_c), v3(*rot_c), st)


def unit(*x):
    n = math.sqrt(sum(c * c for c in x))
    return tuple(c / n for c in x)


def whole_body():
    """A gait-style whole body with arms, structurally unlike coupled_legs: a CustomJoint pelvis turning
    rotation-list-tilt (y, x, z), a three-axis lumbar CustomJoint, CustomJoint hips with the left side's axes
    reversed, knees whose x and y translations follow flexion by SimmSplines (no multiplier), ankles and
    subtalar joints on their own oblique axes (a CustomJoint axis; a PinJoint in turned offset frames), toes,
    three-axis shoulders, elbows and forearm rotations on oblique axes, two-axis wrists: 37 coordinates."""
    m = osim.Model()
    m.setName("whole_body")
    m.setGravity(v3(0, -9.80665, 0))
    g = m.getGround()
    pelvis = add_body(m, "pelvis", 10.5, (-0.068, 0.0, 0.0), (0.093, 0.079, 0.052), (0.0, 0.0, 0.0))
    torso = add_body(m, "torso", 30.0, (-0.03, 0.31, 0.0), (1.47, 0.75, 1.43), (0.02, 0.0, 0.0))
    yz = ((0, 1, 0), (1, 0, 0), (0, 0, 1))
    joints = [
        custom("ground_pelvis", g, (0, 0, 0), (0, 0, 0), pelvis, (0, 0, 0), (0, 0, 0), ["pelvis_rotation", "pelvis_list", "pelvis_tilt"], yz,
               [("pelvis_tx", osim.LinearFunction(1, 0)), ("pelvis_ty", osim.LinearFunction(1, 0)), ("pelvis_tz", osim.LinearFunction(1, 0))]),
        custom("back", pelvis, (-0.1007, 0.0815, 0), (0, 0, 0), torso, (0, 0, 0), (0, 0, 0), ["lumbar_extension", "lumbar_bending", "lumbar_rotation"],
               ((0, 0, 1), (1, 0, 0), (0, 1, 0))),
    ]
    # Knee translations (m) as functions of flexion (rad), sampled unevenly as gait models do.
    knee_x = [-2.0944, -1.5708, -1.0472, -0.6981, -0.3491, -0.1745, 0.0, 0.1745, 0.35]
    knee_tx = spline(knee_x, lambda q: 0.0035 * math.sin(2.1 * q + 0.4) - 0.0015 * q)
    knee_ty = spline(knee_x, lambda q: -0.396 - 0.006 * q * (q + 0.5) + 0.0008 * q**3)
    for side, s in (("r", 1.0), ("l", -1.0)):
        femur = add_body(m, f"femur_{side}", 8.4, (0.0, -0.17, 0.0), (0.112, 0.029, 0.118), (0.0, 0.0, 0.0))
        tibia = add_body(m, f"tibia_{side}", 3.3, (0.0, -0.187, 0.0), (0.045, 0.0046, 0.046), (0.0, 0.0, 0.0))
        talus = add_body(m, f"talus_{side}", 0.09, (0.0, 0.0, 0.0), (0.001, 0.001, 0.001), (0.0, 0.0, 0.0))
        calcn = add_body(m, f"calcn_{side}", 1.1, (0.1, 0.03, 0.0), (0.0014, 0.0039, 0.0041), (0.0, 0.0, 0.0))
        toes = add_body(m, f"toes_{side}", 0.19, (0.035, 0.006, -0.018 * s), (0.0001, 0.0002, 0.0001), (0.0, 0.0, 0.0))
        humerus = add_body(m, f"humerus_{side}", 2.0, (0.0, -0.164, 0.0), (0.0141, 0.0046, 0.0158), (0.0, 0.0, 0.0))
        ulna = add_body(m, f"ulna_{side}", 0.61, (0.0, -0.12, 0.0), (0.0030, 0.0006, 0.0032), (0.0, 0.0, 0.0))
        radius = add_body(m, f"radius_{side}", 0.61, (0.0, -0.12, 0.0), (0.0030, 0.0006, 0.0032), (0.0, 0.0, 0.0))
        hand = add_body(m, f"hand_{side}", 0.46, (0.0, -0.068, 0.0), (0.0009, 0.0005, 0.0013), (0.0, 0.0, 0.0))
        # Mirrored: the left side's adduction and rotation axes reversed.
        joints.append(custom(f"hip_{side}", pelvis, (-0.0707, -0.0661, 0.0835 * s), (0, 0, 0), femur, (0, 0, 0), (0, 0, 0),
                             [f"hip_flexion_{side}", f"hip_adduction_{side}", f"hip_rotation_{side}"], ((0, 0, 1), (s, 0, 0), (0, s, 0))))
        joints.append(custom(f"knee_{side}", femur, (0, 0, 0), (0, 0, 0), tibia, (0, 0, 0), (0, 0, 0), [f"knee_angle_{side}", None, None],
                             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), [(f"knee_angle_{side}", osim.SimmSpline(knee_tx)), (f"knee_angle_{side}", osim.SimmSpline(knee_ty)), None]))
        joints.append(custom(f"ankle_{side}", tibia, (0, -0.43, 0), (0, 0, 0), talus, (0, 0, 0), (0, 0, 0), [f"ankle_angle_{side}", None, None],
                             (unit(-0.105 * s, -0.174 * s, 0.979), (1, 0, 0), (0, 1, 0))))
        # The subtalar axis as a PinJoint's z in turned frames (body-fixed XYZ angles, rad).
        joints.append(osim.PinJoint(f"subtalar_{side}", talus, v3(-0.0488, -0.0419, 0.0079 * s), v3(-1.768 * s, 0.906 * s, 1.819), calcn,
                                    v3(0.0, 0.0, 0.0), v3(-1.768 * s, 0.906 * s, 1.819)))
        joints.append(osim.PinJoint(f"mtp_{side}", calcn, v3(0.179, -0.002, 0.001 * s), v3(0, -0.5 * s, 0), toes, v3(0, 0, 0), v3(0, -0.5 * s, 0)))
        joints.append(custom(f"acromial_{side}", torso, (0.003, 0.372, 0.17 * s), (0, 0, 0), humerus, (0, 0, 0), (0, 0, 0),
                             [f"arm_flex_{side}", f"arm_add_{side}", f"arm_rot_{side}"], ((0, 0, 1), (s, 0, 0), (0, s, 0))))
        joints.append(custom(f"elbow_{side}", humerus, (0.013, -0.286, -0.0096 * s), (0, 0, 0), ulna, (0, 0, 0), (0, 0, 0), [f"elbow_flex_{side}", None, None],
                             (unit(0.049 * s, 0.036 * s, 0.998), (1, 0, 0), (0, 1, 0))))
        joints.append(custom(f"radioulnar_{side}", ulna, (-0.007, -0.013, 0.026 * s), (0, 0, 0), radius, (0, 0, 0), (0, 0, 0), [f"pro_sup_{side}", None, None],
                             (unit(-0.017 * s, 0.992 * s, -0.123), (1, 0, 0), (0, 0, 1))))
        joints.append(custom(f"radius_hand_{side}", radius, (-0.009, -0.235, 0.013 * s), (0, 0, 0), hand, (0, 0, 0), (0, 0, 0), [f"wrist_flex_{side}", f"wrist_dev_{side}", None],
                             ((0, 0, 1), (s, 0, 0), (0, 1, 0))))
    for j in joints:
        if j.getConcreteClassName() == "PinJoint":
            j.upd_coordinates(0).setName(j.getName().replace("_r", "_angle_r").replace("_l", "_angle_l"))
        m.addJoint(j)
    m.finalizeConnections()
    for side in "rl":
        set_range(m, f"knee_angle_{side}", -2.0944, 0.35)
    set_range(m, "pelvis_tx", -1.0, 1.0)
    set_range(m, "pelvis_ty", 0.0, 1.2)
    return m


def build(out):
    os.makedirs(out, exist_ok=True)
    models = (("skeleton.osim", skeleton), ("coupled_legs.osim", coupled_legs), ("constant_rotation.osim", constant_rotation), ("multi_rotation.osim", multi_rotation),
              ("whole_body.osim", whole_body))
    for name, make in models:
        m = make()
        m.initSystem()
        m.printToXML(os.path.join(out, name))


def index_maps(m, s, coords):
    """Each coordinate's index in Simbody's q and u."""
    nq, nu = s.getNQ(), s.getNU()
    qi, ui = [], []
    for c in coords:
        s.setQ(osim.Vector(nq, 0.0))
        c.setValue(s, 0.5, False)
        qi.append([i for i in range(nq) if s.getQ()[i] != 0.0][0])
        s.setU(osim.Vector(nu, 0.0))
        c.setSpeedValue(s, 0.5)
        ui.append([i for i in range(nu) if s.getU()[i] != 0.0][0])
    return qi, ui


def vec(x):
    v = osim.Vector(len(x), 0.0)
    for i, xi in enumerate(x):
        v[i] = float(xi)
    return v


def arr(v):
    return np.array([v[i] for i in range(v.size())])


def n_times(m, matter, s, q, u, transpose=False, inverse=False):
    """N u (or N^-1 x, N^-T x) at configuration q."""
    s.setQ(vec(q))
    m.realizePosition(s)
    out = osim.Vector(len(q), 0.0)
    (matter.multiplyByNInv if inverse else matter.multiplyByN)(s, transpose, vec(u), out)
    return arr(out)


def state_forces(m, s, matter, solver, q, qd, qdd):
    """OpenSim's generalized forces conjugate to q' (Simbody q order)."""
    u = n_times(m, matter, s, q, qd, inverse=True)
    h = 1e-6
    ndot_u = (n_times(m, matter, s, q + h * qd, u) - n_times(m, matter, s, q - h * qd, u)) / (2 * h)
    udot = n_times(m, matter, s, q, qdd - ndot_u, inverse=True)
    s.setQ(vec(q))
    s.setU(vec(u))
    m.realizeDynamics(s)
    tau_u = arr(solver.solve(s, vec(udot)))
    return n_times(m, matter, s, q, tau_u, transpose=True, inverse=True)


def velocity_inconsistency(m, s, q, qd):
    """max over bodies of |omega - vee(dR/dt R^T)| (rad/s): OpenSim's angular velocities against central
    differences of its orientations along q'."""
    matter = m.getMatterSubsystem()
    u = n_times(m, matter, s, q, qd, inverse=True)
    s.setQ(vec(q))
    s.setU(vec(u))
    m.realizeVelocity(s)
    bodies = [m.getBodySet().get(i) for i in range(m.getBodySet().getSize())]
    omega = [np.array([b.getVelocityInGround(s).get(0)[k] for k in range(3)]) for b in bodies]
    h = 1e-6

    def rotations(qq):
        s.setQ(vec(qq))
        m.realizePosition(s)
        out = []
        for b in bodies:
            r = b.getTransformInGround(s).R()
            out.append(np.array([[r.get(i, j) for j in range(3)] for i in range(3)]))
        return out

    rp, rm = rotations(q + h * qd), rotations(q - h * qd)
    r0 = rotations(q)
    worst = 0.0
    for w, a, b, r in zip(omega, rp, rm, r0):
        wx = (a - b) / (2 * h) @ r.T
        fd = np.array([wx[2, 1], wx[0, 2], wx[1, 0]])
        worst = max(worst, float(np.abs(w - fd).max()))
    return worst


def reference(files):
    rng = np.random.default_rng(20261201)
    out = {"opensim": osim.__version__, "models": []}
    for path in files:
        name = os.path.basename(path)
        m = osim.Model(path)
        # The skeleton and its coordinate springs only: no muscle's passive force, no actuator.
        forces = m.updForceSet()
        for i in range(forces.getSize()):
            if forces.get(i).getConcreteClassName() != "SpringGeneralizedForce":
                forces.get(i).set_appliesForce(False)
        s = m.initSystem()
        matter = m.getMatterSubsystem()
        solver = osim.InverseDynamicsSolver(m)
        cs = m.getCoordinateSet()
        coords = [cs.get(i) for i in range(cs.getSize())]
        qi, ui = index_maps(m, s, coords)
        nq = s.getNQ()
        states = []
        for k in range(STATES):
            qc = np.array([rng.uniform(max(c.getRangeMin(), -1.5), min(c.getRangeMax(), 1.5)) for c in coords])
            if k == STATES - 1:
                # Beyond the knee splines' last point: their straight extensions.
                qc = np.array([0.3 if c.getName().startswith("knee") else x for c, x in zip(coords, qc)])
            vc = rng.uniform(-2.0, 2.0, len(coords))
            ac = rng.uniform(-5.0, 5.0, len(coords))
            q, qd, qdd = np.zeros(nq), np.zeros(nq), np.zeros(nq)
            q[qi], qd[qi], qdd[qi] = qc, vc, ac
            tau = state_forces(m, s, matter, solver, q, qd, qdd)
            bad = velocity_inconsistency(m, s, q, qd)
            states.append({"q": qc.tolist(), "v": vc.tolist(), "a": ac.tolist(), "tau": tau[qi].tolist(), "velocity_inconsistency": bad})
        out["models"].append({"file": name, "coordinates": [c.getName() for c in coords], "states": states})
    json.dump(out, sys.stdout, indent=1)


def motion(model, mot):
    m = osim.Model(model)
    m.initSystem()
    storage = osim.Storage(mot)
    m.getSimbodyEngine().convertDegreesToRadians(storage)
    columns = storage.getColumnLabels()
    labels = [columns.get(i) for i in range(1, columns.getSize())]
    cs = m.getCoordinateSet()
    rows = []
    for k in (0, storage.getSize() - 1):
        v = storage.getStateVector(k).getData()
        rows.append([v.get(i) for i in range(v.getSize())])
    out = {"labels": labels, "missing": [l for l in labels if not cs.contains(l)], "first": rows[0], "last": rows[1]}
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    if sys.argv[1] == "build":
        build(sys.argv[2])
    elif sys.argv[1] == "mot":
        motion(sys.argv[2], sys.argv[3])
    else:
        reference(sys.argv[2:])
