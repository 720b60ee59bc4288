"""Every construction at many random positions of several mechanisms matches the engine and the
curvature layer to 1e-9 (relative); the numbers asserted come from the engine, linkwork.instant
or closed forms, never from the construction itself."""

import zlib

import numpy as np
import pytest

import linkwork
from linkwork.constructions import CONSTRUCTIONS, construct
from linkwork.drawing import Construction

RTOL = 1e-9

FOUR_BARS = ["crank-rocker", "double-crank", "double-rocker", "pmks-teaching-four-bar"]
SLIDER_CRANKS = ["slider-crank-centric", "slider-crank-offset", "pmks-teaching-slider-crank",
                 "pmks-slider-crank-tracer"]
SIX_BARS = ["watt-i-six-bar", "stephenson-iii-six-bar", "pmks-stephenson-iii", "jansen-linkage"]
SLOTTED = ["whitworth-quick-return", "oscillating-crank-slotted-lever", "rotating-crank-slotted-lever"]

CASES = {
    "rotated-velocities": FOUR_BARS + SLIDER_CRANKS + SIX_BARS + SLOTTED,
    "velocity-plan": FOUR_BARS + SLIDER_CRANKS + SIX_BARS + SLOTTED,
    "acceleration-plan": FOUR_BARS + SLIDER_CRANKS + SIX_BARS + SLOTTED,
    "euler-savary": FOUR_BARS + SLIDER_CRANKS + ["ellipsograph"],
    "bobillier": FOUR_BARS + SLIDER_CRANKS + ["ellipsograph"],
    "hartmann": FOUR_BARS + SLIDER_CRANKS + ["ellipsograph"],
    "two-points": FOUR_BARS + SLIDER_CRANKS + SIX_BARS + ["whitworth-quick-return"],
    "klein": SLIDER_CRANKS,
    "mohr": FOUR_BARS + SLIDER_CRANKS,
    "kennedy": FOUR_BARS + SLIDER_CRANKS + SIX_BARS + SLOTTED + ["ellipsograph", "roemer-mechanism"],
    "slide-pairs": SLOTTED + ["rosenauer-shaping-machine", "poeschl-quick-return-shaper"],
    "relative-normals": FOUR_BARS + SLIDER_CRANKS + SIX_BARS + SLOTTED,
    "rolling-lever": ["rolling-lever-valve-gear"],
}


def random_positions(name: str, n: int = 40, seed: int = 5):
    """n random positions along the whole motion, each with its own input velocity sense."""
    mech = linkwork.load(f"library:{name}")
    motion = linkwork.whole_motion(mech, step=np.radians(0.25))
    rng = np.random.default_rng(zlib.crc32(f"{name}-{seed}".encode()))
    k = np.sort(rng.choice(len(motion), size=min(n, len(motion)), replace=False))
    w = motion.link(mech.drivers[0].driven).omega[k]
    return mech, linkwork.solve(mech, motion.inputs[k], velocities=w)


@pytest.mark.parametrize("name,mech_name", [(c, m) for c, ms in CASES.items() for m in ms])
def test_construction_matches_analytic(name, mech_name):
    mech, sol = random_positions(mech_name)
    con = construct(name, mech, sol)
    assert isinstance(con, Construction) and con.n == len(sol)
    assert con.results, "a construction must read numbers off the drawing"
    con.check(RTOL)
    assert con.max_error() <= RTOL
    # nearly every random position is a regular one; the degenerate ones say why
    assert con.degenerate.mean() < 0.2
    for i in np.flatnonzero(con.degenerate):
        assert con.messages(i), "a degenerate position needs a message"


@pytest.mark.parametrize("mech_name", ["crank-rocker", "double-rocker", "slider-crank-offset",
                                       "pmks-slider-crank-tracer", "antiparallelogram"])
def test_dense_sweep_through_singular_positions(mech_name):
    """Every 0.2° of the whole motion, limit positions, poles at infinity and change points
    included: wherever a construction gives a result it is right to 1e-9; elsewhere it says why."""
    mech = linkwork.load(f"library:{mech_name}")
    motion = linkwork.whole_motion(mech, step=np.radians(0.2))
    for name in CONSTRUCTIONS:
        try:
            con = construct(name, mech, motion)
        except linkwork.LinkworkError:
            continue  # not applicable to this mechanism (said clearly, tested elsewhere)
        con.check(RTOL)
        for i in np.flatnonzero(con.degenerate):
            assert con.messages(i)


def test_every_construction_is_covered():
    assert set(CASES) == set(CONSTRUCTIONS)


def test_check_raises_on_a_wrong_result():
    mech, sol = random_positions("crank-rocker", 5)
    con = construct("velocity-plan", mech, sol)
    r = con.results["v_B"]
    bad = Construction(con.name, con.title, con.source, con.n, con.elements, con.steps,
                       {**con.results, "v_B": type(r)(r.key, r.label, r.description,
                                                     r.constructed * (1 + 1e-7), r.analytic, r.scale)},
                       con.notes, con.spaces)
    with pytest.raises(linkwork.LinkworkError, match="disagrees"):
        bad.check()


# ---------------------------------------------------------------------------- Klein, seed 004
def test_klein_dead_centres_closed_form():
    """seed 004 §174: a = r ω² (1 ± r/l) at the dead centres (r = 50, l = 200, 120 rpm)."""
    mech = linkwork.load("library:slider-crank-centric")
    con = construct("klein", mech, np.radians([0.0, 180.0]))
    con.check()
    w = 120 * 2 * np.pi / 60
    a = con.results["a_A"].constructed[:, 0]
    assert a[0] == pytest.approx(-50 * w * w * (1 + 50 / 200), rel=1e-12)
    assert a[1] == pytest.approx(50 * w * w * (1 - 50 / 200), rel=1e-12)
    assert not con.degenerate.any()


def test_klein_zero_piston_acceleration_table():
    """seed 004 §176: for l/r = 4 the piston acceleration vanishes (H = C) at 76°43' from the
    dead centre (printed to the minute): the constructed a changes sign within ±2'."""
    mech = linkwork.load("library:slider-crank-centric")
    alpha = 76 + 43 / 60
    con = construct("klein", mech, np.radians([alpha - 2 / 60, alpha + 2 / 60]))
    a = con.results["a_A"].constructed[:, 0]
    assert a[0] * a[1] < 0


def test_klein_limiting_case_rod_not_turning():
    """At 90° (centric) the rod does not turn: N = P, F = G = P, the chord is its limit."""
    mech = linkwork.load("library:slider-crank-centric")
    con = construct("klein", mech, np.radians([90.0, 270.0]))
    con.check()
    assert not con.degenerate.any()
    assert any("rod does not turn" in m for m in con.messages())
    w = 4 * np.pi
    # closed form at 90°: a = -r ω² · r/√(l² − r²) · ... here: x = √(l²−r² sin²), a = -r²ω²/√(l²−r²)
    a = con.results["a_A"].constructed[0, 0]
    assert a == pytest.approx(50 ** 2 * w * w / np.sqrt(200 ** 2 - 50 ** 2), rel=1e-12)


def test_klein_rejects_a_four_bar():
    with pytest.raises(linkwork.LinkworkError, match="not a slider-crank"):
        construct("klein", linkwork.load("library:crank-rocker"), [0.3])


def test_velocity_plan_piston_closed_form():
    """Centric slider-crank: x = r cos φ + √(l² − r² sin² φ), v = dx/dt by hand."""
    mech = linkwork.load("library:slider-crank-centric")
    phi = np.radians(np.linspace(3, 357, 60))
    con = construct("velocity-plan", mech, phi)
    con.check()
    r, l, w = 50.0, 200.0, 4 * np.pi
    v = -r * w * np.sin(phi) - r * r * w * np.sin(phi) * np.cos(phi) / np.sqrt(l * l - (r * np.sin(phi)) ** 2)
    np.testing.assert_allclose(con.results["v_B"].constructed[:, 0], v, rtol=0, atol=1e-9 * r * w)


# ---------------------------------------------------------------------------- scales, degenerate
def test_rotated_velocities_do_not_depend_on_the_scale():
    from linkwork.drawing import Scale, Scales
    mech, sol = random_positions("crank-rocker", 10)
    for kv in (0.05, 1.0, 7.0):
        s = Scales(Scale("length", "mm", 1.0), Scale("velocity", "mm/s", 1.0 / kv))
        for sense in (1, -1):
            construct("rotated-velocities", mech, sol, scales=s, sense=sense).check()


@pytest.mark.parametrize("name", ["euler-savary", "bobillier", "hartmann", "two-points"])
def test_translating_coupler_is_reported(name):
    """The parallelogram's coupler translates: the pole is at infinity — a clear message and
    NaN, never garbage."""
    mech = linkwork.load("library:parallelogram")
    con = construct(name, mech, np.radians([30.0, 100.0]))
    assert con.degenerate.all()
    assert any("infinity" in m for m in con.messages())
    with pytest.raises(linkwork.LinkworkError, match="infinity"):
        con.require(0)
    for r in con.results.values():
        assert np.isnan(r.constructed).all()


def test_point_at_the_pole_is_reported():
    """Double-rocker at its limit: B lies at the coupler's pole."""
    mech = linkwork.load("library:double-rocker")
    motion = linkwork.whole_motion(mech)
    k = int(np.argmin(np.abs(motion.link("output").omega)))
    sol = linkwork.solve(mech, motion.inputs[k:k + 1])
    con = construct("euler-savary", mech, sol)
    if con.degenerate[0]:
        assert any("pole" in m for m in con.messages(0))
    else:
        con.check()


def test_bobillier_centre_at_pole_message():
    """Crank-rocker with the crank on the frame line: O₄ is the pole; Bobillier says so."""
    mech = linkwork.load("library:crank-rocker")
    con = construct("bobillier", mech, np.radians([180.0]))
    assert con.degenerate[0]
    assert any("lies at the pole" in m for m in con.messages(0))
    construct("euler-savary", mech, np.radians([180.0])).check()


def test_group_driven_from_inside_draws():
    """The ellipsograph's group (its driver between the rod and a block) is drawn as a double
    slider; other groups driven from inside are refused by name (test_inner_driver.py)."""
    mech = linkwork.load("library:ellipsograph")
    construct("velocity-plan", mech, [0.1]).check()


def test_kennedy_draws_every_pole_of_jansens_linkage():
    """Jansen's linkage: three links share each of the hinges A, B and D, so many pairs of pole
    lines through them are one line (P15P58 and P16P68 to P18 both run along BD). The schedule
    draws each pole from two different lines, so all 28 are found and agree with the poles from
    the velocities, with no coincident lines to report."""
    mech, sol = random_positions("jansen-linkage", 8)
    con = construct("kennedy", mech, sol)
    con.check(RTOL)
    assert len(con.results) == 28
    assert all(np.isfinite(r.constructed).all() for r in con.results.values())
    assert not any("coincide" in m for m in con.messages())


def test_two_points_limiting_parallel_accelerations():
    mech = linkwork.load("library:parallelogram")
    con = construct("two-points", mech, np.radians([30.0]))
    assert any("parallel" in m for m in con.messages())


def test_describe_and_sample():
    mech = linkwork.load("library:crank-rocker")
    con = construct("euler-savary", mech, np.radians([10.0, 230.0]))
    one = con.sample(1)
    assert one.n == 1 and one.sampled == 1
    text = one.describe()
    assert "Task I" in text and "Task II" in text and "Task III" in text
    assert "relative error" in text
    with pytest.raises(IndexError):
        con.sample(5)


def test_two_points_on_a_pivoted_link_is_a_clear_error():
    mech = linkwork.load("library:oscillating-crank-slotted-lever")
    with pytest.raises(linkwork.LinkworkError, match="turns about the frame pivot"):
        construct("two-points", mech, [0.3])


def test_unknown_construction():
    with pytest.raises(linkwork.LinkworkError, match="unknown construction"):
        construct("rittershaus", linkwork.load("library:crank-rocker"), [0.0])
