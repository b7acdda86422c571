# Rendering from Python (issue 28): rscene.render/render_depth/
# render_segmentation and Renderer, checked against closed-form pixels and
# against rscene-render's own PNG of the same scene.
import struct
import threading
import zlib

import numpy as np
import pytest

import rscene
from conftest import ROOT, corpus_scene, tool

pytestmark = pytest.mark.skipif(not rscene.render_available(), reason="built without lib/render")

HEAD = "raisim_engine_scene 1\ntime_step 0.001\n"
RED = "material red 1 0 0 1 0 0.8 0 0 0 0 false - - - - - - id=red\n"
# A unit red box whose near face is 2.5 m in front of the camera, centred
# on its axis; the camera looks along +x from (0, 0, 1).
FRONT = HEAD + RED + (
    "object /World/Box box 3 0 1 1 0 0 0 1 1 1 1 1 1 default red false true false - static true 1 "
    "18446744073709551615 id=box\n"
    "camera /World/Cam 0 0 1 1 0 0 0 60 0.1 100 64 48 rgb true id=cam\n")
# A dynamic box falling (no ground) under a camera at z = 10 looking down.
FALL = HEAD + RED + (
    "object /World/Box box 0 0 5 1 0 0 0 1 1 1 1 1 1 default red false true false - dynamic true 1 "
    "18446744073709551615 id=box\n"
    "camera /World/Cam 0 0 10 0.7071067811865476 0 0.7071067811865476 0 60 0.1 100 64 48 rgb true id=cam\n")


def read_png(path):
    """A PNG as a (H, W, C) uint8 array: 8-bit grey, RGB or RGBA, no
    interlace (what rscene-render writes), decoded with zlib alone."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    i, idat = 8, b""
    while i < len(data):
        (n,) = struct.unpack(">I", data[i:i + 4])
        kind, body = data[i + 4:i + 8], data[i + 8:i + 8 + n]
        i += 12 + n
        if kind == b"IHDR":
            w, h, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and interlace == 0
        elif kind == b"IDAT":
            idat += body
    ch = {0: 1, 2: 3, 6: 4}[color]
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(h, 1 + w * ch)
    out = np.zeros((h, w * ch), np.uint8)
    prev = np.zeros(w * ch, np.int32)
    for y in range(h):
        f, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        cur = np.zeros(w * ch, np.int32)
        if f in (0, 2):
            cur = (line + (prev if f == 2 else 0)) & 255
        else:
            for x in range(w * ch):
                a = cur[x - ch] if x >= ch else 0
                b = prev[x]
                c = prev[x - ch] if x >= ch else 0
                if f == 1:
                    p = a
                elif f == 3:
                    p = (a + b) // 2
                else:
                    e = a + b - c
                    pa, pb, pc = abs(e - a), abs(e - b), abs(e - c)
                    p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (line[x] + p) & 255
        out[y] = cur
        prev = cur
    return out.reshape(h, w, ch)


def test_colour_red_box_in_front():
    img = rscene.render(rscene.loads(FRONT))
    assert img.shape == (48, 64, 4) and img.dtype == np.uint8
    r, g, b, a = (int(v) for v in img[24, 32])
    assert r > 100 and r > 3 * g and r > 3 * b and a == 255
    # A corner sees the sky, not the box: not red.
    r, g, b, _ = (int(v) for v in img[0, 0])
    assert b > r


def test_depth_centre_is_distance_to_face():
    depth = rscene.render_depth(rscene.loads(FRONT))
    assert depth.shape == (48, 64) and depth.dtype == np.float32
    assert depth[24, 32] == pytest.approx(2.5, abs=2e-3)
    assert np.isnan(depth[0, 0])  # nothing hit
    # Depth is the distance along the axis, not along the ray: 2.5 across
    # the face (pixel column 36 is 0.27 m off the axis there: fy = 24 /
    # tan 30 deg), NaN past its edge at 0.5 m (column 45).
    assert depth[24, 36] == pytest.approx(2.5, abs=2e-3)
    assert depth[30, 28] == pytest.approx(2.5, abs=2e-3)
    assert np.isnan(depth[24, 45])


def test_segmentation_and_legend():
    seg, legend = rscene.render_segmentation(rscene.loads(FRONT))
    assert seg.shape == (48, 64, 4)
    (entry,) = legend["segments"]
    assert entry["path"] == "/World/Box" and entry["id"] == "box" and entry["kind"] == "object"
    assert list(seg[24, 32, :3]) == entry["color"]
    assert list(seg[0, 0, :3]) == legend["background"]["color"] == [0, 0, 0]
    r = rscene.Renderer(rscene.loads(FRONT))
    assert r.segment_of(seg[24, 32])["path"] == "/World/Box"
    assert r.segment_of(seg[0, 0]) is None


def test_matches_rscene_render_png(tmp_path):
    scene = tmp_path / "front.rscene"
    scene.write_text(FRONT)
    out = tmp_path / "front.png"
    code, _ = tool("rscene-render", scene, "-o", out)
    assert code == 0
    png = read_png(out)
    img = rscene.render(rscene.load(scene))
    assert png.shape == img.shape
    assert np.array_equal(png, img)


def test_matches_rscene_render_example(tmp_path):
    # A scene with lights, shadows, a robot and post-processing: the same
    # pixels as the tool at the same size.
    scene = ROOT / "examples" / "robot_cell.rscene"
    out = tmp_path / "cell.png"
    code, _ = tool("rscene-render", scene, "--width", 160, "--height", 100, "-o", out)
    assert code == 0
    assert np.array_equal(read_png(out), rscene.render(rscene.load(scene), width=160, height=100))


def test_allow_missing_assets_as_rscene_render(tmp_path):
    # From a fresh-user trial: Python had no way to say
    # --allow-missing-assets; the corpus warehouse's meshes are not there.
    scene = corpus_scene("rayrai_warehouse.rscene")
    doc = rscene.load(scene)
    with pytest.raises(rscene.RenderError, match="RS5001"):
        rscene.render(doc, width=64, height=48)
    img = rscene.render(doc, width=64, height=48, allow_missing_assets=True)
    out = tmp_path / "w.png"
    code, _ = tool("rscene-render", scene, "--allow-missing-assets", "--width", 64, "--height", 48, "-o", out)
    assert code == 0
    assert np.array_equal(read_png(out), img)
    r = rscene.Renderer(doc, width=64, height=48, allow_missing_assets=True)
    assert np.array_equal(r.draw(), img)
    assert any(d.severity == "warning" and d.code == "RS5001" for d in r.diagnostics)
    assert rscene.render_depth(doc, width=64, height=48, allow_missing_assets=True).shape == (48, 64)
    seg, legend = rscene.render_segmentation(doc, width=64, height=48, allow_missing_assets=True)
    assert seg.shape == (48, 64, 4) and legend["segments"]
    with pytest.raises(TypeError, match="allow_missing_assets must be a bool"):
        rscene.Renderer(doc, allow_missing_assets="yes")


def test_base_dir_as_rscene_render(tmp_path):
    # A scene from text has no folder: base_dir (--base-dir) says where
    # its relative asset paths start.
    examples = ROOT / "examples"
    doc = rscene.loads((examples / "robot_cell.rscene").read_text())
    with pytest.raises(rscene.RenderError, match="does not exist.*RS5001"):
        rscene.render(doc, width=96, height=60)
    expected = rscene.render(rscene.load(examples / "robot_cell.rscene"), width=96, height=60)
    assert np.array_equal(rscene.render(doc, width=96, height=60, base_dir=examples), expected)
    assert np.array_equal(rscene.render(doc, width=96, height=60, base_dir=str(examples)), expected)
    # (A Renderer tessellates for any view, render() for its one: compare like with like.)
    assert np.array_equal(rscene.Renderer(doc, width=96, height=60, base_dir=examples).draw(),
                          rscene.Renderer(rscene.load(examples / "robot_cell.rscene"), width=96, height=60).draw())
    assert rscene.render_depth(doc, width=96, height=60, base_dir=examples).shape == (60, 96)
    assert rscene.render_segmentation(doc, width=96, height=60, base_dir=examples)[0].shape == (60, 96, 4)
    with pytest.raises(TypeError, match="base_dir must be a path"):
        rscene.render(doc, base_dir=3)
    with pytest.raises(ValueError, match="base_dir must name a folder"):
        rscene.render(doc, base_dir="")


def test_depth_matches_rscene_render_npy(tmp_path):
    text = FRONT.replace("64 48 rgb true", "64 48 depth true")
    scene = tmp_path / "d.rscene"
    scene.write_text(text)
    code, _ = tool("rscene-render", scene, "--all-cameras", "-o", tmp_path / "{name}.{kind}.png")
    assert code == 0
    npy = np.load(tmp_path / "World_Cam.depth.npy")
    depth = rscene.render_depth(rscene.load(scene))
    assert np.array_equal(np.isnan(npy), np.isnan(depth))
    assert np.array_equal(npy[~np.isnan(npy)], depth[~np.isnan(depth)])


def test_renderer_draws_simulation_poses():
    doc = rscene.loads(FALL)
    sim = rscene.Simulation(doc)
    r = rscene.Renderer(doc)
    assert r.draw_depth(sim)[24, 32] == pytest.approx(10 - 5.5, abs=2e-3)
    sim.step(300)
    z = sim.body_pose("/World/Box")[2]
    assert z < 4.6
    out = r.draw_passes(sim)
    assert set(out) == {"rgb", "depth", "segmentation", "view"}
    assert out["depth"][24, 32] == pytest.approx(10 - (z + 0.5), abs=2e-3)
    # The same image as the scene written back, drawn afresh.
    assert np.array_equal(out["rgb"], rscene.Renderer(sim.document()).draw())
    # A draw without the simulation shows the document as written again.
    assert r.draw_depth()[24, 32] == pytest.approx(10 - 5.5, abs=2e-3)
    assert r.draw_depth(sim)[24, 32] == pytest.approx(10 - (z + 0.5), abs=2e-3)


def test_plain_draw_after_simulation_draws_the_document():
    # From a fresh-user trial: after draw(sim), draw() still showed the
    # simulation's poses.  Every pass, and a robot's links, go back.
    doc = rscene.load(ROOT / "examples" / "robot_cell.rscene")
    r = rscene.Renderer(doc, width=160, height=100)
    before = r.draw_passes()
    sim = rscene.Simulation(doc)
    sim.step(1000)
    moved = r.draw(sim)
    assert not np.array_equal(before["rgb"], moved)
    after = r.draw_passes()
    assert np.array_equal(before["rgb"], after["rgb"])
    assert np.array_equal(before["segmentation"], after["segmentation"])
    assert np.array_equal(before["depth"], after["depth"], equal_nan=True)
    assert np.array_equal(after["rgb"], rscene.Renderer(doc, width=160, height=100).draw())
    # And the simulation's poses again when given it.
    assert np.array_equal(r.draw(sim), moved)


def test_plain_draw_after_simulation_puts_particles_back():
    # Deformable and granular particles too (soft_bodies has both).
    doc = rscene.load(ROOT / "examples" / "soft_bodies.rscene")
    r = rscene.Renderer(doc, width=96, height=64)
    before = r.draw()
    sim = rscene.Simulation(doc)
    sim.step(150)
    moved = r.draw(sim)
    assert not np.array_equal(before, moved)
    assert np.array_equal(r.draw(), before)
    assert np.array_equal(r.draw(sim), moved)


def test_renderer_robot_follows_simulation():
    doc = rscene.load(ROOT / "examples" / "robot_cell.rscene")
    r = rscene.Renderer(doc, width=96, height=60)
    sim = rscene.Simulation(doc)
    sim.step(200)
    moved = r.draw(sim)
    assert np.array_equal(moved, rscene.Renderer(sim.document(), width=96, height=60).draw())


def test_renderer_cameras_and_sizes():
    r = rscene.Renderer(rscene.loads(FRONT))
    assert [v["name"] for v in r.views] == ["/World/Cam"]
    assert r.draw(camera="cam").shape == (48, 64, 4)
    assert r.backend[0] in ("cpu", "gpu") and r.backend[1]
    assert r.draw(width=20, height=10).shape == (10, 20, 4)
    assert r.draw(camera="auto", width=30).shape == (720, 30, 4)
    # A look-at view from the camera's own place sees the same face.
    d = r.draw_depth(camera=rscene.LookAt((0, 0, 1), (3, 0, 1), fov=60), width=64, height=48)
    assert d[24, 32] == pytest.approx(2.5, abs=2e-3)
    d = r.draw_depth(camera=rscene.LookAt((-1, 0, 1), (3, 0, 1)), width=64, height=48)
    assert d[24, 32] == pytest.approx(3.5, abs=2e-3)


def test_misuse_raises_clear_errors():
    doc = rscene.loads(FRONT)
    with pytest.raises(rscene.RenderError, match="'nope'.*/World/Cam"):
        rscene.render(doc, camera="nope")
    with pytest.raises(ValueError, match="width must be at least 1"):
        rscene.render(doc, width=0)
    with pytest.raises(ValueError, match="16384"):
        rscene.render(doc, width=20000)
    with pytest.raises(rscene.RenderError, match="25000000 pixels"):
        rscene.render(doc, width=5000, height=5000)
    with pytest.raises(TypeError):
        rscene.render(doc, camera=5)
    with pytest.raises(TypeError):
        rscene.render(doc, width=1.5)
    with pytest.raises(TypeError, match="samples must be an int"):
        rscene.render(doc, samples=True)
    with pytest.raises(ValueError, match="samples must be 1 to 64"):
        rscene.render(doc, samples=np.int64(65))
    assert rscene.render(doc, samples=np.int64(1), width=np.int32(8), height=np.uint16(6)).shape == (6, 8, 4)
    with pytest.raises(TypeError):
        rscene.render("scene.rscene")
    with pytest.raises(rscene.RenderError, match="same point"):
        rscene.render(doc, camera=rscene.LookAt((0, 0, 0), (0, 0, 0)))
    with pytest.raises(rscene.RenderError, match="1 to 175"):
        rscene.render(doc, camera=rscene.LookAt((0, 0, 0), (1, 0, 0), fov=200))
    with pytest.raises(ValueError, match="3 numbers"):
        rscene.LookAt((0, 0), (1, 0, 0))
    r = rscene.Renderer(doc)
    with pytest.raises(ValueError, match="unknown pass"):
        r.draw_passes(passes=["normals"])
    with pytest.raises(TypeError):
        r.draw(sim="not a simulation")
    # A simulation of another scene: its bodies are not the renderer's.
    other = rscene.Simulation(rscene.loads(FALL.replace("/World/Box", "/World/Other")))
    with pytest.raises(rscene.RenderError, match="does not match"):
        r.draw(other)
    # Still usable afterwards.
    assert r.draw().shape == (48, 64, 4)


def test_messages_name_no_flag_python_lacks():
    # From a fresh-user trial: a camera record too large for the pixel
    # limit said "more than --max-pixels 16777216", hint "give --width and
    # --height, or raise --max-pixels": flags Python does not have.
    doc = rscene.loads(FRONT.replace("64 48 rgb true", "5000 5000 rgb true"))
    with pytest.raises(rscene.RenderError) as e:
        rscene.render(doc)
    text = str(e.value) + "".join(str(d) for d in e.value.diagnostics)
    assert "more than the pixel limit 16777216" in str(e.value)
    assert "--" not in text
    assert e.value.diagnostics[0].hint == "give a smaller width and height"
    # A missing mesh drawn as a placeholder: the warning names the keyword.
    doc = rscene.loads(FRONT.replace("box 3 0 1", "mesh 3 0 1").replace("false - static", "false gone.obj static"))
    r = rscene.Renderer(doc, allow_missing_assets=True)
    r.draw()
    assert r.diagnostics and not any("--" in str(d) for d in r.diagnostics)


def test_scene_with_errors_raises():
    # A mesh object without a mesh file (RS7004): an error at its record.
    doc = rscene.loads(FRONT.replace("box 3 0 1", "mesh 3 0 1"))
    with pytest.raises(rscene.RenderError) as e:
        rscene.render(doc)
    assert e.value.diagnostics and e.value.diagnostics[0].severity == "error"


def test_threads_draw_in_turn():
    doc = rscene.loads(FRONT)
    expected = rscene.Renderer(doc).draw()
    renderers = [rscene.Renderer(doc) for _ in range(3)]
    results = [None] * 6

    def work(i):
        results[i] = renderers[i % 3].draw()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(x, expected) for x in results)


# A depth sensor on the falling box, looking up at a static slab whose
# underside is at z = 9.5.
RIDER = HEAD + RED + (
    "object /World/Box box 0 0 5 1 0 0 0 1 1 1 1 1 1 default red false true false - dynamic true 1 "
    "18446744073709551615 id=box\n"
    "object /World/Slab box 0 0 10 1 0 0 0 20 20 1 1 1 1 default red false true false - static true 1 "
    "18446744073709551615 id=slab\n"
    "sensor /World/Eye depth box 0 0 0.6 0.7071067811865476 0 -0.7071067811865476 0 id=eye width=32 height=24 "
    "verticalFov=60\n")


def test_sensor_rides_on_simulated_body():
    doc = rscene.loads(RIDER)
    r = rscene.Renderer(doc, camera="eye")
    assert r.views[0]["sensor"] and r.views[0]["name"] == "/World/Eye"
    d = r.draw_depth()
    assert d.shape == (24, 32)
    assert d[12, 16] == pytest.approx(9.5 - 5.6, abs=2e-3)
    sim = rscene.Simulation(doc)
    sim.step(300)
    z = sim.body_pose("box")[2]
    assert d[12, 16] + 0.3 < r.draw_depth(sim)[12, 16] == pytest.approx(9.5 - (z + 0.6), abs=2e-3)
    # A sensor keeps its own size: asking for another warns.
    with pytest.warns(RuntimeWarning, match="keeps its own size"):
        assert r.draw_depth(width=100).shape == (24, 32)


def readme_block(heading):
    """The first python block under a README heading."""
    section = (ROOT / "README.md").read_text().split("\n" + heading + "\n", 1)[1]
    return section.split("```python\n", 1)[1].split("```\n", 1)[0]


def test_readme_depth_dataset_runs(tmp_path, monkeypatch):
    code = readme_block("### Rendering from Python")
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the example warns of nothing
        exec(compile(code, "README.md", "exec"), {})
    depths = [np.load(tmp_path / ("depth_%03d.npy" % i)) for i in range(8)]
    assert all(d.shape == (120, 160) and d.dtype == np.float32 for d in depths)
    # Each view sees the scene: most pixels hit something, nearer than 100 m.
    assert all(np.isfinite(d).mean() > 0.5 and np.nanmin(d) > 0.5 for d in depths)
    head = np.load(tmp_path / "head_002.npy")
    assert head.shape == (240, 320) and np.isfinite(head).any()


@pytest.mark.parametrize("name", ["soft_bodies", "robot_cell"])
def test_draw_sim_matches_rscene_render_trajectory(tmp_path, name):
    # renderer.draw(sim) is the frame rscene-render --trajectory draws of
    # what rscene-sim --trajectory writes at that step: bodies, a robot's
    # joints, deformable and granular particles alike.
    scene = ROOT / "examples" / (name + ".rscene")
    traj = tmp_path / "t.jsonl"
    code, _ = tool("rscene-sim", scene, "--steps", 150, "--every", 150, "--trajectory", traj, "-o", tmp_path / "o.rscene")
    assert code == 0
    code, _ = tool("rscene-render", scene, "--trajectory", traj, "--width", 96, "--height", 64,
                   "-o", tmp_path / "f{frame}.png")
    assert code == 0
    doc = rscene.load(scene)
    r = rscene.Renderer(doc, width=96, height=64)
    sim = rscene.Simulation(doc)
    first = r.draw(sim)
    sim.step(150)
    last = r.draw(sim)
    assert np.array_equal(read_png(tmp_path / "f000000.png"), first)
    assert np.array_equal(read_png(tmp_path / "f000001.png"), last)
    assert not np.array_equal(first, last)
