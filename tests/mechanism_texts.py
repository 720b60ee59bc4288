"""Mechanism files shared by several test modules (TOML text for `linkwork.load_text`).

Each is a hand-made drawing; the numbers the tests assert about them come from the seeds or
from hand derivations in the tests themselves. The builders at the end write the hinged loops
(four-bar, five-bar) that many tests draw with small differences: other coordinates, names,
drivers; `mechanism_text` with `joint` writes any other mechanism (sliding pairs, slots, several
drivers). Texts whose exact spelling is under test (error messages naming a line) stay literal.
"""

import math

import numpy as np

TRIPLE_PARALLEL_CRANKS = """
name = "triple parallel cranks"
description = "Rosenauer's trijparallēlkloķu ķēde (Fig. 287): three equal parallel cranks"
[points]
O1 = [0, 0]
O2 = [20, 0]
O3 = [40, 0]
A1 = [5, 10]
A2 = [25, 10]
A3 = [45, 10]
[links]
frame = ["O1", "O2", "O3"]
c1 = ["O1", "A1"]
c2 = ["O2", "A2"]
c3 = ["O3", "A3"]
coupler = ["A1", "A2", "A3"]
[joints]
O1 = { type = "revolute", links = ["frame", "c1"] }
O2 = { type = "revolute", links = ["frame", "c2"] }
O3 = { type = "revolute", links = ["frame", "c3"] }
A1 = { type = "revolute", links = ["c1", "coupler"] }
A2 = { type = "revolute", links = ["c2", "coupler"] }
A3 = { type = "revolute", links = ["c3", "coupler"] }
[driver]
joint = "O1"
"""


SCOTCH_YOKE = """
name = "Scotch yoke"
[points]
O = [0, 0]
A = [10, 0]
Y = [10, 20]
[links]
frame = ["O"]
crank = ["O", "A"]
block = ["A"]
yoke  = ["Y"]
[joints]
O     = { type = "revolute", links = ["frame", "crank"] }
A     = { type = "revolute", links = ["crank", "block"] }
slot  = { type = "prismatic", links = ["yoke", "block"], axis = [0, 1], point = "A" }
guide = { type = "prismatic", links = ["frame", "yoke"], axis = [1, 0], point = "Y" }
[driver]
joint = "O"
"""


# ---------------------------------------------------------------------------- builders
def _num(v) -> str:
    return repr(v) if isinstance(v, int) else repr(float(v))


def _value(v) -> str:
    """A TOML value: a string quoted, a number as `_num` writes it, a list or pair bracketed."""
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (list, tuple)) or getattr(v, "ndim", 0) == 1:
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return _num(v)


def _drivers(driver, speed) -> str:
    """One `[driver]` table, or a `[[drivers]]` table per joint when `driver` is a tuple. A speed
    is a quoted quantity ("1 rad/s") or a bare number (in the file's units)."""
    def speed_line(s):
        return f"speed = {_value(s)}\n" if s is not None and s != "" else ""
    if isinstance(driver, str):
        return f'[driver]\njoint = "{driver}"\n' + speed_line(speed)
    speeds = speed if speed is not None else (None,) * len(driver)
    return "".join(f'[[drivers]]\njoint = "{j}"\n' + speed_line(s)
                   for j, s in zip(driver, speeds, strict=True))


def joint(name: str, kind: str, a: str, b: str, **fields) -> str:
    """One line of the [joints] table: the pair `kind` between links `a` and `b`, with further
    fields (`axis = [1, 0]`, `point = "A"`, `center = "O4"`) in the order given."""
    extra = "".join(f", {k} = {_value(v)}" for k, v in fields.items())
    return f'{name} = {{ type = "{kind}", links = ["{a}", "{b}"]{extra} }}'


def revolute(name: str, a: str, b: str) -> str:
    return joint(name, "revolute", a, b)


def _loop(hinges: dict, links: tuple) -> tuple[dict, dict]:
    """Links and joints of a closed hinge chain: `links[0]` is the frame, links[i] runs from the
    (i−1)-th hinge to the i-th, the frame from the first hinge to the last, and each hinge joins
    the link ending there to the next one."""
    h = list(hinges)
    if len(h) != len(links):
        raise ValueError("a hinged loop has as many hinges as links")
    pts = {links[0]: [h[0], h[-1]]} | {links[i]: [h[i - 1], h[i]] for i in range(1, len(h))}
    joints = {h[0]: revolute(h[0], links[0], links[1])}
    joints |= {h[i]: revolute(h[i], links[i], links[(i + 1) % len(h)]) for i in range(1, len(h))}
    return pts, joints


def mechanism_text(*, name: str, points: dict, links: dict, joints, driver, speed=None,
                   units: str | None = None, description: str | None = None) -> str:
    """A mechanism file from its parts: `points` name → (x, y), `links` name → point names (the
    first link is the frame, named in the file unless it is called `frame`), `joints` the lines
    of the [joints] table (see `joint`), `driver` a joint or a tuple of joints (then `speed` a
    tuple too)."""
    frame = next(iter(links))
    return (f'\nname = "{name}"\n'
            + (f'description = "{description}"\n' if description else "")
            + (f'units = {{ length = "{units}" }}\n' if units else "")
            + (f'frame = "{frame}"\n' if frame != "frame" else "")
            + "[points]\n" + "".join(f"{p} = [{_num(x)}, {_num(y)}]\n" for p, (x, y) in points.items())
            + "[links]\n" + "".join(f"{k} = {list(v)}\n".replace("'", '"') for k, v in links.items())
            + "[joints]\n" + "".join(f"{j}\n" for j in joints)
            + _drivers(driver, speed))


def hinged_loop_text(*, name: str, hinges: dict, links: tuple, driver, speed=None,
                     units: str | None = None, link_points: dict | None = None) -> str:
    """A closed chain of links hinged one to the next (see `_loop`), `hinges` name → (x, y) in
    the loop's order; `link_points` gives some links their points in another order."""
    pts, joints = _loop(hinges, links)
    return mechanism_text(name=name, points=hinges, links=pts | (link_points or {}),
                          joints=joints.values(), driver=driver, speed=speed, units=units)


def four_bar_text(*, name: str = "four-bar", O2=(0, 0), A=(0, 10), B=(30, 30), O4=(40, 0),
                  links=("frame", "crank", "coupler", "rocker"), rocker_points=("B", "O4"),
                  coupler_points: dict | None = None, curved_slot: bool = False,
                  driver="O2", speed=None, units: str | None = None) -> str:
    """The four-bar frame O2–O4, crank O2–A, coupler A–B (plus `coupler_points` name → (x, y)),
    rocker B–O4 (its points in the order `rocker_points`), all hinged, driven at `driver`.

    With `curved_slot` the rocker is left out and B is a block in a circular slot of the frame
    about O4 (Rosenauer §4, Fig. 30): the same path for B, three links."""
    frame, crank, coupler, rocker = links
    cp = dict(coupler_points or {})
    pts, joints = _loop({"O2": O2, "A": A, "B": B, "O4": O4}, links)
    pts[coupler] += list(cp)
    pts[rocker] = list(rocker_points)
    if curved_slot:
        del pts[rocker], joints["O4"]
        joints["B"] = joint("B", "circular-slot", frame, coupler, center="O4")
    return mechanism_text(name=name, points={"O2": O2, "A": A, "B": B, "O4": O4} | cp,
                          links=pts, joints=joints.values(), driver=driver, speed=speed,
                          units=units)


def five_bar_text(*, name: str = "five-bar", O2=(0, 0), A=(0, 10), B=(30, 30), O4=(40, 0),
                  O5=(50, -10), driver="O2", speed=None, units: str | None = None) -> str:
    """The hinged pentagon: the four-bar of `four_bar_text` with its rocker B–O4 hinged to a
    lever O4–O5 instead of to the frame, which runs O2–O5. Two freedoms (001c §86)."""
    return hinged_loop_text(name=name, hinges={"O2": O2, "A": A, "B": B, "O4": O4, "O5": O5},
                            links=("frame", "crank", "coupler", "rocker", "lever"),
                            driver=driver, speed=speed, units=units)


def four_bar_from_lengths(d, a, b, c, phi_deg, name="four-bar", driver="O2",
                          links=("frame", "input", "coupler", "output"), speed=None) -> str:
    """A four-bar file from its lengths: frame O2 (0,0)–O4 (d,0), input O2A of length a at φ
    (degrees), coupler AB = b, output O4B = c, B above the line A O4 (to the left of A→O4)."""
    phi = math.radians(phi_deg)
    A = np.array([a * math.cos(phi), a * math.sin(phi)])
    O4 = np.array([d, 0.0])
    D = np.hypot(*(O4 - A))
    x = (b * b - c * c + D * D) / (2 * D)
    h = math.sqrt(b * b - x * x)
    ex = (O4 - A) / D
    B = A + x * ex + h * np.array([-ex[1], ex[0]])
    return four_bar_text(name=name, A=A, B=B, O4=(float(d), 0), driver=driver, links=links,
                         speed=speed)


def slider_crank_text(*, name: str, A, B, O=(0, 0), slot: bool = False, pivot: str = "O",
                      block: str = "block", driver: str | None = None, speed=None,
                      units: str | None = None) -> str:
    """Crank `pivot`–A on the frame, rod A–B, B guided along the x-axis direction: the rod's
    pin in a slot of the frame (`slot`), or hinged to `block` on a prismatic guide."""
    links = {"frame": [pivot], "crank": [pivot, "A"], "rod": ["A", "B"]}
    joints = [revolute(pivot, "frame", "crank"), revolute("A", "crank", "rod")]
    if slot:
        joints.append(joint("B", "slot", "frame", "rod", axis=[1, 0]))
    else:
        links[block] = ["B"]
        joints += [revolute("B", "rod", block),
                   joint("guide", "prismatic", "frame", block, axis=[1, 0], point="B")]
    return mechanism_text(name=name, points={pivot: O, "A": A, "B": B}, links=links,
                          joints=joints, driver=driver or pivot, speed=speed, units=units)


def two_crank_five_bar_text(*, units: str | None = None) -> str:
    """Two cranks on the frame, O2 (|O2A| = 10) and O5 (|O5B| = 15), joined by the dyad A–P–B:
    two freedoms (3·4 − 2·5), both driven, O2 at 2 rad/s and O5 at −1 rad/s."""
    return hinged_loop_text(
        name="five-bar with two cranks",
        hinges={"O2": (0, 0), "A": (0, 10), "P": (20, 30), "B": (40, 15), "O5": (40, 0)},
        links=("frame", "crank2", "left", "right", "crank5"),
        link_points={"right": ["B", "P"], "crank5": ["O5", "B"]},
        driver=("O2", "O5"), speed=("2 rad/s", "-1 rad/s"), units=units)
