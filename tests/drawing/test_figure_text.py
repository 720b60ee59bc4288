"""Text on the figures: user names printed as written, the books' notation as sub- and
superscripts, text widths measured from the font, legend lines clear of the scale bars."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from matplotlib.font_manager import FontProperties
from matplotlib.textpath import TextPath

import linkwork
from linkwork.constructions.construction import literal
from linkwork.drawing import scene_at, scene_figure
from linkwork.drawing.svg import SUB, SUP, label_markup, segments, text_width
from linkwork.instant import poles

SVG = "{http://www.w3.org/2000/svg}"


def parse(svg: str) -> ET.Element:
    return ET.fromstring(svg.encode("utf-8"))


def jansen_figure():
    mech = linkwork.load("library:jansen-linkage")
    sc = scene_at(mech, 0.7)
    return mech, sc, parse(scene_figure(sc, ["mechanism", "poles", "velocities"]).to_svg())


def test_user_names_are_printed_as_written():
    assert segments(literal("link_j")) == [("link_j", 0)]
    assert segments("3 = " + literal("a^b_{c}")) == [("3 = a^b_{c}", 0)]
    # the books' notation stays: subscripts, superscripts stacked on them
    assert segments("P_{13}") == segments("P_13") == [("P", 0), ("13", SUB)]
    assert segments("b_B^(n)") == [("b", 0), ("B", SUB), ("(n)", SUP)]
    assert segments("v_{" + literal("p_1") + "}") == [("v", 0), ("p_1", SUB)]
    # the books' O_4 inside a subscript, and a superscript before the subscript
    assert segments("a^n_BO_4") == [("a", 0), ("n", SUP), ("BO4", SUB)]
    m = label_markup("b_B^(n)", 3.0)
    assert "^" not in m and ">(n)</tspan>" in m and ">B</tspan>" in m


def test_jansen_pole_legend_names_the_links_as_the_file_does():
    mech, sc, root = jansen_figure()
    links = poles(sc.sol).links
    assert any("_" in ln for ln in links)  # the library's Jansen linkage has link_j, link_k …
    legend = root.find(f".//{SVG}g[@id='legend']")
    lines = ["".join(t.itertext()) for t in legend.iter(f"{SVG}text") if "poles" in "".join(t.itertext())]
    text = " ".join(lines)
    for k, ln in enumerate(links):
        assert f"{k + 1} = {ln}" in text
    # no part of the legend line is set smaller (as a subscript would be)
    for t in legend.iter(f"{SVG}text"):
        if "poles" in "".join(t.itertext()):
            assert all(s.get("font-size") is None for s in t.iter(f"{SVG}tspan"))


def test_point_labels_carry_the_file_names():
    mech, sc, root = jansen_figure()
    labels = root.find(f".//{SVG}g[@id='labels']")
    found = {t.get("id"): "".join(t.itertext()) for t in labels.iter(f"{SVG}text") if t.get("id")}
    for p in mech.points:
        assert found[f"label-point-{p}"] == p
    moving = [p for p in mech.points if mech.point_owner[p] != mech.frame]
    for p in moving:
        assert found[f"label-velocity-{p}"] == "v" + p


@pytest.mark.parametrize("text,italic", [("link_j as written", False), ("Bresse circle (coupler)", False),
                                         ("inflection pole", True), ("1 mm = 5 mm/s", False)])
def test_text_width_is_measured_from_the_font(text, italic):
    # independent: Matplotlib's own text layout of the same face, outline extents at 100 units
    prop = FontProperties(family="DejaVu Serif", style="italic" if italic else "normal")
    ext = TextPath((0, 0), text, size=100, prop=prop).get_extents()
    want = 3.0 * ext.x1 / 100  # ink extent from the pen's start; advance adds the last bearing
    got = text_width(literal(text), 3.0, italic)
    assert got == pytest.approx(want, rel=0.04, abs=0.15)


def _box(x, y_base, width, size):
    return (x, y_base - 0.8 * size, x + width, y_base + 0.25 * size)


def test_legend_lines_clear_of_the_scale_bars():
    mech, sc, root = jansen_figure()
    legend = root.find(f".//{SVG}g[@id='legend']")
    width = float(root.get("viewBox").split()[2])
    bars, lines = [], []
    for g in legend.findall(f"{SVG}g"):
        ys = [float(v) for el in g for v in (el.get("y1"), el.get("y2"), el.get("y")) if v is not None]
        xs = [float(v) for el in g for v in (el.get("x1"), el.get("x2"), el.get("x")) if v is not None]
        # the bar and ticks, the value under it and the words at their measured width
        bars.append((min(xs), min(ys) - 2.8 * 0.8, max(xs) + 40.0, max(ys) + 0.3 * 2.5))
    assert len(bars) == 2  # length and velocity
    for t in legend.findall(f"{SVG}text"):
        s = "".join(t.itertext())
        w = 3.0 * TextPath((0, 0), s, size=100, prop=FontProperties(family="DejaVu Serif")).get_extents().x1 / 100
        box = _box(float(t.get("x")), float(t.get("y")), w, 3.0)
        lines.append(box)
        assert box[2] <= width  # on the sheet
    assert lines
    for a in lines:
        for b in bars:
            dy = min(a[3], b[3]) - max(a[1], b[1])
            dx = min(a[2], b[2]) - max(a[0], b[0])
            assert not (dx > 0 and dy > 0), (a, b)
    for i, a in enumerate(lines):
        for b in lines[i + 1:]:
            assert min(a[3], b[3]) - max(a[1], b[1]) <= 0


def test_long_legend_lines_are_wrapped_to_the_sheet():
    mech = linkwork.load("library:crank-rocker")
    fig = scene_figure(scene_at(mech, 0.5), ["mechanism"])
    fig.note("x " * 400)
    root = parse(fig.to_svg())
    width = float(root.get("viewBox").split()[2])
    legend = root.find(f".//{SVG}g[@id='legend']")
    rows = [t for t in legend.findall(f"{SVG}text") if "x x" in "".join(t.itertext())]
    assert len(rows) > 1
    for t in rows:
        s = "".join(t.itertext())
        assert float(t.get("x")) + text_width(s, 3.0) <= width
