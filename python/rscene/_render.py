"""Rendering: rscene-render's images as numpy arrays (issue 28).

Images are drawn exactly as ``rscene-render`` draws them (the same scene
build, views, lights, shadows and post-processing), headless through EGL
(a GPU when one answers, else Mesa's llvmpipe on the CPU).  Colour comes
as an ``(H, W, 4)`` uint8 RGBA array (rows top to bottom), depth as an
``(H, W)`` float32 array in metres along the view's axis (NaN where
nothing is hit), segmentation as an RGBA array whose colours the legend
names.
"""
from __future__ import annotations

import json as _json
import os as _os
import warnings as _warnings
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _rscene
from . import Diagnostic, Document, Simulation, _base_dir, _check_document, _count, _diagnostics, _flag

__all__ = ["LookAt", "RenderError", "Renderer", "render", "render_depth", "render_segmentation",
           "render_available"]

_AVAILABLE = bool(getattr(_rscene, "render_available", False))


def render_available() -> bool:
    """Whether this build of the package can render: lib/render needs EGL
    and OpenGL when the package is built.  Where it cannot, every rendering
    call raises ``RuntimeError``.  (Whether an OpenGL context can be made
    here is known at the first draw: ``RuntimeError`` then too.)"""
    return _AVAILABLE

_PASSES = ("rgb", "depth", "segmentation")


class RenderError(ValueError):
    """A scene or view that cannot be drawn: an asset that does not read, an
    unknown camera, an image size over the limits, a scene with errors.
    ``diagnostics`` lists the findings (``file:line:col`` as rscene-render
    prints them); ``str()`` is the first error."""

    def __init__(self, message: str, diagnostics: Optional[List[Diagnostic]] = None) -> None:
        self.diagnostics = diagnostics or []
        errors = [d for d in self.diagnostics if d.severity == "error"]
        if errors and (not message or message == errors[0].message):
            message = str(errors[0]).split("\n")[0]
            if len(errors) > 1:
                message += " (and %d more errors)" % (len(errors) - 1)
        super().__init__(message)


def _render_error(message: str, raw: list, scene: str) -> RenderError:
    # Made by the C++ side (python/render.cpp) for a failure.
    return RenderError(message, _diagnostics(raw, scene))


class LookAt:
    """A camera placed by hand, as ``rscene-render --camera-position
    --look-at --fov``: at ``position`` looking at ``target`` (world
    coordinates, metres) with +z up and a vertical field of view of ``fov``
    degrees (1 to 175).  Pass it as ``camera=``."""

    __slots__ = ("position", "target", "fov")

    def __init__(self, position: Sequence[float], target: Sequence[float], fov: float = 50.0) -> None:
        self.position = _point(position, "position")
        self.target = _point(target, "target")
        if isinstance(fov, bool) or not isinstance(fov, (int, float, _np.integer, _np.floating)):
            raise TypeError("LookAt: fov must be a number of degrees")
        self.fov = float(fov)

    def __repr__(self) -> str:
        return "LookAt(%r, %r, fov=%g)" % (self.position, self.target, self.fov)


def _point(value: Any, name: str) -> Tuple[float, float, float]:
    try:
        a = _np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError("LookAt: %s must be 3 numbers" % name) from None
    if a.shape != (3,):
        raise ValueError("LookAt: %s must be 3 numbers, not shape %s" % (name, a.shape))
    return (float(a[0]), float(a[1]), float(a[2]))


def _size(value: Any, name: str) -> int:
    if value is None:
        return 0
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
        raise TypeError("%s must be an int, not %s" % (name, type(value).__name__))
    if value < 1:
        raise ValueError("%s must be at least 1, not %d" % (name, value))
    return min(int(value), 2**31 - 1)


def _camera(camera: Any) -> Tuple[Optional[str], Optional[tuple]]:
    if camera is None:
        return None, None
    if isinstance(camera, LookAt):
        return None, (list(camera.position), list(camera.target), camera.fov)
    if isinstance(camera, str):
        if not camera:
            raise ValueError("camera must name a camera or sensor (path or id), or be 'auto', a LookAt or None")
        return camera, None
    raise TypeError("camera must be a str (a camera's or sensor's path or id, or 'auto'), a LookAt or None, not %s"
                    % type(camera).__name__)


def _require() -> None:
    if not _AVAILABLE:
        raise RuntimeError("this build of rscene has no rendering (lib/render needs EGL and OpenGL when it is built)")


class Renderer:
    """A scene built and uploaded once, drawn many times: from other
    cameras, at other sizes, and at a :class:`Simulation`'s poses
    (``renderer.draw(sim)``).  ``camera``, ``width`` and ``height`` are the
    defaults of every draw; each draw may give its own.

    ``camera``: None (the scene's first enabled camera record, else the
    automatic three-quarter view), ``"auto"``, a camera record's or
    camera-like sensor's path or id, or a :class:`LookAt`.  ``width`` and
    ``height`` size camera records and the automatic view (a sensor keeps
    its own size: its intrinsics are written for it); each side left out is
    the camera's own, else 1280 x 720.  ``samples`` is the colour pass's
    MSAA, ``post`` the scene's post-processing (``rscene-render
    --no-post`` is ``post=False``), ``transparent`` gives alpha 0 where no
    geometry covers a pixel.  ``allow_missing_assets=True`` is
    ``rscene-render --allow-missing-assets``: a missing mesh is drawn as a
    magenta box and a missing texture left out, each with a warning (see
    :attr:`diagnostics`) instead of a :class:`RenderError`.  ``base_dir``
    is ``--base-dir``: the folder relative asset paths resolve against, in
    place of the scene file's folder.

    Raises :class:`RenderError` when the scene cannot be drawn.  Drawing
    releases the GIL; renderers in several threads take turns on the one
    OpenGL context of the process."""

    __slots__ = ("_r", "_doc", "_camera", "_look", "_width", "_height")

    def __init__(self, doc: Document, camera: Union[str, LookAt, None] = None, width: Optional[int] = None,
                 height: Optional[int] = None, *, samples: int = 4, post: bool = True,
                 transparent: bool = False, allow_missing_assets: bool = False,
                 base_dir: Union[str, "_os.PathLike[str]", None] = None) -> None:
        self._r = None
        _require()
        raw = _check_document(doc)
        self._camera, self._look = _camera(camera)
        self._width, self._height = _size(width, "width"), _size(height, "height")
        samples = _count(samples, "samples")
        if not 1 <= samples <= 64:
            raise ValueError("samples must be 1 to 64, not %d" % samples)
        allow = _flag(allow_missing_assets, "allow_missing_assets")
        base = _base_dir(base_dir)
        self._doc = doc
        self._r = _rscene.renderer(raw, self._still(), samples, bool(post), bool(transparent), allow, base)

    @staticmethod
    def _still() -> bool:
        return False

    def draw_passes(self, sim: Optional[Simulation] = None, passes: Sequence[str] = _PASSES,
                    camera: Union[str, LookAt, None] = None, width: Optional[int] = None,
                    height: Optional[int] = None) -> Dict[str, Any]:
        """Draws the ``passes`` (``"rgb"``, ``"depth"``, ``"segmentation"``)
        of one view in one go (``width``/``height`` given here for a
        sensor, which keeps its own size, warn with ``RuntimeWarning``): a dict with ``"rgb"`` (``(H, W, 4)`` uint8),
        ``"depth"`` (``(H, W)`` float32 metres, NaN where nothing is hit),
        ``"segmentation"`` (``(H, W, 4)`` uint8, colours as in
        :attr:`legend`) for the passes asked, and ``"view"`` (the view's
        name).  With ``sim`` the bodies, robots and particles are drawn
        where the simulation has them now (and cameras and sensors riding
        on them move along).  A draw without ``sim`` draws the document as
        written (as a fresh renderer does), whatever earlier draws were
        given."""
        if isinstance(passes, str):
            passes = [passes]
        names = list(passes)
        for p in names:
            if p not in _PASSES:
                raise ValueError("unknown pass %r: use 'rgb', 'depth' or 'segmentation'" % (p,))
        if not names:
            raise ValueError("no pass to draw")
        raw_sim = None
        if sim is not None:
            if not isinstance(sim, Simulation):
                raise TypeError("sim must be an rscene.Simulation, not %s" % type(sim).__name__)
            raw_sim = sim._sim
        if camera is None:
            cam, look = self._camera, self._look
        else:
            cam, look = _camera(camera)
        w = self._width if width is None else _size(width, "width")
        h = self._height if height is None else _size(height, "height")
        out = self._r.draw(raw_sim, cam, look, w, h, names)
        # A size this call gives that the view does not take; the
        # renderer's own defaults apply where they can, silently.
        if width is not None or height is not None:
            for text in out.pop("warnings"):
                _warnings.warn(text, RuntimeWarning, stacklevel=3)
        else:
            out.pop("warnings")
        return out

    def draw(self, sim: Optional[Simulation] = None, camera: Union[str, LookAt, None] = None,
             width: Optional[int] = None, height: Optional[int] = None) -> "_np.ndarray":
        """The colour image, ``(H, W, 4)`` uint8 RGBA, rows top to bottom
        (at ``sim``'s poses when given: see :meth:`draw_passes`)."""
        return self.draw_passes(sim, ("rgb",), camera, width, height)["rgb"]

    def draw_depth(self, sim: Optional[Simulation] = None, camera: Union[str, LookAt, None] = None,
                   width: Optional[int] = None, height: Optional[int] = None) -> "_np.ndarray":
        """The depth image, ``(H, W)`` float32: metres along the view's
        axis (as rscene-render's ``.npy``), NaN where nothing is hit within
        the near and far planes; a sensor's noise added."""
        return self.draw_passes(sim, ("depth",), camera, width, height)["depth"]

    def draw_segmentation(self, sim: Optional[Simulation] = None, camera: Union[str, LookAt, None] = None,
                          width: Optional[int] = None, height: Optional[int] = None) -> "_np.ndarray":
        """The segmentation image, ``(H, W, 4)`` uint8: each record's colour
        (see :attr:`legend`), black where nothing is hit."""
        return self.draw_passes(sim, ("segmentation",), camera, width, height)["segmentation"]

    @property
    def legend(self) -> Dict[str, Any]:
        """The segmentation legend as rscene-render writes it beside its
        images: ``{"background": {...}, "segments": [{"color": [r, g, b],
        "hex", "kind", "path", "id", "semanticClass", "instanceId"}, ...]}``."""
        return _json.loads(self._r.legend)

    def segment_of(self, color: Sequence[int]) -> Optional[Dict[str, Any]]:
        """The legend entry of a segmentation colour (``[r, g, b]``, or an
        RGBA pixel), or None for the background and unknown colours."""
        c = [int(x) for x in list(color)[:3]]
        for s in self.legend["segments"]:
            if s["color"] == c:
                return s
        return None

    @property
    def views(self) -> List[Dict[str, Any]]:
        """Every camera record and camera-like sensor of the scene, in
        rscene-render's order: dicts with ``name`` (path), ``id``,
        ``sensor``, ``enabled``, ``width``, ``height``."""
        return self._r.views

    @property
    def backend(self) -> Optional[Tuple[str, str]]:
        """Where drawing happens: ``("gpu", renderer)`` or ``("cpu",
        "llvmpipe ...")`` (the process's one OpenGL context, made by the
        first draw), or None before any draw."""
        return self._r.backend

    @property
    def diagnostics(self) -> List[Diagnostic]:
        """Warnings of building and drawing the scene (as rscene-render
        prints them)."""
        return _diagnostics(self._r.diagnostics, _os.fsdecode(self._doc._doc.path))

    def __repr__(self) -> str:
        return "<rscene.Renderer of %s>" % (repr(self._doc.path) if self._doc.path else "a scene from text")


class _StillRenderer(Renderer):
    # render(): one view at rest, tessellated for it as rscene-render's
    # still is (the same pixels as the tool).
    __slots__ = ()

    @staticmethod
    def _still() -> bool:
        return True


def _once(doc: Document, camera: Any, width: Any, height: Any, passes: Sequence[str], **options: Any) -> dict:
    r = _StillRenderer(doc, camera, width, height, **options)
    return r.draw_passes(None, passes)


def render(doc: Document, camera: Union[str, LookAt, None] = None, width: Optional[int] = None,
           height: Optional[int] = None, *, samples: int = 4, post: bool = True,
           transparent: bool = False, allow_missing_assets: bool = False,
           base_dir: Union[str, "_os.PathLike[str]", None] = None) -> "_np.ndarray":
    """The colour image of one view of ``doc``, ``(H, W, 4)`` uint8 RGBA,
    rows top to bottom: the pixels ``rscene-render`` writes to its PNG for
    the same camera and size.  ``camera``, ``width``, ``height`` and the
    options are :class:`Renderer`'s.  Raises :class:`RenderError` when the
    scene or view cannot be drawn (an unknown camera, a size over the
    limits), ``RuntimeError`` when no OpenGL context can be made.  Drawing
    many images of one scene?  A :class:`Renderer` uploads it once."""
    return _once(doc, camera, width, height, ("rgb",), samples=samples, post=post, transparent=transparent,
                 allow_missing_assets=allow_missing_assets, base_dir=base_dir)["rgb"]


def render_depth(doc: Document, camera: Union[str, LookAt, None] = None, width: Optional[int] = None,
                 height: Optional[int] = None, *, allow_missing_assets: bool = False,
                 base_dir: Union[str, "_os.PathLike[str]", None] = None) -> "_np.ndarray":
    """The depth image of one view of ``doc``, ``(H, W)`` float32 metres
    along the view's axis, NaN where nothing is hit: rscene-render's
    ``.npy``.  Arguments as :func:`render`."""
    return _once(doc, camera, width, height, ("depth",), allow_missing_assets=allow_missing_assets,
                 base_dir=base_dir)["depth"]


def render_segmentation(doc: Document, camera: Union[str, LookAt, None] = None, width: Optional[int] = None,
                        height: Optional[int] = None, *, allow_missing_assets: bool = False,
                        base_dir: Union[str, "_os.PathLike[str]", None] = None) -> Tuple["_np.ndarray", Dict[str, Any]]:
    """The segmentation image of one view of ``doc`` (``(H, W, 4)`` uint8,
    one colour per record, black background) and its legend (the JSON
    rscene-render writes beside it, as a dict).  Arguments as
    :func:`render`."""
    r = _StillRenderer(doc, camera, width, height, allow_missing_assets=allow_missing_assets, base_dir=base_dir)
    return r.draw_passes(None, ("segmentation",))["segmentation"], r.legend
