"""A rendered field for the README: the seed sphere's von Mises stress near the
contact, from hertz.edp's -vtk files, drawn off-screen with pyvista.

`hertz field` runs the case into results/runs/field/ and writes results/field.png
(`make sweep` calls it). pyvista is an optional dependency (extra `fields`).
"""
from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

from driver import freefem

CASE = ["-method", "lagrange"]  # the seed scene, exact contact: no penalty in the field


def run_case(workdir: Path) -> Path:
    """hertz.edp with -vtk into workdir; the near-field file."""
    workdir.mkdir(parents=True, exist_ok=True)
    vtu = workdir / "seed.vtu"
    proc = subprocess.run(freefem.command(CASE + ["-vtk", str(vtu), "-out", str(workdir)]),
                          capture_output=True, text=True, env=freefem.freefem_env(), check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"hertz.edp exited {proc.returncode}: {proc.stderr.strip() or proc.stdout[-300:]}")
    return workdir / "seed_near.vtu"


def render(near: Path, contact_radius: float, png: Path) -> Path:
    """von Mises in the r-z plane within 2.5 contact radii, with the contact marked."""
    import pyvista as pv  # optional: only this command needs it
    from vtkmodules.vtkCommonCore import vtkLogger

    # without a display VTK warns once that it has no X server, then renders off-screen anyway
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)
    pv.OFF_SCREEN = True
    mesh = pv.read(near)
    a = contact_radius
    clip = mesh.clip_box([0, 2.5 * a, -2.5 * a, 0, -1, 1], invert=False)
    plotter: Any = pv.Plotter(off_screen=True, window_size=[1000, 720])  # pyvista's stubs lag its API
    plotter.add_mesh(clip, scalars="von_mises", cmap="viridis",
                     scalar_bar_args={"title": "von Mises [units of E]", "vertical": True,
                                      "position_x": 0.86, "position_y": 0.2, "height": 0.6, "width": 0.06})
    plotter.add_mesh(clip.contour(isosurfaces=8, scalars="von_mises"), color="white", line_width=1)
    plotter.add_mesh(pv.Line((0, 0, 0.01), (a, 0, 0.01)), color="red", line_width=5)
    plotter.add_text("Seed sphere (axisymmetric, lagrange P2, n = 16): von Mises stress near the contact.\n"
                     "Red: the contact, r < a; white: iso-lines. Peak below the surface at about 0.48 a.", font_size=9)
    plotter.show_bounds(xtitle="r [length]", ytitle="z [length]", show_zaxis=False, show_zlabels=False,
                        font_size=10, fmt="%.3f", location="outer", ticks="outside")
    plotter.view_xy()
    plotter.camera.zoom(0.95)
    png.parent.mkdir(parents=True, exist_ok=True)
    plotter.screenshot(str(png))
    plotter.close()
    return png


def make_field_picture(results_dir: Path) -> Path:
    import pandas as pd

    workdir = results_dir / "runs" / "field"
    near = run_case(workdir)
    a = float(pd.read_csv(workdir / "summary.csv").iloc[0]["a_fe"])
    return render(near, a, results_dir / "field.png")
