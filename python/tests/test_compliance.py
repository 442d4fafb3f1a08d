"""Loaded stiffness and compliance (paper Eqs. 32 and 36) against independent references:
finite differences of `deflect` (the compliance is d(pose)/d(load) at an equilibrium),
finite differences of the energy and Jacobian (the stiffness), and the cantilever's closed form.
"""

import numpy as np
import pytest

import flexure

# Central differences in the load with step H: truncation H^2/6 * |d^3 pose / d load^3|.
# At the loads below the error measured at H = 1e-2, 1e-3, 1e-4 falls as 6.4 H^2 (6.4e-8 at
# H = 1e-4), so H^2 scaling holds; deflect's 1e-12 relative tolerance adds about 1e-12 / H = 1e-8.
# TOL = 1e-6 covers both more than tenfold, and is 5e5 times smaller than the load term
# (0.46 in C_yy at the first load), which a compliance without it would miss.
H = 1e-4
TOL = 1e-6

LOADED = [
    # (flexure, (moment, fx, fy)): the unit flexure of the issue, compressed near buckling
    # (free buckling at 2.4677) with a side force; and a curved order-5 flexure under mixed load.
    (dict(), (0.0, -2.0, 0.3)),
    (dict(length=0.5, ei=2.0, order=5, kappa=[0.3, 0.1, 0.0, 0.0, 0.0]), (0.4, 1.0, -3.0)),
    (dict(order=4), (0.8, 1.5, 1.0)),
]


def pose_under(f, load):
    return f.pose(f.deflect(*load))


@pytest.mark.parametrize("options, load", LOADED)
def test_loaded_compliance_is_the_derivative_of_deflect(options, load):
    f = flexure.Flexure(**options)
    load = np.array(load)
    alpha = f.deflect(*load)
    c = f.compliance(alpha, *load)
    fd = np.zeros((3, 3))
    for j in range(3):
        step = np.zeros(3)
        step[j] = H
        fd[:, j] = (pose_under(f, load + step) - pose_under(f, load - step)) / (2 * H)
    assert np.max(np.abs(c - fd)) < TOL, (c, fd)
    # A compliance is symmetric: Maxwell–Betti, here from C = J K^-1 J^T.
    assert np.max(np.abs(c - c.T)) < 1e-14


def test_the_load_term_matters():
    # Under fx = -2, fy = 0.3 the axial compression softens the flexure: C_yy is 0.726,
    # not the 0.261 of the same shape unloaded (the old compliance(alpha)). The value
    # itself is checked by the finite differences above; here only that the two differ.
    f = flexure.Flexure()
    alpha = f.deflect(fx=-2.0, fy=0.3)
    loaded, unloaded = f.compliance(alpha, fx=-2.0, fy=0.3), f.compliance(alpha)
    assert loaded[2, 2] - unloaded[2, 2] > 0.4


def test_moment_adds_no_stiffness():
    # Eq. 32: phi_tip = alpha_1 is linear in alpha, so M multiplies a zero Hessian.
    f = flexure.Flexure(order=4)
    alpha = np.array([0.7, -0.2, 0.1, 0.05])
    assert np.array_equal(f.stiffness(alpha, moment=5.0, fx=1.0, fy=-2.0), f.stiffness(alpha, fx=1.0, fy=-2.0))


@pytest.mark.parametrize("options", [dict(), dict(length=0.3, ei=0.7, order=5)])
def test_stiffness_against_finite_differences(options):
    # K = ∇∇U − Fx∇∇x − Fy∇∇y from the energy's second differences (U is quadratic: exact
    # up to rounding, 1e-16 * U / h^2 = 1e-10 at h = 1e-3) and the Jacobian's central
    # differences (truncation h^2/6 * |∂³x| < 1e-7 at h = 1e-3 for these O(1) shapes).
    f = flexure.Flexure(**options)
    n = f.order
    rng = np.random.default_rng(11)
    alpha = rng.uniform(-1.0, 1.0, n)
    fx, fy = 1.3, -0.6
    h = 1e-3
    k = f.stiffness(alpha, fx=fx, fy=fy)
    fd = np.zeros((n, n))
    eye = np.eye(n) * h
    for i in range(n):
        for j in range(n):
            e = [f.energy(alpha + s * eye[i] + t * eye[j]) for s, t in ((1, 1), (1, -1), (-1, 1), (-1, -1))]
            fd[i, j] = (e[0] - e[1] - e[2] + e[3]) / (4 * h * h)
        dj = (f.jacobian(alpha + eye[i]) - f.jacobian(alpha - eye[i])) / (2 * h)
        fd[i, :] -= fx * dj[1] + fy * dj[2]
    assert np.max(np.abs(k - fd)) < 1e-6, (k, fd)
    assert np.array_equal(k, k.T)


def test_unloaded_compliance_is_the_cantilevers():
    # Straight cantilever, closed form (Eq. 36 is exact here): C_phiphi = L/EI,
    # C_phiy = L^2/(2EI), C_yy = L^3/(3EI), C_x* = 0; at the rest shape with no load,
    # compliance and rest_compliance agree to rounding.
    f = flexure.Flexure(length=2.0, ei=4.0)
    expected = np.array([[0.5, 0.0, 0.5], [0.0, 0.0, 0.0], [0.5, 0.0, 8.0 / 12.0]])
    assert np.max(np.abs(f.rest_compliance() - expected)) < 1e-14
    assert np.max(np.abs(f.compliance(np.zeros(3)) - expected)) < 1e-14


def test_unstable_state_has_no_compliance():
    # A straight column past its buckling load (2.4677, Table I): K is indefinite.
    f = flexure.Flexure()
    with pytest.raises(ValueError, match="not positive definite"):
        f.compliance(np.zeros(3), fx=-3.0)
    # Its stiffness is still returned, with a negative eigenvalue that says why.
    assert np.min(np.linalg.eigvalsh(f.stiffness(np.zeros(3), fx=-3.0))) < 0
