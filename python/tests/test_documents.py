# The documents API of `import rscene` (issue 28): load/loads, format,
# save, validate, diff, to_json/from_json, each checked against the tool
# that does the same from the command line.
import json
import os
import stat
import threading

import pytest

import rscene
from conftest import CORPUS, EXAMPLES, ROOT, tool

SCENES = EXAMPLES + CORPUS
IDS = [os.path.relpath(p, ROOT.parent) for p in SCENES]

BROKEN = (
    "raisim_engine_scene 1\n"
    "time_step 0.001\n"
    "object /World/B box 0 0 1x 1 0 0 0 1 1 1 1 1 1 default nomat\n"
)

BOX = (
    "raisim_engine_scene 1\n"
    "time_step 0.001\n"
    "# the box\n"
    "object /World/Box box {x} 0 0.5 1 0 0 0 1 1 1 1 1 1 default engine_default false true false - dynamic true 1 "
    "18446744073709551615 id=box\n"
)


def test_examples_present():
    assert len(EXAMPLES) >= 3


def test_corpus_optional():
    if not CORPUS:
        pytest.skip("../shared/corpus has no scenes")
    assert all(p.suffix == ".rscene" for p in CORPUS)


@pytest.mark.parametrize("path", SCENES, ids=IDS)
def test_round_trip_lossless(path):
    doc = rscene.load(path)
    text = rscene.format(doc)
    # Canonical text is what rscene-fmt writes, byte for byte.
    _, fmt = tool("rscene-fmt", path)
    assert text.encode("utf-8", "surrogateescape") == fmt
    # Reading the canonical text back changes nothing, and is the same scene.
    again = rscene.loads(text)
    assert rscene.format(again) == text
    assert rscene.diff(doc, again) == []
    assert doc.source.encode("utf-8", "surrogateescape") == path.read_bytes()


@pytest.mark.parametrize("path", SCENES, ids=IDS)
def test_json_round_trip_matches_tool(path):
    doc = rscene.load(path)
    data = rscene.to_json(doc)
    _, out = tool("rscene-to-json", path)
    assert data == json.loads(out)
    back = rscene.from_json(data)
    assert rscene.format(back) == rscene.format(doc)
    # The tool reads what Python made from it.
    _, scene = tool("rscene-from-json", "-", stdin=json.dumps(data).encode())
    assert scene.decode("utf-8", "surrogateescape") == rscene.format(doc)


def test_comments_and_unknown_records_kept():
    text = ("raisim_engine_scene 1\n# head comment\ntime_step 0.001\n"
            "future_thing a b k=v\n# trailing\n")
    doc = rscene.loads(text)
    out = rscene.format(doc)
    assert "# head comment" in out and "# trailing" in out and "future_thing a b k=v" in out
    assert "future_thing" in doc.tags()


def test_validate_codes_match_tool(tmp_path):
    path = tmp_path / "broken.rscene"
    path.write_text(BROKEN)
    found = rscene.validate(rscene.load(path))
    rc, out = tool("rscene-validate", "--format", "json", path)
    assert rc == 1
    expected = json.loads(out)["files"][0]["findings"]
    assert [d.code for d in found] == [e["code"] for e in expected] == ["RS2001", "RS3008"]
    for d, e in zip(found, expected):
        assert (d.severity, d.line, d.column, d.message, d.hint) == \
            (e["severity"], e["line"], e["column"], e["message"], e["hint"])
    assert str(found[0]).startswith(str(path) + ":3:25: error: expected a number")


def test_validate_clean_and_profile():
    doc = rscene.loads(BOX.format(x=0))
    assert rscene.validate(doc) == []
    with pytest.raises(ValueError, match="profile"):
        rscene.validate(doc, profile="bogus")


def test_diff_moved_box():
    a = rscene.loads(BOX.format(x=0))
    b = rscene.loads(BOX.format(x=2))
    changes = rscene.diff(a, b)
    assert len(changes) == 1
    c = changes[0]
    assert (c.change, c.tag, c.path) == ("changed", "object", "/World/Box")
    assert [(f.name, f.change, f.old, f.new) for f in c.fields] == [("position", "changed", "0,0,0.5", "2,0,0.5")]
    assert rscene.diff(a, b, tolerance=2) == []
    assert rscene.diff(a, b, ignore=["position"]) == []
    with pytest.raises(ValueError, match="ignore"):
        rscene.diff(a, b, ignore=["positon"])


def test_diff_names_a_robots_coordinates_by_joint_as_rscene_diff_does():
    path = ROOT / "examples" / "robot_cell.rscene"
    a = rscene.load(path)
    text = path.read_text().replace("0,0,0.3882,1,0,0,0,0,0.6,-1.2,", "0,0,0.3882,1,0,0,0,0,0.7,-1.2,", 1)
    b = rscene.loads(text, name=str(path))
    (change,) = [c for c in rscene.diff(a, b) if c.path == "/World/Robot"]
    names = [f.name for f in change.fields if f.entry]
    assert names == ["generalizedCoordinate[LF_HFE]"], names
    status, out = tool("rscene-diff", "--format", "json", "--stdin-filename", path, path, "-", check=False,
                       stdin=text.encode())
    assert status == 1
    assert "generalizedCoordinate[LF_HFE]" in out.decode()


def test_parse_error_carries_diagnostics():
    with pytest.raises(rscene.ParseError) as e:
        rscene.loads("not a scene\n", name="bad.rscene")
    assert e.value.diagnostics[0].code == "RS1001"
    assert e.value.diagnostics[0].severity == "error"
    assert str(e.value).startswith("bad.rscene:1:1: error:")
    assert isinstance(e.value, ValueError)


def test_from_json_refuses_non_scene():
    with pytest.raises(rscene.ParseError) as e:
        rscene.from_json({"format": "nope"})
    assert e.value.diagnostics[0].code.startswith("RS8")
    with pytest.raises(TypeError):
        rscene.from_json("{}")


def test_misuse_raises():
    with pytest.raises(TypeError):
        rscene.format("raisim_engine_scene 1\n")
    with pytest.raises(TypeError):
        rscene.loads(42)
    with pytest.raises(TypeError):
        rscene.Document()
    with pytest.raises(FileNotFoundError):
        rscene.load("/nonexistent/x.rscene")
    with pytest.raises(TypeError):
        rscene.diff(rscene.loads(BOX.format(x=0)), None)


def test_save_writes_canonical_atomically(tmp_path):
    doc = rscene.loads(BOX.format(x=1))
    out = tmp_path / "out.rscene"
    out.write_text("old")
    out.chmod(0o640)
    doc.save(out)
    assert out.read_text() == rscene.format(doc)
    assert stat.S_IMODE(out.stat().st_mode) == 0o640  # mode kept, as the tools do
    assert sorted(os.listdir(tmp_path)) == ["out.rscene"]  # no temporary file left


def test_save_through_symlink_keeps_link(tmp_path):
    doc = rscene.loads(BOX.format(x=1))
    target = tmp_path / "target.rscene"
    target.write_text("old")
    link = tmp_path / "link.rscene"
    link.symlink_to(target.name)
    doc.save(link)
    assert link.is_symlink() and target.read_text() == rscene.format(doc)


def test_save_refusals(tmp_path):
    doc = rscene.loads(BOX.format(x=1))
    dangling = tmp_path / "dangling.rscene"
    dangling.symlink_to("nowhere/x.rscene")
    with pytest.raises(OSError, match="dangling"):
        doc.save(dangling)
    assert dangling.is_symlink() and not dangling.exists()
    with pytest.raises(OSError):
        doc.save(tmp_path)  # a directory
    linked = tmp_path / "a.rscene"
    linked.write_text("old")
    os.link(linked, tmp_path / "b.rscene")
    with pytest.raises(OSError, match="hard link"):
        doc.save(linked)
    assert linked.read_text() == "old"
    readonly = tmp_path / "ro.rscene"
    readonly.write_text("old")
    readonly.chmod(0o444)
    with pytest.raises(OSError):
        doc.save(readonly)
    assert readonly.read_text() == "old"


def test_save_writes_through_fifo(tmp_path):
    doc = rscene.loads(BOX.format(x=1))
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()))
    reader.start()
    doc.save(fifo)  # the GIL is released while it waits for the reader
    reader.join(timeout=30)
    assert got == [rscene.format(doc).encode()]
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)  # written through, not replaced


def test_bytes_that_are_not_utf8_never_raise_unicode_errors():
    # %FF decodes to a byte that is not UTF-8: kept, compared and shown.
    scene = ("raisim_engine_scene 1\ntime_step 0.001\n"
             "material m%{} 1 1 1 1 0 0.5 0 0 0 0 false - - - - - - id=x\n")
    a, b = rscene.loads(scene.format("FF")), rscene.loads(scene.format("FE"))
    [change] = rscene.diff(a, b)
    assert [(f.name, f.old, f.new) for f in change.fields] == [("name", "m%FF", "m%FE")]
    assert rscene.to_json(a)["records"][2]["fields"]["name"] == {"raw": "m%FF"}
    assert rscene.format(rscene.from_json(rscene.to_json(a))) == rscene.format(a)


def test_bad_paths_and_json_raise_cleanly(tmp_path):
    doc = rscene.loads(BOX.format(x=0))
    with pytest.raises(ValueError, match="null"):
        doc.save(str(tmp_path / "a\0b"))
    with pytest.raises(TypeError):
        doc.save(None)
    assert os.listdir(tmp_path) == []
    deep = json.loads("[" * 900 + "]" * 900)
    with pytest.raises(rscene.ParseError):
        rscene.from_json({"format": "rscene", "version": 1, "records": deep})
    with pytest.raises(rscene.ParseError):  # a lone surrogate is no JSON string
        rscene.from_json({"format": "rscene", "version": 1,
                          "records": [{"tag": "raisim_engine_scene", "fields": {"version": "\udcff"}}]})


def test_threads_give_the_serial_results():
    from concurrent.futures import ThreadPoolExecutor
    docs = [rscene.load(p) for p in SCENES]
    serial = [([str(d) for d in rscene.validate(doc)], rscene.format(doc)) for doc in docs]
    with ThreadPoolExecutor(4) as pool:
        parallel = list(pool.map(lambda doc: ([str(d) for d in rscene.validate(doc)], rscene.format(doc)), docs * 2))
    assert parallel == serial * 2


def test_readme_example_runs(tmp_path, monkeypatch, capsys):
    # The README's Python example, exactly as printed there, in a folder
    # where examples/ is the repository's.
    readme = (ROOT / "README.md").read_text()
    section = readme.split("\n## Python\n", 1)[1]
    code = section.split("```python\n", 1)[1].split("```\n", 1)[0]
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "changed time_step" in out and "[RS1001]" in out
    assert "time_step 0.002" in (tmp_path / "faster.rscene").read_text()
    assert (tmp_path / "after.rscene").read_text() != (ROOT / "examples" / "robot_cell.rscene").read_text()


def test_every_public_name_has_a_doc_string_and_a_stub():
    import ast
    import inspect
    stub = ast.parse((ROOT / "python" / "rscene" / "__init__.pyi").read_text())
    stubbed = {n.name for n in stub.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    assert set(rscene.__all__) <= stubbed
    assert rscene.__doc__ and "ParseError" in rscene.__doc__
    for name in rscene.__all__:
        obj = getattr(rscene, name)
        assert inspect.getdoc(obj), name
        if inspect.isclass(obj):
            for attr, value in vars(obj).items():
                if not attr.startswith("_") and (callable(value) or isinstance(value, property)):
                    assert inspect.getdoc(value), "%s.%s" % (name, attr)


def test_diagnostic_file_is_the_scene_name():
    # From a fresh-user trial: str(d) showed the name given to loads(), but
    # d.file was empty.
    doc = rscene.loads("raisim_engine_scene 1\ntime_step x\n", name="n.rscene")
    (d,) = rscene.validate(doc)
    assert d.file == "n.rscene" and str(d).startswith("n.rscene:2:11: error:")
    with pytest.raises(rscene.ParseError) as e:
        rscene.loads("not a scene\n", name="m.rscene")
    assert e.value.diagnostics[0].file == "m.rscene"
    # A scene from text without a name: no file, "<scene>" in str().
    (d,) = rscene.validate(rscene.loads("raisim_engine_scene 1\ntime_step x\n"))
    assert d.file == "" and str(d).startswith("<scene>:2:11")


def test_typing_names_do_not_leak():
    for name in ("Any", "List", "Optional", "Union", "Iterator", "NamedTuple"):
        assert not hasattr(rscene, name), name
    assert set(rscene.__all__) <= set(dir(rscene))
