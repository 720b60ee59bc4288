"""The wedge (*Keil*, *Keiltrieb*, *ķīlis*): a closed loop of straight sliding pairs.

Rosenauer §95 (seed digest 001c, "§95. Rules for introducing prismatic pairs", Figs. 273–274)
gives the exception to the count. The three-link slider chain, the wedge or cotter joint, is
constrained although 2z − 3n + 4 = 2·3 − 9 + 4 = 1 ≠ 0. Its criterion is 2z − 3n + 4 = γ, with
γ the closed slider groups. `topology.groups.solution_order` therefore counts a sliding pair
that closes such a loop once, not twice. These tests check that the order finds the wedge's
groups, that it refuses wedges whose guides cannot transmit motion with one message naming the
pairs, and that `linkwork.solve` gives the wedge's closed form.

The wedge's closed form (Rosenauer §70, Example 27, digest 001b: the input slide's velocity is
split along the other two sliding directions):

* the wedge slides on the frame along d = (cos δ, sin δ), displaced by u (the driver's input);
* its face is the line through the contact point C with direction f = (cos α, sin α), fixed in
  the wedge (pair `face`);
* the follower carries C and slides on the frame along g = (cos β, sin β) (pair `guide`).

At the displacement u, C has moved along the follower's guide by s and along the face by t:
C = C₀ + s·g = C₀ + u·d + t·f, i.e. s·g − t·f = u·d. Take the cross product with f and then
with g (a × b = a_x b_y − a_y b_x; g × f = sin(α − β), d × f = sin(α − δ), d × g = sin(β − δ)):

    s = u · sin(α − δ) / sin(α − β),        t = u · sin(β − δ) / sin(α − β).

This is the sine law of the velocity triangle. For the usual wedge, with the input horizontal
(δ = 0) and the follower vertical (β = 90°), s = u · sin α / (−cos α) = −u · tan α: pushing the
wedge forward by u lowers a follower resting on a face that rises at α by u·tan α. The map is
linear, so ṡ = k·u̇ and s̈ = k·ü with the same ratio k, and no link turns.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import StructureError
from linkwork.structure import constraint_count, mobility, solution_order
from linkwork.topology.groups import slider_loop
from linkwork.structure.mobility import slider_groups, structure_report
from mechanism_texts import joint, mechanism_text, revolute

C0 = np.array([40.0, 30.0])
W0 = np.array([0.0, 0.0])


def wedge_text(delta: float = 0.0, alpha: float = 20.0, beta: float = 90.0,
               driver: str = "slide") -> str:
    """A wedge in the README's file format. Angles are in degrees: δ for the input slide, α for
    the wedge's face and β for the follower's guide."""
    return mechanism_text(
        name=f"Wedge δ={delta} α={alpha} β={beta}", units="mm",
        description="Three-link slider chain (wedge, Rosenauer Figs. 273-274)",
        points={"O": (0, 0), "W": W0, "C": C0},
        links={"frame": ["O"], "wedge": ["W"], "follower": ["C"]},
        joints=[joint("slide", "prismatic", "frame", "wedge", axis=delta, point="W"),
                joint("face", "prismatic", "wedge", "follower", axis=alpha, point="C"),
                joint("guide", "prismatic", "frame", "follower", axis=beta, point="C")],
        driver=driver, speed=10)


# A slider-crank pushes the wedge: n = 5 links (frame, crank, rod, wedge, follower), z = 6 lower
# pairs (3 hinges, 3 sliders), γ = 1. This is Rosenauer's Fig. 276 count,
# 2·6 − 3·5 + 4 = 1 = γ, so the chain is constrained.
CRANK_WEDGE = mechanism_text(
    name="Crank-driven wedge",
    points={"O": (0, 0), "A": (0, 20), "B": (80, 0), "C": (120, 30)},
    links={"frame": ["O"], "crank": ["O", "A"], "rod": ["A", "B"], "wedge": ["B"],
           "follower": ["C"]},
    joints=[revolute("O", "frame", "crank"), revolute("A", "crank", "rod"),
            revolute("B", "rod", "wedge"),
            joint("slide", "prismatic", "frame", "wedge", axis=[1, 0], point="B"),
            joint("face", "prismatic", "wedge", "follower", axis=25, point="C"),
            joint("guide", "prismatic", "frame", "follower", axis=90, point="C")],
    driver="O")

# Rosenauer Fig. 270: four sliders in a loop are not constrained. The count gives
# 2·4 − 3·4 + 4 = 0 ≠ γ = 1, so one more input is needed.
FOUR_SLIDERS = mechanism_text(
    name="four sliders",
    points={"O": (0, 0), "p1": (10, 0), "p2": (10, 10), "p3": (0, 12)},
    links={"frame": ["O"], "s1": ["p1"], "s2": ["p2"], "s3": ["p3"]},
    joints=[joint("a", "prismatic", "frame", "s1", axis=[1, 0], point="p1"),
            joint("b", "prismatic", "s1", "s2", axis=[0, 1], point="p2"),
            joint("c", "prismatic", "s2", "s3", axis=[1, 1], point="p3"),
            joint("d", "prismatic", "frame", "s3", axis=[1, -2], point="p3")],
    driver="a")

# Not a wedge: a block sliding both on the frame and on a turning crank. The two links it slides
# on turn against each other, so its two "no turning" conditions contradict each other rather
# than repeat one another. The block stays over-constrained.
BLOCK_ON_TWO_TURNING_GUIDES = mechanism_text(
    name="block on two guides",
    points={"O": (0, 0), "A": (30, 0), "P": (20, 0)},
    links={"frame": ["O"], "crank": ["O", "A"], "block": ["P"]},
    joints=[revolute("O", "frame", "crank"),
            joint("g1", "prismatic", "frame", "block", axis=[1, 0], point="P"),
            joint("g2", "prismatic", "crank", "block", axis=[1, 0], point="P")],
    driver="O")


def load(text: str):
    return linkwork.load_text(text)


def wedge_ratio(delta: float, alpha: float, beta: float) -> tuple[float, float]:
    """(s/u, t/u) from the closed form in the module docstring (angles in degrees)."""
    d, a, b = np.radians([delta, alpha, beta])
    return np.sin(a - d) / np.sin(a - b), np.sin(b - d) / np.sin(a - b)


def unit(deg: float) -> np.ndarray:
    return np.array([np.cos(np.radians(deg)), np.sin(np.radians(deg))])


# ---------------------------------------------------------------------------- the closed form
@pytest.mark.parametrize("delta,alpha,beta", [(0, 20, 90), (10, 35, 100), (-15, 60, 120)])
def test_closed_form_closes_the_wedge(delta, alpha, beta):
    """Test setup: the closed form puts C on both guide lines (s·g = u·d + t·f)."""
    k, kt = wedge_ratio(delta, alpha, beta)
    u = 3.7
    np.testing.assert_allclose(k * u * unit(beta), u * unit(delta) + kt * u * unit(alpha),
                               atol=1e-12)
    if (delta, alpha, beta) == (0, 20, 90):
        assert k == pytest.approx(-np.tan(np.radians(20)))


# ---------------------------------------------------------------------------- the solution order
def test_wedge_loads_and_has_a_solution_order():
    m = load(wedge_text())
    groups = solution_order(m)
    assert [g.links for g in groups] == [("wedge",), ("follower",)]
    assert groups[0].drivers == ("slide",) and groups[0].wedge_pairs == ()
    follower = groups[1]
    assert set(follower.joints) == {"face", "guide"}
    # exactly one of the follower's two sliding pairs closes the loop slide, face, guide, and
    # its rotation condition is counted once: 2 + 2 − 1 = 3 freedoms for one link
    assert len(follower.wedge_pairs) == 1 and follower.wedge_pairs[0] in {"face", "guide"}
    js = [m.joint(j) for j in follower.joints]
    assert constraint_count(js, set(), follower.wedge_pairs) == 3
    assert constraint_count(js, set()) == 4


def test_wedge_driven_at_the_follower():
    """The inverse wedge: the follower's guide is the input, and the wedge follows."""
    groups = solution_order(load(wedge_text(driver="guide")))
    assert [g.links for g in groups] == [("follower",), ("wedge",)]
    assert len(groups[1].wedge_pairs) == 1


def test_crank_driven_wedge_is_rosenauers_fig_276_count():
    m = load(CRANK_WEDGE)
    c = mobility(m).counts
    # n = 5, z = 6, γ = 1 (hand count of the text above): 2·6 − 15 + 4 = 1 = γ
    assert (c.n, c.z, c.gamma) == (5, 6, 1) and c.constrained
    groups = solution_order(m)
    assert [set(g.links) for g in groups] == [{"crank"}, {"rod", "wedge"}, {"follower"}]
    assert groups[1].wedge_pairs == () and len(groups[2].wedge_pairs) == 1


@pytest.mark.parametrize("text", [wedge_text(), wedge_text(driver="guide"), CRANK_WEDGE,
                                  wedge_text(10, 35, 100)])
def test_wedge_pairs_are_the_closed_slider_groups_of_the_count(text):
    """Every pair that solution_order counts once belongs to one of the γ closed slider groups
    that structure.mobility counts, and each such group has exactly one of them."""
    m = load(text)
    groups = solution_order(m)
    wedge = [w for g in groups for w in g.wedge_pairs]
    assert len(wedge) == slider_groups(m) == 1
    assert set(slider_loop(m, wedge[0])) == {"slide", "face", "guide"}
    # every link is fixed: 3 freedoms per moving link removed over all groups
    drivers = {d.joint for d in m.drivers}
    removed = sum(constraint_count([m.joint(j) for j in g.joints], drivers, g.wedge_pairs)
                  for g in groups)
    assert removed == 3 * len(m.moving_links)


def test_structure_report_gives_the_wedge_groups():
    rep = structure_report(load(wedge_text()), limits=False)
    assert rep.structure_error is None
    assert [list(g.links) for g in rep.groups] == [["wedge"], ["follower"]]
    assert rep.mobility.real_mobility == 1 and rep.mobility.constrained


def test_four_sliders_still_need_a_second_input():
    with pytest.raises(StructureError,
                       match=r"under-constrained: the links s2, s3 .* needs 1 more input"):
        solution_order(load(FOUR_SLIDERS))


def test_two_guides_that_turn_against_each_other_stay_over_constrained():
    with pytest.raises(StructureError, match=r"over-constrained: the links block .* g1, g2"):
        solution_order(load(BLOCK_ON_TWO_TURNING_GUIDES))


# ---------------------------------------------------------------------------- wrong wedges
@pytest.mark.parametrize("delta,alpha,beta,driver,pairs,link", [
    # all three guides parallel: the follower slides freely along the common direction
    (0, 0, 0, "slide", "face and guide", "follower"),
    # the follower's two guides parallel (face and guide vertical): the wedge locks, and the
    # follower is free along its guide
    (0, 90, 90, "slide", "face and guide", "follower"),
    # all parallel, driven at the follower: now the wedge's two guides are the parallel ones
    (0, 0, 0, "guide", "slide and face", "wedge"),
])
def test_wedge_with_parallel_guides_is_one_clear_error(delta, alpha, beta, driver, pairs, link):
    m = load(wedge_text(delta, alpha, beta, driver))
    with pytest.raises(StructureError) as exc:
        linkwork.solve(m, [0.0, 1.0])
    msg = str(exc.value)
    assert f"the pairs {pairs} hold {link} on parallel lines" in msg
    assert "closed slider group (wedge) slide, face, guide" in msg
    assert "Rosenauer §95" in msg
    # the same message from the order and from the structure report (no crash)
    with pytest.raises(StructureError, match="parallel lines"):
        solution_order(m)
    assert "parallel lines" in structure_report(m, limits=False).structure_error


def test_wedge_whose_input_runs_along_the_face_is_not_an_error():
    """δ = α: the wedge slides along its own face, so s = u·sin 0/sin(α − β) = 0. The follower
    stands still. It is a well-defined (if useless) motion, not a structural error."""
    assert len(solution_order(load(wedge_text(20, 20, 90)))) == 2
    assert wedge_ratio(20, 20, 90)[0] == 0.0


# ---------------------------------------------------------------------------- the solve
def _solve(m, u, v, a):
    n = len(u)
    return linkwork.solve(m, u, velocities=np.full(n, v), accelerations=np.full(n, a))


@pytest.mark.parametrize("delta,alpha,beta", [(0, 20, 90), (10, 35, 100), (-15, 60, 120)])
def test_solve_gives_the_wedge_closed_form(delta, alpha, beta):
    m = load(wedge_text(delta, alpha, beta))
    k, kt = wedge_ratio(delta, alpha, beta)
    u = np.linspace(-6.0, 6.0, 13)
    v, a = 2.5, -0.8
    sol = _solve(m, u, v, a)
    assert (sol.status == linkwork.Status.OK).all()
    g, d, f = unit(beta), unit(delta), unit(alpha)
    C, W = sol.point("C"), sol.point("W")
    np.testing.assert_allclose(C.position, C0 + (k * u)[:, None] * g, atol=1e-10)
    np.testing.assert_allclose(W.position, W0 + u[:, None] * d, atol=1e-10)
    np.testing.assert_allclose(C.velocity, np.tile(k * v * g, (len(u), 1)), atol=1e-10)
    np.testing.assert_allclose(C.acceleration, np.tile(k * a * g, (len(u), 1)), atol=1e-10)
    # C's slide along the face, seen from the wedge: t = u·sin(β − δ)/sin(α − β)
    slide = C.position - (W.position - W0) - C0
    np.testing.assert_allclose(slide, (kt * u)[:, None] * f, atol=1e-10)
    # no link turns
    for ln in ("wedge", "follower"):
        np.testing.assert_allclose(sol.link(ln).angle, 0.0, atol=1e-12)
        np.testing.assert_allclose(sol.link(ln).omega, 0.0, atol=1e-12)


def test_solve_velocities_match_finite_differences():
    m = load(wedge_text(10, 35, 100))
    h = 1e-4
    u = np.array([-2.0, 0.0, 1.5])
    v = 1.0  # unit input rate: velocities are d(position)/du
    lo, mid, hi = (_solve(m, u + e, v, 0.0) for e in (-h, 0.0, h))
    for p in ("C", "W"):
        fd = (hi.point(p).position - lo.point(p).position) / (2 * h)
        np.testing.assert_allclose(mid.point(p).velocity, fd, atol=1e-8)


def test_crank_driven_wedge_solves_against_its_closed_form():
    """The crank drives the wedge through an in-line slider-crank (crank r = 20, rod l = √6800,
    both from the drawing). The block's place along the stroke is x_B = r cos φ + √(l² − r² sin² φ),
    and the follower moves by s = (x_B − 80)·sin 25°/sin(25° − 90°)."""
    m = load(CRANK_WEDGE)
    phi = np.radians(np.arange(0.0, 360.0, 15.0)) + np.pi / 2  # design: crank vertical
    sol = linkwork.solve(m, phi)
    r, l = 20.0, np.hypot(80.0, 20.0)
    xB = r * np.cos(phi) + np.sqrt(l * l - (r * np.sin(phi)) ** 2)
    k, _ = wedge_ratio(0, 25, 90)
    np.testing.assert_allclose(sol.point("B").position[:, 0], xB, atol=1e-9)
    np.testing.assert_allclose(sol.point("C").position[:, 1], 30.0 + k * (xB - 80.0), atol=1e-9)


def test_structure_report_with_input_limits_does_not_crash():
    """A wedge's input has no limit position: the report says so instead of a limit range."""
    rep = structure_report(load(wedge_text()))
    assert rep.groups is not None and rep.input_limits is None
