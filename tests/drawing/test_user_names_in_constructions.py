"""A user's point name with `_` in it keeps its underscore in the vector labels of the
two-points and Hartmann constructions (v, a, u of a point: the file's name, not the books'
notation; it was set as a subscript, or its underscore dropped)."""

from __future__ import annotations

import numpy as np

import linkwork
from linkwork.constructions import construct
from linkwork.drawing.svg import segments


FOUR_BAR = """
name = "crank-rocker with a pin named pin_A"
units = { length = "mm" }
[points]
O2 = [0, 0]
pin_A = [0, 10]
B = [30, 30]
O4 = [40, 0]
C = [15, 25]
[links]
frame = ["O2", "O4"]
crank = ["O2", "pin_A"]
coupler = ["pin_A", "B", "C"]
rocker = ["B", "O4"]
[joints]
O2 = { type = "revolute", links = ["frame", "crank"] }
pin_A = { type = "revolute", links = ["crank", "coupler"] }
B = { type = "revolute", links = ["coupler", "rocker"] }
O4 = { type = "revolute", links = ["rocker", "frame"] }
[driver]
joint = "O2"
speed = "60 rpm"
"""


def test_names_with_underscores_are_printed_as_written():
    mech = linkwork.load_text(FOUR_BAR)
    sol = linkwork.solve(mech, np.radians([30.0]))
    for kind, opts in (("two-points", {}), ("hartmann", {"point": "C"})):
        con = construct(kind, mech, sol, **opts)
        labels = [e.label for e in con.elements.values()
                  if getattr(e, "label", None) and e.label[:2] in ("v_", "a_", "u_", "K_")]
        names = ["".join(t for t, _ in segments(lab)) for lab in labels]
        assert any("pin_A" in n for n in names), (kind, labels)
        assert not any("pinA" in n for n in names), (kind, labels)


def test_point_labels_and_step_texts_keep_a_users_underscore():
    # labels made by constructibility.upper/lower (plans, Euler–Savary, Bobillier) print `pin_A`
    # (and its image `pin_a`) as written; the step sentences read the same name without escapes
    mech = linkwork.load_text(FOUR_BAR)
    sol = linkwork.solve(mech, np.radians([30.0]))
    for kind, opts in (("velocity-plan", {}), ("acceleration-plan", {}), ("euler-savary", {"point": "C"}),
                       ("bobillier", {"point": "C"})):
        con = construct(kind, mech, sol, **opts)
        names = ["".join(t for t, _ in segments(e.label)) for e in con.elements.values() if e.label]
        assert any("pin_A" in n or "pin_a" in n for n in names), (kind, names)
        assert not any("pinA" in n or "pina" in n for n in names), (kind, names)
        # no label sets the user's `_A` as a subscript of `pin`
        for e in con.elements.values():
            if e.label and "pin" in e.label:
                segs = segments(e.label)
                assert not any(t.startswith(("A", "a")) and lvl != 0 and segs[k - 1][0].endswith("pin")
                               for k, (t, lvl) in enumerate(segs) if k), (kind, e.label, segs)
        text = con.describe()
        assert "pin_A" in text and "\\" not in text, (kind, text)


def test_pole_table_prints_link_names_as_written(tmp_path):
    # instant.Poles.legend() is plain text; the CLI's table is rendered without Rich markup, so
    # a name with brackets or an underscore is printed as written (not read as a style, no escape)
    from typer.testing import CliRunner

    from linkwork.cli import app
    text = (FOUR_BAR.replace('crank = ["O2", "pin_A"]', '"[b]link_j" = ["O2", "pin_A"]')
            .replace('"frame", "crank"', '"frame", "[b]link_j"').replace('"crank", "coupler"', '"[b]link_j", "coupler"'))
    path = tmp_path / "m.toml"
    path.write_text(text)
    mech = linkwork.load_text(text)
    from linkwork.instant import poles
    assert "2 = [b]link_j" in poles(linkwork.solve(mech, np.radians([30.0]))).legend()
    r = CliRunner().invoke(app, ["poles", str(path), "--at", "30"])
    assert r.exit_code == 0, r.output
    assert "2 = [b]link_j" in r.output and "\\[" not in r.output
