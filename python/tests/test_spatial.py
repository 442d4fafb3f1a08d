"""flexure.SpatialFlexure: the spatial flexure from Python, against closed forms."""

import math
import warnings

import numpy as np
import pytest

import flexure


def test_pose_of_an_arc_and_a_batch():
    # Reference: a circular arc of 1 rad about z: tip (sin 1, 1 - cos 1, 0), 1e-13.
    f = flexure.SpatialFlexure()
    alpha = [0, 0, 0, 0, 0, 0, 1, 0, 0]
    g = f.pose(alpha)
    assert g.shape == (4, 4)
    assert abs(g[0, 3] - math.sin(1)) < 1e-13 and abs(g[1, 3] - (1 - math.cos(1))) < 1e-13
    batch = f.pose(np.array([alpha, [0.0] * 9]))
    assert batch.shape == (2, 4, 4)
    # Straight: the tip frame is the root's, moved by L along x.
    straight = np.eye(4)
    straight[0, 3] = 1.0
    assert np.allclose(batch[0], g, atol=1e-15) and np.allclose(batch[1], straight, atol=1e-15)
    assert f.jacobian(alpha).shape == (6, 9)


def test_deflect_pure_twist():
    # Reference: pure twist, angle TL/GJ (closed form, 1e-10).
    f = flexure.SpatialFlexure(length=0.8, gj=0.25)
    d = f.deflect(moment=(0.4, 0.0, 0.0))
    r = d["pose"][:3, :3]
    assert abs(math.atan2(r[2, 1], r[1, 1]) - 0.4 * 0.8 / 0.25) < 1e-10
    assert d["stable"] and not d["flagged"] and d["error_estimate"]["position"] >= 0


def test_compliance_closed_forms():
    # Reference: L/GJ, L/EI_y, L^3/3EI_z (closed forms, 1e-12 relative).
    c = flexure.SpatialFlexure(length=2.0, ei=1.0, ei_y=4.0, gj=0.5).compliance()
    assert c.shape == (6, 6)
    assert abs(c[0, 0] - 4.0) < 1e-12 and abs(c[1, 1] - 0.5) < 1e-12 and abs(c[4, 4] - 8.0 / 3.0) < 1e-12


def test_lateral_torsional_buckling_warns():
    # Reference: Michell, P = 4.013 sqrt(EI_z GJ)/L^2 = 2.64 N for a 10 x 0.2 x 50 mm steel strip;
    # 20 N along z is beyond it, so the equilibrium followed from rest is unstable.
    f = flexure.SpatialFlexure(length=0.05, modulus=200e9, width=0.01, thickness=2e-4)
    with pytest.warns(flexure.StabilityWarning):
        d = f.deflect(force=(0.0, 0.0, 20.0))
    assert not d["stable"] and 0.12 < d["limit_fraction"] < 0.14
    s = f.stress(d["alpha"])
    assert s["max"] > 0 and s["point"] in ("corner", "width_side", "thickness_side")


def test_bad_input_raises_value_error_naming_it():
    with pytest.raises(ValueError, match="gj"):
        flexure.SpatialFlexure(gj=-1.0)
    with pytest.raises(ValueError, match="force"):
        flexure.SpatialFlexure().deflect(force=(0.0, 1.0))
    with pytest.raises(ValueError, match="force"):
        flexure.SpatialFlexure().deflect(force=(0.0, float("nan"), 0.0))
    with pytest.raises(TypeError):
        flexure.SpatialFlexure(length=True)
    with pytest.raises(ValueError, match="kappa_y"):
        flexure.SpatialFlexure(kappa_y=[1.0, 0.0])


def test_exact_rod_meets_the_model():
    # Reference: the exact Kirchhoff rod (flexure.exact.rod); the model at orders 6 within
    # 1e-6 of L of it under a 3-D load, and pure twist TL/GJ (closed form, 1e-10).
    from flexure import exact

    f = flexure.SpatialFlexure(order=6, ei_y=2.0, gj=0.7)
    force, moment = (0.1, 0.4, 0.3), (0.05, 0.1, 0.2)
    model = f.deflect(force=force, moment=moment)["pose"]
    e = exact.rod(f, force=force, moment=moment)
    assert e["stable"] and np.linalg.norm(model[:3, 3] - e["pose"][:3, 3]) < 1e-6
    twist = exact.rod(flexure.SpatialFlexure(length=0.8, gj=0.25), moment=(0.1, 0.0, 0.0))
    assert abs(twist["pose"][2, 1] - math.sin(0.32)) < 1e-10
    with pytest.raises(ValueError, match="flexure"):
        exact.rod(flexure.Flexure())


def test_shape_of_a_helix_and_its_tip():
    # Reference: constant body curvature u = (tau, 0, kappa) with GJ = EI is a helix whose
    # frame is R(s) = exp(s [u]x), p(s) = integral of R e1 (closed form, 1e-12 of L); the
    # last section is pose(alpha)'s tip to rounding.
    f = flexure.SpatialFlexure(length=1.0, modulus=2e9, diameter=0.01, order=1)
    tau, kappa = 0.7, 1.3
    alpha = [tau, 0.0, kappa]
    line = f.shape(alpha, 5)
    assert line.shape == (5,) and line["position"].shape == (5, 3) and line["rotation"].shape == (5, 3, 3)
    w = np.array([tau, 0.0, kappa])
    theta = np.linalg.norm(w)
    k = w / theta
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    e1 = np.array([1.0, 0.0, 0.0])
    for row in line:
        s = row["s"]
        a = theta * s
        r = np.eye(3) + math.sin(a) * kx + (1 - math.cos(a)) * kx @ kx
        p = s * k * k.dot(e1) + (math.sin(a) / theta) * (e1 - k * k.dot(e1)) + ((1 - math.cos(a)) / theta) * np.cross(k, e1)
        assert np.allclose(row["rotation"], r, atol=1e-12) and np.allclose(row["position"], p, atol=1e-12)
        assert np.allclose(row["curvature"], w, atol=1e-12)
    g = f.pose(alpha)
    assert np.allclose(line["position"][-1], g[:3, 3], atol=1e-14) and np.allclose(line["rotation"][-1], g[:3, :3], atol=1e-14)
    # A round rod has a shape: every section carries its peak stress, largest where the curvature is.
    assert "stress" in line.dtype.names and np.all(line["stress"] > 0)
    # A section given by its stiffnesses alone has none.
    assert "stress" not in flexure.SpatialFlexure(order=1).shape(alpha, 3).dtype.names


def test_shape_bad_points_raise_value_error():
    f = flexure.SpatialFlexure()
    with pytest.raises(ValueError, match="k|points"):
        f.shape([0.0] * 9, 1)


def test_mass_of_a_strip_and_a_tapered_rod_is_the_closed_form():
    # Reference: mass = ρ·w·h·L for a strip, and for a rod tapering linearly from d0 to d1
    # ρ·π/4·L·(d0² + d0·d1 + d1²)/3; the quadrature is exact for these (μ at most quadratic
    # in s), so 1e-13 relative.
    rho, l, w, h = 7850.0, 0.05, 0.01, 2e-4
    strip = flexure.SpatialFlexure(length=l, modulus=200e9, width=w, thickness=h, density=rho)
    assert strip.density == rho and strip.mass_per_length is None
    assert abs(strip.mass() / (rho * w * h * l) - 1) < 1e-13
    assert abs(strip.mass_per_length_at(0.02) / (rho * w * h) - 1) < 1e-13
    d0, d1 = 2e-3, 1e-3
    rod = flexure.SpatialFlexure(length=l, modulus=200e9, diameter=(d0, d1), density=rho)
    exact = rho * math.pi / 4 * l * (d0 * d0 + d0 * d1 + d1 * d1) / 3
    assert abs(rod.mass() / exact - 1) < 1e-13
    at = rod.mass_per_length_at(np.array([0.0, l]))
    assert np.allclose(at, [rho * math.pi * d0 * d0 / 4, rho * math.pi * d1 * d1 / 4], rtol=1e-13, atol=0)
    # Without mass: None, as the planar Flexure's mass_per_length_at.
    bare = flexure.SpatialFlexure()
    assert bare.mass() is None and bare.mass_per_length_at(0.5) is None and bare.density is None


def test_rotary_inertia_per_length_as_the_file_key_takes_it():
    # The file key's rules (crates/flexure/src/section/spatial.rs): with mass_per_length only,
    # finite and not negative, the twist's at most the sum of the bendings' (a section's polar
    # moment); each refusal names the argument and its value.
    f = flexure.SpatialFlexure(length=10.0, ei=1e3, order=4, mass_per_length=1.0, rotary_inertia_per_length=[20.0, 10.0, 10.0])
    assert f.rotary_inertia_per_length == (20.0, 10.0, 10.0)
    assert flexure.SpatialFlexure(mass_per_length=1.0).rotary_inertia_per_length is None
    with pytest.raises(ValueError, match="rotary_inertia_per_length"):
        flexure.SpatialFlexure(rotary_inertia_per_length=[2.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="rotary_inertia_per_length.*-1"):
        flexure.SpatialFlexure(mass_per_length=1.0, rotary_inertia_per_length=[2.0, -1.0, 1.0])
    with pytest.raises(ValueError, match="rotary_inertia_per_length.*twist, y, z"):
        flexure.SpatialFlexure(mass_per_length=1.0, rotary_inertia_per_length=[2.0, 1.0])


def test_mass_per_length_as_given_and_its_mass():
    # Reference: a taper μ = (root, tip) has mass (root + tip)/2·L; a table's piecewise-linear
    # μ whose kink lies on a Magnus subinterval's end (t = 1/2, of 8) integrates exactly:
    # L·(μ0 + 2μ½ + μ1)/4. Both 1e-13 relative.
    f = flexure.SpatialFlexure(length=0.2, ei=0.01, mass_per_length=(0.05, 0.03))
    assert f.mass_per_length == (0.05, 0.03) and f.density is None
    assert abs(f.mass() / (0.04 * 0.2) - 1) < 1e-13
    assert abs(f.mass_per_length_at(0.1) / 0.04 - 1) < 1e-13
    table = [[0.0, 0.05], [0.5, 0.02], [1.0, 0.04]]
    g = flexure.SpatialFlexure(length=0.2, ei=0.01, mass_per_length=table)
    assert np.array_equal(g.mass_per_length, np.array(table))
    assert abs(g.mass() / (0.2 * (0.05 + 2 * 0.02 + 0.04) / 4) - 1) < 1e-13
    # A number reads back as a float.
    assert flexure.SpatialFlexure(mass_per_length=0.5).mass_per_length == 0.5


SPATIAL_BEAM = """dimension = 3
[[joint]]
name = "beam"
kind = "flexure"
parent = "ground"
child = "tip"
length = 0.05
{section}
"""


def test_bad_mass_raises_value_error_naming_it_as_the_file_does():
    # Each refusal names the argument and its value, with the file's reason for the same keys.
    strip = dict(length=0.05, modulus=200e9, width=0.01, thickness=2e-4)
    with pytest.raises(ValueError, match=r"density = 7850(\.0)? and mass_per_length") as both:
        flexure.SpatialFlexure(**strip, density=7850.0, mass_per_length=0.01)
    with pytest.raises(ValueError, match="give density or mass_per_length, not both"):
        flexure.Mechanism.from_toml(
            SPATIAL_BEAM.format(section="modulus = 200e9\nwidth = 0.01\nthickness = 2e-4\ndensity = 7850.0\nmass_per_length = 0.01")
        )
    assert "give density or mass_per_length, not both" in str(both.value)
    # density on a section given by its stiffnesses: no area.
    with pytest.raises(ValueError, match=r"invalid density = 7850: needs a rectangle's width and thickness") as ei:
        flexure.SpatialFlexure(ei=0.01, density=7850.0)
    with pytest.raises(ValueError) as file_ei:
        flexure.Mechanism.from_toml(SPATIAL_BEAM.format(section="ei = 0.01\ndensity = 7850.0"))
    assert str(ei.value).split(": ", 1)[1] in str(file_ei.value)
    for bad in (-1.0, 0.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="density"):
            flexure.SpatialFlexure(**strip, density=bad)
    with pytest.raises(ValueError, match=r"mass_per_length.*-0\.01"):
        flexure.SpatialFlexure(ei=0.01, mass_per_length=(0.02, -0.01))
    with pytest.raises(ValueError, match="mass_per_length"):
        flexure.SpatialFlexure(ei=0.01, mass_per_length=[[0.0, 0.02], [0.7, 0.01]])
    with pytest.raises(TypeError):
        flexure.SpatialFlexure(ei=0.01, mass_per_length="0.01")
    # The properties are read-only.
    f = flexure.SpatialFlexure(**strip, density=7850.0)
    with pytest.raises(AttributeError):
        f.density = 1.0


def test_a_dead_twisting_moment_is_judged_by_the_static_test():
    # Reference: a clamped-free rod under a dead axial torque T has no neighbouring equilibrium at
    # any T (EI w'' = iT w', w(0) = w'(0) = 0 has only w = 0: Ziegler), so past Greenhill's
    # 2 pi EI/L, at 10 EI/L (issue 39 item 4), the model and the exact rod both answer stable, with
    # no StabilityWarning, and say which question: stability_test "static". Without a moment the
    # test is the energy's.
    from flexure import exact

    f = flexure.SpatialFlexure()
    with warnings.catch_warnings():
        warnings.simplefilter("error", flexure.StabilityWarning)
        d = f.deflect(moment=(10.0, 0.0, 0.0))
    e = exact.rod(f, moment=(10.0, 0.0, 0.0))
    assert d["stable"] and e["stable"] and "limit_fraction" not in d
    assert d["stability_test"] == "static" and e["stability_test"] == "static"
    assert f.deflect(force=(-1.0, 0.0, 0.1))["stability_test"] == "energy"
