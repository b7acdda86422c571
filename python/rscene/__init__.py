"""rscene: read, format, validate, diff and convert RaiSim Engine 2 scenes.

The same library as the rscene command-line tools, for Python::

    import rscene
    doc = rscene.load("examples/pendulum.rscene")
    for d in rscene.validate(doc):
        print(d)                      # file:line:col: error: message [RSnnnn]
    text = rscene.format(doc)         # what rscene-fmt writes
    data = rscene.to_json(doc)        # what rscene-to-json writes, as dicts
    same = rscene.from_json(data)     # and back
    doc.save("out.rscene")            # canonical text, written as the tools write

Documents are lossless: every record, unknown tag, unknown key and comment
is kept, and ``format`` gives the canonical text (DESIGN.md, "Canonical
form").

A scene that does not parse raises :class:`ParseError`; its
``diagnostics`` attribute lists the loader's findings (RS1xxx, or RS8xxx
for JSON) with their lines and columns.  A scene that parses but has
other errors (a wrong type, a dangling reference) loads, and
:func:`validate` lists them.  Misuse (a wrong argument type, an unknown
profile) raises ``TypeError`` or ``ValueError``; file problems raise
``OSError``.
"""
from __future__ import annotations

import json as _json
import operator as _operator
import os as _os
from typing import Any as _Any, Iterator as _Iterator, List as _List, NamedTuple as _NamedTuple, Optional as _Optional, Union as _Union

import numpy as _np

from . import _rscene

__all__ = [
    "Diagnostic", "Document", "ParseError", "RecordChange", "FieldChange",
    "load", "loads", "format", "validate", "diff", "to_json", "from_json",
    "Simulation", "SimulationError", "Robot", "Contacts", "Contact",
]


class Diagnostic:
    """One finding: ``code`` (``"RS2001"``), ``severity`` (``"error"`` or
    ``"warning"``), 1-based ``line`` and ``column`` (0 when unknown),
    ``message``, ``hint`` (may be empty), ``tag`` and ``field`` of the record,
    and ``file``: the file the finding is in (the scene's name as loaded, or
    another file such as a robot's URDF; empty for a scene from text
    without a name)."""

    __slots__ = ("code", "severity", "line", "column", "message", "hint", "tag", "field", "file", "_scene")

    def __init__(self, fields: dict, scene: str = "") -> None:
        for k in ("code", "severity", "line", "column", "message", "hint", "tag", "field", "file"):
            setattr(self, k, fields[k])
        self._scene = scene
        if not self.file and scene and not scene.startswith("<"):
            self.file = scene  # the scene's own name, as str() shows it

    def __str__(self) -> str:
        """The tools' form: ``file:line:col: severity: message [code]``."""
        where = self.file or self._scene or "<scene>"
        if self.line:
            where += ":%d" % self.line
            if self.column:
                where += ":%d" % self.column
        text = "%s: %s: %s [%s]" % (where, self.severity, self.message, self.code)
        if self.hint:
            text += "\n  hint: " + self.hint
        return text

    def __repr__(self) -> str:
        return "Diagnostic(%r, %r, line=%d, column=%d, message=%r)" % (
            self.code, self.severity, self.line, self.column, self.message)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Diagnostic):
            return NotImplemented
        return all(getattr(self, k) == getattr(other, k) for k in ("code", "severity", "line", "column", "message",
                                                                  "hint", "tag", "field", "file"))

    __hash__ = None  # type: ignore[assignment]


class ParseError(ValueError):
    """A scene (or its JSON form) that does not parse.  ``diagnostics`` lists
    the findings (errors and any warnings before them); ``str()`` shows the
    first error as the tools print it."""

    def __init__(self, diagnostics: _List[Diagnostic], name: str = "") -> None:
        self.diagnostics = diagnostics
        self.name = name
        errors = [d for d in diagnostics if d.severity == "error"]
        first = errors[0] if errors else (diagnostics[0] if diagnostics else None)
        message = str(first).split("\n")[0] if first else "%s: does not parse" % (name or "<scene>")
        if len(errors) > 1:
            message += " (and %d more errors)" % (len(errors) - 1)
        super().__init__(message)


def _diagnostics(raw: list, name: str) -> _List[Diagnostic]:
    return [Diagnostic(d, name) for d in raw]


class Document:
    """A parsed scene, lossless.  Make one with :func:`load`, :func:`loads`
    or :func:`from_json`; ``str(doc)`` is its canonical text."""

    __slots__ = ("_doc",)

    def __init__(self, *args: _Any, **kwargs: _Any) -> None:
        raise TypeError("use rscene.load(path), rscene.loads(text) or rscene.from_json(obj) to make a Document")

    @classmethod
    def _wrap(cls, raw: "_rscene._Document") -> "Document":
        self = object.__new__(cls)
        self._doc = raw
        return self

    @property
    def path(self) -> _Optional[str]:
        """The file it was loaded from, or None."""
        return _os.fsdecode(self._doc.path) or None

    @property
    def version(self) -> int:
        """The header's format version (1 or 2)."""
        return self._doc.version

    @property
    def source(self) -> str:
        """The text as read (for a document from JSON, its canonical text)."""
        return self._doc.source.decode("utf-8", "surrogateescape")

    @property
    def diagnostics(self) -> _List[Diagnostic]:
        """The loader's warnings (a loaded document has no errors)."""
        return _diagnostics(self._doc.diagnostics, _os.fsdecode(self._doc.path))

    def tags(self) -> _List[str]:
        """The tag of every record in file order, the header first."""
        return self._doc.tags()

    def __len__(self) -> int:
        """The number of records, the header included."""
        return self._doc.record_count

    def save(self, path: _Union[str, "_os.PathLike[str]"], as_written: bool = False) -> None:
        """Writes the canonical text to ``path`` through the tools' output
        routine: a regular file is replaced atomically (temporary file and
        rename, mode kept); a symbolic link keeps pointing where it did and
        its target is replaced; a FIFO or character device is written
        through (a FIFO waits for a reader; the GIL is released meanwhile).
        Refused with ``OSError``, nothing changed: a dangling link, a
        directory, a read-only or hard-linked file, an unwritable
        directory.  ``as_written=True`` writes :attr:`source` instead: the
        text as read with the fields :meth:`set` changed, every other byte
        as it was."""
        if not isinstance(path, (str, bytes, _os.PathLike)):
            raise TypeError("save() needs a path (str or os.PathLike), not %s" % type(path).__name__)
        if not isinstance(as_written, (bool, _np.bool_)):
            raise TypeError("save(): as_written must be a bool (True or False), not %s" % type(as_written).__name__)
        target = _os.fsencode(path)
        save = _rscene.save_source if as_written else _rscene.save
        error = save(self._doc, target)
        if error:
            raise OSError("%s: %s" % (_os.fsdecode(target), error))

    def scene(self, load_robots: bool = True) -> "Scene":
        """The typed scene (:class:`Scene`): objects, compounds, robots,
        cameras, sensors, lights and materials as read-only views with
        numpy fields, read by the model validate, sim and render share.
        ``load_robots`` reads each robot's model for its joint and
        coordinate names and start state."""
        from . import _scene
        return _scene.scene(self, load_robots)

    def set(self, record: _Any, field: str, value: _Any) -> None:
        """Sets one field of one record: ``record`` is a scene view, a
        node's path or id, the tag of a record the scene has once
        (``"time_step"``, ``"gravity"``), or a record number; ``field`` is
        the schema's name (``"mass"``, ``"position"``,
        ``"contactMaterial"``; snake_case works too).  The value is encoded
        by the field's type as ``rscene-from-json`` encodes it (numbers,
        bools, str, sequences or numpy arrays for vectors and lists); None
        removes a key (its default applies).  Only that field's text
        changes: :attr:`source` and ``save(path, as_written=True)`` keep
        every other byte.  Raises ``KeyError`` for an unknown record,
        ``ValueError`` for an unknown field or a value the type refuses,
        ``TypeError`` for a value that is no scene value."""
        from . import _scene
        if not isinstance(field, str):
            raise TypeError("field must be a str, not %s" % type(field).__name__)
        _scene.update(self, record, {field: value})

    def update(self, record: _Any, values: dict) -> None:
        """Sets several fields of one record at once (``{field: value}``),
        as :meth:`set` does each."""
        from . import _scene
        _scene.update(self, record, values)

    def __str__(self) -> str:
        return format(self)

    def __repr__(self) -> str:
        return "<rscene.Document %s, %d records>" % (repr(self.path) if self.path else "from text", len(self))


def _check_document(doc: _Any, name: str = "doc") -> "_rscene._Document":
    if not isinstance(doc, Document):
        raise TypeError("%s must be an rscene.Document, not %s" % (name, type(doc).__name__))
    return doc._doc


def loads(text: _Union[str, bytes], name: _Optional[str] = None) -> Document:
    """Parses scene text (str, or bytes as read from a file) into a
    :class:`Document`.  ``name`` is the file name diagnostics show; it is
    also the directory relative asset paths start from in :func:`validate`.
    Raises :class:`ParseError` when the text does not parse."""
    if isinstance(text, str):
        data = text.encode("utf-8", "surrogateescape")
    elif isinstance(text, (bytes, bytearray, memoryview)):
        data = bytes(text)
    else:
        raise TypeError("loads() needs str or bytes, not %s" % type(text).__name__)
    if name is not None and not isinstance(name, str):
        raise TypeError("name must be a str")
    raw, diags = _rscene.parse(data, _os.fsencode(name or ""))
    if raw is None:
        raise ParseError(_diagnostics(diags, name or "<scene>"), name or "<scene>")
    return Document._wrap(raw)


def load(path: _Union[str, "_os.PathLike[str]"]) -> Document:
    """Reads and parses the scene file at ``path``.  Raises ``OSError`` when
    it cannot be read and :class:`ParseError` when it does not parse."""
    target = _os.fsdecode(_os.fspath(path))
    with open(target, "rb") as f:
        data = f.read()
    return loads(data, name=target)


def format(doc: Document) -> str:
    """The canonical text of ``doc``, byte for byte what ``rscene-fmt``
    writes."""
    return _rscene.format(_check_document(doc)).decode("utf-8", "surrogateescape")


def validate(doc: Document, profile: str = "engine2", check_files: bool = False,
             base_dir: _Optional[str] = None) -> _List[Diagnostic]:
    """Everything ``rscene-validate`` reports for ``doc`` (syntax, types,
    references, sizes, the scene model's checks and the robots'), in its
    order.  ``profile`` is ``"engine2"`` or ``"raisim"``; ``check_files``
    also checks that asset files exist (as ``--check-files``), relative to
    ``base_dir`` or the document's directory.  An empty list: no findings."""
    raw = _check_document(doc)
    if not isinstance(profile, str):
        raise TypeError("profile must be a str")
    base = _os.fsencode(base_dir) if base_dir is not None else b""
    return _diagnostics(_rscene.validate(raw, profile, bool(check_files), base), _os.fsdecode(raw.path))


class FieldChange:
    """A changed field of a :class:`RecordChange`: ``name``, ``change``
    (``"added"``, ``"removed"``, ``"changed"``), ``type`` (the schema type,
    e.g. ``"vec3"``), ``old`` and ``new`` (canonical text, ``""`` on the
    missing side), ``old_default``/``new_default`` (not written: the
    default), and for long lists ``summarized`` with ``old_count``,
    ``new_count``, ``changed_count``, ``max_delta``."""

    __slots__ = ("name", "change", "type", "key_form", "entry", "old", "new", "old_default", "new_default",
                 "summarized", "old_count", "new_count", "changed_count", "listed_count", "max_delta")

    def __init__(self, fields: dict) -> None:
        for k in self.__slots__:
            setattr(self, k, fields[k])

    def __repr__(self) -> str:
        return "FieldChange(%r, %s, %r -> %r)" % (self.name, self.change, self.old, self.new)


class RecordChange:
    """One record that differs (as ``rscene-diff`` reports it): ``change``
    (``"added"``, ``"removed"``, ``"changed"``), ``tag``, ``key`` (its
    identity), ``path``, ``old_path`` (a renamed node, else ``""``),
    ``old_line``/``new_line``, and ``fields``: a list of
    :class:`FieldChange`."""

    __slots__ = ("change", "tag", "key", "path", "old_path", "old_line", "new_line", "fields")

    def __init__(self, fields: dict) -> None:
        for k in self.__slots__[:-1]:
            setattr(self, k, fields[k])
        self.fields = [FieldChange(f) for f in fields["fields"]]

    def __repr__(self) -> str:
        return "RecordChange(%s %s %r, %d fields)" % (self.change, self.tag, self.path or self.key, len(self.fields))


def diff(a: Document, b: Document, tolerance: float = 0.0, rel_tolerance: float = 0.0,
         ignore_editor_state: bool = False, ignore: _Optional[_List[str]] = None) -> _List[RecordChange]:
    """The semantic difference from ``a`` to ``b`` as ``rscene-diff``
    computes it: records matched by identity, values compared by type (with
    absolute and relative ``tolerance``), reordering is no change.
    ``ignore`` lists field names (``NAME`` or ``TAG.NAME``) to leave out.
    An empty list: the scenes are the same."""
    ra, rb = _check_document(a, "a"), _check_document(b, "b")
    names = list(ignore or [])
    if not all(isinstance(n, str) for n in names):
        raise TypeError("ignore must be a list of str")
    return [RecordChange(r) for r in
            _rscene.diff(ra, rb, float(tolerance), float(rel_tolerance), bool(ignore_editor_state), names)]


def to_json(doc: Document) -> dict:
    """The JSON form of ``doc`` (what ``rscene-to-json`` writes) as Python
    objects: dicts, lists, str, int, float, bool."""
    return _json.loads(_rscene.to_json_text(_check_document(doc)))


def from_json(obj: dict) -> Document:
    """The :class:`Document` of a JSON form (``to_json``'s result, or
    ``json.load`` of ``rscene-to-json``'s output).  Raises
    :class:`ParseError` (codes RS8001, RS8002) when it is not a scene."""
    if not isinstance(obj, dict):
        raise TypeError("from_json() needs a dict (the parsed JSON form), not %s; use json.loads for text"
                        % type(obj).__name__)
    try:
        text = _json.dumps(obj, allow_nan=False)
    except (TypeError, ValueError, RecursionError) as e:
        raise ValueError("from_json(): not JSON data: %s" % e) from None
    raw, diags = _rscene.from_json_text(text)
    if raw is None:
        raise ParseError(_diagnostics(diags, "<json>"), "<json>")
    return Document._wrap(raw)


class SimulationError(ValueError):
    """A scene that cannot be simulated, or a step that failed (a state that
    is not finite, the broadphase's pair cap).  ``diagnostics`` lists the
    findings as rscene-sim prints them."""

    def __init__(self, diagnostics: _List[Diagnostic], name: str = "", *, message: _Optional[str] = None) -> None:
        self.diagnostics = diagnostics
        if message is None:
            errors = [d for d in diagnostics if d.severity == "error"] or diagnostics
            message = str(errors[0]).split("\n")[0] if errors else "%s: cannot be simulated" % (name or "<scene>")
            if len(errors) > 1:
                message += " (and %d more errors)" % (len(errors) - 1)
        super().__init__(message)


def _count(value: _Any, what: str) -> int:
    """An integral argument (int, numpy integer, anything with
    ``__index__``) as an int; bool and floats are refused."""
    if isinstance(value, (bool, _np.bool_)):
        raise TypeError("%s must be an int, not %s" % (what, type(value).__name__))
    try:
        return _operator.index(value)
    except TypeError:
        raise TypeError("%s must be an int, not %s" % (what, type(value).__name__)) from None


def _base_dir(base_dir: _Any) -> bytes:
    """``base_dir=`` (None, str or os.PathLike) as the C++ side takes it."""
    if base_dir is None:
        return b""
    if not isinstance(base_dir, (str, bytes, _os.PathLike)):
        raise TypeError("base_dir must be a path (str or os.PathLike) or None, not %s" % type(base_dir).__name__)
    data = _os.fsencode(base_dir)
    if not data:
        raise ValueError("base_dir must name a folder, not an empty string (None: the scene's folder)")
    return data


def _flag(value: _Any, name: str) -> bool:
    if not isinstance(value, (bool, _np.bool_)):
        raise TypeError("%s must be a bool, not %s" % (name, type(value).__name__))
    return bool(value)


class Simulation:
    """A scene in the physics engine, prepared as ``rscene-sim`` prepares it
    (the same checks, robots, time step and solver settings).  Raises
    :class:`SimulationError` when the scene cannot be simulated.

    ``allow_missing_assets=True`` is ``rscene-sim --allow-missing-assets``:
    a body whose collision mesh is missing or unreadable (and a robot whose
    file is missing) is left out with a warning (see :attr:`diagnostics`)
    instead of an error.  ``base_dir`` is
    ``--base-dir``: the folder relative asset paths resolve against, in
    place of the scene file's folder (for a scene from :func:`loads`
    without a name: the current folder)."""

    __slots__ = ("_sim", "_doc", "_bodies")

    def __init__(self, doc: Document, *, allow_missing_assets: bool = False,
                 base_dir: _Union[str, "_os.PathLike[str]", None] = None) -> None:
        raw = _check_document(doc)
        name = _os.fsdecode(raw.path)
        sim, diags = _rscene.simulation(raw, _flag(allow_missing_assets, "allow_missing_assets"),
                                        _base_dir(base_dir))
        if sim is None:
            raise SimulationError(_diagnostics(diags, name), name)
        self._sim = sim
        self._doc = doc
        self._bodies: _Optional[frozenset] = None  # the paths contacts name, read once

    def step(self, n: int = 1) -> None:
        """Takes ``n`` fixed time steps (``n >= 0``) with the GIL released.
        Raises :class:`SimulationError` when a state stops being finite;
        the simulation then takes no more steps (each later call raises
        :class:`SimulationError` with that failure's diagnostics).  ``n`` is
        any integer (a numpy one too; not a bool or a float).  Ctrl-C (a signal handler
        that raises) ends a long call within about 0.1 s, or after the
        step under way when one step takes longer, with the exception it
        raised (``KeyboardInterrupt``): the world stops between two steps,
        consistent, and ``step()`` goes on from there.  Robots' PD targets
        and torques set before the call act in each of its steps."""
        if type(n) is not int:  # the usual case without a call
            n = _count(n, "step(n): n")
        if n > 2**63 - 1:
            raise ValueError("step(n): n is too large")
        failure = self._sim.step(n)
        if failure is not None:
            found, earlier = failure
            diagnostics = [Diagnostic(found, _os.fsdecode(self._doc._doc.path))]
            if earlier:
                raise SimulationError(diagnostics, message="the simulation stopped at an earlier failure and takes no "
                                      "more steps: " + str(diagnostics[0]).split("\n")[0])
            raise SimulationError(diagnostics)

    @property
    def time(self) -> float:
        """Simulated seconds since the start."""
        return self._sim.time

    @property
    def steps(self) -> int:
        """Steps taken since the start."""
        return self._sim.steps

    @property
    def time_step(self) -> float:
        """Seconds per step (the scene's time_step)."""
        return self._sim.time_step

    @property
    def contact_count(self) -> int:
        """Contact points after the last step."""
        return self._sim.contact_count

    @property
    def at_rest(self) -> bool:
        """Whether every dynamic body still in the world sleeps."""
        return self._sim.at_rest

    @property
    def diagnostics(self) -> _List[Diagnostic]:
        """The warnings of preparing the scene (as rscene-sim prints them)."""
        return _diagnostics(self._sim.diagnostics, _os.fsdecode(self._doc._doc.path))

    def body_pose(self, path: str) -> "_np.ndarray":
        """The world pose now of the dynamic or kinematic body named by
        ``path`` (or id): a float64 array ``[x, y, z, qw, qx, qy, qz]``.
        Raises ``KeyError`` for a name that is no moving body (a static body
        stays where the scene puts it)."""
        if not isinstance(path, str):
            raise TypeError("body_pose(path): path must be a str, not %s" % type(path).__name__)
        pose = self._sim.body_pose(path)
        if pose is None:
            raise KeyError("no dynamic or kinematic body named %r (a static body stays where the scene puts it)"
                           % path)
        return pose

    def body_velocity(self, path: str) -> "_np.ndarray":
        """The world-frame velocity now of the moving body named by ``path``
        (or id), at its record frame's origin (the point ``body_pose``
        gives): a float64 array ``[vx, vy, vz, wx, wy, wz]`` (m/s, rad/s).
        Raises ``KeyError`` as ``body_pose`` does."""
        if not isinstance(path, str):
            raise TypeError("body_velocity(path): path must be a str, not %s" % type(path).__name__)
        velocity = self._sim.body_velocity(path)
        if velocity is None:
            raise KeyError("no dynamic or kinematic body named %r (a static body stays where the scene puts it)"
                           % path)
        return velocity

    def robot(self, path: str) -> "Robot":
        """The simulated articulated system named by ``path`` (or id), to
        read its state and drive it (:class:`Robot`).  Raises ``KeyError``
        for a name no record has and ``ValueError`` for a record that is no
        simulated robot (an object, a robot left out)."""
        if not isinstance(path, str):
            raise TypeError("robot(path): path must be a str, not %s" % type(path).__name__)
        index, what = self._sim.robot_lookup(path)
        if index < 0:
            if what:
                raise ValueError("%r is %s, not a simulated robot" % (path, what))
            raise KeyError("no articulated system named %r" % path)
        return Robot(self, index)

    @property
    def robots(self) -> _List["Robot"]:
        """Every simulated robot, in the scene's order."""
        out = []
        i = 0
        while True:
            try:
                out.append(Robot(self, i))
            except IndexError:
                return out
            i += 1

    def contacts(self) -> "Contacts":
        """The rigid contact points after the last step (empty before the
        first), as :class:`Contacts`: numpy arrays, one row per point."""
        if self._bodies is None:
            self._bodies = frozenset(self._sim.body_paths())
        return Contacts(self._sim.contacts(), self._bodies)

    def sensors(self) -> _List[dict]:
        """The LiDARs and IMUs read while stepping (sensor records and the
        sensor sets of robots, as ``rscene-sim --sensors`` records them):
        a dict ``{"name", "id", "kind"}`` each (``kind``: ``"lidar"`` or
        ``"imu"``).  ``name`` is a sensor record's path or, for a robot's
        sensor, ``"<robot path>/<set>/<sensor>"``."""
        return [{"name": n, "id": i, "kind": k} for n, i, k in self._sim.sensor_list()]

    def _sensor(self, name: str, kind: str) -> int:
        if not isinstance(name, str):
            raise TypeError("the sensor name must be a str, not %s" % type(name).__name__)
        index = self._sim.sensor_index(name)
        if index < 0:
            raise KeyError("no LiDAR or IMU named %r is read in this simulation (see sensors())" % name)
        actual = self._sim.sensor_list()[index][2]
        if actual != kind:
            shown = {"lidar": "a LiDAR", "imu": "an IMU"}
            raise ValueError("sensor %r is %s, not %s" % (name, shown.get(actual, actual), shown[kind]))
        return index

    def lidar(self, name: str) -> _Optional[dict]:
        """The latest scan of the LiDAR ``name`` (path, id, or a robot
        sensor's name from :meth:`sensors`), or ``None`` before
        :meth:`step` first ran (a LiDAR scans at time 0 and then at its
        updateRate, as ``rscene-sim --sensors``): a dict with ``points``, an
        ``(N, 3)`` float32 array of the hits in the sensor frame (+x
        forward, +z up), ``pose`` (the sensor's world pose
        ``[x, y, z, qw, qx, qy, qz]``), ``time`` and ``index`` (the scan's
        number)."""
        return self._sim.lidar_scan(self._sensor(name, "lidar"))

    def imu(self, name: str) -> _Optional[dict]:
        """The latest reading of the IMU ``name``, or ``None`` before its
        first (after the first step, or 1/updateRate): a dict with
        ``specific_force`` (m/s^2, the point's acceleration minus gravity,
        sensor frame: +9.81 up at rest), ``angular_velocity`` (rad/s, sensor
        frame), both float64 ``(3,)``, and ``time``."""
        return self._sim.imu_reading(self._sensor(name, "imu"))

    def document(self) -> Document:
        """The scene with the bodies' poses now and the robots' states
        written back, as ``rscene-sim -o`` writes it."""
        raw = self._doc._doc
        return loads(self._sim.document_text(), name=_os.fsdecode(raw.path) or None)

    def __repr__(self) -> str:
        return "<rscene.Simulation t=%g s, %d steps>" % (self.time, self.steps)


_NO_VECTOR = _np.zeros(0)


def _vector(value: _Any, size: int, what: str) -> "_np.ndarray":
    """``value`` (a scalar, or anything numpy reads as a vector of ``size``)
    as a float64 vector; ValueError with what is wrong.  Whether the
    numbers are finite the library checks (each setter says so)."""
    if type(value) is _np.ndarray and value.dtype == _np.float64 and value.shape == (size,):
        return value  # the RL loop's usual case, without a copy
    if type(value) in (int, float):
        return _np.full(size, float(value))
    try:
        a = _np.asarray(value, dtype=_np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError("%s: not numbers (%s)" % (what, e)) from None
    if a.ndim == 0:
        a = _np.full(size, float(a))
    if a.shape != (size,):
        raise ValueError("%s: expected shape (%d,), got %s" % (what, size, a.shape))
    return a


class Robot:
    """One simulated articulated system (:meth:`Simulation.robot`).

    State in RaiSim's layout: ``q`` (generalized coordinates: a floating
    base's position and quaternion ``w x y z`` first, then the joints in the
    robot's order, a spherical joint's quaternion as four entries) and
    ``u`` (generalized velocities: a floating base's linear then angular
    velocity, world frame, then one entry per joint dof).  The names of the
    entries are ``coordinate_names`` and ``velocity_names``.

    Control as RaiSim's ArticulatedSystem has it: :meth:`set_pd_targets` and
    :meth:`set_torques` act from the next :meth:`Simulation.step` on and
    stay in force until changed."""

    __slots__ = ("_owner", "_index", "_info", "_nq", "_nv")

    def __init__(self, sim: Simulation, index: int) -> None:
        self._owner = sim
        self._index = index
        self._info = sim._sim.robot_info(index)  # IndexError past the last robot
        self._nq = len(self._info["coordinate_names"])
        self._nv = len(self._info["velocity_names"])

    @property
    def path(self) -> str:
        """The articulated record's path."""
        return self._info["path"]

    @property
    def joint_names(self) -> _List[str]:
        """The movable joints, in the order of ``q`` and ``u``."""
        return list(self._info["joint_names"])

    @property
    def coordinate_names(self) -> _List[str]:
        """The name of each entry of ``q`` (``base_x`` ... ``base_qz``, a
        joint's name, ``NAME_qw`` ... for a spherical joint)."""
        return list(self._info["coordinate_names"])

    @property
    def velocity_names(self) -> _List[str]:
        """The name of each entry of ``u``."""
        return list(self._info["velocity_names"])

    @property
    def link_names(self) -> _List[str]:
        """The model's links (the names contacts give)."""
        return list(self._info["link_names"])

    @property
    def floating_base(self) -> bool:
        """Whether the base is free (its pose and velocity lead q and u)."""
        return bool(self._info["floating_base"])

    @property
    def q(self) -> "_np.ndarray":
        """The generalized coordinates now (float64, a copy)."""
        return self._owner._sim.robot_state(self._index)[0]

    @property
    def u(self) -> "_np.ndarray":
        """The generalized velocities now (float64, a copy)."""
        return self._owner._sim.robot_state(self._index)[1]

    def state(self) -> tuple:
        """``(q, u)`` now, in one call."""
        return self._owner._sim.robot_state(self._index)

    def set_pd_targets(self, q: _Any, kp: _Any, kd: _Any, u: _Any = None) -> None:
        """Drives every joint toward position target ``q`` (the shape of
        :attr:`q`) and velocity target ``u`` (the shape of :attr:`u`;
        ``None``: zero) with gains ``kp`` and ``kd`` (each a scalar or an
        array shaped like :attr:`u`; >= 0; a floating base's six entries
        are ignored: it has no actuator).  The law is RaiSim's stable PD,
        ``kp (q* - q) + kd (u* - u)``, integrated implicitly per joint; it
        acts from the next step on, in place of ``--pd-gains``, until set
        again (gains of zero turn it off).  Raises ``ValueError`` for a
        wrong shape, a value that is not finite, a negative gain or a zero
        quaternion."""
        target = _vector(q, self._nq, "set_pd_targets(q)")
        velocity = _NO_VECTOR if u is None else _vector(u, self._nv, "set_pd_targets(u)")
        gains = _vector(kp, self._nv, "set_pd_targets(kp)"), _vector(kd, self._nv, "set_pd_targets(kd)")
        error = self._owner._sim.robot_set_pd(self._index, target, velocity, gains[0], gains[1])
        if error:
            raise ValueError("set_pd_targets: " + error)

    def set_torques(self, tau: _Any) -> None:
        """Applies the generalized force ``tau`` (a scalar or an array
        shaped like :attr:`u`: a joint's torque or force; a floating base's
        six entries are a world-frame force at the base frame's origin and a
        world-frame torque) at every step from the next one on, added to
        the PD drive, until set again (``set_torques(0)`` ends it), as
        RaiSim's setGeneralizedForce.  Raises ``ValueError`` for a wrong
        shape or a value that is not finite."""
        error = self._owner._sim.robot_set_force(self._index, _vector(tau, self._nv, "set_torques(tau)"))
        if error:
            raise ValueError("set_torques: " + error)

    def set_state(self, q: _Any, u: _Any = None) -> None:
        """Puts the robot at ``q`` with velocity ``u`` (``None``: zero) now,
        as an articulated record's generalizedCoordinate and
        generalizedVelocity would (quaternions are normalised): a reset.
        Raises ``ValueError`` for a wrong shape, a value that is not finite
        or a zero quaternion."""
        coords = _vector(q, self._nq, "set_state(q)")
        velocity = _np.zeros(self._nv) if u is None else _vector(u, self._nv, "set_state(u)")
        error = self._owner._sim.robot_set_state(self._index, coords, velocity)
        if error:
            raise ValueError("set_state: " + error)

    def __repr__(self) -> str:
        return "<rscene.Robot %s: %d coordinates, %d joints>" % (self.path, self._nq, len(self._info["joint_names"]))


class Contact(_NamedTuple):
    """One contact point of :class:`Contacts` (``contacts[i]``, or
    iterating): the fields of its row."""
    body_a: str
    body_b: str
    link_a: str
    link_b: str
    position: "_np.ndarray"
    normal: "_np.ndarray"
    depth: float
    impulse: float


class Contacts:
    """The rigid contact points of one moment (:meth:`Simulation.contacts`),
    one row per point: ``body_a`` and ``body_b`` (the records' paths, ``""``
    for none), ``link_a`` and ``link_b`` (a robot's link, else ``""``),
    ``position`` ``(N, 3)`` (the point on B, world frame), ``normal``
    ``(N, 3)`` (B's surface normal, pointing toward A), ``depth`` ``(N,)``
    (penetration, m; negative: a point kept within the contact margin) and
    ``impulse`` ``(N,)`` (the normal impulse of the last step, N s;
    ``impulse / time_step`` is the force).  ``len()`` is the number of
    points."""

    __slots__ = ("body_a", "body_b", "link_a", "link_b", "position", "normal", "depth", "impulse", "_bodies")

    def __init__(self, raw: dict, bodies: _Optional[_Any] = None) -> None:
        for k in self.__slots__[:-1]:
            setattr(self, k, raw[k])
        self._bodies = bodies

    def __len__(self) -> int:
        return len(self.depth)

    def __getitem__(self, i: _Any) -> "Contact":
        """Point ``i`` (negative from the end) as a :class:`Contact`."""
        index = _operator.index(i) if not isinstance(i, (bool, _np.bool_)) else None
        if index is None:
            raise TypeError("contacts are indexed by an int, not %s" % type(i).__name__)
        n = len(self)
        if not -n <= index < n:
            raise IndexError("contact %d of %d" % (index, n))
        index %= n
        return Contact(self.body_a[index], self.body_b[index], self.link_a[index], self.link_b[index],
                       self.position[index], self.normal[index], float(self.depth[index]),
                       float(self.impulse[index]))

    def __iter__(self) -> "_Iterator[Contact]":
        for i in range(len(self)):
            yield self[i]

    def involving(self, path: str) -> "_np.ndarray":
        """A boolean mask of the points on the body ``path`` (either side).
        Raises ``KeyError`` for a name that is no body of the simulation
        (an object, compound, terrain or robot record's path)."""
        if not isinstance(path, str):
            raise TypeError("involving(path): path must be a str, not %s" % type(path).__name__)
        if self._bodies is not None and path not in self._bodies:
            raise KeyError("no body named %r in this simulation (contacts name bodies by their record's path)" % path)
        return _np.array([a == path or b == path for a, b in zip(self.body_a, self.body_b)], dtype=bool)

    def __repr__(self) -> str:
        return "<rscene.Contacts %d points>" % len(self)


from ._render import LookAt, RenderError, Renderer, render, render_available, render_depth, render_segmentation, _render_error  # noqa: E402,F401
__all__ += ["LookAt", "RenderError", "Renderer", "render", "render_depth", "render_segmentation", "render_available"]
from ._scene import Camera, Compound, CompoundChild, Light, Material, RecordView, RobotRecord, Scene, SceneObject, Sensor  # noqa: E402,F401
__all__ += ["Scene", "RecordView", "SceneObject", "Compound", "CompoundChild", "RobotRecord", "Camera", "Sensor", "Light", "Material"]
