"""Labels placed where they cover least (issue 16: Jansen's pole labels crowded near O): no two
labels overlap, no label covers another label's point, and a label put far from its point is
joined to it by a leader line."""

import xml.etree.ElementTree as ET

import numpy as np

import linkwork
from linkwork.drawing import scene_at, scene_figure

SVG = "{http://www.w3.org/2000/svg}"


def _boxes(root):
    out = []
    for g in root.find(f".//{SVG}g[@id='labels']"):
        r = g.find(f"{SVG}rect")
        x, y, w, h = (float(r.get(k)) for k in ("x", "y", "width", "height"))
        out.append((x, y, x + w, y + h, "".join(g.find(f"{SVG}text").itertext()), g))
    return out


def test_jansen_pole_labels_do_not_collide():
    mech = linkwork.load("library:jansen-linkage")
    fig = scene_figure(scene_at(mech, 0.0), ["mechanism", "poles"])
    root = ET.fromstring(fig.to_svg().encode())
    boxes = _boxes(root)
    assert len(boxes) >= 28 + 8 - 3  # the 28 poles and the points (some poles fall on points)
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            w = min(a[2], b[2]) - max(a[0], b[0])
            h = min(a[3], b[3]) - max(a[1], b[1])
            assert w <= 1e-6 or h <= 1e-6, (a[4], b[4])
    # no label's box over another label's point
    tf = fig.transforms()["mechanism"]
    per, (ox, oy), lo, hi = tf["per_mm"], tf["origin"], tf["lo"], tf["hi"]
    anchors = [(ox + (lab.xy[0] - lo[0]) / per, oy + (hi[1] - lab.xy[1]) / per, lab.text) for lab in fig.labels]
    for x0, y0, x1, y1, text, _ in boxes:
        for ax, ay, owner in anchors:
            inside = x0 < ax < x1 and y0 < ay < y1
            assert not inside or owner.replace("_{", "").replace("}", "").replace("_", "") == \
                text.replace("_", ""), (text, owner)


def test_a_far_label_has_a_leader_line():
    mech = linkwork.load("library:jansen-linkage")
    root = ET.fromstring(scene_figure(scene_at(mech, 0.0), ["mechanism", "poles"]).to_svg().encode())
    for x0, y0, x1, y1, text, g in _boxes(root):
        line = g.find(f"{SVG}line")
        if line is not None:  # the leader ends on the label's box
            q = np.array([float(line.get("x2")), float(line.get("y2"))])
            assert x0 - 0.15 <= q[0] <= x1 + 0.15 and y0 - 0.15 <= q[1] <= y1 + 0.15  # the halo is 0.1 in
