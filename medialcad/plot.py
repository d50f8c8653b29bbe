"""Pictures of a 2D medial axis (matplotlib, imported only when used; headless-safe)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from medialcad.api import MedialAxis2D

__all__ = ["plot_medial_axis_2d"]


def plot_medial_axis_2d(
    mat: MedialAxis2D, path: str | os.PathLike[str], *, disks: int = 12, dpi: int = 150
) -> None:
    """Draw the profile, its medial axis coloured by radius, the nodes and a few maximal
    disks to a PNG (in the face's own frame)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    fig, ax = plt.subplots(figsize=(7, 7))
    for xy in mat.outline(200):
        ax.plot(xy[:, 0], xy[:, 1], color="black", lw=1.2)
    segs: list[np.ndarray] = []
    vals: list[float] = []
    for b in mat.branches:
        lo, hi = b.spline.domain
        v = b.spline(np.linspace(lo, hi, 200))
        segs.extend(np.stack([v[:-1, :2], v[1:, :2]], axis=1))
        vals.extend(0.5 * (v[:-1, 2] + v[1:, 2]))
    rmax = max(mat.rmax, 1e-300)
    if segs:
        lc = LineCollection(segs, cmap="viridis", linewidths=2.0)
        lc.set_array(np.array(vals))
        lc.set_clim(0.0, rmax)
        ax.add_collection(lc)
        fig.colorbar(lc, ax=ax, shrink=0.7, label="radius")
    markers = {"branch_point": "o", "convex_vertex": "s", "curvature_centre": "^"}
    for n in mat.nodes:
        ax.plot(*n.point_2d, markers[n.kind.value], color="crimson", ms=4)
    shown = sorted(mat.nodes, key=lambda n: -n.radius)[:disks]
    for n in shown:
        if n.radius > 0:
            ax.add_patch(
                plt.Circle(tuple(n.point_2d), n.radius, fill=False, color="tab:orange", lw=0.6)
            )
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(
        f"medial axis: {len(mat.branches)} branches, {len(mat.branch_points)} branch points, "
        f"{len(mat.end_points)} end points"
    )
    fig.savefig(os.fspath(path), dpi=dpi, bbox_inches="tight")
    plt.close(fig)
