"""Test mechanisms for `linkwork.instant`, written as mechanism-file text (`load_text`).

Each builder places the design drawing from the classical dimensions, so that closed forms
(ellipsograph, antiparallelogram, rolling wheel, swinging block, …) can be stated for it.
"""

from __future__ import annotations

import numpy as np

import linkwork
from mechanism_texts import joint, mechanism_text, revolute, slider_crank_text


def _pts(points: dict) -> str:
    return "\n".join(f"{k} = [{float(v[0])!r}, {float(v[1])!r}]" for k, v in points.items())


def load(text: str):
    return linkwork.load_text(text)


def four_bar_from_points(O2, A, B, O4, C=None, *, names=("frame", "crank", "coupler", "rocker")) -> str:
    f, c, k, r = names
    pts = {"O2": O2, "A": A, "B": B, "O4": O4}
    cpl = '"A", "B"'
    if C is not None:
        pts["C"] = C
        cpl += ', "C"'
    return f"""
name = "four-bar"
units = {{ length = "mm" }}
frame = "{f}"
[points]
{_pts(pts)}
[links]
{f} = ["O2", "O4"]
{c} = ["O2", "A"]
{k} = [{cpl}]
{r} = ["B", "O4"]
[joints]
O2 = {{ type = "revolute", links = ["{f}", "{c}"] }}
A = {{ type = "revolute", links = ["{c}", "{k}"] }}
B = {{ type = "revolute", links = ["{k}", "{r}"] }}
O4 = {{ type = "revolute", links = ["{r}", "{f}"] }}
[driver]
joint = "O2"
reference = "A"
"""


def four_bar(ground: float, crank: float, coupler: float, rocker: float, theta: float,
             upper: bool = True, point=None) -> tuple[str, dict]:
    """Four-bar with pivots O2 = (0, 0), O4 = (ground, 0) at crank angle theta; `point` =
    (along, across) places a coupler point C = A + along·û + across·û⊥ (û: A → B)."""
    O2, O4 = np.zeros(2), np.array([ground, 0.0])
    A = crank * np.array([np.cos(theta), np.sin(theta)])
    d = O4 - A
    dist = np.hypot(*d)
    a = (coupler ** 2 - rocker ** 2 + dist ** 2) / (2 * dist)
    h = np.sqrt(coupler ** 2 - a ** 2)
    ex = d / dist
    B = A + a * ex + (1 if upper else -1) * h * np.array([-ex[1], ex[0]])
    C = None
    if point is not None:
        u = (B - A) / np.hypot(*(B - A))
        C = A + point[0] * u + point[1] * np.array([-u[1], u[0]])
    return four_bar_from_points(O2, A, B, O4, C), {"O2": O2, "A": A, "B": B, "O4": O4, "C": C}


def slider_crank(r: float, l: float, offset: float, theta: float, *, slot: bool = False) -> str:
    """Slider-crank: crank r about C1 = (0, 0), rod l, rod end B on the line y = offset
    (a block on a prismatic guide, or with `slot` the rod's pin in a straight slot)."""
    A = r * np.array([np.cos(theta), np.sin(theta)])
    B = np.array([A[0] + np.sqrt(l ** 2 - (offset - A[1]) ** 2), offset])
    return slider_crank_text(name="slider-crank (slot)" if slot else "slider-crank",
                             O=(0.0, 0.0), A=A, B=B, slot=slot, pivot="C1", block="slider")


def swinging_block(r: float, pivot, theta: float, *, slot: bool = False) -> str:
    """Swinging block (Pöschl's Kurbelschwinge): crank r about O = (0, 0); the rod, hinged at
    the crank pin A, slides through a sleeve pivoted at the fixed point B = `pivot` (with
    `slot`: the rod passes the frame's pin B, the sleeve folded into a slot pair). The rod
    carries the point R, its point at B in the design position, and E beyond B."""
    A = r * np.array([np.cos(theta), np.sin(theta)])
    B = np.asarray(pivot, dtype=float)
    u = (B - A) / np.hypot(*(B - A))
    E = B + 0.5 * np.hypot(*(B - A)) * u
    links = {"frame": ["O", "B"], "crank": ["O", "A"], "rod": ["A", "R", "E"]}
    joints = [revolute("O", "frame", "crank"), revolute("A", "crank", "rod")]
    if slot:
        joints.append(joint("B", "slot", "rod", "frame", axis=u))
    else:
        links["sleeve"] = ["B"]
        joints += [revolute("B", "frame", "sleeve"),
                   joint("slide", "prismatic", "sleeve", "rod", axis=u, point="R")]
    return mechanism_text(name="swinging block (slot)" if slot else "swinging block",
                          points={"O": (0.0, 0.0), "A": A, "B": B, "R": B, "E": E}, links=links,
                          joints=joints, driver="O")


def slotted_lever(r: float, pivot, theta: float, *, slot: bool = True) -> str:
    """Crank-slotted lever (*Kurbelschleife*): crank r about C = (0, 0) drives the lever
    pivoted at B = `pivot` through the crank pin A sliding in the lever's slot (`slot`), or
    through a block hinged at A sliding on the lever (prismatic)."""
    A = r * np.array([np.cos(theta), np.sin(theta)])
    B = np.asarray(pivot, dtype=float)
    u = (A - B) / np.hypot(*(A - B))
    T = B + 1.5 * np.hypot(*(A - B)) * u
    links = {"frame": ["C", "B"], "crank": ["C", "A"]}
    joints = [revolute("C", "frame", "crank")]
    if slot:
        links["lever"] = ["B", "T"]
        joints += [revolute("B", "frame", "lever"), joint("A", "slot", "lever", "crank", axis=u)]
    else:
        links |= {"block": ["A"], "lever": ["B", "T"]}
        joints += [revolute("A", "crank", "block"), revolute("B", "frame", "lever"),
                   joint("slide", "prismatic", "lever", "block", axis=u, point="A")]
    return mechanism_text(name="crank-slotted lever (slot)" if slot else "crank-slotted lever (block)",
                          points={"C": (0.0, 0.0), "A": A, "B": B, "T": T}, links=links,
                          joints=joints, driver="C")


def ellipsograph(l: float, phi: float, point_fraction: float = 0.25) -> str:
    """Trammel: block A on the x-axis, block B on the y-axis, rod AB = l at angle phi; the rod
    carries D at `point_fraction` of the way from A to B and its midpoint M. Driven by the
    rod's angle in its pin A (block A does not turn)."""
    A = np.array([l * np.cos(phi), 0.0])
    B = np.array([0.0, l * np.sin(phi)])
    D = A + point_fraction * (B - A)
    return f"""
name = "ellipsograph"
[points]
{_pts({"O": (0, 0), "A": A, "B": B, "D": D, "M": (A + B) / 2})}
[links]
frame = ["O"]
block_a = ["A"]
block_b = ["B"]
rod = ["A", "B", "D", "M"]
[joints]
guide_a = {{ type = "prismatic", links = ["frame", "block_a"], axis = [1, 0], point = "A" }}
guide_b = {{ type = "prismatic", links = ["frame", "block_b"], axis = [0, 1], point = "B" }}
A = {{ type = "revolute", links = ["block_a", "rod"] }}
B = {{ type = "revolute", links = ["rod", "block_b"] }}
[driver]
joint = "A"
reference = "B"
"""


def antiparallelogram(a: float, c: float, t: float) -> tuple[str, dict]:
    """Crossed four-bar CD = AB = 2c (frame CD, coupler AB), CB = AD = 2a (cranks), built
    from the pole P = (a cos t, b sin t) on the ellipse with foci C, D (a > c) or the
    hyperbola branch (a < c): B on the ray C→P, A on the ray D→P."""
    C, D = np.array([-c, 0.0]), np.array([c, 0.0])
    if a > c:
        b = np.sqrt(a * a - c * c)
        P = np.array([a * np.cos(t), b * np.sin(t)])
    else:
        b = np.sqrt(c * c - a * a)
        P = np.array([a * np.cosh(t), b * np.sinh(t)])
    B = C + 2 * a * (P - C) / np.hypot(*(P - C))
    A = D + 2 * a * (P - D) / np.hypot(*(P - D))
    if a < c:  # |PC| − |PD| = 2a: one crank points away from its pivot through P
        B = C + 2 * a * (P - C) / np.hypot(*(P - C))
        A = D - 2 * a * (P - D) / np.hypot(*(P - D))
    text = f"""
name = "antiparallelogram"
[points]
{_pts({"C": C, "D": D, "A": A, "B": B})}
[links]
frame = ["C", "D"]
crank = ["C", "B"]
coupler = ["A", "B"]
rocker = ["A", "D"]
[joints]
C = {{ type = "revolute", links = ["frame", "crank"] }}
B = {{ type = "revolute", links = ["crank", "coupler"] }}
A = {{ type = "revolute", links = ["coupler", "rocker"] }}
D = {{ type = "revolute", links = ["rocker", "frame"] }}
[driver]
joint = "C"
reference = "B"
"""
    return text, {"C": C, "D": D, "A": A, "B": B, "P": P}


def rolling_wheel(r: float) -> str:
    """A wheel of radius r rolling on the frame's line y = 0: its axle (a block on a
    horizontal guide) is driven along the line; wheel and frame are a rack-and-pinion pair
    with the axle as carrier. The wheel carries its centre O, a rim point A (at the contact
    point in the design position) and a point K inside."""
    return f"""
name = "rolling wheel"
[points]
{_pts({"O": (0, r), "G": (0, 0), "A": (0, 0), "K": (0.5 * r, 1.3 * r), "Q": (0.7 * r, 0.9 * r)})}
[links]
frame = ["G"]
axle = ["O"]
wheel = ["O", "A", "K", "Q"]
[joints]
guide = {{ type = "prismatic", links = ["frame", "axle"], axis = [1, 0], point = "O" }}
O = {{ type = "revolute", links = ["axle", "wheel"] }}
roll = {{ type = "gear", links = ["wheel", "frame"], carrier = "axle", radii = [{r!r}], kind = "rack", point = "G" }}
[driver]
joint = "guide"
speed = 1
"""


def planetary(r_sun: float, r_planet: float) -> str:
    """A planet wheel rolling outside the fixed sun wheel (the frame), pivoted on the arm."""
    d = r_sun + r_planet
    return f"""
name = "planet on a fixed sun"
[points]
{_pts({"S": (0, 0), "O": (d, 0), "K": (d + 0.5 * r_planet, 0.4 * r_planet)})}
[links]
frame = ["S"]
arm = ["S", "O"]
planet = ["O", "K"]
[joints]
S = {{ type = "revolute", links = ["frame", "arm"] }}
O = {{ type = "revolute", links = ["arm", "planet"] }}
mesh = {{ type = "gear", links = ["frame", "planet"], carrier = "arm", radii = [{r_sun!r}, {r_planet!r}] }}
[driver]
joint = "S"
"""


def six_link(joints: dict[str, tuple], links: dict[str, list[str]], frame: str, driver: str,
             extra: str = "", rng=None) -> str:
    """A hinge chain from named joint points: joints {name: (x, y, link_a, link_b)}; with `rng`
    every point is moved at random by up to ±0.6 in x and y (a random member of the family)."""
    shake = (lambda: rng.uniform(-0.6, 0.6, 2)) if rng is not None else (lambda: np.zeros(2))
    pts = {k: np.array(v[:2], dtype=float) + shake() for k, v in joints.items()}
    jl = "\n".join(f'{k} = {{ type = "revolute", links = ["{v[2]}", "{v[3]}"] }}' for k, v in joints.items())
    ll = "\n".join(f'{k} = [{", ".join(repr(p) for p in ps)}]'.replace("'", '"') for k, ps in links.items())
    return f"""
name = "chain"
frame = "{frame}"
[points]
{_pts(pts)}
[links]
{ll}
[joints]
{jl}
{extra}
[driver]
joint = "{driver}"
"""


def watt(rng=None) -> str:
    """Watt chain with Rosenauer's numbering (§91): joints 12, 23, 34, 45, 56, 16, 25; link 6
    is the frame, link 1 is driven at 16."""
    j = {"J16": (0, 0, "l1", "l6"), "J56": (10, 0, "l5", "l6"), "J12": (2, 3, "l1", "l2"),
         "J25": (7, 5, "l2", "l5"), "J23": (4, 8, "l2", "l3"), "J34": (8, 11, "l3", "l4"),
         "J45": (11, 6, "l4", "l5")}
    links = {"l1": ["J16", "J12"], "l2": ["J12", "J23", "J25"], "l3": ["J23", "J34"],
             "l4": ["J34", "J45"], "l5": ["J45", "J56", "J25"], "l6": ["J16", "J56"]}
    return six_link(j, links, "l6", "J16", rng=rng)


def stephenson(rng=None) -> str:
    """Stephenson chain as reconstructed for Rosenauer §92: joints 12, 23, 34, 15, 45, 16, 46,
    ternary links 1 and 4; link 6 is the frame, link 1 driven at 16."""
    j = {"J16": (0, 0, "l1", "l6"), "J46": (10, 0, "l4", "l6"), "J15": (3, 4, "l1", "l5"),
         "J45": (9, 5, "l4", "l5"), "J12": (0.5, 3, "l1", "l2"), "J23": (3, 9, "l2", "l3"),
         "J34": (8, 8, "l3", "l4")}
    links = {"l1": ["J16", "J12", "J15"], "l2": ["J12", "J23"], "l3": ["J23", "J34"],
             "l4": ["J34", "J45", "J46"], "l5": ["J15", "J45"], "l6": ["J16", "J46"]}
    return six_link(j, links, "l6", "J16", rng=rng)


def rosenkranz(rng=None) -> str:
    """Pöschl's Beispiel 16 (Rosenkranz indicator) topology: joints 16, 12, 24, 23, 45, 36 and
    the slider 56 (a block on a guide of the frame)."""
    j = {"J16": (0, 0, "l1", "l6"), "J36": (8, 0, "l3", "l6"), "J12": (1, 3, "l1", "l2"),
         "J23": (7, 5, "l2", "l3"), "J24": (4, 7, "l2", "l4"), "J45": (9, 10, "l4", "l5")}
    links = {"l1": ["J16", "J12"], "l2": ["J12", "J23", "J24"], "l3": ["J23", "J36"],
             "l4": ["J24", "J45"], "l5": ["J45"], "l6": ["J16", "J36"]}
    extra = 'J56 = { type = "prismatic", links = ["l6", "l5"], axis = [1, 0.2], point = "J45" }'
    return six_link(j, links, "l6", "J16", extra, rng=rng)


def no_four_bar_loops() -> str:
    """Rosenauer 1937 / Alt 1937: the 8-link hinge chain whose three loops are all pentagons
    (frame 8 = {C, O1, O2}, driver 1 = {C, A, B}, 2 = AD, 3 = O1E, 4 = DEF, 5 = FGH,
    6 = BG, 7 = O2H)."""
    j = {"C": (0, 0, "l1", "l8"), "A": (2, 1, "l1", "l2"), "B": (-2, 1.5, "l1", "l6"),
         "D": (4, 6, "l2", "l4"), "O1": (9, 0, "l3", "l8"), "E": (8.5, 5, "l3", "l4"),
         "F": (3, 10, "l4", "l5"), "G": (-3, 8, "l5", "l6"), "O2": (-9, 0, "l7", "l8"),
         "H": (-7.5, 6, "l5", "l7")}
    links = {"l1": ["C", "A", "B"], "l2": ["A", "D"], "l3": ["O1", "E"], "l4": ["D", "E", "F"],
             "l5": ["F", "G", "H"], "l6": ["B", "G"], "l7": ["O2", "H"], "l8": ["C", "O1", "O2"]}
    return six_link(j, links, "l8", "C")


def parallelogram(theta: float) -> str:
    A = 3 * np.array([np.cos(theta), np.sin(theta)])
    return four_bar_from_points((0, 0), A, A + (7, 0), (7, 0))


# ---------------------------------------------------------------------------- checks
def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def perp(v):
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def relative_kinematics(sol, link, relative_to, xy):
    """Velocity and acceleration relative to `relative_to` of the points of `link` at frame
    positions xy (N, 2), from the engine's absolute motions by the theorem of relative motion
    (Coriolis): a_rel = a_i − a_j − 2 ω_j J v_rel (Rosenauer §72, eq. 40)."""
    pi = sol.point_on(link, sol.local(link, xy))
    pj = sol.point_on(relative_to, sol.local(relative_to, xy))
    wj = sol.link(relative_to).omega
    v = pi.velocity - pj.velocity
    a = pi.acceleration - pj.acceleration - 2 * wj[:, None] * perp(v)
    return v, a


def osculating_centre(positions_fn, u, h):
    """Centre of the circle through three path points at u − h, u, u + h, Richardson-
    extrapolated from steps h and h/2 (an independent estimate of the osculating circle)."""
    def through(hh):
        p, q, r = positions_fn(u - hh), positions_fn(u), positions_fn(u + hh)
        b, c = q - p, r - p
        d = 2 * cross(b, c)
        uc = ((c * c).sum(-1)[:, None] * perp(b) - (b * b).sum(-1)[:, None] * perp(c)) / d[:, None]
        return p + uc
    return (4 * through(h / 2) - through(h)) / 3


def cardan(r: float) -> str:
    """A planet of radius r rolling inside a fixed ring of radius 2r (Cardan circles), pivoted
    on the arm at the ring's centre S; the planet carries its pitch point T and a point K."""
    return f"""
name = "Cardan circles"
[points]
{_pts({"S": (0, 0), "O": (r, 0), "T": (2 * r, 0), "K": (1.5 * r, 0.3 * r)})}
[links]
frame = ["S"]
arm = ["S", "O"]
planet = ["O", "T", "K"]
[joints]
S = {{ type = "revolute", links = ["frame", "arm"] }}
O = {{ type = "revolute", links = ["arm", "planet"] }}
mesh = {{ type = "gear", links = ["frame", "planet"], carrier = "arm", radii = [{2 * r!r}, {r!r}], kind = "internal" }}
[driver]
joint = "S"
"""


def circular_slot_four_bar() -> str:
    """The crank pin A runs in a circular slot of the rocker, centred at the rocker's point K
    (kinematically the four-bar O2-A-K-O4)."""
    return f"""
name = "crank in a curved slot"
[points]
{_pts({"O2": (0, 0), "A": (1.0, 1.2), "K": (3.5, 3.0), "O4": (5.0, 0.0)})}
[links]
frame = ["O2", "O4"]
crank = ["O2", "A"]
rocker = ["O4", "K"]
[joints]
O2 = {{ type = "revolute", links = ["frame", "crank"] }}
O4 = {{ type = "revolute", links = ["rocker", "frame"] }}
A = {{ type = "circular-slot", links = ["rocker", "crank"], center = "K" }}
[driver]
joint = "O2"
"""



def four_bar_with_driven_arm() -> str:
    """Four-bar O2 A B O4 with an arm BG hinged at B, where coupler, rocker and arm share the
    hinge, driven by a second input at B2 (arm against rocker). The three-pole theorem gives the
    pole of the arm relative to frame or crank only one line (every line to it runs through B),
    so those two poles depend on the second input's speed."""
    text = four_bar_from_points((0, 0), (0, 10), (30, 30), (40, 0))
    for old, new in (('O4 = [', 'G = [45.0, 50.0]\nO4 = ['),
                     ('rocker = ["B", "O4"]\n', 'rocker = ["B", "O4"]\narm = ["B", "G"]\n'),
                     ('[driver]\njoint = "O2"\nreference = "A"\n',
                      'B2 = { type = "revolute", links = ["rocker", "arm"], point = "B" }\n'
                      '[[drivers]]\njoint = "O2"\n[[drivers]]\njoint = "B2"\n')):
        assert old in text, old
        text = text.replace(old, new)
    return text
