# rscene.Simulation (issue 28, first step): prepared and stepped as
# rscene-sim does, poses as numpy arrays, the scene written back as
# rscene-sim -o writes it.
import threading

import numpy as np
import pytest

import rscene
from conftest import ROOT, corpus_scene, tool

DROP = (
    "raisim_engine_scene 1\n"
    "time_step 0.001\n"
    "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default engine_default false true false - static true 1 "
    "18446744073709551615\n"
    "object /World/Box box 0 0 {z} 1 0 0 0 0.2 0.2 0.2 1 1 1 default engine_default false true false - dynamic true 1 "
    "18446744073709551615 id=box\n"
)


def test_box_falls_and_rests():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    assert sim.time == 0 and sim.steps == 0 and sim.time_step == 0.001
    start = sim.body_pose("/World/Box")
    assert start.dtype == np.float64 and start.shape == (7,)
    assert start.tolist() == [0, 0, 1, 1, 0, 0, 0]
    sim.step(1000)
    assert sim.steps == 1000 and sim.time == pytest.approx(1.0)
    pose = sim.body_pose("/World/Box")
    assert pose[2] == pytest.approx(0.1, abs=2e-3)  # a 0.2 m box resting on the ground
    assert np.array_equal(pose, sim.body_pose("box"))  # by id too
    assert sim.contact_count > 0
    velocity = sim.body_velocity("/World/Box")
    assert velocity.shape == (6,) and np.all(np.abs(velocity) < 0.05)  # at rest


def test_falling_velocity():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=5)))
    assert sim.body_velocity("box").tolist() == [0] * 6
    sim.step(100)  # 0.1 s of free fall
    vx, vy, vz, wx, wy, wz = sim.body_velocity("box")
    assert vz == pytest.approx(-9.81 * 0.1, rel=0.02)
    assert (vx, vy, wx, wy, wz) == pytest.approx((0, 0, 0, 0, 0), abs=1e-9)
    with pytest.raises(KeyError):
        sim.body_velocity("/World/Ground")


def test_document_matches_rscene_sim(tmp_path):
    path = tmp_path / "drop.rscene"
    path.write_text(DROP.format(z=1))
    sim = rscene.Simulation(rscene.load(path))
    sim.step(300)
    sim.step(200)  # stepping in parts is stepping once
    out = tmp_path / "out.rscene"
    tool("rscene-sim", "--steps", 500, "-o", out, path)
    assert rscene.format(sim.document()) == out.read_text()


def test_robot_scene_steps():
    sim = rscene.Simulation(rscene.load(ROOT / "examples" / "robot_cell.rscene"))
    sim.step(10)
    assert np.all(np.isfinite(sim.body_pose("/World/Crate")))
    doc = sim.document()
    assert "generalizedCoordinate=" in rscene.format(doc)


def test_scene_that_cannot_be_simulated():
    with pytest.raises(rscene.SimulationError) as e:
        rscene.Simulation(rscene.loads(DROP.format(z="1x")))
    # As rscene-sim reports it: the warning about the start overlap, then the error.
    errors = [d for d in e.value.diagnostics if d.severity == "error"]
    assert [d.code for d in errors] == ["RS2001"]
    assert str(e.value).startswith("<scene>:4:27: error: expected a number, found '1x' [RS2001]")


def test_allow_missing_assets_as_rscene_sim(tmp_path):
    # From a fresh-user trial: Python had no way to say
    # --allow-missing-assets; the corpus warehouse's meshes are not there.
    scene = corpus_scene("rayrai_warehouse.rscene")
    doc = rscene.load(scene)
    with pytest.raises(rscene.SimulationError) as e:
        rscene.Simulation(doc)
    assert "RS5001" in str(e.value)
    sim = rscene.Simulation(doc, allow_missing_assets=True)
    assert sim.diagnostics and all(d.severity == "warning" for d in sim.diagnostics)
    sim.step(50)
    out = tmp_path / "out.rscene"
    code, _ = tool("rscene-sim", "--steps", 50, "--allow-missing-assets", "-o", out, scene)
    assert code == 0
    assert rscene.format(sim.document()) == out.read_text()
    with pytest.raises(TypeError, match="allow_missing_assets must be a bool"):
        rscene.Simulation(doc, allow_missing_assets=1)


def test_base_dir_as_rscene_sim(tmp_path):
    # A scene from text has no folder: base_dir (--base-dir) says where
    # its relative asset paths (here a robot file) start.
    examples = ROOT / "examples"
    text = (examples / "robot_cell.rscene").read_text()
    with pytest.raises(rscene.SimulationError, match="does not exist.*RS5001"):
        rscene.Simulation(rscene.loads(text))
    sim = rscene.Simulation(rscene.loads(text), base_dir=examples)
    sim.step(20)
    out = tmp_path / "out.rscene"
    code, _ = tool("rscene-sim", "--steps", 20, "-o", out, examples / "robot_cell.rscene")
    assert code == 0
    assert rscene.format(sim.document()) == out.read_text()
    # A file's own folder gives way to base_dir, as with --base-dir.
    (tmp_path / "cell.rscene").write_text(text)
    with pytest.raises(rscene.SimulationError, match="RS5001"):
        rscene.Simulation(rscene.load(tmp_path / "cell.rscene"))
    assert rscene.Simulation(rscene.load(tmp_path / "cell.rscene"), base_dir=str(examples)).robots
    with pytest.raises(TypeError, match="base_dir must be a path"):
        rscene.Simulation(rscene.loads(text), base_dir=1)
    # Without the robot file, allowed: left out, the warning naming the
    # keyword (not rscene-sim's flag).
    sim = rscene.Simulation(rscene.loads(text), allow_missing_assets=True)
    assert sim.robots == []
    assert "left out (allow_missing_assets=True)" in sim.diagnostics[0].message
    assert not any("--" in str(d) for d in sim.diagnostics)


def test_step_takes_any_integral():
    # From a fresh-user trial: sim.step(np.int64(2)) raised TypeError.
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    sim.step(np.int64(2))
    sim.step(np.uint8(3))
    sim.step(np.arange(5)[4])
    assert sim.steps == 9
    for bad in (True, np.bool_(True), 1.0, np.float64(2), "3", None):
        with pytest.raises(TypeError, match="must be an int"):
            sim.step(bad)
    assert sim.steps == 9


def test_step_after_a_failure_raises_the_failure_again():
    # A body whose inertia underflows passes the up-front checks and is
    # stopped at its first step (RS7024, as in shell-tests/sim.bats).
    doc = rscene.loads(DROP.format(z=1).replace("0.2 0.2 0.2 1 1 1 default", "0.2 0.2 0.2 1 1 2.2250738585072014e-308 default"))
    sim = rscene.Simulation(doc)
    with pytest.raises(rscene.SimulationError) as first:
        sim.step(10)
    assert [d.code for d in first.value.diagnostics] == ["RS7024"]
    # Python writes nothing: the message does not say rscene-sim's words.
    assert first.value.diagnostics[0].message.endswith("the simulation stopped")
    # From a fresh-user trial: the next call raised a plain ValueError
    # without the diagnostics.
    with pytest.raises(rscene.SimulationError) as again:
        sim.step(1)
    assert again.value.diagnostics == first.value.diagnostics
    assert str(again.value).startswith("the simulation stopped at an earlier failure")
    assert str(first.value.diagnostics[0]).split("\n")[0] in str(again.value)
    with pytest.raises(rscene.SimulationError):
        sim.step(0)


def test_misuse_raises():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    with pytest.raises(ValueError):
        sim.step(-1)
    with pytest.raises(TypeError):
        sim.step("10")
    with pytest.raises(TypeError):
        sim.step(1.5)
    with pytest.raises(KeyError):
        sim.body_pose("/World/Nope")
    with pytest.raises(KeyError):
        sim.body_pose("/World/Ground")  # static
    with pytest.raises(TypeError):
        sim.body_pose(3)
    with pytest.raises(TypeError):
        rscene.Simulation("not a document")
    sim.step(0)
    assert sim.steps == 0


def test_parallel_simulations_match_serial():
    heights = [0.5, 1.0, 1.5, 2.0]

    def run(z):
        sim = rscene.Simulation(rscene.loads(DROP.format(z=z)))
        sim.step(400)
        return sim.body_pose("/World/Box")

    serial = [run(z) for z in heights]
    results = [None] * len(heights)

    def worker(i):
        results[i] = run(heights[i])

    threads = [threading.Thread(target=worker, args=(i,)) for i in range(len(heights))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(serial, results):
        assert np.array_equal(a, b)


def test_one_simulation_shared_by_threads():
    sim = rscene.Simulation(rscene.loads(DROP.format(z=1)))
    threads = [threading.Thread(target=sim.step, args=(100,)) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sim.steps == 400
