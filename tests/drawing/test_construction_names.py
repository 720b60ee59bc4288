"""Mohr's and Klein's constructions draw the file's point names at the file's points; the book's
letters of the steps are given in a key, never silently renamed."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest

import linkwork
from linkwork.constructions import construct
from linkwork.drawing import Scene, scene_figure

SVG = "{http://www.w3.org/2000/svg}"


def labels_at(fig, root):
    """Label text → anchor position in world units (from the figure's world-to-paper map)."""
    tf = fig.transforms()["mechanism"]
    out = {}
    for g in root.find(f".//{SVG}g[@id='labels']"):
        t = g.find(f"{SVG}text")
        r = g.find(f"{SVG}rect")
        cx = float(r.get("x")) + float(r.get("width")) / 2
        cy = float(r.get("y")) + float(r.get("height")) / 2
        wx = tf["lo"][0] + (cx - tf["origin"][0]) * tf["per_mm"]
        wy = tf["hi"][1] - (cy - tf["origin"][1]) * tf["per_mm"]
        out.setdefault("".join(t.itertext()), []).append(np.array([wx, wy]))
    return out


@pytest.mark.parametrize("name,lib,key", [
    # crank-rocker: the book's O_1, O_2 are the file's O2, O4
    ("mohr", "library:crank-rocker", ["O1 = O2", "O2 = O4"]),
    # Klein's C, P, A are the file's O, A, B
    ("klein", "library:slider-crank-centric", ["C = O", "P = A", "A = B"]),
    # Pöschl's slider-crank letters are the file's: no key
    ("mohr", "library:slider-crank-centric", None)])
def test_given_points_carry_the_file_names(name, lib, key):
    mech = linkwork.load(lib)
    sol = linkwork.solve(mech, np.radians([40.0]))
    fig = scene_figure(Scene(mech, sol), ["mechanism"], construction=construct(name, mech, sol))
    root = ET.fromstring(fig.to_svg().encode())
    found = labels_at(fig, root)
    tf = fig.transforms()["mechanism"]
    near = 8.0 * tf["per_mm"]  # a label sits within a few mm of its point
    for p in mech.points:
        at = sol.point(p).position[0]
        assert p in found, f"{p} not labelled (labels: {sorted(found)})"
        assert min(np.linalg.norm(q - at) for q in found[p]) < near
    legend = "".join(ET.tostring(root.find(f".//{SVG}g[@id='legend']"), encoding="unicode", method="text"))
    if key is None:
        assert "key" not in legend
    else:
        assert "key, book's letters in the steps = the file's points" in legend
        for k in key:
            assert k in legend


def test_no_book_letter_replaces_a_file_name():
    # crank-rocker: the crank centre O2 is not drawn as the book's O_1, nor the rocker pivot as O_2
    mech = linkwork.load("library:crank-rocker")
    sol = linkwork.solve(mech, np.radians([40.0]))
    fig = scene_figure(Scene(mech, sol), ["mechanism"], construction=construct("mohr", mech, sol))
    found = labels_at(fig, ET.fromstring(fig.to_svg().encode()))
    for book in ("O1",):
        if book not in mech.points:
            assert book not in found
