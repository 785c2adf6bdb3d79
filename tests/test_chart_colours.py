"""The charts' series colours stay apart under a colour-vision deficiency: simulated (Machado,
Oliveira and Fernandes 2009, full severity, on linear RGB) and compared in CIELAB."""
import itertools

import numpy as np
import pytest

from driver.charts.common import QUANTITY_COLORS, SHAPE_COLORS
from driver.charts.loading import CYLINDER_A, CYLINDER_P0, STYLES

# Machado et al. (2009), severity 1
SIMULATIONS = {
    "normal vision": np.eye(3),
    "deuteranopia": np.array([[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                              [-0.011820, 0.042940, 0.968881]]),
    "protanopia": np.array([[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                            [-0.003882, -0.048116, 1.051998]]),
    "tritanopia": np.array([[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602],
                            [0.004733, 0.691367, 0.303900]]),
}
# CIE76 colour difference two series must keep: 2.3 is just noticeable between patches side
# by side; thin lines and small markers need several times more
APART = 16.0


def linear_rgb(colour: str) -> np.ndarray:
    srgb = np.array([int(colour[k:k + 2], 16) / 255 for k in (1, 3, 5)])
    return np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)


def lab(rgb: np.ndarray) -> np.ndarray:
    to_xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    xyz = to_xyz @ rgb / np.array([0.95047, 1.0, 1.08883])  # D65 white
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def seen(colour: str, simulation: np.ndarray) -> np.ndarray:
    return lab(np.clip(simulation @ linear_rgb(colour), 0, 1))


def closest_pair(colours: dict[str, str]) -> tuple[float, str]:
    return min((float(np.linalg.norm(seen(a, m) - seen(b, m))), f"{na} and {nb} under {kind}")
               for kind, m in SIMULATIONS.items()
               for (na, a), (nb, b) in itertools.combinations(colours.items(), 2))


@pytest.mark.parametrize("name,colours", [
    ("shapes", SHAPE_COLORS),
    ("quantities p0, F, a", dict(zip(("p0", "F", "a"), QUANTITY_COLORS))),
    ("loading series", {name: colour for name, (colour, _) in STYLES.items()}),
    ("the cylinder's a and p0", {"a": CYLINDER_A, "p0": CYLINDER_P0}),
])
def test_series_colours_stay_apart_under_every_deficiency(name, colours):
    distance, pair = closest_pair(colours)
    assert distance >= APART, f"{name}: {pair} are {distance:.1f} apart"


def test_the_simulation_confuses_what_deuteranopes_confuse():
    # red against green of the same lightness: far apart in normal vision, close for a deuteranope
    red, green = "#c62828", "#2e7d32"
    assert np.linalg.norm(seen(red, SIMULATIONS["normal vision"]) - seen(green, SIMULATIONS["normal vision"])) > 60
    assert np.linalg.norm(seen(red, SIMULATIONS["deuteranopia"]) - seen(green, SIMULATIONS["deuteranopia"])) < APART
