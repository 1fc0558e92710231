"""The Python package against the Rust library's own physics: identities between the algorithms,
finite differences, the bundled examples planned from a file and from a dict, errors, sweeps, the GIL."""

import os
import threading
import time

import numpy as np
import pytest

import mintorque

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PENDULUM = os.path.join(ROOT, "examples", "pendulum.toml")


@pytest.fixture
def jack():
    return mintorque.Model.human("sagittal", stature=1.83, mass=81.0)


def random_states(model, n, seed=1):
    rng = np.random.default_rng(seed)
    return [rng.uniform(-1, 1, (n, model.nv)) for _ in range(3)]


def test_model_properties(jack):
    assert jack.nv == 7
    assert jack.joint_names == ["ankle", "knee", "hip", "lumbar", "shoulder", "elbow", "wrist"]


def test_batched_rnea_equals_one_state_at_a_time(jack):
    q, v, a = random_states(jack, 5)
    batch = jack.rnea(q, v, a)
    assert batch.shape == (5, 7)
    for k in range(5):
        np.testing.assert_allclose(batch[k], jack.rnea(q[k], v[k], a[k]), rtol=0, atol=1e-12)


def test_inverse_and_forward_dynamics_agree_with_the_mass_matrix(jack):
    q, v, a = random_states(jack, 4)
    zero = np.zeros_like(v)
    # Without velocity or gravity, inverse dynamics is H(q) q̈ (two algorithms, one identity).
    tau = jack.rnea(q, zero, a, gravity=[0.0, 0.0, 0.0])
    h = jack.crba(q)
    np.testing.assert_allclose(tau, np.einsum("kij,kj->ki", h, a), rtol=1e-10, atol=1e-10)
    # Forward dynamics inverts inverse dynamics.
    np.testing.assert_allclose(jack.aba(q, v, jack.rnea(q, v, a)), a, rtol=1e-9, atol=1e-9)


def test_derivatives_match_finite_differences(jack):
    q, v, a = (x[0] for x in random_states(jack, 1, seed=3))
    dq, dv, h = jack.rnea_derivatives(q, v, a)
    eps = 1e-6
    for i in range(jack.nv):
        e = np.zeros(jack.nv)
        e[i] = eps
        np.testing.assert_allclose(dq[:, i], (jack.rnea(q + e, v, a) - jack.rnea(q - e, v, a)) / (2 * eps), atol=1e-5)
        np.testing.assert_allclose(dv[:, i], (jack.rnea(q, v + e, a) - jack.rnea(q, v - e, a)) / (2 * eps), atol=1e-5)
    np.testing.assert_allclose(h, jack.crba(q), atol=1e-12)


def test_bad_arrays_and_files_raise_with_the_field(jack):
    with pytest.raises(mintorque.MintorqueError, match=r"v: shape \[6\], expected \(7,\)"):
        jack.rnea(np.zeros(7), np.zeros(6), np.zeros(7))
    with pytest.raises(mintorque.MintorqueError, match="not finite"):
        jack.rnea(np.full(7, np.nan), np.zeros(7), np.zeros(7))
    with pytest.raises(mintorque.MintorqueError, match="structure"):
        mintorque.Model.human("sagital")
    with pytest.raises(mintorque.MintorqueError, match="no_such.urdf"):
        mintorque.Model.load("no_such.urdf")


def test_plan_from_a_file_and_from_a_dict_agree():
    from_file = mintorque.plan(PENDULUM)
    assert from_file.converged, from_file.reason
    assert from_file.q.shape == (len(from_file.t), 1) and from_file.tau.shape == from_file.q.shape
    assert from_file.summary["converged"] is True
    # The compound pendulum's free swing needs almost no torque (paper 7.1).
    assert np.max(np.abs(from_file.tau)) < 0.16
    task = {
        "model": {"urdf": os.path.join(ROOT, "models", "pendulum.urdf")},
        "motion": {"duration": 0.6052, "start": {"pivot": -70.0}, "goal": {"pivot": 70.0}},
        "environment": {"gravity": "earth"},
        "discretization": {"control_points": 16},  # as the file fixes it (left out, N would be refined)
    }
    from_dict = mintorque.plan(task)
    assert from_dict.converged
    assert abs(from_dict.effort - from_file.effort) <= 1e-9 * max(1.0, from_file.effort)


def test_a_misspelt_task_field_raises_naming_it():
    task = {"model": {"urdf": os.path.join(ROOT, "models", "pendulum.urdf")}, "motion": {"duraton": 1.0}}
    with pytest.raises(mintorque.MintorqueError, match="duraton"):
        mintorque.plan(task)
    with pytest.raises(mintorque.MintorqueError, match="solver"):
        mintorque.plan(PENDULUM, solver="fastest")


def test_starts_take_a_number_or_auto():
    three = mintorque.plan(PENDULUM, starts=3)
    assert len(three.summary["starts"]) == 3
    auto = mintorque.plan(PENDULUM, starts="auto")
    # The automatic rule runs rounds of two starts: two where they agree, four where they do not.
    assert len(auto.summary["starts"]) in (2, 4)
    assert auto.effort == mintorque.plan(PENDULUM).effort
    with pytest.raises(mintorque.MintorqueError, match='starts: expected "auto" or a whole number of starts, got "many"'):
        mintorque.plan(PENDULUM, starts="many")
    with pytest.raises(mintorque.MintorqueError, match="starts"):
        mintorque.plan(PENDULUM, starts=2.5)


def test_planning_releases_the_gil():
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=tick)
    thread.start()
    try:
        start = time.perf_counter()
        result = mintorque.plan(os.path.join(ROOT, "examples", "weight_lift_earth.toml"))
        end = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    during = [t for t in ticks if start < t < end]
    # The other thread ran during the solve (it could not while the GIL was held).
    assert len(during) > 10, (len(during), end - start, result.solve_seconds)


def test_sweep_returns_a_table_sorted_by_index(tmp_path):
    sweep_file = tmp_path / "sweep.toml"
    sweep_file.write_text(
        f'base = "{PENDULUM}"\n'
        '[[parameter]]\npath = "motion.duration"\nrange = { from = 0.5, to = 0.7, step = 0.05 }\n'
    )
    table = mintorque.sweep(sweep_file, tmp_path / "out")
    import pandas  # installed by scripts/python-test.sh
    assert isinstance(table, pandas.DataFrame)
    assert list(table["index"]) == [0, 1, 2, 3, 4]
    assert set(table["status"]) == {"converged"}
    # Least effort at the free-swing duration (0.6052 s ≈ the 0.6 s row).
    assert table.loc[table["effort"].idxmin(), "motion.duration"] == pytest.approx(0.6)


def test_ctrl_c_interrupts_a_long_solve():
    import signal

    # A slow plan: the weight lift on a 4 cm support with 64 control points and 8 nodes per span (about 10 s
    # on the 2-core CI machine; at N = 16 it took 0.35 s, close enough to the 0.3 s timer that it sometimes
    # finished first once the solver got faster).
    task = {
        "model": {"human": "sagittal", "stature": 1.83, "mass": 81.0},
        "motion": {"duration": 2.0, "start": {}, "goal": {"shoulder": 170.0}},
        "environment": {"gravity": "earth", "payload": [{"frame": "barbell", "mass": 25.0, "inertia": [2.9, 0.02, 2.9]}]},
        "constraints": {"balance": {"x": [0.01, 0.05], "y": [-0.15, 0.15]}},
        "discretization": {"control_points": 64, "nodes_per_span": 8},
        "solver": {"max_iterations": 10000000, "time_limit": 600.0},
    }
    # Python keeps SIGINT ignored when it starts with it ignored (a job started in the background by a
    # non-interactive shell, as CI scripts may be): install Python's own Ctrl-C handler for this test.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    try:
        with pytest.raises(KeyboardInterrupt):
            mintorque.plan(task)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert time.perf_counter() - start < 3.0, "the solve went on after Ctrl-C"
