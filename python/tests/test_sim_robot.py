# rscene.Simulation's robots (issue 28): state in RaiSim's layout, PD
# targets and torques applied from the next step (the RL control loop),
# resets, and clear exceptions for misuse.  A pendulum written here, and
# ANYmal C from ../shared/corpus (skipped where it is absent).
import numpy as np
import pytest

import rscene
from conftest import ROOT

PENDULUM = """<robot name="pendulum">
  <link name="world"/>
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 1"/></joint>
  <link name="bob">
    <inertial><origin xyz="0 0 -0.5"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0 0 -0.5"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="hinge" type="continuous"><parent link="base"/><child link="bob"/><axis xyz="0 1 0"/></joint>
</robot>
"""
# About the hinge: the bob's own inertia plus m L^2.
PENDULUM_INERTIA = 0.01 + 2 * 0.5 ** 2

# A free body (floating base, no joints) of 2 kg.
BLOCK = """<robot name="block">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.4"/></inertial>
  </link>
</robot>
"""

ANYMAL = ROOT / ".." / "shared" / "corpus" / "robots" / "anymal_c" / "urdf" / "anymal.urdf"
ANYMAL_Q = [0, 0, 0.54, 1, 0, 0, 0, 0.03, 0.4, -0.8, -0.03, 0.4, -0.8, 0.03, -0.4, 0.8, -0.03, -0.4, 0.8]
GROUND = ("object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - "
          "static true 1 18446744073709551615\n")


def robot_scene(urdf, gravity="0 0 0", dt=0.001, more="", record_more=""):
    return rscene.loads(
        "raisim_engine_scene 1\ntime_step %g\ngravity %s\n%sarticulated_resource res Robot %s\n"
        "articulated /World/Robot res 0 0 0 1 0 0 0 true true id=robot%s\n" % (dt, gravity, more, urdf, record_more))


@pytest.fixture
def pendulum(tmp_path):
    f = tmp_path / "pendulum.urdf"
    f.write_text(PENDULUM)
    return f


@pytest.fixture
def block(tmp_path):
    f = tmp_path / "block.urdf"
    f.write_text(BLOCK)
    return f


def anymal_sim(extra=""):
    if not ANYMAL.exists():
        pytest.skip("../shared/corpus/robots/anymal_c is absent")
    return rscene.Simulation(rscene.loads(
        "raisim_engine_scene 1\ntime_step 0.0025\ngravity 0 0 -9.81\n" + GROUND +
        "articulated_resource res ANYmal %s\narticulated /World/Anymal res 0 0 0.54 1 0 0 0 true true id=anymal "
        "generalizedCoordinate=%s\n" % (ANYMAL, ",".join(map(str, ANYMAL_Q))) + extra))


def test_pendulum_names_and_state(pendulum):
    sim = rscene.Simulation(robot_scene(pendulum))
    r = sim.robot("/World/Robot")
    assert r.path == "/World/Robot" and not r.floating_base
    assert r.joint_names == ["hinge"] and r.coordinate_names == ["hinge"] and r.velocity_names == ["hinge"]
    assert r.q.dtype == np.float64 and r.q.shape == (1,) and r.u.shape == (1,)
    assert r.q.tolist() == [0] and r.u.tolist() == [0]
    assert sim.robot("robot").path == "/World/Robot"  # by id
    assert [x.path for x in sim.robots] == ["/World/Robot"]


def test_torque_gives_the_closed_form_acceleration_at_step_one(pendulum):
    # No gravity, at rest: the first step's velocity is tau / I dt exactly
    # (Bullet integrates the velocity first).
    sim = rscene.Simulation(robot_scene(pendulum))
    r = sim.robot("robot")
    r.set_torques([2.6])
    assert r.u[0] == 0  # applied from the next step
    sim.step()
    assert r.u[0] == pytest.approx(2.6 / PENDULUM_INERTIA * 0.001, rel=1e-9)
    # It stays in force (RaiSim's setGeneralizedForce) ...
    sim.step()
    assert r.u[0] == pytest.approx(2 * 2.6 / PENDULUM_INERTIA * 0.001, rel=1e-6)
    # ... until changed: set_torques(0) ends it, the speed stays.
    r.set_torques(0)
    u = r.u[0]
    sim.step(10)
    assert r.u[0] == pytest.approx(u, rel=1e-9)


def test_torque_against_gravity(pendulum):
    # Held horizontal (q = pi/2), gravity's torque about the hinge is m g L;
    # a torque that matches it leaves the first step's velocity at zero.
    sim = rscene.Simulation(robot_scene(pendulum, gravity="0 0 -9.81"))
    r = sim.robot("robot")
    r.set_state([np.pi / 2])
    sim.step()
    free = r.u[0]
    assert abs(free) == pytest.approx(2 * 9.81 * 0.5 / PENDULUM_INERTIA * 0.001, rel=1e-6)
    sim2 = rscene.Simulation(robot_scene(pendulum, gravity="0 0 -9.81"))
    r2 = sim2.robot("robot")
    r2.set_state([np.pi / 2])
    r2.set_torques(-np.sign(free) * 2 * 9.81 * 0.5)
    sim2.step()
    assert abs(r2.u[0]) < 1e-9


def test_pd_target_holds_the_joint_near_it(pendulum):
    sim = rscene.Simulation(robot_scene(pendulum, gravity="0 0 -9.81"))
    r = sim.robot("robot")
    r.set_pd_targets([0.5], kp=1000, kd=20)
    sim.step(3000)
    # Sagging under the bob's weight by m g L sin(q) / kp at the most.
    assert r.q[0] == pytest.approx(0.5, abs=0.01)
    assert abs(r.u[0]) < 1e-3
    # A new target, as an array: it moves there.
    r.set_pd_targets(np.array([-0.3]), np.array([1000.0]), np.array([20.0]))
    sim.step(3000)
    assert r.q[0] == pytest.approx(-0.3, abs=0.01)
    # Gains of zero let it go: it swings down past the bottom.
    r.set_pd_targets([0.0], 0, 0)
    sim.step(300)
    assert r.q[0] > -0.25


def test_velocity_target(pendulum):
    # kd alone toward a velocity: the joint turns at it.
    sim = rscene.Simulation(robot_scene(pendulum))
    r = sim.robot("robot")
    r.set_pd_targets([0.0], 0, 5, u=[1.5])
    sim.step(2000)
    assert r.u[0] == pytest.approx(1.5, rel=1e-3)


def test_set_state_resets_and_is_written_back(pendulum):
    sim = rscene.Simulation(robot_scene(pendulum))
    r = sim.robot("robot")
    r.set_state([0.25], [0.5])
    q, u = r.state()
    assert q[0] == pytest.approx(0.25) and u[0] == pytest.approx(0.5)
    sim.step(100)
    assert r.q[0] == pytest.approx(0.25 + 0.5 * 0.1, rel=1e-6)  # no gravity, no torque: uniform motion
    # Written back as rscene-sim -o writes it.
    line = [x for x in rscene.format(sim.document()).splitlines() if x.startswith("articulated ")][0]
    written = [t for t in line.split() if t.startswith("generalizedCoordinate=")][0]
    assert float(written.split("=")[1]) == pytest.approx(r.q[0], rel=1e-12)


def test_floating_base_force(block):
    # A world-frame force on a free 2 kg body: a = F / m at step one; a
    # torque about z: alpha = tau / Izz.
    sim = rscene.Simulation(robot_scene(block, record_more=" generalizedCoordinate=0,0,1,1,0,0,0"))
    r = sim.robot("robot")
    assert r.floating_base and r.q.shape == (7,) and r.u.shape == (6,)
    assert r.coordinate_names[:3] == ["base_x", "base_y", "base_z"]
    r.set_torques([4, 0, 0, 0, 0, 0.8])
    sim.step()
    assert r.u[0] == pytest.approx(2 * 0.001, rel=1e-9)
    assert r.u[5] == pytest.approx(0.8 / 0.4 * 0.001, rel=1e-9)
    assert np.allclose(r.u[[1, 2, 3, 4]], 0, atol=1e-12)


def test_misuse_raises_clear_errors(pendulum):
    sim = rscene.Simulation(robot_scene(pendulum, more=GROUND))
    r = sim.robot("robot")
    with pytest.raises(KeyError, match="no articulated system named 'nope'"):
        sim.robot("nope")
    with pytest.raises(ValueError, match="is an object, not a simulated robot"):
        sim.robot("/World/Ground")
    with pytest.raises(TypeError):
        sim.robot(3)
    with pytest.raises(ValueError, match=r"expected shape \(1,\), got \(2,\)"):
        r.set_torques([1, 2])
    with pytest.raises(ValueError, match="not finite"):
        r.set_torques(np.nan)
    with pytest.raises(ValueError, match="not finite"):
        r.set_pd_targets([np.inf], 1, 1)
    with pytest.raises(ValueError, match=r"got \(1, 1\)"):
        r.set_pd_targets([[0.1]], 1, 1)
    with pytest.raises(ValueError, match=">= 0"):
        r.set_pd_targets([0.1], -1, 1)
    with pytest.raises(ValueError, match="not numbers"):
        r.set_pd_targets(["a"], 1, 1)
    with pytest.raises(ValueError):
        r.set_state([0.1], [1, 2, 3])
    # Nothing of that changed the robot.
    sim.step(10)
    assert r.q.tolist() == [0] and r.u.tolist() == [0]


def test_zero_quaternion_is_refused(block):
    sim = rscene.Simulation(robot_scene(block, record_more=" generalizedCoordinate=0,0,1,1,0,0,0"))
    r = sim.robot("robot")
    with pytest.raises(ValueError, match="quaternion"):
        r.set_state([0, 0, 1, 0, 0, 0, 0])
    with pytest.raises(ValueError, match="quaternion"):
        r.set_pd_targets([0, 0, 1, 0, 0, 0, 0], 1, 1)
    r.set_state([0, 0, 2, 2, 0, 0, 0])  # normalised, as a record's
    assert r.q[3:].tolist() == pytest.approx([1, 0, 0, 0])


def test_anymal_pd_stands_and_its_feet_touch_the_ground():
    sim = anymal_sim()
    r = sim.robot("/World/Anymal")
    assert r.q.shape == (19,) and r.u.shape == (18,)
    assert r.q.tolist() == ANYMAL_Q
    assert r.joint_names[:3] == ["LF_HAA", "LF_HFE", "LF_KFE"] and len(r.joint_names) == 12
    assert r.coordinate_names[7] == "LF_HAA" and r.velocity_names[6] == "LF_HAA"
    r.set_pd_targets(ANYMAL_Q, 400, 10)
    sim.step(400)  # 1 s
    q = r.q
    assert 0.45 < q[2] < 0.56
    assert np.abs(q[7:] - ANYMAL_Q[7:]).max() < 0.15
    c = sim.contacts()
    assert len(c) >= 4
    feet = {a or b for a, b in zip(c.link_a, c.link_b)}
    assert feet == {"LF_SHANK", "RF_SHANK", "LH_SHANK", "RH_SHANK"}  # the feet are merged into the shanks
    assert set(c.body_a) | set(c.body_b) == {"/World/Anymal", "/World/Ground"}
    assert np.all(np.abs(c.normal[:, 2]) > 0.9)


def test_anymal_rl_loop_with_resets():
    # A Gymnasium-style loop: reset by set_state, act by PD targets.
    sim = anymal_sim()
    r = sim.robot("anymal")
    q0 = np.array(ANYMAL_Q)
    rng = np.random.default_rng(1)
    for episode in range(2):
        r.set_state(q0)
        for _ in range(50):
            action = q0 + np.r_[np.zeros(7), rng.normal(0, 0.05, 12)]
            r.set_pd_targets(action, 300, 8)
            sim.step(4)
            assert np.all(np.isfinite(r.q))
        assert 0.3 < r.q[2] < 0.7


def test_spherical_joints_reach_quaternion_targets():
    # RaiSim's chain (three spherical joints): q holds a quaternion per
    # joint, u and the gains three entries; each joint turned 0.3 rad
    # about x by its target gets there (no gravity).
    chain = ROOT / ".." / "shared" / "corpus" / "robots" / "chain" / "robot.urdf"
    if not chain.exists():
        pytest.skip("../shared/corpus/robots/chain is absent")
    sim = rscene.Simulation(robot_scene(chain))
    r = sim.robot("robot")
    assert r.q.shape == (12,) and r.u.shape == (9,)
    assert r.coordinate_names[:4] == ["link1Tolink2_qw", "link1Tolink2_qx", "link1Tolink2_qy", "link1Tolink2_qz"]
    assert r.velocity_names[:3] == ["link1Tolink2_wx", "link1Tolink2_wy", "link1Tolink2_wz"]
    target = np.tile([np.cos(0.15), np.sin(0.15), 0, 0], 3)
    r.set_pd_targets(target, 50, 2)
    sim.step(6000)
    angles = 2 * np.arcsin(r.q[[1, 5, 9]])
    assert angles == pytest.approx([0.3, 0.3, 0.3], abs=2e-3)
    assert np.abs(r.q[[2, 3, 6, 7, 10, 11]]).max() < 1e-6
    assert np.abs(r.u).max() < 1e-2
