"""The engine driven by given point velocities (`kinematics.point_inputs.solve_given`): free and
open chains at their drawn position (Rosenauer 1937, paper 2).

Expected values come from elsewhere than the engine's own solve:
* a second linear solve in another formulation (unknowns: every point's velocity and every
  link's ω; equations: the rigid-body relation between the points of each link, written here);
* the closure of the pairs when every link is moved by h·(its rates) + h²/2·(its accelerations):
  the hinge gaps must shrink like h² for right velocities and like h³ for right accelerations
  (positions only, no derivative taken by the engine);
* the projection theorem along every link and the three-pole theorem for the poles;
* the singular triad: three binary links whose lines meet in one point Z leave the ternary
  link free to turn about Z (a classical special position), which the error must name.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError, LinkworkError, MechanismFileError, ModelError, StructureError
from linkwork.kinematics import Status
from linkwork.kinematics.point_inputs import check_count, solve_given
from linkwork.model import GivenDirection, GivenVelocity, Mechanism, Revolute, hinge_chain

WATT = {"CDG": "CDG", "DEF": "DEF", "AC": "AC", "AE": "AE", "BG": "BG", "BF": "BF"}
TRIAD = {"ABC": "ABC", "AK": "AK", "BL": "BL", "CM": "CM"}
SERIAL = {"AE": "AE", "EBF": "EBF", "CGF": "CGF", "GD": "GD"}
DREISPANN = {"AGH": "AGH", "EFG": "EFG", "CDE": "CDE", "JKB": "JKB", "AC": "AC", "HJ": "HJ",
             "FK": "FK", "DB": "DB"}


def free_chain(links: dict, pos: dict, given=(), name="free chain") -> Mechanism:
    """A hinge chain without a frame: every point shared by two links is a hinge."""
    return hinge_chain(name, pos, links, given)


def random_positions(links, seed):
    rng = np.random.default_rng(seed)
    names = sorted({p for pts in links.values() for p in pts})
    return {p: rng.uniform(-100, 100, 2) for p in names}


def reference(mech: Mechanism, given) -> tuple[dict, dict]:
    """Point velocities and ω from the rigid-body relations v_P − v_F = ω·J(P − F) of each link
    (F its first point), the given velocities and directions: one least-squares solve, whose
    matrix must have full column rank."""
    A, b, col, wcol = reference_system(mech, given)
    assert np.linalg.matrix_rank(A) == A.shape[1]
    x = np.linalg.lstsq(A, b, rcond=None)[0]
    return ({p: x[c:c + 2] for p, c in col.items()}, {ln: x[c] for ln, c in wcol.items()})


def reference_system(mech: Mechanism, given, omega=None):
    """The matrix and right-hand side of `reference`, and the columns of points and links. With
    ``omega`` (ω per link) the same for accelerations: a_P − a_F = α·J(P − F) − ω²·(P − F), the
    given points' accelerations (columns: a_P and α)."""
    pts = sorted(mech.points)
    links = [ln for ln in mech.links if ln.name != mech.frame]
    col = {p: 2 * i for i, p in enumerate(pts)}
    wcol = {ln.name: 2 * len(pts) + i for i, ln in enumerate(links)}
    n = 2 * len(pts) + len(links)
    rows, rhs = [], []
    for ln in links:
        F = ln.points[0]
        for P in ln.points[1:]:
            d = mech.points[P] - mech.points[F]
            for axis, jd in ((0, -d[1]), (1, d[0])):
                r = np.zeros(n)
                r[col[P] + axis], r[col[F] + axis], r[wcol[ln.name]] = 1, -1, -jd
                rows.append(r)
                rhs.append(0.0 if omega is None else -omega[ln.name] ** 2 * d[axis])
    for g in given:
        if isinstance(g, GivenVelocity):
            for axis in (0, 1):
                r = np.zeros(n)
                r[col[g.point] + axis] = 1
                rows.append(r)
                rhs.append((g.velocity if omega is None else g.acceleration)[axis])
        else:
            d = np.asarray(g.direction, float)
            r = np.zeros(n)
            r[col[g.point]], r[col[g.point] + 1] = -d[1], d[0]
            rows.append(r)
            rhs.append(0.0)
    return np.array(rows), np.array(rhs), col, wcol


def random_given(links, kinds, seed):
    """(point, kind) pairs → given conditions with random values."""
    rng = np.random.default_rng(100 + seed)
    out = []
    for p, kind in kinds:
        if kind == "v":
            out.append(GivenVelocity(p, rng.uniform(-50, 50, 2), rng.uniform(-20, 20, 2)))
        else:
            a = rng.uniform(0, np.pi)
            out.append(GivenDirection(p, np.array([np.cos(a), np.sin(a)]), rng.uniform(-0.02, 0.02)))
    return out


EXAMPLES = {
    "Ex I Watt v_A v_B": (WATT, [("A", "v"), ("B", "v")]),
    "Ex II triad v_K v_L v_M": (TRIAD, [("K", "v"), ("L", "v"), ("M", "v")]),
    "Ex III serial v_A v_D, directions B C": (SERIAL, [("A", "v"), ("D", "v"), ("B", "d"), ("C", "d")]),
    "Ex IV Dreispann v_A v_B": (DREISPANN, [("A", "v"), ("B", "v")]),
    "Ex IV Dreispann v_A v_F": (DREISPANN, [("A", "v"), ("F", "v")]),
}


@pytest.mark.parametrize("example", list(EXAMPLES))
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_velocities_equal_a_second_linear_solve(example, seed):
    links, kinds = EXAMPLES[example]
    pos = random_positions(links, seed)
    given = random_given(links, kinds, seed)
    mech = free_chain(links, pos, given)
    sol = solve_given(mech)
    assert sol.status[0] == Status.OK
    v_ref, w_ref = reference(mech, given)
    scale = max(np.hypot(*v) for v in v_ref.values())
    for p, v in v_ref.items():
        for ln in mech.links:
            if p in ln.points:
                assert np.allclose(sol.point_on(ln.name, mech.points[p]).velocity[0], v, atol=1e-9 * scale), (p, ln.name)
    for ln, w in w_ref.items():
        assert sol.link(ln).omega[0] == pytest.approx(w, abs=1e-9 * scale / mech.length_scale)


def _hinge_gaps(mech, sol, h):
    """The largest distance between the two links' copies of a hinge after moving every link by
    its pose at time h, from its rates (and accelerations) as a Taylor polynomial."""
    gap = 0.0
    for j in mech.joints:
        P = mech.points[j.point]
        where = []
        for ln in j.links:
            D = sol.pose_derivatives(ln)[:, 0]
            q = sum(D[k] * h ** k / np.prod(range(1, k + 1)) for k in range(1, D.shape[0]))
            c, s = np.cos(q[2]), np.sin(q[2])
            where.append(q[:2] + np.array([c * P[0] - s * P[1], s * P[0] + c * P[1]]))
        gap = max(gap, float(np.hypot(*(where[0] - where[1]))))
    return gap


@pytest.mark.parametrize("example", list(EXAMPLES))
def test_moving_by_the_rates_keeps_the_hinges_closed_to_second_and_third_order(example):
    """Positions only: the gaps after a step h shrink like h² with the rates (first order
    right) and like h³ with the accelerations too (second order right)."""
    links, kinds = EXAMPLES[example]
    pos = random_positions(links, 7)
    mech = free_chain(links, pos, random_given(links, kinds, 7))
    sol = solve_given(mech)
    assert sol.order == 2
    T = mech.length_scale / max(np.abs(sol.point(p).velocity).max() for p in mech.points)
    h = 1e-3 * T
    g1, g2 = _hinge_gaps(mech, sol, h), _hinge_gaps(mech, sol, h / 2)
    assert 6.5 < g1 / g2 < 9.5  # h³: a factor 8
    assert g1 < 1e-6 * mech.length_scale


@pytest.mark.parametrize("example", list(EXAMPLES))
def test_given_data_hold_and_the_projection_theorem_along_every_link(example):
    links, kinds = EXAMPLES[example]
    mech = free_chain(links, random_positions(links, 4), random_given(links, kinds, 4))
    sol = solve_given(mech)
    scale = max(np.abs(sol.point(p).velocity).max() for p in mech.points)
    ascale = max(np.abs(sol.point(p).acceleration).max() for p in mech.points)
    for g in mech.given:
        m = sol.point_on(g.link, mech.points[g.point])
        if isinstance(g, GivenVelocity):
            assert np.allclose(m.velocity[0], g.velocity, atol=1e-12 * scale)
            assert np.allclose(m.acceleration[0], g.acceleration, atol=1e-9 * ascale)
        else:
            d = g.direction / np.hypot(*g.direction)
            n = np.array([-d[1], d[0]])
            assert abs(m.velocity[0] @ n) <= 1e-12 * scale
            # on a path of curvature κ the normal acceleration is κ·v²
            assert m.acceleration[0] @ n == pytest.approx(g.curvature * (m.velocity[0] @ m.velocity[0]),
                                                          abs=1e-9 * ascale)
    for ln in mech.links:
        for i, X in enumerate(ln.points):
            for Y in ln.points[i + 1:]:
                d = mech.points[Y] - mech.points[X]
                vx, vy = (sol.point_on(ln.name, mech.points[p]).velocity[0] for p in (X, Y))
                assert abs((vy - vx) @ d) <= 1e-11 * scale * np.hypot(*d)


def test_poles_from_velocities_agree_with_the_three_pole_theorem():
    """Aronhold–Kennedy: every pole the theorem reaches from the hinges equals the pole found from
    the velocities; and for each hinge of links a, b, the absolute poles of a and b lie on a line
    with it (the frame being the third plane)."""
    from linkwork.instant.poles import agreement, kennedy_poles, poles

    links, kinds = EXAMPLES["Ex I Watt v_A v_B"]
    mech = free_chain(links, random_positions(links, 5), random_given(links, kinds, 5))
    sol = solve_given(mech)
    vp, kp = poles(sol), kennedy_poles(sol)
    ag = agreement(vp, kp, mech.length_scale)
    reached = [p for p, d in ag.items() if np.isfinite(d).all()]
    assert len(reached) >= 6
    assert max(float(ag[p][0]) for p in reached) <= 1e-9
    for j in mech.joints:
        a, b = j.links
        Pa = np.asarray(vp[a, "frame"].coords)[0]
        Pb = np.asarray(vp[b, "frame"].coords)[0]
        H = np.array([*mech.points[j.point], 1.0])
        det = np.linalg.det(np.array([Pa / np.linalg.norm(Pa), Pb / np.linalg.norm(Pb), H / np.linalg.norm(H)]))
        assert abs(det) <= 1e-9, j.name


def test_a_batch_of_velocity_sets_is_solved_sample_by_sample():
    links, kinds = EXAMPLES["Ex III serial v_A v_D, directions B C"]
    pos = random_positions(links, 9)
    rng = np.random.default_rng(3)
    N = 6
    dirs = rng.normal(size=(N, 2))
    batch = [GivenVelocity("A", rng.uniform(-9, 9, (N, 2))), GivenVelocity("D", rng.uniform(-9, 9, (N, 2))),
             GivenDirection("B", dirs), GivenDirection("C", np.array([1.0, 2.0]))]
    mech = free_chain(links, pos)
    sol = solve_given(mech, batch)
    assert len(sol) == N and sol.point("F").velocity.shape == (N, 2)
    for i in range(N):
        one = [GivenVelocity("A", batch[0].velocity[i]), GivenVelocity("D", batch[1].velocity[i]),
               GivenDirection("B", dirs[i]), GivenDirection("C", np.array([1.0, 2.0]))]
        ref, _ = reference(mech, one)
        for p in ("E", "F", "G", "B", "C"):
            assert np.allclose(sol.point(p).velocity[i], ref[p], atol=1e-10 * 9 * 100)


# ------------------------------------------------------------------ counting and singular positions
WATT_POS = {"A": [-90, -5], "C": [-40, 45], "D": [0, 0], "G": [50, 55], "E": [-45, -50],
            "F": [55, -40], "B": [100, 10]}


def test_too_few_conditions_say_how_many_more():
    mech = free_chain(WATT, WATT_POS, [GivenVelocity("A", [1.0, 2.0])])
    with pytest.raises(StructureError, match=r"under-determined: 2 more conditions needed.*4 degrees of freedom"):
        solve_given(mech)
    assert check_count(mech, [GivenVelocity("A", [1.0, 2.0]), GivenVelocity("B", [0.0, 1.0])]) == 4


def test_too_many_conditions_name_the_points():
    given = [GivenVelocity("A", [1.0, 2.0]), GivenVelocity("B", [0.0, 1.0]), GivenDirection("D", [1.0, 0.0])]
    with pytest.raises(StructureError, match=r"over-determined: 1 condition too many.*the direction of v_D.*(drop 1 condition)"):
        solve_given(free_chain(WATT, WATT_POS, given))


@pytest.mark.parametrize("vb,word", [([1.0, 5.0], "say 1 time what the others fix already"),
                                     ([0.0, 1.0], "contradict each other")])
def test_two_velocities_of_one_free_bar_repeat_or_contradict(vb, word):
    """A free bar AB (3 degrees of freedom) with v_A and v_B given: four conditions, one too many;
    consistent when the components along AB agree (projection theorem), else contradictory."""
    bar = hinge_chain("bar", {"A": [0.0, 0.0], "B": [50.0, 0.0]}, {"AB": ["A", "B"]})
    with pytest.raises(StructureError, match=rf"over-determined: 1 condition too many.*{word}"):
        solve_given(bar, [GivenVelocity("A", [1.0, 0.0]), GivenVelocity("B", vb)])


def test_triad_with_concurrent_binary_links_is_singular_and_says_about_which_point():
    """K on line AZ, L on line BZ, M on line CZ: with K, L, M held the ternary ABC can still
    turn about Z (its binary links turn about K, L, M)."""
    Z = np.array([35.0, 15.0])
    A, B, C = np.array([0.0, 0.0]), np.array([70.0, -5.0]), np.array([30.0, 50.0])
    pos = {"A": A, "B": B, "C": C, "K": A + 1.5 * (A - Z), "L": B + 1.2 * (B - Z), "M": C + (C - Z)}
    given = [GivenVelocity(p, v) for p, v in (("K", [1.0, 0.0]), ("L", [0.0, 2.0]), ("M", [1.0, 1.0]))]
    with pytest.raises(StructureError) as exc:
        solve_given(free_chain(TRIAD, pos, given))
    msg = str(exc.value)
    assert "singular at the drawn position" in msg
    assert all(f"velocity of {p}" in msg for p in "KLM")
    assert "ABC turns about (35, 15)" in msg
    # moved off the concurrency, the same data solve
    pos["M"] = pos["M"] + np.array([5.0, 0.0])
    assert solve_given(free_chain(TRIAD, pos, given)).status[0] == Status.OK


def test_a_batch_marks_its_singular_samples_only():
    """Directions of v_B varying per sample: the one for which the serial chain is singular
    (found from the second formulation: its square matrix's determinant is linear in the normal
    n of B's direction, det = n·w, so n ⟂ w makes it singular) has the status singular and NaN
    rates; the others are solved."""
    pos = {"A": [0, 0], "E": [45, 35], "B": [75, 70], "F": [105, 30], "C": [135, 75], "G": [160, 20],
           "D": [205, 45]}
    mech = free_chain(SERIAL, pos)
    rest = [GivenVelocity("A", [20.0, 30.0]), GivenVelocity("D", [-10.0, 35.0]),
            GivenDirection("C", [np.cos(2.0), np.sin(2.0)])]

    def det(n):  # the direction whose left normal is n
        A = reference_system(mech, rest + [GivenDirection("B", np.array([n[1], -n[0]]))])[0]
        return np.linalg.det(A)

    w = np.array([det([1.0, 0.0]), det([0.0, 1.0])])
    n_bad = np.array([-w[1], w[0]])
    dirs = np.array([[1.0, 0.2], [n_bad[1], -n_bad[0]], [0.3, 1.0]])
    sol = solve_given(mech, rest + [GivenDirection("B", dirs)])
    assert list(np.asarray(sol.status)) == [Status.OK, Status.SINGULAR, Status.OK]
    assert np.isnan(sol.point("F").velocity[1]).all() and np.isfinite(sol.point("F").velocity[[0, 2]]).all()
    with pytest.raises(StructureError, match="singular at the drawn position: .*direction of v_B"):
        solve_given(mech, rest + [GivenDirection("B", dirs[1])])


def test_accelerations_need_every_conditions_second_order_data():
    mech = free_chain(WATT, WATT_POS, [GivenVelocity("A", [1.0, 2.0]), GivenVelocity("B", [0.0, 1.0], [0.0, 0.0])])
    assert solve_given(mech).order == 1
    with pytest.raises(StructureError, match="the accelerations need the acceleration of A"):
        solve_given(mech, order=2)


def test_an_open_chain_on_its_frame_driven_by_a_point_velocity():
    """A two-link arm on the frame (O, A, B) with the velocity of its tip B given: the classical
    inverse velocity problem, v_B = ω₁·J(B − O) + (ω₂ − ω₁)·J(B − A)... written per link:
    v_A = ω₁·J(A − O), v_B = v_A + ω₂·J(B − A), two equations for ω₁, ω₂ solved here by
    Cramer's rule."""
    O, A, B = np.array([0.0, 0.0]), np.array([40.0, 30.0]), np.array([90.0, 10.0])
    mech = Mechanism.build(name="arm", points={"O": O, "A": A, "B": B},
                           links={"frame": ["O"], "upper": ["O", "A"], "fore": ["A", "B"]},
                           joints=[Revolute("O", "O", ("frame", "upper")), Revolute("A", "A", ("upper", "fore"))],
                           drivers=[], given=[GivenVelocity("B", [3.0, -4.0], [1.0, 0.5])])
    sol = solve_given(mech)
    J = lambda v: np.array([-v[1], v[0]])  # noqa: E731
    M = np.column_stack([J(A - O), J(B - A)])
    w1, w2 = np.linalg.solve(M, [3.0, -4.0])
    assert sol.link("upper").omega[0] == pytest.approx(w1, rel=1e-12)
    assert sol.link("fore").omega[0] == pytest.approx(w2, rel=1e-12)
    # accelerations: a_B = α₁·J(B − O) − ω₁²(A − O) + α₂·J(B − A) − ω₂²(B − A) ... with A's part
    rhs = np.array([1.0, 0.5]) + w1 ** 2 * (A - O) + w2 ** 2 * (B - A)
    a1, a2 = np.linalg.solve(M, rhs)
    assert sol.link("upper").alpha[0] == pytest.approx(a1, rel=1e-12)
    assert sol.link("fore").alpha[0] == pytest.approx(a2, rel=1e-12)


# ------------------------------------------------------------------ bad data
@pytest.mark.parametrize("given,match", [
    ([GivenVelocity("Z", [1.0, 0.0])], "given point 'Z' is not in"),
    ([GivenVelocity("A", [1.0, 0.0]), GivenDirection("A", [0.0, 1.0])], "given point 'A' is given twice"),
    ([GivenDirection("A", [0.0, 0.0])], "the direction is the zero vector"),
    ([GivenVelocity("A", [np.nan, 0.0])], "finite"),
    ([GivenVelocity("A", np.zeros((3, 2))), GivenVelocity("B", np.zeros((4, 2)))], "batches of different lengths"),
    ([GivenVelocity("A", [1.0, 0.0], link="BG")], "link 'BG' does not carry it"),
])
def test_bad_given_data_are_model_errors(given, match):
    with pytest.raises(ModelError, match=match):
        free_chain(WATT, WATT_POS, given)


def test_a_frame_point_cannot_be_given_and_drivers_exclude_given_data():
    mech = linkwork.load("library:crank-rocker")
    frame_pt = next(p for p in mech.link(mech.frame).points)
    with pytest.raises(ModelError, match="is a point of the frame"):
        solve_given(mech, [GivenVelocity(frame_pt, [1.0, 0.0])])
    with pytest.raises(ModelError, match=r"has drivers \(O2\) and given point velocities"):
        Mechanism.build(name=mech.name, points=dict(mech.points),
                        links={ln.name: list(ln.points) for ln in mech.links}, joints=list(mech.joints),
                        drivers=list(mech.drivers), frame=mech.frame,
                        given=[GivenVelocity("B", [1.0, 0.0])])


FILE = """
name = "free Watt chain"
[points]
A = [-90, -5]
C = [-40, 45]
D = [0, 0]
G = [50, 55]
E = [-45, -50]
F = [55, -40]
B = [100, 10]
[links]
CDG = ["C", "D", "G"]
DEF = ["D", "E", "F"]
AC  = ["A", "C"]
AE  = ["A", "E"]
BG  = ["B", "G"]
BF  = ["B", "F"]
[joints]
A = { type = "revolute", links = ["AC", "AE"] }
B = { type = "revolute", links = ["BG", "BF"] }
C = { type = "revolute", links = ["AC", "CDG"] }
D = { type = "revolute", links = ["CDG", "DEF"] }
E = { type = "revolute", links = ["AE", "DEF"] }
F = { type = "revolute", links = ["BF", "DEF"] }
G = { type = "revolute", links = ["BG", "CDG"] }
[[given]]
point = "A"
velocity = [40, 30]
[[given]]
point = "B"
GIVEN_B
"""


def test_the_file_section_builds_the_same_conditions():
    mech = linkwork.load_text(FILE.replace("GIVEN_B", "direction = 90\n[[given]]\npoint = \"D\"\ndirection = [1, 1]"))
    kinds = [(g.point, g.kind, g.link) for g in mech.given]
    assert kinds == [("A", "velocity", "AC"), ("B", "direction", "BG"), ("D", "direction", "CDG")]
    assert np.allclose(mech.given[1].direction, [0.0, 1.0], atol=1e-15)
    assert mech.frame == "frame" and mech.link("frame").points == ()
    assert solve_given(mech).status[0] == Status.OK


@pytest.mark.parametrize("text,match", [
    ("velocity = [1, 2]\ndirection = 30", "either `velocity`"),
    ("direction = 30\nacceleration = [0, 0]", "`acceleration` goes with `velocity`"),
    ("velocity = [1, 2]\ncurvature = 0.1", "`curvature` goes with `direction`"),
    ("velocity = [1, 2]\nlink = \"XY\"", "names link 'XY'"),
    ("velocity = [1, 2]\nlink = \"BG\"\n[driver]\njoint = \"A\"", "not both"),
])
def test_file_errors_name_the_key(text, match):
    with pytest.raises(MechanismFileError, match=match) as exc:
        linkwork.load_text(FILE.replace("GIVEN_B", text))
    assert "given" in str(exc.value) or "driver" in str(exc.value)


def test_a_file_without_driver_or_given_data_says_both_ways():
    text = FILE.split("[[given]]")[0].replace("[links]\n", "[links]\nframe = []\n")
    with pytest.raises(LinkworkError, match=r"no \[driver\] given.*\[\[given\]\]"):
        linkwork.load_text(text)


def test_library_triad_accelerations_from_a_second_solve():
    """Paper 4, Example III's data on paper 2's triad (library): the accelerations of K, L, M
    given. Second formulation: a_P − a_F = α·J(P − F) − ω²·(P − F) for the points of each link,
    with ω from the second velocity solve, and the given accelerations."""
    mech = linkwork.load("library:rosenauer-free-triad")
    sol = solve_given(mech)
    _, w = reference(mech, mech.given)
    A, b, col, acol = reference_system(mech, mech.given, omega=w)
    x = np.linalg.solve(A, b)
    scale = max(np.abs(x[:2 * len(col)]).max(), 1.0)
    for p, c in col.items():
        assert np.allclose(sol.point(p).acceleration[0], x[c:c + 2], atol=1e-10 * scale), p
    for ln, c in acol.items():
        assert sol.link(ln).alpha[0] == pytest.approx(x[c], abs=1e-10 * scale / mech.length_scale)


def test_five_bar_from_its_coupler_point_velocity_inverts_the_driven_solve():
    """The library's five-bar (two drivers) solved from the velocity and acceleration of its
    coupler hinge C instead: the cranks' ω and α are the ones the driven solve (group solvers
    from the drivers' laws) gives at that position."""
    mech = linkwork.load("library:five-bar")
    driven = linkwork.solve(mech, times=[0.0], order=2)
    C = driven.point("C")
    sol = solve_given(mech, [GivenVelocity("C", C.velocity[0], C.acceleration[0])])
    for ln in mech.moving_links:
        assert sol.link(ln).omega[0] == pytest.approx(driven.link(ln).omega[0], rel=1e-10, abs=1e-12)
        assert sol.link(ln).alpha[0] == pytest.approx(driven.link(ln).alpha[0], rel=1e-9, abs=1e-9)


def test_solve_of_a_chain_driven_by_given_velocities_says_which_solver_to_use():
    """`solve` takes driver inputs; a free chain has none and is sent to `solve_given` by name
    (not told that its links are "under-constrained")."""
    mech = linkwork.load("library:rosenauer-free-triad")
    with pytest.raises(InputError, match=r"given point velocities.*solve_given"):
        linkwork.solve(mech)
