"""Named studies and user grids.

A study is a list of cases, each with a variant label (the series it belongs
to, which charts and tests select by) and whether it must converge (cases that
probe where a method fails are expected not to). Each quick study is a subset
of its full one, so a full sweep after a quick one runs only the missing cases.
Cases name only the options they change; hertz.edp holds the defaults (the
seed scene: E = 10, nu = 0.3, R = 0.5, d = 0.02).
"""
from __future__ import annotations

import itertools
import json
import math
import tomllib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from driver import freefem
from driver.cases import Case, Value
from driver.errors import OptionError, SpecError, TableError
from driver.studytable import check_name

DECADES = [10.0**k for k in range(1, 10)]            # absolute kpen on the seed scene
GAMMAS = [10.0**k for k in range(-2, 7)]             # kpen in units of E*/h


def grid(base: Case, **axes: Sequence[Value]) -> list[Case]:
    """All combinations of the given values, on top of base."""
    names = list(axes)
    return [base.with_(**dict(zip(names, combo)))
            for combo in itertools.product(*(axes[k] for k in names))]


def labelled(cases: list[Case], label: Callable[[Case], str],
             expect: Callable[[Case], bool] = lambda c: True) -> list[Case]:
    return [c.labelled(label(c), expect(c)) for c in cases]


def method_label(c: Case) -> str:
    return f"{c.get('method', 'newton')} P{c.get('order', 2)}"


def kpen_study(quick: bool) -> list[Case]:
    """The penalty error against kpen, next to the exact methods on the same scene."""
    decades = [1e1, 1e3, 1e5, 1e7, 1e9] if quick else DECADES
    cases = grid(Case(), method=["newton"], order=[1, 2], kpen=decades)
    cases += grid(Case(), method=["lagrange"], order=[2] if quick else [1, 2], kpen=decades)
    if not quick:
        cases += grid(Case(), method=["uzawa"], order=[2], kpen=decades)
    cases += grid(Case(), method=["fixedpoint"], order=[2] if quick else [1, 2],
                  kpen=[1e1, 1e3] if quick else decades)
    # a soft penalty leaves a large penetration (inaccurate), Uzawa is slow
    # below ~E*/h and the lagged fixed point diverges beyond ~45: probes
    # (P1 at n = 16 is 4% off and says so: inaccurate)
    return labelled(cases, method_label,
                    lambda c: c.get("order") == 2 and (c.get("method") == "lagrange"
                                                      or (c.get("method") == "newton" and c.get("kpen") >= 1e5)))


def mesh_study(quick: bool) -> list[Case]:
    """Convergence in the element size: a fixed penalty, the scaled one, exact contact."""
    ns = {1: [5, 10, 20, 40], 2: [5, 10, 20, 40]} if quick else \
        {1: [5, 10, 20, 40, 80, 160], 2: [5, 10, 20, 40, 80]}
    cases = []
    for order, values in ns.items():
        if not quick:
            cases += labelled(grid(Case(), order=[order], n=values, kpen=[1e5]),
                              lambda c: f"kpen 1e5 P{c.get('order')}")
        cases += labelled(grid(Case(), order=[order], n=values),
                          lambda c: f"gamma 100 P{c.get('order')}")
        cases += labelled(grid(Case(), method=["lagrange"], order=[order], n=values),
                          lambda c: f"lagrange P{c.get('order')}")
    # coarse meshes are expected to be off by more than 1% (inaccurate)
    return [c.labelled(c.variant, False) for c in cases]


def domain_study(quick: bool) -> list[Case]:
    """The far boundary's bias on F against the domain radius, clamped and Boussinesq's, with exact contact."""
    Ls = [10.0, 20.0, 100.0, 1000.0] if quick else \
        [10.0, 15.0, 20.0, 30.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0, 20000.0]
    # n = 32: the mesh's own error of F (0.03% at n = 16) would blur the clamped 1.1 a/L at 1000 a
    cases = grid(Case.of(method="lagrange", n=32), farfield=["clamped", "boussinesq"], L=Ls)
    # below L = 200 a a clamped boundary's bias passes 1%: inaccurate, and said so
    return labelled(cases, lambda c: f"lagrange P2, {c.get('farfield')}",
                    lambda c: c.get("farfield") == "boussinesq" or c.get("L") >= 200)


def plane_study(quick: bool) -> list[Case]:
    """The cylinder: a(P), p0(P) and p0 = E* a/(2R) over meshes and depths."""
    base = Case.of(model="plane")
    if quick:
        cases = grid(base, n=[16, 32], d=[0.01, 0.04])
    else:
        cases = grid(base, n=[8, 16, 32], d=[0.01, 0.02, 0.04])
        cases += grid(base, method=["lagrange"], n=[8, 16, 32], d=[0.01, 0.02, 0.04])
    return labelled(cases, method_label)


def stability_study(quick: bool) -> list[Case]:
    """Where each method and Newton start fails: fixed point (kpen x omega), Newton
    from each start with and without line search and continuation, Uzawa and lagrange,
    over the penalty in units of E*/h."""
    fp = Case.of(method="fixedpoint")
    if quick:
        cases = grid(fp, n=[8, 16], omega=[0.5, 1.0], kpen=[10.0, 30.0, 100.0, 300.0, 1000.0])
        gammas = [1e-2, 1.0, 1e2, 1e4, 1e6]
        newton = grid(Case(), start=["coarse", "zero"], gamma=gammas)
        exact = grid(Case(), method=["lagrange", "uzawa"], gamma=gammas[:-1])
    else:
        cases = grid(fp, n=[8, 16, 32], omega=[0.1, 0.2, 0.5, 1.0, 1.5],
                     kpen=[3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 1e4])
        # options at their defaults are left out, so that quick cases are the same cases
        newton = []
        extras: list[dict[str, Value]] = [{}, {"linesearch": 0}, {"cont": 1}, {"linesearch": 0, "cont": 1},
                                          {"order": 1}]
        for extra in extras:
            newton += grid(Case().with_(**extra), start=["coarse", "zero", "hertz"], gamma=GAMMAS)
        exact = grid(Case(), method=["lagrange", "uzawa"], gamma=GAMMAS)
        exact += grid(Case.of(order=1), method=["lagrange", "uzawa"], gamma=GAMMAS)
    cases = labelled(cases, lambda c: f"fixedpoint n={c.get('n')}", lambda c: False)

    def newton_label(c: Case) -> str:
        return (f"P{c.get('order', 2)} start {c.get('start')}"
                + ("" if c.get("linesearch", 1) else ", no line search")
                + (", continuation" if c.get("cont", 0) else ""))
    # the default path (coarse start, line search, no continuation) must converge
    # (P1 at n = 16 is 4% off on p0 and says so: inaccurate, whatever the iteration does)
    cases += labelled(newton, newton_label,
                      lambda c: c.get("start") == "coarse" and c.get("linesearch", 1) == 1
                      and c.get("cont", 0) == 0 and c.get("gamma") >= 10 and c.get("order", 2) == 2)
    cases += labelled(exact, method_label, lambda c: c.get("method") == "lagrange" and c.get("order", 2) == 2)
    return cases


def speed_study(quick: bool) -> list[Case]:
    """Accuracy against speed: mesh series of each method and order."""
    if quick:
        cases = grid(Case(), order=[1, 2], n=[4, 8, 16])
        cases += grid(Case(), method=["lagrange"], n=[8, 16])
    else:
        cases = grid(Case(), order=[1, 2], n=[4, 8, 16, 32, 64])
        cases += grid(Case(), order=[1], n=[128])
        cases += grid(Case(), method=["lagrange"], n=[4, 8, 16, 32, 64])
        cases += grid(Case.of(order=1), method=["lagrange"], n=[4, 8, 16, 32, 64])
        cases += grid(Case(), method=["uzawa"], n=[4, 8, 16, 32, 64])
        cases += grid(Case(), kpen=[1e5], n=[8, 16, 32, 64])
        cases += grid(Case(), method=["fixedpoint"], kpen=[30.0], n=[8, 16])
    return labelled(cases, method_label, lambda c: False)


# The same dimensionless scene in several unit systems: E, R and d scaled so
# that E*, d/R and the mesh are the same scene (relative errors must agree).
UNIT_SYSTEMS = {"seed units": (1.0, 1.0), "SI": (1e9, 1e-3), "mm-N-MPa": (1e3, 1.0)}
SCENES = {"seed sphere": dict(E=10.0, nu=0.3, R=0.5, d=0.02),
          "steel ball": dict(E=210.0, nu=0.3, R=10.0, d=0.01),
          "rubber": dict(E=0.002, nu=0.49, R=5.0, d=0.2)}


def units_study(quick: bool) -> list[Case]:
    """One scene given in three unit systems: identical relative errors and iterations."""
    cases = []
    scenes = list(SCENES)[:2] if quick else list(SCENES)
    for scene in scenes:
        for units, (stress, length) in UNIT_SYSTEMS.items():
            s = SCENES[scene]
            base = Case.of(E=s["E"] * stress, nu=s["nu"], R=s["R"] * length, d=s["d"] * length)
            for method in (["newton"] if quick else ["newton", "lagrange"]):
                cases.append(base.with_(method=method).labelled(f"{scene}, {method}, {units}"))
    return cases


def figures_study(quick: bool) -> list[Case]:
    """The runs behind the profile, seed-figure and axis-stress charts (their
    profile.csv and axis.csv are kept)."""
    cases = labelled(grid(Case(), n=[8], order=[1, 2], kpen=[1e3, 1e5, 1e8]),
                     lambda c: f"profile P{c.get('order')}", lambda c: False)
    cases += labelled(grid(Case(), kpen=[1e1, 1e2, 1e3, 1e5]), lambda c: "seed figure",
                      lambda c: False)
    cases += [Case.of(method="lagrange").labelled("axis")]
    return cases


def calibration_study(quick: bool) -> list[Case]:
    """The error estimate against the true error on scenes with closed forms
    (units, nu, depth, plane, P1, lagrange), and -accuracy X on several scenes."""
    if quick:
        return [Case.of(nu=-0.5).labelled("nu", False),
                Case.of(model="plane", nu=0.3, d=0.01).labelled("plane", False),
                Case.of(accuracy=0.01).labelled("accuracy 0.01"),
                Case.of(nu=0.45, accuracy=0.01).labelled("accuracy 0.01")]
    cases = [Case.of(nu=nu).labelled("nu", False) for nu in [-0.5, 0.0, 0.3, 0.45, 0.49, 0.499]]
    cases += [Case.of(d=0.5 * ratio).labelled("depth", False) for ratio in [1e-6, 1e-4, 1e-2, 0.1]]
    cases += [Case.of(E=210e9, R=0.01, d=1e-5).labelled("SI steel", False),
              Case.of(E=2e6, nu=0.49, R=0.005, d=2e-4).labelled("SI rubber", False)]
    cases += labelled(grid(Case.of(model="plane"), nu=[0.3, 0.45], d=[0.01, 0.04]), lambda c: "plane",
                      lambda c: False)
    cases += labelled(grid(Case.of(order=1), n=[16, 32]), lambda c: "P1", lambda c: False)
    cases += labelled(grid(Case.of(method="lagrange"), nu=[0.3, 0.45, 0.49]), lambda c: "lagrange",
                      lambda c: False)
    # -accuracy must reach X by the truth, or say why (inaccurate)
    scenes = [Case(), Case.of(nu=0.45), Case.of(E=2e6, nu=0.49, R=0.005, d=2e-4), Case.of(d=0.5e-4),
              Case.of(model="plane")]
    for x in [0.05, 0.01, 0.003, 0.001, 3e-4, 1e-4]:
        cases += [c.with_(accuracy=x).labelled(f"accuracy {x:g}") for c in scenes]
    return cases


# Ellipsoids by their radii (Rx, Ry) on the seed scene's depth: the
# long semi-axis lies along the larger radius.
ELLIPSOIDS = {"Ry/Rx = 2": (0.5, 1.0), "Ry/Rx = 4": (0.5, 2.0), "Rx/Ry = 4": (2.0, 0.5)}


def study_3d(quick: bool) -> list[Case]:
    """The price of over-modelling (a sphere as axi and as 3d over meshes), and
    ellipsoids against elliptical Hertz, with -model auto choosing the model."""
    if quick:
        # n = 4 is below the default: the estimate may pass 1% (inaccurate)
        return (labelled(grid(Case.of(model="3d"), n=[4]), lambda c: "sphere 3d newton P2", lambda c: False)
                + labelled(grid(Case.of(Rx=0.5, Ry=1.0), n=[4]), lambda c: "ellipsoid Ry/Rx = 2", lambda c: False))
    cases = labelled(grid(Case(), n=[4, 8, 16, 32]), lambda c: "sphere axi newton P2")
    cases += labelled(grid(Case.of(method="lagrange"), n=[4, 8, 16, 32]), lambda c: "sphere axi lagrange P2")
    cases += labelled(grid(Case.of(model="3d"), n=[4, 6, 8]), lambda c: "sphere 3d newton P2")
    cases += labelled(grid(Case.of(model="3d", method="lagrange"), n=[4, 6, 8]),
                      lambda c: "sphere 3d lagrange P2")
    # P1 in 3D at an affordable n is several % off, and says so
    cases += labelled(grid(Case.of(model="3d", order=1), n=[8, 16]), lambda c: "sphere 3d newton P1",
                      lambda c: False)
    for name, (rx, ry) in ELLIPSOIDS.items():
        cases += [c.labelled(f"ellipsoid {name}") for c in grid(Case.of(Rx=rx, Ry=ry), n=[4, 6, 8])]
    cases += labelled(grid(Case.of(Rx=0.5, Ry=2.0, method="lagrange"), n=[8]),
                      lambda c: "ellipsoid Ry/Rx = 4 lagrange")
    # below the default n = 8 the pair (n/2, n) may read past 1% (inaccurate)
    return [c.labelled(c.variant, c.expect_converged and c.get("n") >= 8) for c in cases]


def shapes_study(quick: bool) -> list[Case]:
    """Indenters beyond the parabola against Sneddon: the exact sphere beside Hertz's
    parabola over d/R, F(d) of each shape over a decade of depths, and each shape's
    convergence in n."""
    ratios = [0.01, 0.1] if quick else [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3]
    cases = labelled(grid(Case.of(shape="sphere"), d=[round(0.5 * r, 6) for r in ratios]), lambda c: "sphere over d/R")
    cases += labelled(grid(Case.of(R=0.5), d=[round(0.5 * r, 6) for r in ratios]), lambda c: "parabola over d/R")
    depths = [0.005, 0.02] if quick else [0.0025, 0.005, 0.01, 0.02, 0.04]
    shapes = {"cone 70.3": Case.of(shape="cone"), "punch": Case.of(shape="punch"),
              "power k = 3": Case.of(shape="power", k=3), "sphere": Case.of(shape="sphere")}
    for name, base in shapes.items():
        cases += [c.labelled(f"F(d) {name}") for c in grid(base, d=depths)]
    if not quick:
        # (a cone at another angle is the same problem in the solver's units: one cone)
        shapes.update({"power k = 1.5": Case.of(shape="power", k=1.5)})
        for name, base in shapes.items():
            # a cusped tip's p0 converges slowly and says so (inaccurate) at coarse n
            cases += [c.labelled(f"n {name}", name != "power k = 1.5")
                      for c in grid(base.with_(method="lagrange"), n=[8, 16, 32])]
    return cases


def layers_study(quick: bool) -> list[Case]:
    """Coated bodies: the effective modulus over a/t for substrates 100 times softer to
    100 times stiffer and a rigid base, and the two pressure profiles of a stiff film on a
    soft substrate and a soft film on a stiff one."""
    ratios = [0.1, 10.0] if quick else [0.01, 0.1, 10.0, 100.0]
    thickness = [0.1, 1.0] if quick else [0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0]  # t/a (a = 0.1)
    # exact contact: a thin film on a stiff base is far stiffer than E*/h, against which
    # the default penalty is scaled (a penalty run says so: inaccurate)
    films = [round(0.1 * x, 6) for x in thickness]
    cases = []

    def converges(r: float, t: float) -> bool:
        # a stiff film up to a tenth of a contact radius thick on a substrate 100 times softer:
        # its pressure peaks within about t of the edge, and p0's estimate reads 1.4% at n = 16;
        # at t = 0.03 (0.39 a and 0.68 a of their own contact radii) on substrates 10 and 100
        # times softer the pressure peaks off the axis and zig-zags there: p0 +0.8% and +0.9%,
        # estimated 1.6% and 1.7% (inaccurate; F and a within 0.2% in both)
        return not ((r <= 0.01 and t <= 0.01) or (r <= 0.1 and t == 0.03))

    for r in ratios:
        cases += [c.labelled(f"E2/E = {r:g}", converges(r, c.get("t")))
                  for c in grid(Case.of(E2=10.0 * r, method="lagrange"), t=films)]
    cases += labelled(grid(Case.of(E2=math.inf, method="lagrange"), t=films), lambda c: "rigid base")
    cases += [Case.of(t=0.03, E2=1000.0, method="lagrange").labelled("profile soft film"),
              Case.of(t=0.03, E2=0.1, method="lagrange").labelled("profile stiff film", converges(0.01, 0.03))]
    return cases


def loading_study(quick: bool) -> list[Case]:
    """Loading curves: F against d for the sphere, the cylinder (by its load per unit
    length) and an ellipsoid, from 1e-3 to 1e-1 of the radius, with the contact stiffness
    S = dF/dd; a point of each curve again under load control (the unloading leg of an
    elastic frictionless body is the loading one)."""
    fractions = [1e-3, 1e-2, 1e-1] if quick else [1e-3, 3e-3, 1e-2, 3e-2, 1e-1]
    depths = [round(0.5 * f, 8) for f in fractions]
    cases = labelled(grid(Case(), d=depths), lambda c: "sphere")
    cases += labelled(grid(Case.of(shape="sphere"), d=depths), lambda c: "exact sphere")
    # the cylinder's depth depends on the domain: its curve is a(P) and p0(P)
    loads = [0.002, 0.02, 0.2] if quick else [0.002, 0.006, 0.02, 0.06, 0.2]
    cases += labelled(grid(Case.of(Ry=math.inf, Rx=0.5), P=loads), lambda c: "cylinder")
    if not quick:
        cases += labelled(grid(Case.of(Rx=0.5, Ry=1.0), d=depths), lambda c: "ellipsoid Ry/Rx = 2")
    # two loads within the sphere's curve, given: their points must fall on it
    cases += labelled(grid(Case(), P=[0.004, 0.1]), lambda c: "sphere under load")
    return cases


@dataclass(frozen=True)
class Study:
    name: str
    make: Callable[[bool], list[Case]]
    keep: tuple[str, ...] = ()  # per-case files gathered into results/<name>/<file>
    repeats: int = 1            # runs per case: wall_time is their median (the speed study)
    charts: tuple[str, ...] = ()  # its charts in the report, drawn by driver/charts/ under these names


def friction_study(quick: bool) -> list[Case]:
    """Spence's problem: the stick zone c/a of a sphere pressed in with Coulomb
    friction, against beta/mu for several nu, and the cylinder's against the
    boundary-element reference (driver/references/spence.py); full stick's
    stiffness against Mossakovskii's; and, not in the quick subset, a
    cylinder loaded and unloaded to half its load, its stick zone along the
    path against the boundary elements, and a cylinder under a tangential
    force of half mu P, against Cattaneo (nu = 1/2) and the boundary elements
    (nu = 0.3), once and in a fretting cycle (Mindlin and Deresiewicz).
    c is read to half a node gap, so most finite-mu runs end inaccurate
    (their estimate of c, 2% to 6% at n = 16)."""
    nus = [0.3] if quick else [0.0, 0.2, 0.3, 0.4]
    mus = [0.1, 0.3, 1.0] if quick else [0.05, 0.1, 0.2, 0.3, 0.5, 1.0, 2.0]
    cases = [c.labelled(f"sphere, nu = {c.get('nu'):g}", False) for c in grid(Case(), nu=nus, mu=mus)]
    cases += [c.labelled("full stick", c.get("nu") == 0.0) for c in grid(Case.of(mu=math.inf), nu=nus)]
    plane = Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01)
    cases += labelled(grid(plane, mu=[0.2, 0.5] if quick else [0.1, 0.2, 0.3, 0.5, 1.0]),
                      lambda c: "cylinder, nu = 0.3", lambda c: False)
    # (not in the quick subset, whose paths tests/test_path.py and test_tangential.py run)
    if not quick:
        # loaded, then unloaded to half the load: the stick zone along the path
        cases.append(Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.2, path="1,0.5")
                     .labelled("cylinder unloaded, nu = 0.3", False))
        # a tangential force of half mu P: Cattaneo where beta = 0, the boundary elements at nu = 0.3
        cases += [Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.3, Q=0.0015, nu=nu)
                  .labelled(f"cylinder under Q, nu = {nu:g}", False) for nu in (0.5, 0.3)]
        # a fretting cycle: Q to mu P/2, back to -mu P/2 and up again (Mindlin and Deresiewicz's branches)
        cases.append(Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.3, Q=0.0015, nu=0.5, Qpath="1,-1,1")
                     .labelled("cylinder, a fretting cycle, nu = 0.5", False))
    return cases


def bodies_study(quick: bool) -> list[Case]:
    """Two elastic bodies (-E1): F and a against the approach for identical and for
    dissimilar spheres, against Hertz with the combined E* (and R); Code_Aster's SSNV104
    (two hemispheres of R = 50 mm, E = 20,000 MPa, nu = 0.3, 4 mm approach); an elastic
    exact sphere on a flat body as a/R grows, against Sneddon's; and, not in the quick
    subset, an ellipsoid pair in 3D, and two cylinders under a tangential force of half mu P: identical (beta = 0,
    Cattaneo exact at nu = 0.3) and dissimilar (E1 = 3E: beta = 0.14, the boundary
    elements of the rigid indenter with the same E* and beta)."""
    fractions = [1e-3, 1e-2, 1e-1] if quick else [1e-3, 3e-3, 1e-2, 3e-2, 1e-1]
    depths = [round(0.5 * f, 8) for f in fractions]
    cases = labelled(grid(Case.of(E1=10.0), d=depths), lambda c: "identical spheres")
    if not quick:
        cases += labelled(grid(Case.of(E1=30.0, nu1=0.3, nu=0.33, R2=1.0), d=depths),
                          lambda c: "dissimilar: E1 = 3E, R2 = 2R")
        cases += labelled(grid(Case.of(E1=1.0, nu1=0.35), d=depths), lambda c: "soft indenter: E1 = E/10")
    ssnv104 = Case.of(E=20000.0, nu=0.3, E1=20000.0, R=50.0, R2=50.0, d=4.0)
    cases.append(ssnv104.labelled("SSNV104"))
    # its two real spheres: the exact caps, against Sneddon's (and how far from Hertz)
    cases.append(ssnv104.with_(shape="sphere", method="lagrange").labelled("SSNV104, exact caps"))
    # an elastic sphere (its exact cap) on a flat body of the same material, as a/R grows:
    # Hertz's parabola departs from it (the run's parabola warning says by how much)
    caps = [0.03, 0.1, 0.3] if quick else [0.01, 0.03, 0.1, 0.2, 0.3]
    cases += labelled(grid(Case.of(shape="sphere", E1=10.0, method="lagrange"), d=[0.5 * f for f in caps]),
                      lambda c: "elastic exact sphere")
    if not quick:
        # two ellipsoids in 3D (the 2% target): Ry/Rx = 4, a stiffer indenter
        cases.append(Case.of(model="3d", Rx=0.5, Ry=2.0, E1=30.0, nu1=0.2).labelled("ellipsoid pair, 3D"))
        pulled = Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.3, Q=0.0015, nu=0.3)
        cases.append(pulled.with_(E1=10.0).labelled("identical cylinders under Q", False))
        cases.append(pulled.with_(E1=30.0, nu1=0.3).labelled("dissimilar cylinders under Q", False))
    return cases


def indentation_study(quick: bool) -> list[Case]:
    """Elastic-plastic indentation (-Y, J2 with H = 0), loaded to the scene's depth in 10
    steps and unloaded to zero load in 10 more (-unload 1): spheres of the default scene
    (E = 10, nu = 0.3, R = 0.5, d = 0.02) from elastic (Y = 1: p0 below 1.6 Y) through the
    elastic-plastic range to fully plastic (Y = 0.025: E a/(Y R) = 120), a cone of 70.3
    degrees (the Berkovich equivalent), and the elastic sphere unloaded (Y = inf), whose
    Oliver and Pharr analysis returns E*. The plastic runs end inaccurate (exit 5): the
    peak pressure's estimate is 2% to 12% at n = 16. The quick subset: one plastic sphere
    and the elastic one."""
    yields = [0.3] if quick else [1.0, 0.3, 0.1, 0.025]
    cases = labelled(grid(Case.of(unload=1), Y=yields), lambda c: "sphere", lambda c: False)
    cases.append(Case.of(unload=1, method="lagrange", steps=10).labelled("sphere, elastic"))
    if not quick:
        cases.append(Case.of(unload=1, shape="cone", d=0.01, Y=0.3).labelled("cone", False))
    return cases


def adhesion_study(quick: bool) -> list[Case]:
    """Maugis-Dugdale adhesion of the default sphere (w = 0.05), from the load 0.05 to
    separation (-pulloff 1, load control: the pull-off is the least force), for Dugdale
    stresses giving Tabor parameters 0.15, 0.49, 1.2, 2.5 and 4.9 (-sigma0 0.3 to 10). The
    quick subset: lambda = 2.5."""
    sigmas = [5.0] if quick else [0.3, 1.0, 2.5, 5.0, 10.0]
    return labelled(grid(Case.of(w=0.05, P=0.05, pulloff=1), sigma0=sigmas), lambda c: f"sigma0 = {c.get('sigma0')}")


STUDIES = {s.name: s for s in [
    Study("kpen", kpen_study, charts=("penalty",)),
    Study("mesh", mesh_study, charts=("mesh",)),
    Study("domain", domain_study, charts=("domain",)),
    Study("plane", plane_study),
    Study("stability", stability_study, charts=("stability",)),
    Study("speed", speed_study, repeats=3),
    Study("units", units_study, charts=("units",)),
    Study("figures", figures_study, keep=("profile.csv", "axis.csv"),
          charts=("pressure_profiles", "seed_figure1", "axis_stresses")),
    Study("calibration", calibration_study, charts=("calibration",)),
    Study("3d", study_3d, keep=("profile.csv", "profile_y.csv", "outline.csv"), charts=("over_modelling", "ellipses")),
    Study("shapes", shapes_study, keep=("profile.csv",), charts=("shapes",)),
    Study("layers", layers_study, keep=("profile.csv", "axis.csv"), charts=("layers",)),
    Study("loading", loading_study, charts=("loading",)),
    Study("friction", friction_study, keep=("path.csv",), charts=("friction",)),
    Study("bodies", bodies_study, keep=("path.csv",), charts=("bodies",)),
    Study("indentation", indentation_study, keep=("path.csv",), charts=("indentation",)),
    Study("adhesion", adhesion_study, keep=("path.csv",), charts=("adhesion",)),
]}
# the charts that read every study's rows, first in the report
SUMMARY_CHARTS = ("accuracy_vs_speed", "effectivity", "zigzag")


def report_charts() -> list[str]:
    """The report's charts in the order it shows them: the summaries, then each study's."""
    return [*SUMMARY_CHARTS, *(name for study in STUDIES.values() for name in study.charts)]


@dataclass(frozen=True)
class Spec:
    """A grid from a spec file: every combination of the grid's values on top of base.
    Its size is known before any case is built (a product of axes grows fast)."""

    name: str
    base: dict[str, Value] = field(default_factory=dict)
    axes: dict[str, list[Value]] = field(default_factory=dict)

    @property
    def count(self) -> int:
        return math.prod(len(values) for values in self.axes.values())

    def cases(self) -> list[Case]:
        return labelled(grid(Case().with_(**self.base), **self.axes), lambda c: self.name)


def _unique_keys(pairs: list[tuple[str, object]]) -> dict:
    """A JSON object whose keys are all different (json keeps the last of a repeated key)."""
    seen: dict = {}
    for key, value in pairs:
        if key in seen:
            raise ValueError(f"key {key!r} is given twice")
        seen[key] = value
    return seen


MAX_SPEC_BYTES = 1 << 20  # a grid of options fits in a few kB; /dev/zero never ends


def _spec_text(path: Path) -> str:
    try:
        with open(path, "rb") as handle:
            data = handle.read(MAX_SPEC_BYTES + 1)
    except OSError as exc:
        raise SpecError(f"spec {path}: cannot read: {exc.strerror}") from None
    if len(data) > MAX_SPEC_BYTES:
        raise SpecError(f"spec {path}: larger than {MAX_SPEC_BYTES >> 20} MB; a spec is a small TOML or JSON file")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise SpecError(f"spec {path}: not UTF-8 text") from None


def not_in_a_sweep(name: str, value: object) -> str:
    """Why an option cannot be part of a sweep's case ("" if it can): a case that sets it
    could only fail, or would write outside its own folder."""
    if name == "out" or name in freefem.RUN_ONLY:
        return f"{name} is not a case option: the sweep decides where each case runs and what it does"
    if name == "profile":
        return "profile cannot be given to a sweep's case (its path is not part of the case)"
    if name == "shape" and value == "table":
        return "shape = 'table' needs -profile, which a sweep's case cannot give"
    if name == "vtk" and (not isinstance(value, str) or "/" in value or value in ("", ".", "..")):
        return f"vtk must be a file name, written in the case's own folder, got {value!r}"
    return ""


def case_of(values: object, study: str, label: str) -> Case:
    """One case of a user's sweep from its option dict; OptionError naming the first bad key."""
    if not isinstance(values, Mapping):
        raise OptionError(f"{label} must be a dict of options, got {type(values).__name__} {values!r:.80}")
    for name, value in values.items():
        why = not_in_a_sweep(str(name), value)
        if why:
            raise OptionError(f"{label}: {why}")
    return Case.of(**freefem.parse_options(dict(values))).labelled(study)


def load_spec(path: Path) -> Spec:
    """A grid from TOML or JSON: name = "...", [base] fixed values, [grid] lists of values.
    Every key is an option of hertz.edp's table, checked against its kind and range."""
    text = _spec_text(path)
    try:
        data = (json.loads(text, object_pairs_hook=_unique_keys) if path.suffix == ".json"
                else tomllib.loads(text))  # TOML itself refuses a repeated key
    except (ValueError, RecursionError) as exc:
        raise SpecError(f"spec {path}: cannot read: {exc}") from None
    if not isinstance(data, dict):
        raise SpecError(f"spec {path}: the top level must be a table (name, base, grid)")
    unknown = set(data) - {"name", "base", "grid"}
    if unknown:
        raise SpecError(f"spec {path}: unknown key(s) {sorted(unknown)}; allowed: name, base, grid")
    name = data.get("name")
    if not isinstance(name, str):
        raise SpecError(f"spec {path}: 'name' must be a string")
    try:
        check_name(name)
    except TableError as exc:
        raise SpecError(f"spec {path}: {exc}") from None
    if name in STUDIES:
        raise SpecError(f"spec {path}: name '{name}' is a built-in study; choose another")
    options = freefem.case_options()
    base = {k: _value(path, options, k, v) for k, v in _table(path, data, "base").items()}
    axes = {}
    for key, values in _table(path, data, "grid").items():
        if not isinstance(values, list) or not values:
            raise SpecError(f"spec {path}: grid.{key} must be a non-empty list")
        if key in base:  # one of the two would be dropped without a word
            raise SpecError(f"spec {path}: '{key}' is set in both [base] and [grid]; keep one")
        axes[key] = [_value(path, options, key, v) for v in values]
    if not axes:
        raise SpecError(f"spec {path}: [grid] must list at least one parameter")
    return Spec(name, base, axes)


def _table(path: Path, data: dict, key: str) -> dict:
    table = data.get(key, {})
    if not isinstance(table, dict):
        raise SpecError(f"spec {path}: [{key}] must be a table of parameter = value")
    return table


def _value(path: Path, options: dict[str, freefem.Option], key: str, value) -> Value:
    if key not in options:  # out, vtk, profile and check among them: a case never carries them
        raise SpecError(f"spec {path}: unknown parameter '{key}'; known: {', '.join(options)}")
    why = not_in_a_sweep(key, value)
    if why:
        raise SpecError(f"spec {path}: {why}")
    try:
        return options[key].parse(value, key)
    except OptionError as exc:
        raise SpecError(f"spec {path}: {exc}") from None
