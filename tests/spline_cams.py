"""Random smooth disc cams (closed quintic splines through seeded random points around a circle)
with roller, knife, flat-face and oscillating followers, and a pair of elliptical gears, built in
Python for the tests of the equivalent linkage, Euler–Savary through contact and the finite
difference checks. Every design drawing is placed from the profile's own geometry (the follower
touches the cam at its highest point), so the builders need nothing from the engine."""

from __future__ import annotations

import numpy as np

from linkwork.geometry.profiles import EllipseProfile, SplineProfile, curvature
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute, RollingContact

R0 = 40.0      # mean radius of the random cams
RHO = 6.0      # roller radius


def spline_cam(seed: int, *, points: int = 9, bump: float = 2.0, convex: bool = False) -> SplineProfile:
    """A closed quintic spline through `points` points at jittered angles around the origin,
    radii R0 ± `bump` (seeded). `convex`: redrawn (next seeds) until the curvature is positive all
    round, as a flat face needs; otherwise until no concave piece is sharper than the roller."""
    rng = np.random.default_rng(seed)
    while True:
        phi = (np.arange(points) + rng.uniform(-0.25, 0.25, points)) * 2 * np.pi / points
        r = R0 + rng.uniform(-bump, bump, points)
        prof = SplineProfile(np.column_stack([r * np.cos(phi), r * np.sin(phi)]), closed=True)
        u = np.linspace(*prof.domain, 4000, endpoint=False)
        k = curvature(prof, u)
        if (k > 0).all() if convex else (k > -0.5 / RHO).all():
            return prof


def top(prof) -> float:
    """Parameter of the profile's highest point (where its tangent is horizontal)."""
    u = np.linspace(*prof.domain, 4000, endpoint=False)
    u0 = float(u[np.argmax(prof.derivatives(u, 0)[0][:, 1])])
    for _ in range(50):  # Newton on y′(u) = 0
        d = prof.derivatives(np.array(u0), 2)
        step = d[1][1] / d[2][1]
        u0 -= step
        if abs(step) < 1e-15 * prof.domain[1]:
            break
    return u0


def cam_mechanism(prof, follower: str, *, arm: float | None = None) -> Mechanism:
    """The cam `prof` turning about O = (0, 0) (driver), a follower touching it at its highest
    point: 'roller' (radius RHO) or 'knife' on a follower translating vertically, 'flat' (a
    horizontal face on a translating follower), or 'rocker' (a roller on a lever of length
    `arm` pivoted at B0, to the right of the roller)."""
    d = prof.derivatives(np.array(top(prof)), 1)
    X = d[0]
    n = np.array([-d[1][1], d[1][0]])
    n = n / np.hypot(*n) * (1.0 if n[1] > 0 else -1.0)  # up, away from the cam
    rho = RHO if follower in ("roller", "rocker") else 0.0
    C = X + rho * n
    pts = {"O": [0.0, 0.0], "A": [10.0, 0.0], "C": C}
    links = {"frame": ["O"], "cam": ["O", "A"]}
    joints = [Revolute("O", "O", ("frame", "cam"))]
    kind = "roller" if follower == "rocker" else follower
    if follower == "rocker":
        B0 = C + (arm or 35.0) * np.array([np.cos(0.4), np.sin(0.4)])
        pts["B0"] = B0
        links["frame"].append("B0")
        links["follower"] = ["C", "B0"]
        joints.append(Revolute("B0", "B0", ("frame", "follower")))
    else:
        pts["F"] = C + [0.0, 20.0]
        links["follower"] = ["C", "F"]
        joints.append(Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])))
    joints.append(CamContact("K", ("cam", "follower"), "cam", kind, point="C", radius=rho,
                             axis=np.array([1.0, 0.0]) if follower == "flat" else None))
    return Mechanism.build(name=f"spline cam, {follower}", points=pts, links=links, joints=joints,
                           drivers=[{"joint": "O", "reference": "A"}], profiles={"cam": prof})


ELL_A, ELL_B = 30.0, 20.0


def elliptical_gears(phi: float = np.radians(60.0)) -> Mechanism:
    """Two equal ellipses (semi-axes a, b), each turning about a focus, the foci O1, O2 2a apart:
    they stay in contact on O1O2 and roll on each other without slip (the classical elliptical
    gears, Pöschl §46). The first is drawn turned by `phi` (its centre at c·(cos φ, sin φ)); the
    second is its mirror image in the common tangent at the contact X on O1O2 (the mirror of the
    first's other focus is O2, as |XO1| + |XF′| = 2a). Both wheels are pivoted, so the contact
    alone (a cam pair of two profiles) keeps them rolling. At φ = 0 or π the common normal would
    run through both pivots, where the contact leaves the speed ratio undetermined."""
    a, b = ELL_A, ELL_B
    c = np.sqrt(a * a - b * b)
    e, p = c / a, b * b / a
    d = np.array([np.cos(phi), np.sin(phi)])
    X = np.array([p / (1.0 - e * np.cos(phi)), 0.0])  # focal radius towards +x
    e1 = EllipseProfile(tuple(c * d), (a, b), phi)
    u = float(e1.nearest(X))
    t = e1.derivatives(np.array(u), 1)[1]
    t = t / np.hypot(*t)

    def mirror(q):
        q = np.asarray(q) - X
        return X + 2 * (q @ t) * t - q

    tau = np.arctan2(t[1], t[0])
    centre2 = mirror(c * d)
    return Mechanism.build(
        name="elliptical gears",
        points={"O1": [0.0, 0.0], "A1": c * d, "O2": [2 * a, 0.0], "A2": centre2},
        links={"frame": ["O1", "O2"], "driver": ["O1", "A1"], "driven": ["O2", "A2"]},
        joints=[Revolute("O1", "O1", ("frame", "driver")), Revolute("O2", "O2", ("frame", "driven")),
                CamContact("T", ("driver", "driven"), "e1", "profile", mate="e2")],
        drivers=[{"joint": "O1"}],
        profiles={"e1": e1, "e2": EllipseProfile(tuple(centre2), (a, b), 2 * tau - phi)})


ROLL_E1, ROLL_E2, ROLL_O2, ROLL_CRANK = (40.0, 25.0), (15.0, 10.0), np.array([60.0, 0.0]), 15.0


def rolling_ellipses() -> Mechanism:
    """An ellipse (semi-axes ROLL_E2) rolling without slip on a fixed ellipse (ROLL_E1, centred
    at O), touching it on top in the drawing; its centre W is led by a rod from a crank O2A."""
    (a1, b1), (a2, b2) = ROLL_E1, ROLL_E2
    W = np.array([0.0, b1 + b2])
    A = ROLL_O2 + ROLL_CRANK * np.array([np.cos(np.radians(120.0)), np.sin(np.radians(120.0))])
    return Mechanism.build(
        name="rolling ellipses",
        points={"O": [0.0, 0.0], "O2": ROLL_O2, "A": A, "W": W, "M": W + [a2, 0.0]},
        links={"frame": ["O", "O2"], "crank": ["O2", "A"], "rod": ["A", "W"], "wheel": ["W", "M"]},
        joints=[Revolute("O2", "O2", ("frame", "crank")), Revolute("A", "A", ("crank", "rod")),
                Revolute("W", "W", ("rod", "wheel")),
                RollingContact("T", ("frame", "wheel"), ("track", "rim"))],
        drivers=[{"joint": "O2"}],
        profiles={"track": EllipseProfile((0.0, 0.0), (a1, b1)), "rim": EllipseProfile(tuple(W), (a2, b2))})


# ---------------------------------------------------------------------------- as files
def _xy(p) -> str:
    return f"[{float(p[0])!r}, {float(p[1])!r}]"


def cam_file(seed: int, follower: str) -> str:
    """`cam_mechanism(spline_cam(seed), follower)` written as a mechanism file (the spline's
    points in a [profiles] table; 'roller', 'knife' or 'flat')."""
    prof = spline_cam(seed, convex=follower != "roller")
    mech = cam_mechanism(prof, follower)
    pts = "\n".join(f"{k} = {_xy(v)}" for k, v in mech.points.items())
    spline = ", ".join(_xy(p) for p in prof.points)
    extra = {"roller": f'follower = "roller", point = "C", radius = {RHO!r}',
             "knife": 'follower = "knife", point = "C"',
             "flat": 'follower = "flat", point = "C", axis = 0'}[follower]
    return f"""name = "spline cam, {follower}"
[points]
{pts}
[profiles.cam]
type = "spline"
closed = true
points = [{spline}]
[links]
frame = ["O"]
cam = ["O", "A"]
follower = ["C", "F"]
[joints]
O = {{ type = "revolute", links = ["frame", "cam"] }}
F = {{ type = "prismatic", links = ["frame", "follower"], axis = 90 }}
K = {{ type = "cam", links = ["cam", "follower"], profile = "cam", {extra} }}
[driver]
joint = "O"
reference = "A"
"""


def rolling_ellipses_file() -> str:
    """`rolling_ellipses()` as a mechanism file."""
    mech = rolling_ellipses()
    pts = "\n".join(f"{k} = {_xy(v)}" for k, v in mech.points.items())
    (a1, b1), (a2, b2) = ROLL_E1, ROLL_E2
    return f"""name = "rolling ellipses"
[points]
{pts}
[profiles.track]
type = "ellipse"
center = [0, 0]
semi_axes = [{a1}, {b1}]
[profiles.rim]
type = "ellipse"
center = {_xy(mech.points["W"])}
semi_axes = [{a2}, {b2}]
[links]
frame = ["O", "O2"]
crank = ["O2", "A"]
rod = ["A", "W"]
wheel = ["W", "M"]
[joints]
O2 = {{ type = "revolute", links = ["frame", "crank"] }}
A = {{ type = "revolute", links = ["crank", "rod"] }}
W = {{ type = "revolute", links = ["rod", "wheel"] }}
T = {{ type = "rolling", links = ["frame", "wheel"], profiles = ["track", "rim"] }}
[driver]
joint = "O2"
"""
