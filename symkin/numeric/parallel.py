"""Evaluate a compiled law over Dask arrays or bags, chunk by chunk (the ``dask`` extra).

A :class:`~symkin.numeric.function.NumericFunction` pickles as what it was compiled
from, so each worker compiles it once and evaluates its own chunks; nothing but the
inputs and results travels.

    >>> import numpy as np, sympy as sp, symkin
    >>> da = __import__("pytest").importorskip("dask.array")
    >>> x = sp.Symbol("x")
    >>> f = symkin.compile(2 * x + 1, backend="numpy")
    >>> dask_map(f, da.arange(6, chunks=3)).compute()
    array([ 1.,  3.,  5.,  7.,  9., 11.])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from symkin.errors import InputError, UnsupportedError

__all__ = ["dask_map"]


def _import_dask() -> Any:
    try:
        import dask.array as da
        import dask.bag as db
    except ImportError:
        raise UnsupportedError("evaluating over Dask needs the dask extra: pip install 'symkin[dask]'") from None
    return da, db


def _stacked(f: Any, *blocks: Any) -> np.ndarray:
    out = f(*blocks)
    if len(f.outputs) == 1:
        return np.asarray(out)[None, ...]
    return np.stack([np.asarray(o) for o in out])


def _partition(f: Any, rows: Any) -> list[Any]:
    rows = list(rows)
    if not rows:
        return []
    columns = [np.asarray(c) for c in zip(*rows)]
    out = f(*columns)
    outs = [out] if len(f.outputs) == 1 else list(out)
    return list(zip(*(np.asarray(o).tolist() for o in outs))) if len(outs) > 1 else np.asarray(outs[0]).tolist()


def dask_map(f: Any, *args: Any) -> Any:
    """Evaluate ``f`` over Dask arrays (lazily, block by block) or over a Dask bag.

    Parameters
    ----------
    f : NumericFunction
        A float backend (numpy or numba).
    *args : dask arrays, numbers, or one dask bag
        Arrays broadcast blockwise (numbers are passed to every block).  A single bag
        holds one tuple of arguments per item.

    Returns
    -------
    dask array (one law), tuple of dask arrays (several), or a dask bag of results.
    """
    da, db = _import_dask()
    if f.backend not in ("numpy", "numba"):
        raise InputError(f"dask_map evaluates float backends (numpy, numba); this function uses {f.backend}")
    if len(args) == 1 and isinstance(args[0], db.Bag):
        return args[0].map_partitions(lambda rows: _partition(f, rows))
    if len(args) != len(f.args):
        raise InputError(f"this function takes {len(f.args)} arguments ({', '.join(f.args)}), got {len(args)}")
    arrays = [a if isinstance(a, da.Array) else np.asarray(a, dtype=float) for a in args]
    lazy = [a for a in arrays if isinstance(a, da.Array)]
    if not lazy:
        raise InputError("dask_map needs at least one dask array (or a bag); call the function directly on NumPy arrays")
    ndim = max(a.ndim for a in lazy)
    dtype = np.float32 if f.precision == "float32" else np.float64
    scalars = [a if isinstance(a, da.Array) else a.item() for a in arrays]
    stacked = da.map_blocks(
        lambda *blocks: _stacked(f, *blocks), *scalars, dtype=dtype, new_axis=0,
        meta=np.empty((0,) * (ndim + 1), dtype=dtype),
    )
    if len(f.outputs) == 1:
        return stacked[0]
    return tuple(stacked[k] for k in range(len(f.outputs)))
