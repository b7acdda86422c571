"""The typed scene (issue 28): ``doc.scene()`` and field edits.

``doc.scene()`` reads the document through lib/scene's typed model, the one
validate, sim and render read: every field typed, defaults filled in from
the schema, enumerations by their canonical names, asset paths resolved,
poses both as written (``position``, ``orientation``) and in the world frame
(``world_position``, ``world_orientation``).  Vectors are read-only numpy
float64 arrays; quaternions are ``[w, x, y, z]``.

The views are snapshots.  To change the scene, set a field of a record in
the document: ``doc.set(record, field, value)`` (``record``: a view, a
node's path or id, a singleton's tag such as ``"time_step"``, or a record
number).  The new value is encoded by the schema's type (what
``rscene-from-json`` does) and written over that field's text alone:
``doc.save(path, as_written=True)`` then changes that field and no other
byte of the file.
"""
from __future__ import annotations

import json as _json
import re as _re
from typing import Any, Dict, Iterator, List, Optional

import numpy as _np

from . import _rscene
from . import Document, _check_document, _diagnostics

__all__ = ["Scene", "RecordView", "SceneObject", "Compound", "CompoundChild", "RobotRecord", "Camera", "Sensor",
           "Light", "Material"]


def _frozen(value: Any) -> Any:
    if isinstance(value, _np.ndarray):
        value.flags.writeable = False
    return value


class RecordView:
    """A read-only view of one record of the typed scene.  Every view has
    ``record`` (its number in the document, for :meth:`Document.set`),
    ``tag`` and ``line``; node records also ``path`` and ``id``.  The other
    attributes depend on the kind (see each class).  ``as_dict()`` gives
    them all."""

    __slots__ = ("_fields", "_doc")

    def __init__(self, fields: Dict[str, Any], doc: Optional[Document] = None) -> None:
        object.__setattr__(self, "_fields", {k: _frozen(v) for k, v in fields.items()})
        object.__setattr__(self, "_doc", doc)

    def __getattr__(self, name: str) -> Any:
        try:
            return self._fields[name]
        except KeyError:
            raise AttributeError("%s has no attribute %r" % (type(self).__name__, name)) from None

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("scene views are read-only: use doc.set(view, field, value), then doc.scene() again")

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self._fields))

    def as_dict(self) -> Dict[str, Any]:
        """Every attribute of the view as a dict."""
        return dict(self._fields)

    def set(self, field: str, value: Any) -> None:
        """Sets ``field`` (the schema's name, e.g. ``"mass"``,
        ``"position"``, ``"contactMaterial"``; snake_case works too) of this
        record in the document the view was read from:
        ``doc.set(self, field, value)``.  The view itself does not change."""
        if self._doc is None:
            raise ValueError("this view has no document")
        self._doc.set(self, field, value)

    def __repr__(self) -> str:
        name = self._fields.get("path") or self._fields.get("id") or self._fields.get("name") or ""
        return "<rscene.%s %s (line %d)>" % (type(self).__name__, repr(name) if name else "", self._fields["line"])


class SceneObject(RecordView):
    """An ``object`` record: ``path``, ``id``, ``parent_id``, ``primitive``
    (canonical: ground, box, sphere, cylinder, capsule, mesh, half_space),
    ``position``/``orientation`` (as written, parent frame),
    ``world_position``/``world_orientation``, ``scale``, ``radius``,
    ``height``, ``mass``, ``body_mode`` (static, kinematic, dynamic,
    visual_only), ``material``, ``contact_material``, ``visible`` (False
    when a group hides it too), ``collidable``, ``collision_group``,
    ``collision_mask``, ``mesh_path`` and ``collision_mesh_path``
    (resolved, or None), ``semantic_class``, ``instance_id``,
    ``inertia_diagonal`` (None: the shape's)."""
    __slots__ = ()


class CompoundChild(RecordView):
    """A ``compound_child`` record: ``primitive``, ``position`` and
    ``orientation`` in the compound's frame, ``scale``, ``size`` (box
    sides), ``radius``, ``height``, ``material``, ``contact_material``,
    ``mesh_path``."""
    __slots__ = ()


class Compound(RecordView):
    """A ``compound`` record: ``path``, ``id``, ``parent_id``, the poses as
    :class:`SceneObject`'s, ``scale``, ``mass``, ``body_mode``,
    ``material``, ``contact_material``, ``visible``, ``collidable``,
    ``center_of_mass`` and ``inertia_diagonal`` (None: computed), and
    ``children``: a list of :class:`CompoundChild`."""
    __slots__ = ()

    def __init__(self, fields: Dict[str, Any], doc: Optional[Document] = None) -> None:
        fields = dict(fields)
        fields["children"] = [CompoundChild(c, doc) for c in fields["children"]]
        super().__init__(fields, doc)


class RobotRecord(RecordView):
    """An ``articulated`` record: ``path``, ``id``, ``parent_id``,
    ``resource`` (as written), ``source_path`` (the robot file, resolved),
    the poses, ``scale``, ``visible``, ``collidable``,
    ``generalized_coordinate`` and ``generalized_velocity`` (as written, or
    None), ``joint_order``; and from the robot's model (None when it does
    not load, or with ``doc.scene(load_robots=False)``): ``joint_names``
    (movable joints, in coordinate order), ``coordinate_names`` (each entry
    of q: ``base_x`` ... ``base_qz`` for a floating base, then the joints),
    ``velocity_names`` (each entry of u), ``floating_base``, and ``q``,
    ``u``: the state sim and render start from (the record's, else the
    model's rest)."""
    __slots__ = ()


class Camera(RecordView):
    """A ``camera`` record: ``path``, ``id``, the poses (looking along local
    +x, +z up), ``vertical_fov``, ``horizontal_fov`` (degrees; 0: from the
    aspect), ``near_plane``, ``far_plane``, ``width``, ``height``,
    ``render_mode``, ``projection``, ``ortho_scale``, ``enabled``,
    ``output_path`` (or None)."""
    __slots__ = ()


class Sensor(RecordView):
    """A ``sensor`` record: ``path``, ``id``, ``kind`` (rgb, depth,
    segmentation, rgb_depth, imu, lidar, force_torque), ``parent_object``,
    ``parent_link``, the poses (``world_*``: at the scene's state),
    ``width``, ``height``, ``vertical_fov``, ``horizontal_fov``,
    ``near_plane``, ``far_plane`` (0: not given), ``intrinsics`` (``[fx,
    fy, cx, cy]`` or None), ``update_rate``, ``lidar_channels``,
    ``lidar_samples``, ``lidar_min_pitch``, ``lidar_max_pitch``,
    ``lidar_min_range``, ``lidar_max_range``, ``segmentation``,
    ``noise_mean``, ``noise_stddev``, ``noise_seed``, ``enabled``,
    ``output_path``."""
    __slots__ = ()


class Light(RecordView):
    """A ``light`` record: ``path``, ``id``, ``type`` (directional, point,
    spot, area), ``direction`` (world, normalised), ``position`` (world),
    ``intensity``, ``color`` (RGBA), ``range``, ``cone_angle``,
    ``inner_cone_angle``, ``radius``, ``area_size``, ``shadows``,
    ``negative``, ``visible``."""
    __slots__ = ()


class Material(RecordView):
    """A ``material`` (the implicit ``engine_default`` has record -1):
    ``id``, ``name``, ``color`` (RGBA), ``metallic``, ``roughness``,
    ``emissive``, ``emissive_strength``, ``double_sided``, ``alpha_mode``."""
    __slots__ = ()


class Scene:
    """The typed scene of a document (``doc.scene()``): ``time_step``,
    ``gravity``, and lists ``objects``, ``compounds``, ``robots``,
    ``cameras``, ``sensors``, ``lights``, ``materials`` (file order), and
    ``diagnostics``: what reading the model found (the values it could not
    read were given their defaults; :func:`rscene.validate` reports every
    problem)."""

    __slots__ = ("time_step", "gravity", "objects", "compounds", "robots", "cameras", "sensors", "lights",
                 "materials", "diagnostics")

    def __init__(self, raw: Dict[str, Any], doc: Document) -> None:
        self.time_step = raw["time_step"]
        self.gravity = _frozen(raw["gravity"])
        self.objects = [SceneObject(x, doc) for x in raw["objects"]]
        self.compounds = [Compound(x, doc) for x in raw["compounds"]]
        self.robots = [RobotRecord(x, doc) for x in raw["robots"]]
        self.cameras = [Camera(x, doc) for x in raw["cameras"]]
        self.sensors = [Sensor(x, doc) for x in raw["sensors"]]
        self.lights = [Light(x, doc) for x in raw["lights"]]
        self.materials = [Material(x, doc) for x in raw["materials"]]
        self.diagnostics = _diagnostics(raw["diagnostics"], doc.path or "")

    def records(self) -> Iterator[RecordView]:
        """Every node view: objects, compounds, robots, cameras, sensors,
        lights."""
        for group in (self.objects, self.compounds, self.robots, self.cameras, self.sensors, self.lights):
            yield from group

    def find(self, name: str) -> RecordView:
        """The view of the node whose path (with or without the leading
        ``/``) or id is ``name``.  Raises ``KeyError`` when none is."""
        for v in self.records():
            path = v.path
            if name in (path, v.id) or (path.startswith("/") and path[1:] == name):
                return v
        raise KeyError("no object, compound, robot, camera, sensor or light with path or id %r" % (name,))

    def __repr__(self) -> str:
        return "<rscene.Scene: %d objects, %d compounds, %d robots, %d cameras, %d sensors, %d lights>" % (
            len(self.objects), len(self.compounds), len(self.robots), len(self.cameras), len(self.sensors),
            len(self.lights))


def scene(doc: Document, load_robots: bool = True) -> Scene:
    # Document.scene()'s body.
    return Scene(_rscene.scene(_check_document(doc), bool(load_robots)), doc)


def _camel(name: str) -> str:
    return _re.sub(r"_([a-z0-9])", lambda m: m.group(1).upper(), name)


def _jsonable(value: Any, name: str) -> Any:
    if isinstance(value, _np.ndarray):
        return value.tolist()
    if isinstance(value, _np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_jsonable(v, name) for v in value]
    if isinstance(value, (bool, int, float, str)):
        return value
    raise TypeError("field %r: a %s is no scene value (numbers, bools, str, sequences, numpy arrays)"
                    % (name, type(value).__name__))


def _check_numbers(value: Any, field: str, kind: str) -> None:
    """Ints the JSON form cannot carry for ``kind`` (the schema type's
    name), refused with the field's name: past the unsigned or signed 64-bit
    range for integer fields, past the largest double for the others."""
    if isinstance(value, list):
        for v in value:
            _check_numbers(v, field, kind)
        return
    if isinstance(value, bool) or not isinstance(value, int):
        return
    if kind == "uint64":
        if not 0 <= value <= 2**64 - 1:
            raise ValueError("%s: %d is out of the unsigned 64-bit range (0 to %d)" % (field, value, 2**64 - 1))
    elif kind.startswith("integer"):
        if not -2**63 <= value <= 2**63 - 1:
            raise ValueError("%s: %d is out of the signed 64-bit range (%d to %d)" % (field, value, -2**63, 2**63 - 1))
    else:
        try:
            float(value)
        except OverflowError:
            raise ValueError("%s: %s is not a finite number (the format holds numbers up to about 1.8e308)"
                             % (field, _short(value))) from None


def _short(value: int) -> str:
    """A huge int in short scientific form: 10**400 -> "1e400"."""
    digits = str(abs(value))
    tail = digits[1:6].rstrip("0")
    return "%s%s%se%d" % ("-" if value < 0 else "", digits[0], "." + tail if tail else "", len(digits) - 1)


def update(doc: Document, record: Any, values: Dict[str, Any]) -> None:
    # Document.update()'s body: one edit of the text for all the fields.
    raw = _check_document(doc)
    if isinstance(record, RecordView):
        record = record.record
    if isinstance(record, bool) or not isinstance(record, (int, str, _np.integer)):
        raise TypeError("record must be a view, a path, an id, a tag or a record number, not %s"
                        % type(record).__name__)
    if not isinstance(values, dict) or not values:
        raise ValueError("no field to set")
    index = _rscene.find_record(raw, int(record) if isinstance(record, _np.integer) else record)
    positional, keys, types = _rscene.record_fields(raw, index)
    known = set(positional) | set(keys)
    form = _json.loads(_rscene.record_json(raw, index))
    rec = form["records"][1]
    if "fields" not in rec:
        raise ValueError("this %s record repeats a key or names one like a positional field: it cannot be edited "
                         "field by field" % rec.get("tag"))
    edited: List[str] = []
    removed: List[str] = []
    for name, value in values.items():
        if not isinstance(name, str):
            raise TypeError("field names are str")
        field = name if name in known else _camel(name)
        if field not in known:
            raise ValueError("this %s record has no field %r; its fields: %s"
                             % (rec["tag"], name, ", ".join(list(positional) + list(keys))))
        if value is None:
            if field in positional:
                raise ValueError("field %r is positional: it cannot be removed, only set" % field)
            rec["fields"].pop(field, None)
            removed.append(field)
        else:
            rec["fields"][field] = _jsonable(value, field)
            _check_numbers(rec["fields"][field], field, types.get(field, ""))
            edited.append(field)
    try:
        text = _json.dumps(form, allow_nan=False)
    except ValueError:
        raise ValueError("a value is not finite (NaN or infinity): the format holds finite numbers") from None
    doc._doc = _rscene.edit(raw, index, text, edited, removed)
