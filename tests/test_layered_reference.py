"""The coated-body reference (driver/references/layered.py) against what is known without it: its two
derivations of the surface compliance, the homogeneous body, the thick and thin limits, and
Gao, Chiu and Lee's first-order formula. A reference the solver's tests lean on must bite too."""
import math

import pytest

from driver.references import layered as L

from hertz_reference import estar, sphere

E, NU, R = 10.0, 0.3, 0.5


@pytest.mark.parametrize("E2,nu2", [(100.0, 0.3), (0.1, 0.45), (math.inf, 0.3), (3.0, -0.2)])
@pytest.mark.parametrize("u", [0.05, 0.7, 3.0])
def test_the_compliance_factor_has_two_derivations_that_agree(E2, nu2, u):
    c = L.Coating(E1=E, nu1=NU, t=1.0, E2=E2, nu2=nu2)
    assert float(L.surface_factor(u, c)) == pytest.approx(L.surface_factor_by_propagator(u, c), rel=1e-9)


def test_one_material_is_the_half_space_and_hertz():
    c = L.Coating(E1=E, nu1=NU, t=0.05, E2=E, nu2=NU)
    ref, hz = L.sphere_from_depth(c, R, 0.02), sphere(E, NU, R, 0.02)
    assert ref.F == pytest.approx(hz.F, rel=1e-10) and ref.a == pytest.approx(hz.a, rel=1e-10)


@pytest.mark.parametrize("E2", [5.0, 20.0])
def test_a_thick_film_is_the_film_with_the_substrate_seen_from_afar(E2):
    c = L.Coating(E1=E, nu1=NU, t=30.0, E2=E2, nu2=NU)  # t = 300 a
    a = 0.1
    exact, asym = L.sphere(c, R, a), L.thick_film_asymptote(c, R, a)
    # K^ = K1 + O((a/t)^3): the two agree to (a/t)^2 = 1e-5
    assert exact.F == pytest.approx(asym.F, rel=1e-4) and exact.d == pytest.approx(asym.d, rel=1e-4)


def test_a_thin_film_on_a_rigid_base_is_winkler_s_foundation():
    c = L.Coating(E1=E, nu1=NU, t=0.002, E2=math.inf)  # t = a/50
    a = 0.1
    exact, winkler = L.sphere(c, R, a), L.winkler_sphere(c, R, a)
    # the first correction is of order t/a
    assert exact.F == pytest.approx(winkler.F, rel=0.1) and exact.d == pytest.approx(winkler.d, rel=0.1)


def test_gao_s_first_order_formula_is_the_derivative_at_one_material():
    a, t = 0.1, 0.1
    slopes = []
    for E2 in (E * (1 + 1e-4), E * (1 - 1e-4)):
        c = L.Coating(E1=E, nu1=NU, t=t, E2=E2, nu2=NU)
        slopes.append((L.effective_modulus(c, a) - L.gao_effective_modulus(c, a)) / (E2 - E))
    # first order in the mismatch: the difference is second order, its slope vanishes
    assert max(abs(s) for s in slopes) < 1e-3 * estar(E, NU) / E


@pytest.mark.parametrize("t,E2", [(0.03, 100.0), (1.0, 0.1), (0.01, math.inf)])
def test_the_reference_is_converged_to_its_stated_accuracy(t, E2):
    c = L.Coating(E1=E, nu1=NU, t=t, E2=E2, nu2=NU)
    assert L.error_estimate(c, 0.1).F < 1e-7


def test_the_punch_edge_coefficient_is_sneddon_s_on_one_material_and_grows_on_a_stiff_base():
    E, nu, a, d = 10.0, 0.3, 0.1, 0.02
    Es = E / (1 - nu**2)
    # one material: p = E* d / (pi sqrt(a^2 - r^2)), K = E* d / (pi sqrt(2a))
    same = L.Coating(E1=E, nu1=nu, t=0.05, E2=E, nu2=nu)
    assert L.punch_edge_coefficient(same, a, d) == pytest.approx(Es * d / (math.pi * math.sqrt(2 * a)), rel=1e-9)
    # a thick film: the base seen as at a point makes psi the constant 1/(1 + K1) (part 4), and a
    # stiffer base raises the edge's load
    thick = L.Coating(E1=E, nu1=nu, t=10.0, E2=10 * E, nu2=nu)
    K1 = 2 * a / (math.pi * thick.t) * L.deviation_integral(thick)
    assert K1 < 0
    assert L.punch_edge_coefficient(thick, a, d) == pytest.approx(Es * d / (math.pi * math.sqrt(2 * a)) / (1 + K1),
                                                                  rel=1e-6)
    thin = L.Coating(E1=E, nu1=nu, t=0.05, E2=10 * E, nu2=nu)
    assert L.punch_edge_coefficient(thin, a, d) > 2 * L.punch_edge_coefficient(same, a, d)
