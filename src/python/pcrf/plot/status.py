"""`status`: how each case ended, as a map over two axes of the cube (--x, --y); every other
axis must be down to one value (select it with -w NAME=VALUE)."""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from .. import _names as schema
from . import engine, style
from .errors import PlotError

MAX_TICKS = 45


def axis_values(cube, rows, name):
    """The axis values present among the rows, in the cube's order."""
    present = {r[name] for r in rows}
    return [v for v in cube.dimension(name)["values"] if v in present]


def tick_labels(rows, name, values):
    """Labels of an axis's values: the case labels on a `case` axis, else the values."""
    if name == schema.CASE and rows and schema.CASE_LABEL in rows[0]:
        label = {r[schema.CASE]: r[schema.CASE_LABEL] for r in rows}
        return [label[v] for v in values]
    return values


def draw(args):
    cube = engine.Cube(args.input)
    names = [d["name"] for d in cube.dimensions]
    for axis in (args.x, args.y):
        if axis and axis not in names:
            raise PlotError(f"{args.input}: no axis {axis} (axes: {', '.join(names)})")
    rows = cube.export([cube.info["metrics"][0]["name"]], args.where)
    if not rows:
        raise PlotError(f"{args.input}: no case matches the selection")
    several = [n for n in names if len({r[n] for r in rows}) > 1]
    x = args.x or next((n for n in several if n != args.y), None)
    y = args.y or next((n for n in several if n != x), None)
    if x is None or y is None or x == y:
        raise PlotError(f"{args.input}: a status map needs two different axes with several values "
                        f"(axes with several values: {', '.join(several) or 'none'}); name them with --x and --y")
    rest = [n for n in several if n not in (x, y)]
    if rest:
        hint = " ".join(f"-w {n}={rows[0][n]}" for n in rest)
        raise PlotError(f"{', '.join(rest)}: several values left; select one of each, e.g. {hint}")
    xs, ys = axis_values(cube, rows, x), axis_values(cube, rows, y)
    present = {r[schema.STATUS] for r in rows}
    statuses = [s for s in engine.statuses() if s in present] + sorted(present - set(engine.statuses()))
    colours = [style.status_colour(s, engine.status_kind(s)) for s in statuses]
    code = {s: i for i, s in enumerate(statuses)}
    grid = np.full((len(ys), len(xs)), np.nan)
    xi, yi = {v: i for i, v in enumerate(xs)}, {v: i for i, v in enumerate(ys)}
    for r in rows:
        grid[yi[r[y]], xi[r[x]]] = code[r[schema.STATUS]]
    fig, ax = plt.subplots(figsize=(min(14, 2.5 + 0.45 * len(xs)), min(10, 2.0 + 0.35 * len(ys))),
                           constrained_layout=True)
    ax.pcolormesh(np.ma.masked_invalid(grid), cmap=ListedColormap(colours),
                  vmin=-0.5, vmax=len(statuses) - 0.5, edgecolors="white", linewidth=0.5)
    for axis, values, name, set_ticks, set_label in ((ax.xaxis, xs, x, ax.set_xticks, ax.set_xlabel),
                                                      (ax.yaxis, ys, y, ax.set_yticks, ax.set_ylabel)):
        step = max(1, len(values) // MAX_TICKS + (len(values) % MAX_TICKS > 0))
        positions = np.arange(0, len(values), step)
        set_ticks(positions + 0.5, [tick_labels(rows, name, values)[i] for i in positions])
        set_label(style.parameter_label(name) if name in style.PARAMETER_SYMBOLS else name)
    if len(xs) > 8:
        plt.setp(ax.get_xticklabels(), rotation=60, ha="right")
    ax.grid(False)
    ax.legend(handles=[Patch(color=c, label=s.replace("_", " ")) for s, c in zip(statuses, colours)],
              loc="upper left", bbox_to_anchor=(1.01, 1.0), title=schema.STATUS)
    selected = ", ".join(args.where) if args.where else "all cases"
    ax.set_title(args.title or f"How each case ended ({selected})")
    return fig
