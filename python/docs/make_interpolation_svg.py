"""Draws python/docs/interpolation_offset.svg: griddata on 2,000 points offset by 10^7.

    PYTHONPATH=build/python /usr/bin/python3 python/docs/make_interpolation_svg.py

Three panels over the same 2,000 random points of the unit square, shifted by
10^7 in x and y, and the same 24 x 24 queries: the function sin(6x)·y, scipy's
griddata (Qhull triangulates the shifted points into a few triangles (14), drawn
in white) and dewall's. Plain SVG written here (matplotlib is not among the
Debian packages the project installs). Seeded: the same picture every run.
"""

import os

import numpy as np
import scipy.interpolate as si
import scipy.spatial as ss

import dewall
import dewall.interpolate as di

OFFSET, SIZE, CELLS, PANEL, GAP = 1e7, 2000, 24, 240, 20


def colour(value):
    """A blue-white-red ramp for values in [-1, 1]; grey for NaN."""
    if not np.isfinite(value):
        return "#888"
    t = (np.clip(value, -1, 1) + 1) / 2  # 0 blue, 1/2 white, 1 red
    fade = int(round(255 * (2 * t if t < 0.5 else 2 - 2 * t)))
    red, blue = (fade, 255) if t < 0.5 else (255, fade)
    return f"#{red:02x}{fade:02x}{blue:02x}"


def panel(x0, title, field, triangles=None, points=None):
    step = PANEL / CELLS
    out = [f'<text x="{x0 + PANEL / 2}" y="16" text-anchor="middle" font-size="13">{title}</text>']
    out.append(f'<g transform="translate({x0} 24) scale({step})">')  # one unit per cell
    for i in range(CELLS):
        for j in range(CELLS):
            out.append(f'<rect x="{i}" y="{CELLS - 1 - j}" width="1.05" height="1.05" fill="{colour(field[j, i])}"/>')
    out.append("</g>")
    if triangles is not None:
        for t in triangles:
            corners = " ".join(f"{x0 + x * PANEL:.1f},{24 + (1 - y) * PANEL:.1f}" for x, y in points[t])
            out.append(f'<polygon points="{corners}" fill="none" stroke="white" stroke-width="0.8"/>')
    return out


def main():
    rng = np.random.default_rng(1)
    points = rng.random((SIZE, 2))
    values = np.sin(6 * points[:, 0]) * points[:, 1]
    axis = (np.arange(CELLS) + 0.5) / CELLS
    x, y = np.meshgrid(axis, axis)
    exact = np.sin(6 * x) * y
    theirs = si.griddata(points + OFFSET, values, (x + OFFSET, y + OFFSET))
    ours = di.griddata(points + OFFSET, values, (x + OFFSET, y + OFFSET))
    qhull = ss.Delaunay(points + OFFSET)
    width = 3 * PANEL + 2 * GAP
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{PANEL + 44}" '
             f'font-family="sans-serif">']
    parts += panel(0, "sin(6x)·y", exact)
    parts += panel(PANEL + GAP, f"scipy griddata ({qhull.nsimplex} triangles)", theirs,
                   qhull.simplices, points)
    parts += panel(2 * (PANEL + GAP), f"dewall griddata ({dewall.Delaunay(points + OFFSET).nsimplex} triangles)", ours)
    error = f"max error: scipy {np.nanmax(np.abs(theirs - exact)):.2f}, dewall {np.nanmax(np.abs(ours - exact)):.3f}"
    parts.append(f'<text x="{width / 2}" y="{PANEL + 40}" text-anchor="middle" font-size="12">'
                 f"2,000 random points of the unit square + 10^7; {error}</text>")
    parts.append("</svg>\n")
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "interpolation_offset.svg")
    with open(path, "w") as f:
        f.write("\n".join(parts))
    print(path, error)


if __name__ == "__main__":
    main()
