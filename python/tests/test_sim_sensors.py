# rscene.Simulation's sensors (issue 28): the LiDARs and IMUs rscene-sim
# --sensors records, read while stepping, the latest reading of each as
# numpy arrays: a scan as (N, 3) float32 in the sensor frame, an IMU's
# specific force and angular velocity.
import numpy as np
import pytest

import rscene
from conftest import ROOT

# A closed room (inside x -4..4, y -3..3, z 0..2), a crate resting on its
# floor carrying an IMU, and a 1 x 4 LiDAR at its centre, 1 m up (as
# shell-tests/sim_sensors.bats).
WALL = " 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615\n"
ROOM = (
    "raisim_engine_scene 1\ntime_step 0.01\ngravity 0 0 -9.81\n"
    "object /World/Floor box 0 0 -0.1 1 0 0 0 8.4 6.4 0.2" + WALL +
    "object /World/East box 4.1 0 1 1 0 0 0 0.2 6 2" + WALL +
    "object /World/West box -4.1 0 1 1 0 0 0 0.2 6 2" + WALL +
    "object /World/North box 0 3.1 1 1 0 0 0 8.4 0.2 2" + WALL +
    "object /World/South box 0 -3.1 1 1 0 0 0 8.4 0.2 2" + WALL +
    "object /World/Crate box 1 1 0.25 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - "
    "dynamic true 1 18446744073709551615 id=crate\n"
    "sensor /World/Imu imu crate 0 0 0.25 1 0 0 0 updateRate=10 id=imu\n"
    "sensor /World/Lidar lidar - 0 0 1 1 0 0 0 updateRate=5 lidarChannels=1 lidarSamples=4 lidarVerticalFov=0 "
    "id=lidar\n")


def test_sensors_are_listed():
    sim = rscene.Simulation(rscene.loads(ROOM))
    assert sim.sensors() == [{"name": "/World/Imu", "id": "imu", "kind": "imu"},
                             {"name": "/World/Lidar", "id": "lidar", "kind": "lidar"}]


def test_lidar_scan_in_its_own_frame():
    sim = rscene.Simulation(rscene.loads(ROOM))
    assert sim.lidar("/World/Lidar") is None  # nothing read before the first step() call
    sim.step(0)  # the scan at time 0
    scan = sim.lidar("/World/Lidar")
    assert scan["time"] == 0 and scan["index"] == 0
    assert scan["pose"].tolist() == [0, 0, 1, 1, 0, 0, 0]
    points = scan["points"]
    assert points.dtype == np.float32 and points.shape == (4, 3)
    # yaw 0, 90, 180, 270 (counter-clockwise): east 4, north 3, west 4, south 3.
    assert np.allclose(points, [[4, 0, 0], [0, 3, 0], [-4, 0, 0], [0, -3, 0]], atol=1e-5)
    # 5 Hz at dt 0.01: the next scan is at 0.2 s; by id too.
    sim.step(19)
    assert sim.lidar("lidar")["index"] == 0
    sim.step(1)
    later = sim.lidar("lidar")
    assert later["index"] == 1 and later["time"] == pytest.approx(0.2)


def test_imu_of_a_resting_crate_reads_gravity_up():
    sim = rscene.Simulation(rscene.loads(ROOM))
    sim.step(5)
    assert sim.imu("/World/Imu") is None  # 10 Hz: the first reading at 0.1 s
    sim.step(95)
    r = sim.imu("imu")
    assert r["time"] == pytest.approx(1.0)
    assert r["specific_force"].dtype == np.float64 and r["specific_force"].shape == (3,)
    assert np.allclose(r["specific_force"], [0, 0, 9.81], atol=0.05)
    assert np.allclose(r["angular_velocity"], 0, atol=1e-3)


def test_sensor_misuse():
    sim = rscene.Simulation(rscene.loads(ROOM))
    with pytest.raises(KeyError, match="no LiDAR or IMU named"):
        sim.lidar("/World/Nothing")
    with pytest.raises(ValueError, match="is an IMU, not a LiDAR"):
        sim.lidar("/World/Imu")
    with pytest.raises(ValueError, match="is a LiDAR, not an IMU"):
        sim.imu("lidar")
    with pytest.raises(TypeError):
        sim.imu(None)


def test_a_scene_without_sensors():
    sim = rscene.Simulation(rscene.loads(ROOM.split("sensor ")[0]))
    assert sim.sensors() == []
    sim.step(3)


def test_anymal_sensor_set():
    urdf = ROOT / ".." / "shared" / "corpus" / "robots" / "anymal_c" / "urdf" / "anymal_sensored.urdf"
    if not urdf.exists():
        pytest.skip("../shared/corpus/robots/anymal_c is absent")
    sim = rscene.Simulation(rscene.loads(
        "raisim_engine_scene 1\ntime_step 0.0025\ngravity 0 0 -9.81\n"
        "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - "
        "static true 1 18446744073709551615\n"
        "articulated_resource anymal_res ANYmal %s\n"
        "articulated /World/Anymal anymal_res 0 0 0.54 1 0 0 0 true true id=anymal generalizedCoordinate="
        "0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8\n" % urdf))
    sensors = sim.sensors()
    lidars = [s["name"] for s in sensors if s["kind"] == "lidar"]
    imus = [s["name"] for s in sensors if s["kind"] == "imu"]
    assert lidars and imus and all(n.startswith("/World/Anymal/") for n in lidars + imus)
    sim.robot("anymal").set_pd_targets(sim.robot("anymal").q, 200, 4)
    sim.step(40)
    scan = sim.lidar(lidars[0])
    assert scan is not None and scan["points"].dtype == np.float32 and scan["points"].shape[1] == 3
    assert len(scan["points"]) > 100  # the ground around the robot
    assert np.all(np.isfinite(scan["points"]))
    reading = sim.imu(imus[0])
    assert reading is not None and np.linalg.norm(reading["specific_force"]) == pytest.approx(9.81, rel=0.3)
