# Type stubs of the rscene package (python/rscene/__init__.py).
import os
from typing import Any, Dict, Iterator, List, NamedTuple, Optional, Sequence, SupportsIndex, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]

class Diagnostic:
    code: str
    severity: str  # "error" or "warning"
    line: int
    column: int
    message: str
    hint: str
    tag: str
    field: str
    file: str
    def __init__(self, fields: dict, scene: str = ...) -> None: ...

class ParseError(ValueError):
    diagnostics: List[Diagnostic]
    name: str
    def __init__(self, diagnostics: List[Diagnostic], name: str = ...) -> None: ...

class Document:
    @property
    def path(self) -> Optional[str]: ...
    @property
    def version(self) -> int: ...
    @property
    def source(self) -> str: ...
    @property
    def diagnostics(self) -> List[Diagnostic]: ...
    def tags(self) -> List[str]: ...
    def __len__(self) -> int: ...
    def save(self, path: _Path, as_written: bool = ...) -> None: ...
    def scene(self, load_robots: bool = ...) -> Scene: ...
    def set(self, record: Union[RecordView, str, int], field: str, value: Any) -> None: ...
    def update(self, record: Union[RecordView, str, int], values: dict[str, Any]) -> None: ...

class FieldChange:
    name: str
    change: str  # "added", "removed" or "changed"
    type: str
    key_form: bool
    entry: bool
    old: str
    new: str
    old_default: bool
    new_default: bool
    summarized: bool
    old_count: int
    new_count: int
    changed_count: int
    listed_count: int
    max_delta: float

class RecordChange:
    change: str  # "added", "removed" or "changed"
    tag: str
    key: str
    path: str
    old_path: str
    old_line: int
    new_line: int
    fields: List[FieldChange]

def loads(text: Union[str, bytes], name: Optional[str] = ...) -> Document: ...
def load(path: _Path) -> Document: ...
def format(doc: Document) -> str: ...
def validate(doc: Document, profile: str = ..., check_files: bool = ...,
             base_dir: Optional[_Path] = ...) -> List[Diagnostic]: ...
def diff(a: Document, b: Document, tolerance: float = ..., rel_tolerance: float = ...,
         ignore_editor_state: bool = ..., ignore: Optional[List[str]] = ...) -> List[RecordChange]: ...
def to_json(doc: Document) -> dict[str, Any]: ...
def from_json(obj: dict[str, Any]) -> Document: ...

class SimulationError(ValueError):
    diagnostics: List[Diagnostic]
    def __init__(self, diagnostics: List[Diagnostic], name: str = ..., *, message: Optional[str] = ...) -> None: ...

class Simulation:
    def __init__(self, doc: Document, *, allow_missing_assets: bool = ...,
                 base_dir: Optional[_Path] = ...) -> None: ...
    def step(self, n: SupportsIndex = ...) -> None: ...
    @property
    def time(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def time_step(self) -> float: ...
    @property
    def contact_count(self) -> int: ...
    @property
    def at_rest(self) -> bool: ...
    @property
    def diagnostics(self) -> List[Diagnostic]: ...
    def body_pose(self, path: str) -> npt.NDArray[np.float64]: ...
    def body_velocity(self, path: str) -> npt.NDArray[np.float64]: ...
    def robot(self, path: str) -> Robot: ...
    @property
    def robots(self) -> List[Robot]: ...
    def contacts(self) -> Contacts: ...
    def sensors(self) -> List[Dict[str, str]]: ...
    def lidar(self, name: str) -> Optional[Dict[str, Any]]: ...
    def imu(self, name: str) -> Optional[Dict[str, Any]]: ...
    def document(self) -> Document: ...

_Vector = Union[float, Sequence[float], npt.NDArray[np.floating[Any]]]

class Robot:
    @property
    def path(self) -> str: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def coordinate_names(self) -> List[str]: ...
    @property
    def velocity_names(self) -> List[str]: ...
    @property
    def link_names(self) -> List[str]: ...
    @property
    def floating_base(self) -> bool: ...
    @property
    def q(self) -> npt.NDArray[np.float64]: ...
    @property
    def u(self) -> npt.NDArray[np.float64]: ...
    def state(self) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def set_pd_targets(self, q: _Vector, kp: _Vector, kd: _Vector, u: Optional[_Vector] = ...) -> None: ...
    def set_torques(self, tau: _Vector) -> None: ...
    def set_state(self, q: _Vector, u: Optional[_Vector] = ...) -> None: ...

class Contacts:
    body_a: List[str]
    body_b: List[str]
    link_a: List[str]
    link_b: List[str]
    position: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    depth: npt.NDArray[np.float64]
    impulse: npt.NDArray[np.float64]
    def __len__(self) -> int: ...
    def __getitem__(self, i: SupportsIndex) -> Contact: ...
    def __iter__(self) -> Iterator[Contact]: ...
    def involving(self, path: str) -> npt.NDArray[np.bool_]: ...

class Contact(NamedTuple):
    body_a: str
    body_b: str
    link_a: str
    link_b: str
    position: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    depth: float
    impulse: float

# Rendering (python/rscene/_render.py).
from typing import Iterator, Sequence
def render_available() -> bool: ...

class RenderError(ValueError):
    diagnostics: List[Diagnostic]
    def __init__(self, message: str, diagnostics: Optional[List[Diagnostic]] = ...) -> None: ...

class LookAt:
    position: tuple[float, float, float]
    target: tuple[float, float, float]
    fov: float
    def __init__(self, position: Sequence[float], target: Sequence[float], fov: float = ...) -> None: ...

_Camera = Union[str, LookAt, None]

class Renderer:
    def __init__(self, doc: Document, camera: _Camera = ..., width: Optional[int] = ...,
                 height: Optional[int] = ..., *, samples: int = ..., post: bool = ...,
                 transparent: bool = ..., allow_missing_assets: bool = ...,
                 base_dir: Optional[_Path] = ...) -> None: ...
    def draw_passes(self, sim: Optional[Simulation] = ..., passes: Sequence[str] = ..., camera: _Camera = ...,
                    width: Optional[int] = ..., height: Optional[int] = ...) -> dict[str, Any]: ...
    def draw(self, sim: Optional[Simulation] = ..., camera: _Camera = ..., width: Optional[int] = ...,
             height: Optional[int] = ...) -> npt.NDArray[np.uint8]: ...
    def draw_depth(self, sim: Optional[Simulation] = ..., camera: _Camera = ..., width: Optional[int] = ...,
                   height: Optional[int] = ...) -> npt.NDArray[np.float32]: ...
    def draw_segmentation(self, sim: Optional[Simulation] = ..., camera: _Camera = ...,
                          width: Optional[int] = ..., height: Optional[int] = ...) -> npt.NDArray[np.uint8]: ...
    @property
    def legend(self) -> dict[str, Any]: ...
    def segment_of(self, color: Sequence[int]) -> Optional[dict[str, Any]]: ...
    @property
    def views(self) -> List[dict[str, Any]]: ...
    @property
    def backend(self) -> Optional[tuple[str, str]]: ...
    @property
    def diagnostics(self) -> List[Diagnostic]: ...

def render(doc: Document, camera: _Camera = ..., width: Optional[int] = ..., height: Optional[int] = ..., *,
           samples: int = ..., post: bool = ..., transparent: bool = ..., allow_missing_assets: bool = ...,
           base_dir: Optional[_Path] = ...) -> npt.NDArray[np.uint8]: ...
def render_depth(doc: Document, camera: _Camera = ..., width: Optional[int] = ...,
                 height: Optional[int] = ..., *, allow_missing_assets: bool = ...,
                 base_dir: Optional[_Path] = ...) -> npt.NDArray[np.float32]: ...
def render_segmentation(doc: Document, camera: _Camera = ..., width: Optional[int] = ...,
                        height: Optional[int] = ..., *, allow_missing_assets: bool = ...,
                        base_dir: Optional[_Path] = ...) -> tuple[npt.NDArray[np.uint8], dict[str, Any]]: ...

# The typed scene (python/rscene/_scene.py); Document.scene/set/update are
# in Document's stub above.
class RecordView:
    record: int
    tag: str
    line: int
    def __getattr__(self, name: str) -> Any: ...
    def as_dict(self) -> dict[str, Any]: ...
    def set(self, field: str, value: Any) -> None: ...

class SceneObject(RecordView):
    path: str
    id: str
    parent_id: str
    primitive: str
    position: npt.NDArray[np.float64]
    orientation: npt.NDArray[np.float64]
    world_position: npt.NDArray[np.float64]
    world_orientation: npt.NDArray[np.float64]
    scale: npt.NDArray[np.float64]
    radius: float
    height: float
    mass: float
    body_mode: str
    material: str
    contact_material: str
    visible: bool
    collidable: bool
    collision_group: int
    collision_mask: int
    mesh_path: Optional[str]
    collision_mesh_path: Optional[str]
    semantic_class: Optional[str]
    instance_id: Optional[int]
    inertia_diagonal: Optional[npt.NDArray[np.float64]]

class CompoundChild(RecordView):
    primitive: str
    position: npt.NDArray[np.float64]
    orientation: npt.NDArray[np.float64]
    scale: npt.NDArray[np.float64]
    size: npt.NDArray[np.float64]
    radius: float
    height: float
    material: str
    contact_material: str
    mesh_path: Optional[str]

class Compound(RecordView):
    path: str
    id: str
    parent_id: str
    position: npt.NDArray[np.float64]
    orientation: npt.NDArray[np.float64]
    world_position: npt.NDArray[np.float64]
    world_orientation: npt.NDArray[np.float64]
    scale: npt.NDArray[np.float64]
    mass: float
    body_mode: str
    material: str
    contact_material: str
    visible: bool
    collidable: bool
    center_of_mass: Optional[npt.NDArray[np.float64]]
    inertia_diagonal: Optional[npt.NDArray[np.float64]]
    children: List[CompoundChild]

class RobotRecord(RecordView):
    path: str
    id: str
    parent_id: str
    resource: str
    source_path: str
    position: npt.NDArray[np.float64]
    orientation: npt.NDArray[np.float64]
    world_position: npt.NDArray[np.float64]
    world_orientation: npt.NDArray[np.float64]
    scale: npt.NDArray[np.float64]
    visible: bool
    collidable: bool
    generalized_coordinate: Optional[npt.NDArray[np.float64]]
    generalized_velocity: Optional[npt.NDArray[np.float64]]
    joint_order: List[str]
    joint_names: Optional[List[str]]
    coordinate_names: Optional[List[str]]
    velocity_names: Optional[List[str]]
    floating_base: Optional[bool]
    q: Optional[npt.NDArray[np.float64]]
    u: Optional[npt.NDArray[np.float64]]

class Camera(RecordView):
    path: str
    id: str
    position: npt.NDArray[np.float64]
    orientation: npt.NDArray[np.float64]
    world_position: npt.NDArray[np.float64]
    world_orientation: npt.NDArray[np.float64]
    vertical_fov: float
    horizontal_fov: float
    near_plane: float
    far_plane: float
    width: int
    height: int
    render_mode: str
    projection: str
    ortho_scale: float
    enabled: bool
    output_path: Optional[str]

class Sensor(RecordView):
    path: str
    id: str
    kind: str
    parent_object: str
    parent_link: str
    position: npt.NDArray[np.float64]
    orientation: npt.NDArray[np.float64]
    world_position: npt.NDArray[np.float64]
    world_orientation: npt.NDArray[np.float64]
    width: int
    height: int
    vertical_fov: float
    horizontal_fov: float
    near_plane: float
    far_plane: float
    intrinsics: Optional[npt.NDArray[np.float64]]
    update_rate: float
    lidar_channels: int
    lidar_samples: int
    lidar_min_pitch: float
    lidar_max_pitch: float
    lidar_min_range: float
    lidar_max_range: float
    segmentation: bool
    noise_mean: float
    noise_stddev: float
    noise_seed: int
    enabled: bool
    output_path: Optional[str]

class Light(RecordView):
    path: str
    id: str
    type: str
    direction: npt.NDArray[np.float64]
    position: npt.NDArray[np.float64]
    intensity: float
    color: npt.NDArray[np.float64]
    range: float
    cone_angle: float
    inner_cone_angle: float
    radius: float
    area_size: npt.NDArray[np.float64]
    shadows: bool
    negative: bool
    visible: bool

class Material(RecordView):
    id: str
    name: str
    color: npt.NDArray[np.float64]
    metallic: float
    roughness: float
    emissive: npt.NDArray[np.float64]
    emissive_strength: float
    double_sided: bool
    alpha_mode: str

class Scene:
    time_step: float
    gravity: npt.NDArray[np.float64]
    objects: List[SceneObject]
    compounds: List[Compound]
    robots: List[RobotRecord]
    cameras: List[Camera]
    sensors: List[Sensor]
    lights: List[Light]
    materials: List[Material]
    diagnostics: List[Diagnostic]
    def records(self) -> Iterator[RecordView]: ...
    def find(self, name: str) -> RecordView: ...
