"""Contact in `Mechanism.solve` (crates/flexure/src/mechanism/statics/contact.rs):
the answer's `contacts`, as `flexure solve --json` prints them.

Reference: the propped cantilever, a tip moment M pressing a strip's tip
onto a floor g below it: N = 3M/(2L) - 3 EI g / L^3 in linear theory (0.12 N
here); large deflection moves it by about 2e-5 N (the exact elastica with
contact gives 0.1200185, `reference::elastica::contact`), so 1e-3 relative."""

import pytest

import flexure

STRIP = """
[[joint]]
name = "strip"
kind = "flexure"
parent = "ground"
child = "tip"
length = 1.0
ei = 1.0
order = 6
[[force]]
body = "tip"
moment = -0.1
[[geom]]
name = "floor"
body = "ground"
shape = "plane"
origin = [0.0, -0.01]
normal = [0.0, 1.0]
"""


def test_a_tip_pressed_onto_a_floor_reports_its_contact():
    answer = flexure.Mechanism.from_toml(STRIP).solve()
    (contact,) = answer["contacts"]
    assert contact["geom"] == "floor" and contact["flexure"] == "strip" and contact["s"] == 1.0
    assert contact["state"] == "slip"
    assert contact["normal_force"] == pytest.approx(0.12, rel=1e-3)
    assert abs(contact["gap"]) < 1e-12
    assert contact["normal"] == [0.0, 1.0] and contact["friction_force"] == [0.0, 0.0]
    assert not answer["flagged"]


def test_no_contact_no_key():
    far = STRIP.replace("origin = [0.0, -0.01]", "origin = [0.0, -5.0]")
    assert "contacts" not in flexure.Mechanism.from_toml(far).solve()


def test_friction_is_refused_by_name():
    rough = STRIP + "friction = 0.3\n"
    with pytest.raises(ValueError, match=r"friction = 0.3 \(geom \"floor\" \(plane\) and flexure \"strip\"\)"):
        flexure.Mechanism.from_toml(rough).solve()


def test_other_analyses_refuse_a_pair_that_may_touch():
    m = flexure.Mechanism.from_toml(STRIP)
    with pytest.raises(ValueError, match=r"geom \"floor\" \(plane\) and flexure \"strip\": may touch"):
        m.modes(1)
