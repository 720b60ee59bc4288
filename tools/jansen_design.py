"""Design coordinates of Theo Jansen's Strandbeest leg from his "holy numbers".

Run once (`uv run python tools/jansen_design.py`) to print the [points] table of
`src/linkwork/library/jansen-linkage.toml`. Every joint follows from the previous ones by a
circle–circle intersection; the branch of each intersection is the one of Jansen's drawings
(upper triangle above, knee and foot below, the leg hanging to the left of the crank).

Points: O crank axis, A crank pin (m), B fixed pivot (a to the left, l down from O),
C upper joint (j from A, b from B), D lower joint (k from A, c from B),
E outer corner of the upper triangle BCE (d from B, e from C),
F knee (f from E, g from D), G foot (i from D, h from F).
"""

from math import cos, hypot, radians, sin, sqrt

HOLY = dict(a=38.0, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49.0, j=50.0,
            k=61.9, l=7.8, m=15.0)


def circles(p, rp, q, rq, side):
    """Intersection of the circle about p (radius rp) and about q (radius rq): the one to the
    left (side=+1) or right (side=-1) of the directed line p→q."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = hypot(dx, dy)
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    h = sqrt(rp * rp - a * a)
    ex, ey = dx / d, dy / d
    return (p[0] + a * ex - side * h * ey, p[1] + a * ey + side * h * ex)


def design(crank_deg: float = 90.0) -> dict[str, tuple[float, float]]:
    n = HOLY
    O = (0.0, 0.0)
    A = (round(n["m"] * cos(radians(crank_deg)), 12) + 0.0, round(n["m"] * sin(radians(crank_deg)), 12) + 0.0)
    B = (-n["a"], -n["l"])
    C = circles(B, n["b"], A, n["j"], +1)   # above the line B→A
    D = circles(B, n["c"], A, n["k"], -1)   # below it
    E = circles(B, n["d"], C, n["e"], +1)   # the outer corner, left of B→C
    F = circles(E, n["f"], D, n["g"], -1)   # the knee, below E→D
    G = circles(D, n["i"], F, n["h"], +1)   # the foot, lowest (left of D→F)
    return dict(O=O, A=A, B=B, C=C, D=D, E=E, F=F, G=G)


def check(P) -> None:
    n = HOLY
    pairs = dict(m=("O", "A"), b=("B", "C"), j=("A", "C"), c=("B", "D"), k=("A", "D"),
                 d=("B", "E"), e=("C", "E"), f=("E", "F"), g=("D", "F"), i=("D", "G"),
                 h=("F", "G"))
    for key, (p, q) in pairs.items():
        dist = hypot(P[p][0] - P[q][0], P[p][1] - P[q][1])
        assert abs(dist - n[key]) < 1e-12, (key, dist)
    assert abs(P["O"][0] - P["B"][0] - n["a"]) < 1e-12 and abs(P["O"][1] - P["B"][1] - n["l"]) < 1e-12


if __name__ == "__main__":
    P = design()
    check(P)
    for name, (x, y) in P.items():
        print(f"{name} = [{x:.15g}, {y:.15g}]")
