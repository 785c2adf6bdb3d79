"""A rendered field for the README: the seed sphere's von Mises stress near the
contact, from hertz.edp's -vtk files, drawn off-screen with pyvista.

Drawn as engineers read Hertz: sigma_vM / p0 against r / a and z / a, so the
picture is the same in any units and its peak (about 0.62 p0 at 0.48 a below
the surface for nu = 0.3) can be read off the colour bar.

`hertz field` runs the case into <results>/runs/field/ and writes
<results>/field.png (`make sweep` calls it). pyvista is an optional
dependency (extra `fields`).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from driver import files, layout
from driver.cases import Case
from driver.errors import HertzError, ReportError
from driver.run import run_case

CASE = Case.of(method="lagrange")  # the seed scene, exact contact: no penalty in the field
NEAR = 2.5  # the picture's reach, in contact radii
SCALED = "von_mises_over_p0"


def run_seed(workdir: Path) -> tuple[Path, dict]:
    """hertz.edp with -vtk into workdir: the near-field file and the row."""
    vtu = workdir.absolute() / "seed.vtu"
    row = run_case(CASE, workdir, timeout=600, study=layout.FIELD, extra=("-vtk", str(vtu)))
    if row["status"] != "converged":
        raise HertzError(f"the seed case did not converge ({row['status']}): {row['error']}")
    return vtu.with_name("seed_near.vtu"), row


def scaled(mesh: Any, a: float, p0: float) -> Any:
    """The r-z plane within NEAR contact radii, lengths in units of a and von Mises in units of p0."""
    mesh = mesh.copy()
    mesh.points = mesh.points / a
    mesh[SCALED] = mesh["von_mises"] / p0
    return mesh.clip_box([0, NEAR, -NEAR, 0, -1, 1], invert=False)


def render(near: Path, a: float, p0: float, png: Path) -> Path:
    """sigma_vM / p0 in the r-z plane within NEAR contact radii, with the contact marked."""
    import pyvista as pv  # optional: only this command needs it
    from vtkmodules.vtkCommonCore import vtkLogger

    # without a display VTK warns once that it has no X server, then renders off-screen anyway
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)
    pv.OFF_SCREEN = True
    field = scaled(pv.read(near), a, p0)
    plotter: Any = pv.Plotter(off_screen=True, window_size=[1000, 720])  # pyvista's stubs lag its API
    plotter.add_mesh(field, scalars=SCALED, cmap="viridis",
                     scalar_bar_args={"title": "von Mises stress / p0", "vertical": True, "fmt": "%.2f",
                                      "position_x": 0.86, "position_y": 0.2, "height": 0.6, "width": 0.06})
    plotter.add_mesh(field.contour(isosurfaces=8, scalars=SCALED), color="white", line_width=1)
    plotter.add_mesh(pv.Line((0, 0, 0.01), (1, 0, 0.01)), color="red", line_width=5)
    plotter.add_text("Seed sphere (axisymmetric, lagrange P2, n = 16): von Mises stress / p0 near the contact.\n"
                     "Red: the contact, r < a; white: iso-lines. Peak below the surface at about 0.48 a.",
                     font_size=9)
    plotter.show_bounds(xtitle="r / a", ytitle="z / a", show_zaxis=False, show_zlabels=False,
                        font_size=10, fmt="%.1f", location="outer", ticks="outside")
    plotter.view_xy()
    plotter.camera.zoom(0.95)

    def write(tmp: Path) -> None:
        shot = tmp.with_suffix(".png")  # pyvista picks the format by the suffix
        try:
            plotter.screenshot(str(shot))
            shot.replace(tmp)
        finally:
            shot.unlink(missing_ok=True)
    png.parent.mkdir(parents=True, exist_ok=True)
    try:
        files.replace_atomically(png, write, ReportError)
    finally:
        plotter.close()
    return png


def make_field_picture(results_dir: Path) -> Path:
    results_dir = layout.user_path(results_dir)
    near, row = run_seed(layout.work_root(results_dir, layout.FIELD))
    return render(near, float(row["a_fe"]), float(row["p0_fe"]), results_dir / "field.png")
