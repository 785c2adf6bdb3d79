"""driver/fields.py: the README's field picture, sigma_vM / p0 against r / a and z / a."""
import numpy as np
import pytest

pyvista = pytest.importorskip("pyvista", reason="the field picture needs pyvista (extra fields)")


@pytest.fixture(scope="module")
def seed_field(tmp_path_factory):
    from driver.fields import run_seed
    workdir = tmp_path_factory.mktemp("field")
    near, row = run_seed(workdir)
    return pyvista.read(near), row, workdir


def test_the_field_is_drawn_in_units_of_a_and_p0(seed_field):
    # "[units of E]" read as sigma/E; Hertz readers expect sigma/p0 against z/a and r/a
    from driver.fields import NEAR, SCALED, scaled
    mesh, row, _ = seed_field
    field = scaled(mesh, row["a_fe"], row["p0_fe"])
    r, z = field.points[:, 0], field.points[:, 1]
    assert r.max() == pytest.approx(NEAR, rel=0.05) and z.min() == pytest.approx(-NEAR, rel=0.05)
    peak = int(np.argmax(field[SCALED]))
    # Hertz (nu = 0.3): von Mises peaks at about 0.62 p0, 0.48 a below the surface on the axis
    assert field[SCALED][peak] == pytest.approx(0.62, abs=0.03)
    assert -z[peak] == pytest.approx(0.48, abs=0.06) and r[peak] < 0.1


def test_the_field_picture_renders_the_stress_near_the_contact(seed_field, tmp_path):
    import matplotlib.image

    from driver.fields import make_field_picture
    png = make_field_picture(tmp_path)
    image = matplotlib.image.imread(png)
    assert image.shape[0] >= 500 and image.shape[1] >= 800
    # a coloured field, not a blank window: many distinct colours
    colours = {tuple(px) for px in (image[::7, ::7, :3] * 255).astype(int).reshape(-1, 3)}
    assert len(colours) > 200
    assert (tmp_path / "runs" / "field" / "seed_near.vtu").exists()
    assert not list(tmp_path.glob(".*.part")) and not list(tmp_path.glob(".*.png"))
