"""Mechanism files shared by several test modules (TOML text for `linkwork.load_text`).

Each is a hand-made drawing; the numbers the tests assert about them come from the seeds or
from hand derivations in the tests themselves. The builders at the end write the hinged loops
(four-bar, five-bar) that many tests draw with small differences: other coordinates, names,
drivers. Texts whose exact spelling is under test (error messages naming a line) stay literal.
"""

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


def _drivers(driver, speed) -> str:
    """One `[driver]` table, or a `[[drivers]]` table per joint when `driver` is a tuple."""
    if isinstance(driver, str):
        return f'[driver]\njoint = "{driver}"\n' + (f'speed = "{speed}"\n' if speed else "")
    speeds = speed if speed is not None else (None,) * len(driver)
    return "".join(f'[[drivers]]\njoint = "{j}"\n' + (f'speed = "{s}"\n' if s else "")
                   for j, s in zip(driver, speeds, strict=True))


def _revolute(name: str, a: str, b: str) -> str:
    return f'{name} = {{ type = "revolute", links = ["{a}", "{b}"] }}'


def _loop(hinges: dict, links: tuple) -> tuple[dict, dict]:
    """Links and joints of a closed hinge chain: `links[0]` is the frame, links[i] runs from the
    (i−1)-th hinge to the i-th, the frame from the first hinge to the last, and each hinge joins
    the link ending there to the next one."""
    h = list(hinges)
    if len(h) != len(links):
        raise ValueError("a hinged loop has as many hinges as links")
    pts = {links[0]: [h[0], h[-1]]} | {links[i]: [h[i - 1], h[i]] for i in range(1, len(h))}
    joints = {h[0]: _revolute(h[0], links[0], links[1])}
    joints |= {h[i]: _revolute(h[i], links[i], links[(i + 1) % len(h)]) for i in range(1, len(h))}
    return pts, joints


def mechanism_text(*, name: str, points: dict, links: dict, joints, driver, speed=None,
                   units: str | None = None) -> str:
    """A mechanism file from its parts: `points` name → (x, y), `links` name → point names (the
    first link is the frame, named in the file unless it is called `frame`), `joints` the lines
    of the [joints] table, `driver` a joint or a tuple of joints (then `speed` a tuple too)."""
    frame = next(iter(links))
    return (f'\nname = "{name}"\n'
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
        joints["B"] = (f'B = {{ type = "circular-slot", links = ["{frame}", "{coupler}"], '
                       'center = "O4" }')
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
