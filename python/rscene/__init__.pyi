# Type stubs of the rscene package (python/rscene/__init__.py).
import os
from typing import Any, List, Optional, Union

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
    def save(self, path: _Path) -> None: ...

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
    def __init__(self, diagnostics: List[Diagnostic], name: str = ...) -> None: ...

class Simulation:
    def __init__(self, doc: Document) -> None: ...
    def step(self, n: int = ...) -> None: ...
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
    def document(self) -> Document: ...
