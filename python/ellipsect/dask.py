"""The batch queries on dask arrays, chunk by chunk (docs/python.md).

Bodies are described by dask (or numpy) arrays whose rows are bodies; each chunk of rows
becomes one task that builds an Ellipses / Ellipsoids batch in the worker and calls the
query of the ellipsect module on it, so the answers equal one in-process call bit for bit,
whatever the chunking or the cluster::

    import dask.array as da
    from distributed import Client
    import ellipsect.dask as ed

    client = Client("tcp://scheduler:8786")        # or distributed.LocalCluster()
    a = ed.bodies(centers=ca, radii=ra, quaternions=qa, chunks=1_000_000)
    b = ed.bodies(centers=cb, radii=rb, quaternions=qb, chunks=1_000_000)
    hits = ed.overlap(a, b).sum().compute()
    contact = ed.first_contact(a, va, b, vb, t_max=1.0)   # ContactArrays of dask arrays

Workers need the ellipsect package installed (the same version as the client).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import dask
import dask.array as da
import numpy as np

import ellipsect

_ORIENTATIONS = ("angles", "quaternions", "rotations")


@dataclass(frozen=True)
class Bodies:
    """Bodies as dask arrays sharing one chunking of rows: centers (n, N), radii (n, N) and
    optionally one orientation array (angles (n,) in 2D, quaternions (n, 4) in 3D,
    rotations (n, N, N)), as the Ellipses / Ellipsoids constructors take them."""

    dim: int
    centers: da.Array
    radii: da.Array
    orientation: Optional[str] = None
    orientation_values: Optional[da.Array] = None

    def __len__(self):
        return self.centers.shape[0]

    @property
    def row_chunks(self):
        return self.centers.chunks[0]

    def parts(self):
        """Per chunk of rows: the delayed arrays the batch constructor takes."""
        columns = [self.centers, self.radii] + ([self.orientation_values] if self.orientation else [])
        return list(zip(*[c.to_delayed().ravel() for c in columns]))


def _rows(x, row_chunks):
    """x as a dask array chunked like row_chunks along rows, whole in the other axes."""
    x = da.asarray(x)
    return x.rechunk((row_chunks,) + tuple(-1 for _ in x.shape[1:]))


def bodies(centers, radii, *, angles=None, quaternions=None, rotations=None, chunks="auto") -> Bodies:
    """Bodies from arrays of numbers (numpy or dask). `chunks`: rows per task for numpy
    centers (dask centers keep their row chunks); every other array is rechunked to match."""
    given = {name: v for name, v in zip(_ORIENTATIONS, (angles, quaternions, rotations)) if v is not None}
    if len(given) > 1:
        raise ValueError("bodies: give one of angles, quaternions, rotations")
    centers = centers if isinstance(centers, da.Array) else da.from_array(centers, chunks=(chunks, -1))
    centers = centers.rechunk((centers.chunks[0], -1))
    dim = centers.shape[1]
    name, values = next(iter(given.items()), (None, None))
    return Bodies(dim, centers, _rows(radii, centers.chunks[0]), name,
                  None if values is None else _rows(values, centers.chunks[0]))


def _batch(dim, centers, radii, name=None, values=None):
    kind = ellipsect.Ellipses if dim == 2 else ellipsect.Ellipsoids
    extra = {} if name is None else {name: np.ascontiguousarray(values)}
    return kind(centers=np.ascontiguousarray(centers), radii=np.ascontiguousarray(radii), **extra)


def _block(query, dim, a, b, names, extra, kwargs):
    """One task: the query on one chunk of pairs (a, b: centers, radii[, orientation])."""
    batch_a = _batch(dim, a[0], a[1], names[0], *a[2:])
    batch_b = _batch(dim, b[0], b[1], names[1], *b[2:])
    args = [np.ascontiguousarray(e) for e in extra]
    if query == "first_contact":
        return ellipsect.first_contact(batch_a, args[0], batch_b, args[1], args[2], **kwargs)
    return getattr(ellipsect, query)(batch_a, batch_b, **kwargs)


def _apply(query, a: Bodies, b: Bodies, fields, extra=(), **kwargs):
    """Runs `query` on every chunk of pairs; `fields` lists (name, trailing shape, dtype) of
    the result (name None: the result is one array)."""
    if a.dim != b.dim or len(a) != len(b):
        raise ValueError(f"b: expected {len(a)} bodies of dimension {a.dim}, as a, got {len(b)} of {b.dim}")
    values = None if b.orientation_values is None else _rows(b.orientation_values, a.row_chunks)
    b = Bodies(b.dim, _rows(b.centers, a.row_chunks), _rows(b.radii, a.row_chunks), b.orientation, values)
    extra_parts = [_rows(e, a.row_chunks).to_delayed().ravel() for e in extra]
    outputs = {name: [] for name, _, _ in fields}
    run = dask.delayed(_block, pure=True)
    for k, (pa, pb) in enumerate(zip(a.parts(), b.parts())):
        result = run(query, a.dim, pa, pb, (a.orientation, b.orientation), [e[k] for e in extra_parts], kwargs)
        rows = a.row_chunks[k]
        for i, (name, trailing, dtype) in enumerate(fields):
            part = result if name is None else result[i]
            outputs[name].append(da.from_delayed(part, shape=(rows,) + trailing, dtype=dtype))
    arrays = [da.concatenate(outputs[name]) for name, _, _ in fields]
    return arrays[0] if fields[0][0] is None else arrays


def overlap(a: Bodies, b: Bodies, **kwargs) -> da.Array:
    """ellipsect.overlap per chunk: bool (n,)."""
    return _apply("overlap", a, b, [(None, (), np.bool_)], **kwargs)


def classify(a: Bodies, b: Bodies, **kwargs) -> da.Array:
    """ellipsect.classify per chunk: int8 (n,) Relation values."""
    return _apply("classify", a, b, [(None, (), np.int8)], **kwargs)


def first_contact(a: Bodies, velocity_a, b: Bodies, velocity_b, t_max, **kwargs):
    """ellipsect.first_contact per chunk: ContactArrays of dask arrays. t_max: a number or
    an (n,) array."""
    n, d = len(a), a.dim
    windows = da.full((n,), float(t_max)) if np.isscalar(t_max) else t_max
    fields = [("status", (), np.int8), ("time", (), np.float64), ("point", (d,), np.float64),
              ("normal", (d,), np.float64)]
    return ellipsect.ContactArrays(*_apply("first_contact", a, b, fields, (velocity_a, velocity_b, windows), **kwargs))


def _distance_arrays(query, a, b, kwargs):
    d = a.dim
    fields = [("status", (), np.int8), ("distance", (), np.float64)] + [
        (name, (d,), np.float64) for name in ("point_a", "point_b", "normal")]
    return ellipsect.DistanceArrays(*_apply(query, a, b, fields, **kwargs))


def distance(a: Bodies, b: Bodies, **kwargs):
    """ellipsect.distance per chunk: DistanceArrays of dask arrays."""
    return _distance_arrays("distance", a, b, kwargs)


def signed_distance(a: Bodies, b: Bodies, **kwargs):
    """ellipsect.signed_distance per chunk: DistanceArrays of dask arrays."""
    return _distance_arrays("signed_distance", a, b, kwargs)


def overlap_area(a: Bodies, b: Bodies, **kwargs) -> da.Array:
    """ellipsect.overlap_area per chunk (ellipses): float64 (n,)."""
    return _apply("overlap_area", a, b, [(None, (), np.float64)], **kwargs)


def iou(a: Bodies, b: Bodies, **kwargs) -> da.Array:
    """ellipsect.iou per chunk (ellipses): float64 (n,)."""
    return _apply("iou", a, b, [(None, (), np.float64)], **kwargs)
