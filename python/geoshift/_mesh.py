"""Meshes as numpy arrays, and files through the core's reader and writer."""
from __future__ import annotations

import math
from typing import Iterable, Optional, Union

import numpy as np

from . import _geoshift as _core
from ._geoshift import InputError


def _rows(value, name: str, n: Optional[int] = None) -> np.ndarray:
    a = np.asarray(value)
    if a.dtype.kind not in "fiub":
        raise InputError(f"{name} must be an array of numbers (got dtype {a.dtype})")
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim not in (1, 2):
        raise InputError(f"{name} must have shape (N,) or (N, dim) (got {a.shape})")
    if n is not None and a.shape[0] != n:
        raise InputError(f"{name} has {a.shape[0]} rows for {n} vertices")
    return a


class Mesh:
    """A triangle mesh in the caller's own vertex layout.

    positions: float64 (N, 3); faces: int32 (M, 3), counter-clockwise; normals: (N, 3) or None;
    colors: RGBA (N, 4) in [0, 1] or None; attributes: per-vertex arrays by name, (N,) or (N, dim)
    (glTF custom attributes, written as accessors "_NAME"); instances: (K, 4, 4) world transforms
    of the nodes that draw it (empty: identity); z_up: a terrain (written to glTF as the CLI does,
    around a rounded centre with a node turning z-up into glTF's y-up); report: what the terrain
    reader found, else None.

    Filters weld coincident vertices first (as the CLI does) and give results back per vertex of
    this layout.
    """

    def __init__(self, positions, faces, *, normals=None, colors=None, attributes=None, instances=None,
                 label: str = "mesh", z_up: bool = False, report: Optional[dict] = None):
        p = np.asarray(positions)
        if p.dtype.kind not in "fiu" or p.ndim != 2 or p.shape[1] != 3:
            raise InputError(f"positions must be numbers of shape (N, 3) (got {p.dtype} {p.shape})")
        self.positions = np.ascontiguousarray(p, dtype=np.float64)
        f = np.asarray(faces)
        if f.size == 0:
            f = f.reshape(0, 3)
        if f.dtype.kind not in "iu" or f.ndim != 2 or f.shape[1] != 3:
            raise InputError(f"faces must be integers of shape (M, 3) (got {f.dtype} {f.shape})")
        self.faces = np.ascontiguousarray(f, dtype=np.int32)
        n = len(self.positions)
        self.normals = None if normals is None else _rows(normals, "normals", n).reshape(n, 3)
        if colors is not None:
            c = _rows(colors, "colors", n)
            if c.ndim != 2 or c.shape[1] not in (3, 4):
                raise InputError(f"colors must have shape (N, 3) or (N, 4) (got {c.shape})")
            if c.shape[1] == 3:
                c = np.hstack([c, np.ones((n, 1))])
            colors = c
        self.colors = colors
        self.attributes = {str(k): _rows(v, f"attribute '{k}'", n) for k, v in (attributes or {}).items()}
        self.instances = (np.zeros((0, 4, 4)) if instances is None
                          else np.asarray(instances, dtype=np.float64).reshape(-1, 4, 4))
        self.label = label
        self.z_up = z_up
        self.report = report

    @property
    def vertex_count(self) -> int:
        return len(self.positions)

    @property
    def face_count(self) -> int:
        return len(self.faces)

    def copy(self) -> "Mesh":
        """A deep copy (arrays copied)."""
        return Mesh(self.positions.copy(), self.faces.copy(),
                    normals=None if self.normals is None else self.normals.copy(),
                    colors=None if self.colors is None else self.colors.copy(),
                    attributes={k: v.copy() for k, v in self.attributes.items()},
                    instances=self.instances.copy(), label=self.label, z_up=self.z_up, report=self.report)

    def world_positions(self, instance: int = 0) -> np.ndarray:
        """Positions through the transform of one instance (identity when there is none)."""
        if len(self.instances) == 0:
            return self.positions.copy()
        t = self.instances[instance]
        return self.positions @ t[:3, :3].T + t[:3, 3]

    def _built(self, weld: bool = True):
        return _core._build(self.positions, self.faces, weld)

    def __repr__(self) -> str:
        extras = []
        if self.normals is not None:
            extras.append("normals")
        if self.colors is not None:
            extras.append("colors")
        extras += list(self.attributes)
        return (f"Mesh({self.label!r}, {self.vertex_count} vertices, {self.face_count} faces"
                + (f", {', '.join(extras)}" if extras else "") + ")")

    @classmethod
    def _from_dict(cls, d: dict, **extra) -> "Mesh":
        return cls(d["positions"], d["faces"], normals=d.get("normals"), colors=d.get("colors"),
                   attributes=d.get("attributes"), instances=d.get("instances"),
                   label=d.get("label", "mesh"), **extra)


class Document:
    """A mesh file as read: its parts (one Mesh per triangle mesh; glTF: the primitives that share
    a POSITION accessor) and what the reader passed through untouched (warnings). Writing it back
    into its own format keeps everything but the geometry as it was (materials, nodes, extras,
    OBJ groups and texture coordinates)."""

    def __init__(self, path: str, format: str, parts: list, warnings: list, source=None):
        self.path = path
        self.format = format
        self.parts = parts
        self.warnings = warnings
        self._source = source

    @property
    def mesh(self) -> Mesh:
        """The only part; InputError when the file has several."""
        if len(self.parts) != 1:
            raise InputError(f"{self.path}: has {len(self.parts)} meshes; pick one of doc.parts")
        return self.parts[0]

    def __repr__(self) -> str:
        return f"Document({self.path!r}, {self.format}, {len(self.parts)} part(s))"


def read(path) -> Document:
    """Reads a mesh file with the core's reader (format by extension: .gltf .glb .obj .off and
    whatever else the core reads). Raises InputError naming the file and what/where is wrong."""
    d = _core._read(str(path))
    parts = [Mesh._from_dict(p) for p in d["parts"]]
    return Document(d["path"], d["format"], parts, list(d["warnings"]), d["source"])


def _round(x: float) -> float:
    # std::round: halves away from zero
    return math.copysign(math.floor(abs(x) + 0.5), x)


def _placed(mesh: Mesh) -> Mesh:
    """A z-up terrain as `geoshift terrain` writes it: coordinates relative to a rounded centre
    (glTF positions are float32), a node that puts them back and turns z-up into y-up."""
    lo = mesh.positions.min(axis=0)
    hi = mesh.positions.max(axis=0)
    origin = np.array([_round(0.5 * (lo[0] + hi[0])), _round(0.5 * (lo[1] + hi[1])), 0.0])
    y_up = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], dtype=np.float64)
    shift = np.eye(4)
    shift[:3, 3] = origin
    placed = mesh.copy()
    placed.positions = mesh.positions - origin
    placed.instances = (y_up @ shift)[None]
    placed.z_up = False
    return placed


def write(what: Union[Document, Mesh, Iterable[Mesh]], path) -> list:
    """Writes a Document, a Mesh or a list of meshes; format by the extension. Atomic: on any
    error nothing is written. A Document written into its own format keeps everything that is not
    geometry; another format keeps geometry, normals, colors (and attributes in glTF) with a
    warning. Returns the writer's warnings."""
    if isinstance(what, Document):
        source, parts = what._source, what.parts
    elif isinstance(what, Mesh):
        source, parts = None, [what]
    else:
        source, parts = None, list(what)
    parts = [_placed(p) if p.z_up and len(p.instances) == 0 else p for p in parts]
    return list(_core._write(source, parts, str(path)))
