"""What a notebook shows for an :class:`~spectrocolor.UpsamplingTable`: its coverage.

How much of the colour cube the table reproduces exactly: the count of exact nodes and of nodes
moved toward grey (their colour lies outside the object-colour solid, or could not be
certified), the cells with a rigorous roughness-excess bound, and :data:`SLICES` slices through
the cube along its third coordinate, each node a cell in the colour its reflectance produces
(on the default display), a moved node crossed out. Slices are thinned to at most
:data:`SLICE_SIDE` nodes a side, so the picture stays small for a 129-node table.

Examples
--------
>>> from spectrocolor import upsampling_table
>>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
>>> "27 of 27" in upsampling_table_html(table)
True
"""

from __future__ import annotations

import numpy as np

from . import layout
from .colours import object_swatches
from .markup import element, number
from .svg import Canvas, thin

__all__ = ["SLICES", "SLICE_SIDE", "upsampling_table_html", "upsampling_table_svg"]

#: Slices drawn along the cube's third coordinate.
SLICES = 5
#: Largest number of nodes drawn along a side of a slice.
SLICE_SIDE = 13
_CELL = 9.0


def _slices(table) -> Canvas:
    n = table.resolution
    third = thin(n, SLICES)
    side = thin(n, SLICE_SIDE)
    picked = np.ix_(side, side, third)
    XYZ = table.node_XYZ100[picked].transpose(2, 0, 1, 3).reshape(-1, 3)
    moved = (table.node_status[picked] != 0).transpose(2, 0, 1).reshape(-1)
    hexes = object_swatches(XYZ, table.weights.sum(axis=0)).hexes
    block = len(side) * _CELL
    axis = "Z/Zw" if table.space == "XYZ" else "B"
    first_axis, second_axis = ("X/Xw", "Y/Yw") if table.space == "XYZ" else ("R", "G")
    canvas = Canvas(int(len(third) * (block + 14) + 4), int(block + 30),
                    f"coverage of the {n}³ table: slices at {axis} = " + ", ".join(f"{k / (n - 1):.2g}" for k in third))
    k = 0
    for s, level in enumerate(third.tolist()):
        left = 2 + s * (block + 14)
        for i in range(len(side)):  # first coordinate left to right, second bottom to top
            for j in range(len(side)):
                x, y = left + i * _CELL, 2 + (len(side) - 1 - j) * _CELL
                colour = hexes[k] or "#808080"
                canvas.add(element("rect", x=f"{x:.0f}", y=f"{y:.0f}", width=f"{_CELL + 0.3:.1f}",
                                   height=f"{_CELL + 0.3:.1f}", fill=colour))
                if moved[k]:
                    canvas.add(element("path", d=f"M{x + 1:.0f} {y + 1:.0f}l{_CELL - 2:.0f} {_CELL - 2:.0f}m0 "
                                                 f"-{_CELL - 2:.0f}l-{_CELL - 2:.0f} {_CELL - 2:.0f}",
                                       stroke="currentColor", stroke_width="1.2"))
                k += 1
        canvas.add(element("rect", x=f"{left:.0f}", y="2", width=f"{block:.0f}", height=f"{block:.0f}", fill="none",
                           stroke="currentColor", stroke_opacity="0.45"),
                   element("text", f"{axis} = {level / (n - 1):.2g}", x=f"{left + block / 2:.1f}",
                           y=f"{block + 15:.0f}", text_anchor="middle", fill="currentColor"))
    canvas.add(element("text", f"{first_axis} → across, {second_axis} ↑; × moved toward grey", x=2,
                       y=f"{block + 27:.0f}", fill="currentColor", fill_opacity="0.7", font_size=9))
    return canvas


def _coverage(table) -> list:
    nodes = table.node_status.size
    exact = int(np.count_nonzero(table.node_status == 0))
    cells = table.cell_excess_bound.size
    bounded = int(np.count_nonzero(np.isfinite(table.cell_excess_bound)))
    measured = table.cell_excess_measured[np.isfinite(table.cell_excess_measured)]
    bound = table.cell_excess_bound[np.isfinite(table.cell_excess_bound)]
    return [
        ["exact nodes", f"{exact:,} of {nodes:,} ({number(100 * exact / nodes, 1)} %)"],
        ["moved toward grey", f"{nodes - exact:,}"],
        ["cells with a rigorous excess bound", f"{bounded:,} of {cells:,}"],
        ["largest excess bound, nm⁻¹", f"{bound.max():.3g}" if bound.size else "—"],
        ["largest measured excess, nm⁻¹", f"{measured.max():.3g}" if measured.size else "— (not measured)"],
    ]


def upsampling_table_html(table) -> str:
    """HTML: the coverage numbers and the slices through the cube.


    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> "moved toward grey" in upsampling_table_html(upsampling_table("sRGB", "D65", resolution=3,
    ...                                                                measure_excess=False))
    True
    """
    grid = table.wavelengths_nm
    subtitle = (f"{table.space} · {table.illuminant}, {table.observer} · {table.resolution} nodes per axis · "
                f"{grid[0]:g}–{grid[-1]:g} nm, K = {grid.size}")
    verdict = ("every colour inside the cube is reproduced exactly" if table.all_exact else
               "colours in cells with a moved node are not reproduced exactly")
    parts = [layout.row([_slices(table).markup(), layout.table(["coverage", ""], _coverage(table),
                                                                text_columns=(0,))]),
             layout.note(f"{verdict}; nodes are certified smoothest reflectances (van Trigt 1990), 0 ≤ ρ ≤ 1")]
    return str(layout.card("UpsamplingTable", subtitle, parts))


def upsampling_table_svg(table) -> str:
    """Standalone SVG: the slices through the cube.


    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> upsampling_table_svg(upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)).count("<rect") > 27
    True
    """
    return str(_slices(table).markup(standalone=True))
