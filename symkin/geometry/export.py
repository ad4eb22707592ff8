"""A train's tooth outlines for CAD: DXF (through ezdxf) and SVG, in millimetres.

Every spur gear of a :class:`~symkin.geometry.TrainGeometry` is one closed polyline
(:func:`~symkin.geometry.tooth_outline`: involute flanks, tip and root circles, the
trochoidal root fillet of the generating rack), on a layer of its own (``gear-NAME``),
placed at its axis at t = 0 and turned so that the teeth of every mesh interleave.  These
functions return the file's text; the command line writes it (``symkin geometry --out``).

ezdxf is an optional dependency (``pip install "symkin[cad]"``): it writes DXF files that
CAD programs open (and audits them); SVG needs nothing.
"""

from __future__ import annotations

import io
from typing import Any

import numpy as np

from symkin.errors import InputError
from symkin.geometry.outline import tooth_outline
from symkin.geometry.train import TrainGeometry

__all__ = ["placed_outlines", "dxf_document", "dxf_text", "svg_text", "layer_name"]


def layer_name(gear: str) -> str:
    """The DXF layer (and SVG id) of a gear's outline.

    >>> layer_name("s1")
    'gear-s1'
    """
    return f"gear-{gear}"


def placed_outlines(geo: TrainGeometry, *, points: int = 16) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each gear's closed outline (x, y in mm) where the train puts it at t = 0."""
    out = {}
    for name, gear in geo.gears.items():
        cx, cy, phase = geo.placement[name]
        x, y = tooth_outline(gear, phase=phase, points=points)
        out[name] = (x + cx, y + cy)
    return out


def dxf_document(geo: TrainGeometry, *, points: int = 16) -> Any:
    """An ezdxf document (R2010, millimetres) with one closed polyline per gear on its own layer."""
    try:
        import ezdxf
        from ezdxf import units
    except ImportError:
        raise InputError("DXF export needs the ezdxf package: pip install \"symkin[cad]\" (or write --out FILE.svg)") from None
    doc = ezdxf.new("R2010", setup=True)
    doc.units = units.MM
    msp = doc.modelspace()
    for k, (name, (x, y)) in enumerate(placed_outlines(geo, points=points).items()):
        layer = layer_name(name)
        doc.layers.add(layer, color=1 + k % 7)
        msp.add_lwpolyline(list(zip(x[:-1].tolist(), y[:-1].tolist())), close=True, dxfattribs={"layer": layer})
    return doc


def dxf_text(geo: TrainGeometry, *, points: int = 16) -> str:
    """The DXF file's text (see :func:`dxf_document`)."""
    stream = io.StringIO()
    dxf_document(geo, points=points).write(stream)
    return stream.getvalue()


def svg_text(geo: TrainGeometry, *, points: int = 16) -> str:
    """An SVG drawing of the outlines (1 user unit = 1 mm, y up as in the DXF), one path per gear."""
    shapes = placed_outlines(geo, points=points)
    if not shapes:
        raise InputError("the train has no spur gear to draw")
    xs = np.concatenate([x for x, _ in shapes.values()])
    ys = np.concatenate([y for _, y in shapes.values()])
    pad = 0.05 * max(float(np.ptp(xs)), float(np.ptp(ys)), 1.0)
    x0, x1, y0, y1 = xs.min() - pad, xs.max() + pad, ys.min() - pad, ys.max() + pad
    width, height = x1 - x0, y1 - y0
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.3f}mm" height="{height:.3f}mm" '
             f'viewBox="{x0:.4f} {-y1:.4f} {width:.4f} {height:.4f}">',
             f'<g transform="scale(1,-1)" fill="none" stroke="black" stroke-width="{width / 800:.4f}">']
    for name, (x, y) in shapes.items():
        d = "M " + " L ".join(f"{a:.5f},{b:.5f}" for a, b in zip(x[:-1], y[:-1])) + " Z"
        lines.append(f'<path id="{layer_name(name)}" d="{d}"/>')
    lines += ["</g>", "</svg>", ""]
    return "\n".join(lines)
