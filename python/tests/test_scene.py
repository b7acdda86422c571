# The typed scene of `import rscene` (issue 28): doc.scene()'s views, read
# by lib/scene's model, and doc.set()'s edits, which change one field's
# text and keep every other byte as written.
import difflib

import numpy as np
import pytest

import rscene
from conftest import ROOT

CELL = ROOT / "examples" / "robot_cell.rscene"

# Not canonical on purpose: a comment, "2.0", a flag written "yes", keys in
# no particular order, records out of the writer's order.
HAND = (
    "raisim_engine_scene 1\n"
    "# a hand-written scene\n"
    "time_step 0.001\n"
    "object /World/Box box 2.0 0 0.5 1 0 0 0 1 1 1 1 1 1.0 default engine_default false yes false - dynamic true 1 "
    "18446744073709551615 id=box semanticClass=crate\n"
    "object /World/Box/Lid box 0 0 0.6 1 0 0 0 1 1 0.1 1 1 0.5 default engine_default false true false - dynamic true 1 "
    "18446744073709551615 id=lid parentGroupId=box\n"
    "gravity 0 0 -9.81\n"
    "camera /World/Cam -3 0 1 1 0 0 0 60 0.1 100 64 48 rgb true id=cam\n"
)


def changed_lines(a, b):
    """The lines of b that differ from a (a unified diff's + lines)."""
    return [l[1:] for l in difflib.unified_diff(a.splitlines(True), b.splitlines(True), n=0)
            if l.startswith("+") and not l.startswith("+++")]


def test_views_of_robot_cell():
    s = rscene.load(CELL).scene()
    assert [o.path for o in s.objects] == ["/World/Ground", "/World/Crate"]
    crate = s.find("object_crate")
    assert crate.path == "/World/Crate" and crate.record == s.objects[1].record
    assert isinstance(crate, rscene.SceneObject)
    assert crate.primitive == "box" and crate.body_mode == "dynamic" and crate.mass == 4
    assert crate.position.dtype == np.float64 and list(crate.position) == [2.0, -0.9, 0.25]
    assert list(crate.orientation) == [1, 0, 0, 0]
    assert list(crate.scale) == [0.5, 0.5, 0.5]
    assert crate.semantic_class == "crate" and crate.instance_id == 1
    assert crate.material == "mat_crate" and crate.collision_mask == 2**64 - 1
    assert s.objects[0].primitive == "ground" and s.objects[0].body_mode == "static"

    (cart,) = s.compounds
    assert cart.mass == 12 and list(cart.center_of_mass) == [0, 0, 0.1] and cart.inertia_diagonal is None
    assert [c.primitive for c in cart.children] == ["box", "cylinder"]
    assert list(cart.children[0].size) == [1.0, 0.6, 0.1]
    assert cart.children[1].radius == 0.1

    (robot,) = s.robots
    assert robot.path == "/World/Robot" and robot.floating_base
    # The record's view, not the simulated robot (rscene.Robot, sim.robot()).
    assert isinstance(robot, rscene.RobotRecord) and not isinstance(robot, rscene.Robot)
    assert robot.joint_names == ["LF_HAA", "LF_HFE", "LF_KFE", "RF_HAA", "RF_HFE", "RF_KFE",
                                 "LH_HAA", "LH_HFE", "LH_KFE", "RH_HAA", "RH_HFE", "RH_KFE"]
    assert robot.coordinate_names[:7] == ["base_x", "base_y", "base_z", "base_qw", "base_qx", "base_qy", "base_qz"]
    assert robot.coordinate_names[7:] == robot.joint_names
    assert len(robot.velocity_names) == 18 and robot.q.shape == (19,) and robot.u.shape == (18,)
    assert robot.q[9] == pytest.approx(-1.2)
    assert list(robot.generalized_coordinate) == list(robot.q)

    (cam,) = s.cameras
    assert (cam.width, cam.height, cam.vertical_fov, cam.render_mode) == (640, 400, 45, "rgb")
    kinds = {x.path: x.kind for x in s.sensors}
    assert kinds == {"/World/Robot/Imu": "imu", "/World/Robot/HeadCam": "rgb_depth", "/World/Robot/Lidar": "lidar"}
    head = s.find("sensor_head_cam")
    assert head.parent_link == "base" and head.horizontal_fov == 90 and head.segmentation
    assert s.time_step == 0.001 and list(s.gravity) == [0, 0, -9.81]
    assert [m.id for m in s.materials] == ["mat_metal", "mat_crate"]


def test_without_robot_models():
    (robot,) = rscene.load(CELL).scene(load_robots=False).robots
    assert robot.joint_names is None and robot.q is None
    assert robot.generalized_coordinate.shape == (19,)


def test_world_poses_and_defaults():
    s = rscene.loads(HAND).scene()
    box, lid = s.objects
    # The lid is parented to the box: its world pose inherits the box's.
    assert list(lid.position) == [0, 0, 0.6]
    assert list(lid.world_position) == pytest.approx([2, 0, 1.1])
    assert lid.semantic_class is None and lid.instance_id is None  # not written
    assert box.visible is True and box.collidable is True
    assert s.lights == [] and [c.path for c in s.cameras] == ["/World/Cam"]


def test_views_are_read_only():
    box = rscene.loads(HAND).scene().objects[0]
    with pytest.raises(AttributeError, match="read-only"):
        box.mass = 3
    with pytest.raises(ValueError):
        box.position[0] = 5
    with pytest.raises(AttributeError):
        box.no_such_field


def test_set_one_field_keeps_every_other_byte(tmp_path):
    doc = rscene.load(CELL)
    original = CELL.read_text()
    crate = doc.scene().find("/World/Crate")
    doc.set(crate, "mass", 2.5)
    out = tmp_path / "cell.rscene"
    doc.save(out, as_written=True)
    text = out.read_text()
    # One line differs, in one token: "4" became "2.5".
    diff = changed_lines(original, text)
    assert len(diff) == 1
    old_line = [l for l in original.splitlines() if l.startswith("object /World/Crate ")][0]
    assert diff[0].rstrip("\n") == old_line.replace(" 0 0 4 default", " 0 0 2.5 default")
    assert len(text) == len(original) - 1 + 3
    # The scene differs by that field alone, and reads it back.
    changes = rscene.diff(rscene.load(CELL), rscene.load(out))
    assert len(changes) == 1 and [f.name for f in changes[0].fields] == ["mass"]
    assert changes[0].fields[0].old == "4" and changes[0].fields[0].new == "2.5"
    assert rscene.load(out).scene().find("object_crate").mass == 2.5


def test_canonical_save_of_a_canonical_file(tmp_path):
    canonical = rscene.format(rscene.load(CELL))
    doc = rscene.loads(canonical)
    doc.set("object_crate", "position", np.array([1.0, 2.0, 3.0]))
    out = tmp_path / "c.rscene"
    doc.save(out)
    diff = changed_lines(canonical, out.read_text())
    assert len(diff) == 1 and " box 1 2 3 1 0 0 0 " in diff[0]


def test_keys_added_changed_removed():
    doc = rscene.loads(HAND)
    doc.set("lid", "semanticClass", "lid of the box")  # a new key, at the end of its line
    doc.set("box", "semantic_class", "big crate")        # snake_case, an existing key
    doc.update("box", {"customInertia": True, "inertiaDiagonal": (0.1, 0.2, 0.3)})  # a flag and a vec3 key
    doc.update("cam", {"width": 32, "height": 24})       # two positionals at once
    lines = doc.source.splitlines()
    assert lines[4].endswith(" parentGroupId=box semanticClass=lid%20of%20the%20box")
    assert " semanticClass=big%20crate customInertia=true inertiaDiagonal=0.1,0.2,0.3" in lines[3]
    assert lines[6] == "camera /World/Cam -3 0 1 1 0 0 0 60 0.1 100 32 24 rgb true id=cam"
    s = doc.scene()
    assert s.find("lid").semantic_class == "lid of the box"
    assert s.find("box").semantic_class == "big crate"
    assert list(s.find("box").inertia_diagonal) == [0.1, 0.2, 0.3]
    assert (s.cameras[0].width, s.cameras[0].height) == (32, 24)
    # None removes a key: its default applies again.
    doc.set("box", "semanticClass", None)
    doc.update("box", {"inertiaDiagonal": None, "custom_inertia": None})
    assert doc.source.splitlines()[3] == HAND.splitlines()[3].replace(" semanticClass=crate", "")
    assert doc.scene().find("box").semantic_class is None
    # Everything else as written: the comment, "2.0", "yes", the record order.
    assert changed_lines(HAND, doc.source) == [
        doc.source.splitlines(True)[3], doc.source.splitlines(True)[4], doc.source.splitlines(True)[6]]


def test_singletons_and_record_numbers():
    doc = rscene.loads(HAND)
    doc.set("time_step", "dt", 0.002)
    doc.set("gravity", "gravity", [0, 0, -3.7])
    assert doc.source.splitlines()[2] == "time_step 0.002"
    assert doc.source.splitlines()[5] == "gravity 0 0 -3.7"
    s = doc.scene()
    assert s.time_step == 0.002 and list(s.gravity) == [0, 0, -3.7]
    box = s.objects[0]
    doc.set(box.record, "mass", 3)
    box.set("radius", 0.25)  # through the view: the same document
    assert doc.scene().objects[0].mass == 3 and doc.scene().objects[0].radius == 0.25
    # The edited scene is what simulation reads.
    assert rscene.Simulation(doc).time_step == 0.002


def test_edit_errors():
    doc = rscene.loads(HAND)
    before = doc.source
    with pytest.raises(KeyError, match="nope"):
        doc.set("nope", "mass", 1)
    with pytest.raises(ValueError, match="2 records"):
        doc.set("object", "mass", 1)
    # An unknown record number is an unknown record, as the doc string says.
    with pytest.raises(KeyError, match="record 0 is not in the document"):
        doc.set(0, "mass", 1)
    with pytest.raises(KeyError, match="record 999 is not in the document"):
        doc.set(999, "mass", 1)
    with pytest.raises(KeyError, match="record 10{30} is not"):
        doc.set(10**30, "mass", 1)
    with pytest.raises(ValueError, match="no field 'weight'"):
        doc.set("box", "weight", 1)
    with pytest.raises(ValueError, match="expected a number.*RS2001"):
        doc.set("box", "mass", "heavy")
    with pytest.raises(ValueError, match="3 numbers"):
        doc.set("box", "position", [1, 2])
    with pytest.raises(ValueError, match="RS2006"):
        doc.set("box", "primitive", "blob")
    with pytest.raises(ValueError, match="positional"):
        doc.set("box", "mass", None)
    with pytest.raises(ValueError, match="not finite"):
        doc.set("box", "mass", float("nan"))
    with pytest.raises(TypeError):
        doc.set("box", "mass", object())
    with pytest.raises(TypeError):
        doc.set(1.5, "mass", 1)
    assert doc.source == before  # a refused edit changes nothing


def test_edit_numbers_past_the_types_range():
    # From a fresh-user trial: these leaked nlohmann's "[json.exception.
    # out_of_range.406] number overflow" or a JSON-form message.
    doc = rscene.loads(HAND)
    before = doc.source
    with pytest.raises(ValueError, match=r"^mass: 1e400 is not a finite number"):
        doc.set("box", "mass", 10**400)
    with pytest.raises(ValueError, match=r"^position: -1\.5e400 is not a finite number"):
        doc.set("box", "position", [0, 0, -15 * 10**399])
    with pytest.raises(ValueError, match=r"^collisionMask: 18446744073709551616 is out of the unsigned 64-bit range"):
        doc.set("box", "collisionMask", 2**64)
    with pytest.raises(ValueError, match=r"^collisionGroup: -1 is out of the unsigned 64-bit range"):
        doc.set("box", "collision_group", -1)
    assert doc.source == before
    # The edges of the ranges are values.
    doc.set("box", "collisionMask", 2**64 - 1)
    doc.set("box", "collisionGroup", np.uint64(2**64 - 1))
    doc.set("box", "mass", 10**30)
    assert doc.scene().find("box").mass == 1e30


def test_save_as_written_takes_a_bool(tmp_path):
    doc = rscene.loads(HAND)
    with pytest.raises(TypeError, match="as_written must be a bool"):
        doc.save(tmp_path / "a.rscene", as_written="no")
    with pytest.raises(TypeError, match="as_written must be a bool"):
        doc.save(tmp_path / "a.rscene", as_written=1)
    assert not (tmp_path / "a.rscene").exists()
    doc.save(tmp_path / "a.rscene", as_written=np.bool_(True))
    assert (tmp_path / "a.rscene").read_text() == HAND


def test_other_holders_keep_their_document():
    doc = rscene.loads(HAND)
    sim = rscene.Simulation(doc)
    doc.set("time_step", "dt", 0.004)
    assert sim.time_step == 0.001
    assert rscene.Simulation(doc).time_step == 0.004


def test_readme_typed_scene_runs(tmp_path, monkeypatch, capsys):
    section = (ROOT / "README.md").read_text().split("\n### The typed scene\n", 1)[1]
    code = section.split("```python\n", 1)[1].split("```\n", 1)[0]
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out.splitlines()
    # What the comments in the example say it prints.
    for line, printed in zip(code.splitlines()[5:7], out):
        assert printed == line.split("# ", 1)[1].strip()
    assert len(changed_lines(CELL.read_text(), (tmp_path / "heavier.rscene").read_text())) == 2
