"""The Python bindings (spatial_dynamics.dynamics) against the library: bit-for-bit agreement with
the C++ calls (bindings_oracle), ID(FD(tau)) = tau on every bundled robot, several threads on one
model, errors that name the culprit, no leak, and the per-call overhead (printed)."""
import os
import subprocess
import sys
import threading
import time

import numpy as np

from spatial_dynamics import dynamics

HERE = os.path.dirname(os.path.abspath(__file__))
ROBOTS_DIR = os.path.join(HERE, "..", "..", "urdf")
# (URDF, floating base): the fixed-base robots, and the two legged ones floating as well.
ROBOTS = [("panda.urdf", False), ("ur5.urdf", False), ("talos.urdf", False), ("solo12.urdf", False),
          ("double_pendulum.urdf", False), ("solo12.urdf", True), ("talos.urdf", True)]


def report(line):
    """A result line on the real stderr: nose captures stdout, and the line belongs in the test log."""
    sys.__stderr__.write("\n" + line + "\n")  # on a line of its own, after nose's progress dots
    sys.__stderr__.flush()


def robot_path(name):
    return os.path.join(ROBOTS_DIR, name)


def oracle_path():
    """bindings_oracle, in the devel space's lib/spatial_dynamics/ (the module is in lib/python3/...)."""
    if os.environ.get("SD_BINDINGS_ORACLE"):
        return os.environ["SD_BINDINGS_ORACLE"]
    lib = os.path.abspath(os.path.join(os.path.dirname(dynamics.__file__), "..", "..", ".."))
    return os.path.join(lib, "spatial_dynamics", "bindings_oracle")


def random_state(model, rng):
    """q (unit quaternion for a free root), qd, qdd, tau and a wrench."""
    q = rng.uniform(-1.0, 1.0, model.nq)
    if model.floating_base:
        q[3:7] /= np.linalg.norm(q[3:7])
    return (q, rng.uniform(-1.0, 1.0, model.nv), rng.uniform(-1.0, 1.0, model.nv),
            rng.uniform(-10.0, 10.0, model.nv), rng.uniform(-5.0, 5.0, 6))


def run_oracle(urdf, floating, frame, states, timed_calls=0):
    """The library's results for `states`, one dict per state: name → array of the printed floats."""
    lines = [str(len(states))]
    for state in states:
        lines.append(" ".join(float(x).hex() for part in state for x in part))
    command = [oracle_path(), robot_path(urdf), "1" if floating else "0", frame]
    if timed_calls:
        command += ["--time", str(timed_calls)]
    out = subprocess.run(command, input="\n".join(lines) + "\n", capture_output=True, text=True, check=True).stdout
    results, timing = [], None
    for line in out.splitlines():
        name, *values = line.split()
        if name == "rnea_median_us":
            timing = float(values[0])
            continue
        if name == "rnea":
            results.append({})
        results[-1][name] = np.array([float.fromhex(v) for v in values])
    return results, timing


def python_results(model, frame, state):
    q, qd, qdd, tau, wrench = state
    return {
        "rnea": model.rnea(q, qd, qdd),
        "rnea_ext": model.rnea(q, qd, qdd, external_wrenches={frame: wrench}),
        "aba": model.aba(q, qd, tau),
        "aba_refined": model.aba_refined(q, qd, tau),
        "crba": model.crba(q).ravel(),
        "gravity_torques": model.gravity_torques(q),
        "nonlinear_effects": model.nonlinear_effects(q, qd),
        "jacobian_root_aligned": model.frame_jacobian(frame, q).ravel(),
        "jacobian_local": model.frame_jacobian(frame, q, reference="local").ravel(),
    }


def check_bit_for_bit(urdf, floating):
    model = dynamics.Model.from_urdf(robot_path(urdf), floating_base=floating)
    frame = model.frame_names[-1]
    rng = np.random.default_rng(11)
    states = [random_state(model, rng) for _ in range(5)]
    expected, _ = run_oracle(urdf, floating, frame, states)
    assert len(expected) == len(states)
    for k, state in enumerate(states):
        got = python_results(model, frame, state)
        assert set(got) == set(expected[k])
        for name, value in got.items():
            assert value.dtype == np.float64
            assert np.array_equal(value, expected[k][name]), \
                "%s%s state %d: %s differs from the library's (max %g)" % (
                    urdf, " floating" if floating else "", k, name, np.max(np.abs(value - expected[k][name])))


def test_bit_for_bit_against_the_library():
    for urdf, floating in ROBOTS:
        yield check_bit_for_bit, urdf, floating



def check_inverse_of_forward_dynamics(urdf, floating):
    model = dynamics.Model.from_urdf(robot_path(urdf), floating_base=floating)
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(50):
        q, qd, _, tau, _ = random_state(model, rng)
        qdd = model.aba(q, qd, tau)
        worst = max(worst, np.linalg.norm(model.rnea(q, qd, qdd) - tau) / np.linalg.norm(tau))
    report("[bindings] %s%s: ID(FD(tau)) vs tau, max relative error %.3g" % (urdf, " floating" if floating else "", worst))
    assert worst <= 1e-12, worst


def test_inverse_of_forward_dynamics():
    for urdf, floating in ROBOTS:
        yield check_inverse_of_forward_dynamics, urdf, floating


def test_actuator_terms():
    """with_actuators against the law written out in numpy, and FD_actuated inverting ID_actuated."""
    rigid = dynamics.Model.from_urdf(robot_path("ur5.urdf"))
    n = rigid.nv
    rng = np.random.default_rng(19)
    armature, damping = rng.uniform(0, 0.5, n), rng.uniform(0, 2, n)
    friction, speed = rng.uniform(0, 1, n), rng.uniform(1e-3, 0.1, n)
    model = rigid.with_actuators(armature=armature, damping=damping, friction=friction, friction_velocity=speed)
    np.testing.assert_array_equal(model.armature, armature)
    np.testing.assert_array_equal(rigid.armature, np.zeros(n))  # the original is unchanged
    for _ in range(10):
        q, qd, qdd, tau, _ = random_state(model, rng)
        qd *= 0.1  # through the ramp and beyond
        law = damping * qd + friction * np.clip(qd / speed, -1.0, 1.0)
        np.testing.assert_allclose(model.actuator_forces(qd), law, rtol=1e-14, atol=1e-15)
        expected = rigid.rnea(q, qd, qdd) + armature * qdd + law
        np.testing.assert_allclose(model.inverse_dynamics_actuated(q, qd, qdd), expected, rtol=1e-13, atol=1e-12)
        back = model.inverse_dynamics_actuated(q, qd, model.forward_dynamics_actuated(q, qd, tau))
        assert np.linalg.norm(back - tau) <= 1e-12 * np.linalg.norm(tau)
    # By joint name; a bad value or joint is refused naming it.
    named = rigid.with_actuators(armature={rigid.joint_names[2]: 0.25})
    assert named.armature[2] == 0.25 and named.armature[0] == 0.0
    for kwargs, culprit in [({"damping": {"no_such_joint": 1.0}}, "no_such_joint"),
                            ({"armature": {rigid.joint_names[1]: -1.0}}, rigid.joint_names[1]),
                            ({"friction_velocity": np.zeros(n)}, rigid.joint_names[0])]:
        try:
            rigid.with_actuators(**kwargs)
        except ValueError as e:
            assert culprit in str(e), str(e)
        else:
            raise AssertionError("accepted %r" % kwargs)


def test_model_properties():
    model = dynamics.Model.from_urdf(robot_path("solo12.urdf"), floating_base=True)
    assert model.nq == model.nv + 1
    assert len(model.joint_names) == model.nv
    assert model.joint_names[:6] == ["root_joint/" + c for c in ("wx", "wy", "wz", "vx", "vy", "vz")]
    assert len(model.position_names) == model.nq
    assert model.floating_base
    fixed = dynamics.Model.from_urdf(robot_path("panda.urdf"))
    assert not fixed.floating_base and fixed.nq == fixed.nv
    with open(robot_path("panda.urdf")) as f:
        from_text = dynamics.Model.from_urdf(f.read())
    assert from_text.joint_names == fixed.joint_names and from_text.frame_names == fixed.frame_names
    assert dynamics.simd_backend() in ("avx2_fma", "portable")


def test_external_wrench_is_minus_jacobian_transpose():
    # A wrench w (torque; force) on frame F, in F's coordinates about its origin: tau = ID - J_Fᵀ w.
    model = dynamics.Model.from_urdf(robot_path("ur5.urdf"))
    rng = np.random.default_rng(3)
    frame = model.frame_names[-1]
    q, qd, qdd, _, w = random_state(model, rng)
    J = model.frame_jacobian(frame, q, reference="local")
    expected = model.rnea(q, qd, qdd) - J.T @ w
    assert np.allclose(model.rnea(q, qd, qdd, {frame: w}), expected, rtol=0, atol=1e-10)


def test_reduce_and_lock():
    full = dynamics.Model.from_urdf(robot_path("panda.urdf"))
    kept = full.joint_names[:4]
    locked = {name: 0.3 for name in full.joint_names[4:]}
    reduced = full.reduce(joints=kept, positions=locked)
    assert reduced.joint_names == kept and reduced.nv == 4
    same = full.lock(locked)
    assert same.joint_names == kept
    rng = np.random.default_rng(2)
    q, qd, qdd, _, _ = random_state(reduced, rng)
    q_full = np.concatenate([q, np.full(full.nv - 4, 0.3)])
    zeros = np.zeros(full.nv - 4)
    tau_full = full.rnea(q_full, np.concatenate([qd, zeros]), np.concatenate([qdd, zeros]))[:4]
    assert np.allclose(reduced.rnea(q, qd, qdd), tau_full, rtol=1e-12, atol=1e-10)
    assert np.allclose(same.rnea(q, qd, qdd), tau_full, rtol=1e-12, atol=1e-10)
    assert np.allclose(reduced.crba(q), full.crba(q_full)[:4, :4], rtol=1e-12, atol=1e-12)
    assert reduced.frame_names == full.frame_names  # every frame stays addressable
    assert full.lock(list(full.joint_names[4:])).nv == 4  # names alone: locked at 0


def test_results_are_copies():
    model = dynamics.Model.from_urdf(robot_path("panda.urdf"))
    q = np.zeros(model.nq)
    first = model.crba(q)
    second = model.crba(q + 0.5)
    assert not np.array_equal(first, second)
    assert np.array_equal(first, model.crba(q))
    assert first.shape == (model.nv, model.nv) and model.frame_jacobian(model.frame_names[-1], q).shape == (6, model.nv)


def test_threads_share_one_model():
    model = dynamics.Model.from_urdf(robot_path("panda.urdf"))
    calls, threads = 1000, 4
    inputs, expected = [], []
    for t in range(threads):
        rng = np.random.default_rng(100 + t)
        states = [random_state(model, rng) for _ in range(calls)]
        inputs.append(states)
        expected.append([(model.rnea(q, qd, qdd), model.aba(q, qd, tau), model.crba(q))[k % 3]
                         for k, (q, qd, qdd, tau, _) in enumerate(states)])
    mismatches = [0] * threads
    barrier = threading.Barrier(threads)

    def work(t):
        barrier.wait()
        for k, (q, qd, qdd, tau, _) in enumerate(inputs[t]):
            got = (model.rnea, model.aba, model.crba)[k % 3](*((q, qd, qdd), (q, qd, tau), (q,))[k % 3])
            if not np.array_equal(got, expected[t][k]):
                mismatches[t] += 1

    workers = [threading.Thread(target=work, args=(t,)) for t in range(threads)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    assert mismatches == [0] * threads, mismatches


def raises_value_error(call, *fragments):
    try:
        call()
    except ValueError as error:
        for fragment in fragments:
            assert fragment in str(error), "%r not in %r" % (fragment, str(error))
        return str(error)
    raise AssertionError("no ValueError (expected one naming %s)" % (fragments,))


PANDA = None


def panda():
    global PANDA
    if PANDA is None:
        PANDA = dynamics.Model.from_urdf(robot_path("panda.urdf"))
    return PANDA


def test_wrong_length_names_the_argument():
    m = panda()
    z = np.zeros(m.nv)
    raises_value_error(lambda: m.rnea(np.zeros(m.nq - 1), z, z),
                       "q has %d entries; the model expects %d" % (m.nq - 1, m.nq))
    raises_value_error(lambda: m.rnea(np.zeros(m.nq), z[1:], z), "qd has %d entries" % (m.nv - 1))
    raises_value_error(lambda: m.aba(np.zeros(m.nq), z, np.zeros(m.nv + 2)), "tau has %d entries" % (m.nv + 2))
    raises_value_error(lambda: m.crba(np.zeros((m.nq, 1))), "q has 2 dimensions")
    raises_value_error(lambda: m.rnea(np.zeros(m.nq), z, z, {m.frame_names[-1]: [1, 2, 3]}),
                       "external_wrenches['%s'] has 3 entries" % m.frame_names[-1])


def test_unknown_frame_or_joint_names_it():
    m = panda()
    q = np.zeros(m.nq)
    raises_value_error(lambda: m.frame_jacobian("x", q), "unknown frame 'x'")
    raises_value_error(lambda: m.rnea(q, q, q, {"nowhere": np.zeros(6)}), "unknown frame 'nowhere'")
    raises_value_error(lambda: m.frame_jacobian(m.frame_names[-1], q, reference="world"), "unknown reference 'world'")
    raises_value_error(lambda: m.reduce(joints=["elbow_of_nobody"]), "unknown joint 'elbow_of_nobody'")
    raises_value_error(lambda: m.lock({"no_such_joint": 0.0}), "unknown joint 'no_such_joint'")


def test_non_finite_input_names_argument_and_coordinate():
    m = panda()
    q, z = np.zeros(m.nq), np.zeros(m.nv)
    bad = z.copy()
    bad[2] = np.nan
    raises_value_error(lambda: m.rnea(q, bad, z), "qd[2]", m.joint_names[2], "not finite")
    raises_value_error(lambda: m.aba(q, z, bad), "tau[2]", m.joint_names[2])
    bad_q = q.copy()
    bad_q[1] = np.inf
    raises_value_error(lambda: m.crba(bad_q), "q[1]", m.position_names[1])
    raises_value_error(lambda: m.rnea(q, z, z, {m.frame_names[-1]: [0, 0, 0, np.nan, 0, 0]}),
                       "external_wrenches['%s'][3] ('force x')" % m.frame_names[-1])
    raises_value_error(lambda: m.reduce(joints=m.joint_names[:2], positions={m.joint_names[3]: float("nan")}),
                       "joint '%s' is not finite" % m.joint_names[3])
    raises_value_error(lambda: m.rnea(None, z, z), "q is None")


def test_rejected_urdf_gives_the_builder_message():
    message = raises_value_error(lambda: dynamics.Model.from_urdf("<robot name='r'><link name='a'/>"))
    assert message
    raises_value_error(lambda: dynamics.Model.from_urdf(
        "<robot name='r'><link name='a'/><link name='b'><inertial><mass value='-1'/>"
        "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link>"
        "<joint name='j' type='continuous'><parent link='a'/><child link='b'/></joint></robot>"),
        "link 'b'", "negative")
    raises_value_error(lambda: dynamics.Model.from_urdf("/no/such/robot.urdf"), "malformed URDF")


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_no_leak_over_many_calls():
    m = panda()
    rng = np.random.default_rng(9)
    q, qd, qdd, _, w = random_state(m, rng)
    frame = m.frame_names[-1]
    for _ in range(10000):
        m.rnea(q, qd, qdd)
        m.rnea(q, qd, qdd, {frame: w})
    before = rss_bytes()
    for _ in range(100000):
        m.rnea(q, qd, qdd)
    for _ in range(10000):
        m.rnea(q, qd, qdd, {frame: w})
        try:
            m.rnea(q[1:], qd, qdd)
        except ValueError:
            pass
    growth = rss_bytes() - before
    report("[bindings] RSS growth over 1e5 rnea calls (and 1e4 with a wrench, 1e4 failing): %.3f MB" % (growth / 1e6))
    assert growth < 2e6, growth


def test_print_per_call_overhead():
    m = panda()
    rng = np.random.default_rng(1)
    state = random_state(m, rng)
    q, qd, qdd = state[:3]
    calls = 20000
    _, cpp_us = run_oracle("panda.urdf", False, m.frame_names[-1], [state], timed_calls=calls)
    for _ in range(2000):
        m.rnea(q, qd, qdd)
    times = np.empty(calls)
    clock = time.perf_counter_ns
    rnea = m.rnea
    for k in range(calls):
        start = clock()
        rnea(q, qd, qdd)
        times[k] = clock() - start
    python_us = float(np.median(times)) * 1e-3
    report("[bindings] rnea on panda: python %.3f us per call, C++ %.3f us, overhead %.3f us"
          % (python_us, cpp_us, python_us - cpp_us))
    assert cpp_us > 0
