"""Contact in `Mechanism.solve` (crates/flexure/src/mechanism/statics/contact.rs) and
`Mechanism.simulate` (crates/flexure/src/dynamics/contact.rs):
the answer's `contacts`, as `flexure solve --json` prints them.

Reference: the propped cantilever, a tip moment M pressing a strip's tip
onto a floor g below it: N = 3M/(2L) - 3 EI g / L^3 in linear theory (0.12 N
here); large deflection moves it by about 2e-5 N (the exact elastica with
contact gives 0.1200185, `reference::elastica::contact`), so 1e-3 relative."""

import math
import pathlib

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


def test_contacts_is_an_empty_list_where_none_touches_and_absent_without_geoms():
    """A script reads `contacts` whenever a part may reach a geom: the strip
    far above its floor touches nothing, and a file with no geom has no key."""
    far = STRIP.replace("origin = [0.0, -0.01]", "origin = [0.0, -5.0]")
    assert flexure.Mechanism.from_toml(far).solve()["contacts"] == []
    bare = STRIP[: STRIP.index("[[geom]]")]
    assert "contacts" not in flexure.Mechanism.from_toml(bare).solve()


def test_a_rough_floor_holds_the_tip_with_friction():
    """The tip slides back toward the root from the touch (a stuck tip
    would need more than any finite friction: an inextensible strip cannot
    bend further with both its tip's coordinates held), so its friction is
    mu N forward, exactly (1e-12 relative); the Rust tests hold the same case
    to the exact elastica with friction."""
    answer = flexure.Mechanism.from_toml(STRIP + "friction = 0.3\n").solve()
    (contact,) = answer["contacts"]
    assert contact["state"] == "slip"
    assert contact["friction_force"][0] == pytest.approx(0.3 * contact["normal_force"], rel=1e-12)
    assert contact["normal_force"] > 0.11


def test_friction_where_a_contact_rolls_holds_it_in_its_cone():
    """A strip without thickness pressed onto a rough post touches inside its
    span, where the contact rolls (`crates/flexure/tests/contact_rolling.rs`
    checks rolling against closed forms): its friction is within the cone,
    on it where it slides (to 1e-9 of N)."""
    post = STRIP.replace("moment = -0.1", "force = [0.0, -3.0]").replace(
        'shape = "plane"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]',
        'shape = "circle"\norigin = [0.55, -0.3]\nradius = 0.25',
    )
    # The contact kinks the shear: the estimate flags the peak curvature
    # (5 % at order 6), as it should; position and angle meet the target.
    with pytest.warns(flexure.AccuracyWarning, match="peak curvature"):
        contact = flexure.Mechanism.from_toml(post + "friction = 0.3\n").solve()["contacts"][0]
    n, f = contact["normal_force"], math.hypot(*contact["friction_force"])
    assert 0.0 < contact["s"] < 1.0 and n > 0.0
    assert contact["state"] in ("stick", "slip") and f <= 0.3 * n * (1.0 + 1e-9)
    if contact["state"] == "slip":
        assert f == pytest.approx(0.3 * n, rel=1e-9)


def test_friction_where_a_thick_flexure_touches_in_space_is_the_planes():
    """A spatial strip with a thickness touches with its surface, off its
    centreline, whose material point turns with its section (its twist
    too): the spatial file of a planar problem gives the plane's contact,
    its state and its push to 1e-6 (`crates/flexure/tests/contact_rolling.rs`
    holds both to closed forms of rolling)."""
    thick = STRIP.replace("ei = 1.0", "modulus = 1.2e9\nwidth = 0.01\nthickness = 0.01") + "friction = 0.3\n"
    spatial = (
        "dimension = 3\n"
        + thick.replace("moment = -0.1", "moment = [0.0, 0.0, -0.1]")
        .replace("origin = [0.0, -0.01]\nnormal = [0.0, 1.0]", "origin = [0.0, -0.01, 0.0]\nnormal = [0.0, 1.0, 0.0]")
    )
    (plane,) = flexure.Mechanism.from_toml(thick).solve()["contacts"]
    (space,) = flexure.Mechanism.from_toml(spatial).solve()["contacts"]
    assert space["state"] == plane["state"] and space["s"] == pytest.approx(plane["s"], rel=1e-9)
    assert space["normal_force"] == pytest.approx(plane["normal_force"], rel=1e-6)


def test_the_compliance_holds_the_contact_closed():
    """Propped cantilever: the tip's turn per unit tip moment is L/(4 EI) in
    linear theory (0.25 here; large deflection moves it by 8e-5, so 1e-3
    relative), and the floor holds the tip's height."""
    c = flexure.Mechanism.from_toml(STRIP).compliance("tip", [0.0, 0.0])
    assert c[0, 0] == pytest.approx(0.25, rel=1e-3)
    assert abs(c[2, 2]) < 1e-12 * c[0, 0]


def test_other_analyses_refuse_a_pair_that_may_touch():
    m = flexure.Mechanism.from_toml(STRIP)
    with pytest.raises(ValueError, match=r"invalid geom \"floor\" \(plane\) and flexure \"strip\": may touch"):
        m.buckle()


DROP = """
gravity = [0.0, -9.81]
[[joint]]
name = "slide"
kind = "prismatic"
parent = "ground"
child = "ball"
origin = [0.0, 0.0, 1.5707963267948966]
[[body]]
name = "ball"
mass = 2.0
[[geom]]
name = "shot"
body = "ball"
shape = "circle"
radius = 0.05
[[geom]]
name = "floor"
body = "ground"
shape = "plane"
origin = [0.0, -0.25]
normal = [0.0, 1.0]
"""


def test_a_dropped_ball_lands_and_rests_on_the_floor():
    """Reference: free fall from 0.2 m lands at sqrt(2h/g) = 0.2019 s and rests pushed by mg
    (crates/flexure/src/dynamics/contact.rs); 1e-6 s, 1e-6 of mg."""
    run = flexure.Mechanism.from_toml(DROP).simulate(0.4, every=0.02, tolerance=1e-9, start="rest")
    landing = (2 * 0.2 / 9.81) ** 0.5
    assert [c["state"] for c in run["changes"]] == ["slip"]
    assert run["changes"][0]["contact"] == "contact.floor.ball"
    assert abs(run["changes"][0]["time"] - landing) < 1e-6
    for t, contacts in zip(run["time"], run["contacts"]):
        (c,) = contacts
        if t > landing:
            assert c["state"] == "slip" and abs(c["normal_force"] - 2 * 9.81) < 1e-6 * 2 * 9.81
        else:
            assert c["state"] == "open" and c["normal_force"] == 0.0 and c["gap"] > 0.0


def test_a_pendulum_swung_onto_a_rough_floor_rests_on_it():
    """Reference: statics of the arm on its pin. Its bob (0.02 m, 0.2 m out, where its mass
    is) swung from level onto a rough floor 0.1 m below the pin, where the ball rolls: the
    gap stops its one coordinate at sin(phi) = -0.08/0.2, the bob stuck (its friction row
    left out: nothing is left to slide), pushed by N = m g (moments about the pin); the
    angle to 1e-9 rad, N to 1e-6 of m g. Friction where a contact rolls was refused in
    motion before."""
    arm = """
gravity = [0.0, -9.81]
[[joint]]
name = "pin"
kind = "revolute"
parent = "ground"
child = "arm"
[[body]]
name = "arm"
mass = 1.0
com = [0.2, 0.0]
[[geom]]
name = "bob"
body = "arm"
shape = "circle"
origin = [0.2, 0.0]
radius = 0.02
[[geom]]
name = "floor"
body = "ground"
shape = "plane"
origin = [0.0, -0.1]
normal = [0.0, 1.0]
friction = 0.3
"""
    run = flexure.Mechanism.from_toml(arm).simulate(0.5, every=0.05, tolerance=1e-9, start="rest")
    assert run.get("stopped") is None, run.get("stopped")
    assert [c["state"] for c in run["changes"]][-1] == "stick"
    rest = run["changes"][-1]["time"]
    for t, phi, contacts in zip(run["time"], run["coordinates"]["pin"], run["contacts"]):
        if t > rest:
            (c,) = contacts
            assert c["state"] == "stick" and abs(c["normal_force"] - 9.81) < 1e-6 * 9.81, c
            assert abs(phi[0] + math.asin(0.4)) < 1e-9, phi


def test_a_ball_on_a_rough_floor_sticks_until_pulled_past_its_friction():
    """Reference: Coulomb, a ball resting on a floor (mu = 0.5) pulled by 20 t N slips at
    t = mu m g / 20 = 0.4905 s (crates/flexure/src/dynamics/contact.rs); 1e-6 s."""
    carriage = (
        "[[joint]]\nname = \"x\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"carriage\"\n"
    )
    pulled = (
        DROP.replace("parent = \"ground\"\nchild = \"ball\"", "parent = \"carriage\"\nchild = \"ball\"")
        .replace("origin = [0.0, -0.25]", "origin = [0.0, -0.05]")
        .replace("[[joint]]", carriage + "[[joint]]", 1)
        + "friction = 0.5\n[[force]]\nname = \"pull\"\nbody = \"ball\"\nforce = [0.0, 0.0]\n"
        + "[[schedule]]\nload = \"force.pull.fx\"\npoints = [[0.0, 0.0], [1.0, 20.0]]\n"
    )
    run = flexure.Mechanism.from_toml(pulled).simulate(0.6, every=0.05, tolerance=1e-9, start="rest")
    assert [c["state"] for c in run["changes"]] == ["slip"]
    assert abs(run["changes"][0]["time"] - 0.5 * 2 * 9.81 / 20) < 1e-6
    assert run["contacts"][0][0]["state"] == "stick"



GRASP = pathlib.Path(__file__).resolve().parents[2] / "examples" / "grasp.toml"


def test_a_sweep_reports_each_rows_contacts():
    """`examples/grasp.toml`'s tendon sweep tells the story of its header:
    no touch at 0 N, the proximal pad on the rod by 1 N, both pads at 2.5 N,
    the distal pad alone at 4 N (the proximal lifted off by 3 N). Each
    pair's push (`normal_force`, the CLI's `contact.GEOM.PART.normal_force`
    column; the hinges may touch the rod too) is its row's contact's, 0
    while open; each friction is within
    Coulomb's cone (mu = 0.5, to 1e-9 of the push); and the last row is
    `solve`'s at the file's 4 N, which follows the same path in its own
    steps (to 1e-9 of the push; measured 7e-15)."""
    m = flexure.Mechanism.from_file(str(GRASP))
    answer = m.sweep("tendon.flexor.tension", [0.0, 1.0, 2.5, 4.0])
    touching = [{c.get("body", c.get("flexure")) for c in row if c["state"] != "open"} for row in answer["contacts"]]
    assert touching == [set(), {"proximal"}, {"proximal", "distal"}, {"distal"}], touching
    pushes = answer["normal_force"]
    parts = ["mcp", "pip", "proximal", "distal"]
    assert sorted(pushes) == sorted(f"contact.cylinder.{p}" for p in parts), pushes.keys()
    for name, push in pushes.items():
        part = name.split(".")[2]
        for k, row in enumerate(answer["contacts"]):
            mine = [c["normal_force"] for c in row if c.get("body", c.get("flexure")) == part and c["state"] != "open"]
            assert push[k] == (mine[0] if mine else 0.0), (name, k, row)
    for row in answer["contacts"]:
        for c in row:
            friction = math.hypot(*c["friction_force"])
            assert friction <= 0.5 * c["normal_force"] * (1 + 1e-9) + 1e-15, c
    (solved,) = [c for c in m.solve()["contacts"] if c["state"] != "open"]
    (last,) = [c for c in answer["contacts"][-1] if c["state"] != "open"]
    assert (solved["body"], solved["state"]) == (last["body"], last["state"])
    assert solved["normal_force"] == pytest.approx(last["normal_force"], rel=1e-9)


COLUMN = """
joint = [
  { name = "feed", kind = "prismatic", parent = "ground", child = "carriage", stiffness = 100.0 },
  { name = "strip", kind = "flexure", parent = "carriage", child = "tip", length = 0.1, ei = 0.01, order = 10 },
]
force = [{ name = "push", body = "carriage", force = [1.0, 0.0] }]
geom = [{ name = "wall", body = "ground", shape = "plane", origin = [0.1001, 0.0], normal = [-1.0, 0.0], friction = 0.5 }]
"""


def test_solve_limit_follows_the_contacts_state():
    """A column pushed into a wall 0.1 mm past its tip (the carriage's
    100 N/m spring takes 0.01 N to close it): its tip sticks on a rough
    wall, so it buckles pinned, (4.4934)^2 EI/L^2 = 20.19 N; it slides on a
    smooth one and buckles as a cantilever, pi^2 EI/4L^2 = 2.467 N. Each
    factor on the 1 N push to 1e-5 (the stability margin moves a limit by
    about 1e-6 of itself). Without limit=True there is no key."""
    pinned = 4.493409457909064**2 + 0.01
    free = math.pi**2 / 4.0 + 0.01
    for text, exact in [(COLUMN, pinned), (COLUMN.replace("friction = 0.5", "friction = 0.0"), free)]:
        m = flexure.Mechanism.from_toml(text)
        limit = m.solve(limit=True)["stability_limit"]
        assert limit["status"] == "lost"
        assert limit["factor"] == pytest.approx(exact, rel=1e-5)
        assert "stability_limit" not in m.solve()


LID = """
[[joint]]
name = "pivot"
kind = "revolute"
parent = "ground"
child = "lid"
stiffness = 0.5

[[geom]]
name = "block"
body = "lid"
shape = "box"
origin = [0.08, 0.0]
half_extents = [0.02, 0.005]

[[geom]]
name = "floor"
body = "ground"
shape = "plane"
origin = [0.0, -0.03]
normal = [0.0, 1.0]

[[force]]
name = "push"
body = "lid"
at = [0.1, 0.0]
force = [0.0, -20.0]
"""


def _root(f):
    """The angle in [-1, 0] where f (of one sign at each end) crosses zero, by bisection to rounding."""
    lo, hi = -1.0, 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if f(lo) * f(mid) <= 0 else (mid, hi)
    return 0.5 * (lo + hi)


def test_two_geoms_touch_at_corners_summed_in_one_column():
    """A lid on a sprung hinge (k = 0.5 N m/rad) pushed by F at 0.1 m
    carries a box whose outer lower corner (0.1, -0.005) meets a floor
    30 mm below the hinge: there 0.1 sin(t) - 0.005 cos(t) = -0.03, and
    N = (k t + 0.1 F cos t) / (0.1 cos t + 0.005 sin t) (the moments about
    the hinge). The sweep's one column for the box and the floor sums their
    four corners' pushes, and equals the closed form to 1e-9."""

    def f(t):
        return 0.1 * math.sin(t) - 0.005 * math.cos(t) + 0.03

    t = _root(f)
    m = flexure.Mechanism.from_toml(LID)
    answer = m.sweep("force.push.fy", [-10.0, -20.0])
    assert list(answer["normal_force"]) == ["contact.floor.lid"]
    for k, force in enumerate([10.0, 20.0]):
        push = (0.5 * t + 0.1 * force * math.cos(t)) / (0.1 * math.cos(t) + 0.005 * math.sin(t))
        assert answer["normal_force"]["contact.floor.lid"][k] == pytest.approx(push, rel=1e-9)
        touching = [c for c in answer["contacts"][k] if c["state"] != "open"]
        assert sum(c["normal_force"] for c in touching) == pytest.approx(push, rel=1e-9)
        assert [c["point"] for c in touching] == [pytest.approx([0.1 * math.cos(t) + 0.005 * math.sin(t), -0.03], abs=1e-12)]


LID3_RAIL = """
dimension = 3
[[joint]]
name = "pivot"
kind = "revolute"
parent = "ground"
child = "lid"
axis = [1.0, 0.0, 0.0]
stiffness = 0.5
[[geom]]
name = "block"
body = "lid"
shape = "box"
origin = [0.0, 0.08, 0.0]
rpy = [0.0, 0.7853981633974483, 0.0]
half_extents = [0.01, 0.02, 0.005]
[[geom]]
name = "rail"
body = "ground"
shape = "box"
origin = [0.0, 0.09, -0.04]
half_extents = [0.1, 0.002, 0.01]
[[force]]
name = "push"
body = "lid"
at = [0.0, 0.1, 0.0]
force = [0.0, 0.0, -20.0]
"""


def test_two_boxes_meet_edge_across_edge_in_space():
    """A lid on a sprung hinge about x (k = 0.5 N m/rad) pushed by F at
    0.1 m carries a box turned 45 degrees about the lid's y, whose lowest
    edge (z = -0.015/sqrt 2 in the lid's frame) meets a rail's outer top
    edge (x, 0.092, -0.03) across it: there -0.092 sin(t) - 0.03 cos(t) =
    -0.015/sqrt 2, and N = (k t + 0.1 F cos t) / (0.092 cos t - 0.03 sin t)
    (the moments about the hinge, the push along the lid's normal). The
    angle to 1e-12 rad and the push to 1e-9, as the Rust solve gives."""

    def f(t):
        return -0.092 * math.sin(t) - 0.03 * math.cos(t) + 0.015 / math.sqrt(2.0)

    t = _root(f)
    push = (0.5 * t + 2.0 * math.cos(t)) / (0.092 * math.cos(t) - 0.03 * math.sin(t))
    answer = flexure.Mechanism.from_toml(LID3_RAIL).solve()
    assert answer["coordinates"]["pivot"][0] == pytest.approx(t, abs=1e-12)
    (contact,) = answer["contacts"]
    assert contact["normal_force"] == pytest.approx(push, rel=1e-9)
    assert contact["point"][1:] == pytest.approx([0.092, -0.03], abs=1e-12)
    assert contact["normal"] == pytest.approx([0.0, -math.sin(t), math.cos(t)], abs=1e-12)
