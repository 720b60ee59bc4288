"""The workbench page's defects found by the acceptance audit of issue 12, each in a real browser
(the fixtures of test_page.py): what the page shows is compared with the Python API (the
engine's solve of the moved design, the driver's law, the structure), never with the page's own
output."""

from __future__ import annotations

import json
from datetime import datetime
import math
import re
import time

import numpy as np
import pytest

import linkwork
from linkwork.io import load_text, resolve

from test_page import MECH, browser, drawn_input, page, server, wait_drawn  # noqa: F401 (fixtures)

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

TEXT = resolve("library:crank-rocker")[1]


def _transform(page) -> dict:
    return json.loads(page.get_attribute("#drawing", "data-transform"))


def _screen(page, xy) -> tuple[float, float]:
    """Where on the screen the world point `xy` is drawn in the drawing shown (its transform
    and the SVG's placement in the page)."""
    return tuple(page.eval_on_selector("#drawing svg", """(svg, [t, p]) => {
        const x = t.origin[0] + (p[0] - t.lo[0]) / t.per_mm, y = t.origin[1] + (t.hi[1] - p[1]) / t.per_mm;
        const q = new DOMPoint(x, y).matrixTransform(svg.getScreenCTM());
        return [q.x, q.y]; }""", [_transform(page), list(map(float, xy))]))


def _world(page, screen) -> np.ndarray:
    """The world point of the drawing shown under the screen point `screen`."""
    return np.array(page.eval_on_selector("#drawing svg", """(svg, [t, s]) => {
        const q = new DOMPoint(s[0], s[1]).matrixTransform(svg.getScreenCTM().inverse());
        return [t.lo[0] + (q.x - t.origin[0]) * t.per_mm, t.hi[1] - (q.y - t.origin[1]) * t.per_mm]; }""",
        [_transform(page), list(map(float, screen))]))


def _moved(page) -> dict:
    return json.loads(page.get_attribute("#drawing", "data-moved") or "{}")


def _settled(page) -> None:
    """Wait until the page has drawn what it asks for: the moved points and the input drawn
    unchanged for 300 ms."""
    last, since = None, time.monotonic()
    deadline = since + 20
    while time.monotonic() - since < 0.3:
        assert time.monotonic() < deadline, "the drag's frames did not settle"
        now = (page.get_attribute("#drawing", "data-moved"), page.get_attribute("#drawing", "data-input"))
        if now != last:
            last, since = now, time.monotonic()
        page.wait_for_timeout(40)


def _engine_point(page, point: str) -> np.ndarray:
    """The engine's position of `point` in the design the page draws (the file with the moved
    points written in), solved at the input drawn."""
    text = TEXT
    for name, (x, y) in _moved(page).items():
        line = next(ln for ln in TEXT.splitlines() if ln.split("=")[0].strip() == name)
        text = text.replace(line, f"{name} = [{x!r}, {y!r}]")
    mech = load_text(text)
    return linkwork.solve(mech, drawn_input(page)).point(point).position[0]


def _go_to(page, degrees: float) -> None:
    sol = linkwork.whole_motion(MECH)
    k = int(np.argmin(np.abs(sol.inputs[:, 0] - math.radians(degrees))))
    page.focus("#input-slider")
    for _ in range(k):
        page.keyboard.press("ArrowRight")
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([sol.inputs[k, 0]], abs=1e-15),
               f"go to {degrees}°")


def test_a_drag_keeps_the_view_and_the_point_under_the_pointer(page):
    """Crank-rocker at its design sample, B dragged 60 px right and 40 px up in 10 steps: every
    frame is drawn at the scale of the drawing the drag began on, and B (the engine's solve of
    the moved design) is drawn under the pointer."""
    page.check("#edit")
    page.wait_for_timeout(300)
    scale = _transform(page)["per_mm"]
    b0 = MECH.points["B"]
    start = _screen(page, b0)
    page.mouse.move(*start)
    page.mouse.down()
    for k in range(1, 11):
        pointer = (start[0] + 6 * k, start[1] - 4 * k)
        page.mouse.move(*pointer)
        wait_drawn(page, lambda: "B" in _moved(page), "draw the first frame")
        _settled(page)
        assert _transform(page)["per_mm"] == scale, f"the view zoomed at step {k}"
        got = _screen(page, _engine_point(page, "B"))
        assert math.dist(got, pointer) < 2.0, (k, got, pointer)  # px
    page.mouse.up()


@pytest.mark.parametrize("view, message", [
    ({"lo": [0, 0], "hi": [0, 10], "per_mm": 0.5}, "hi must exceed lo"),
    ({"lo": [0, 0], "hi": [10, 10], "per_mm": 0}, "greater than 0"),
    ({"lo": [0, 0], "hi": [10, 10], "per_mm": 1e13}, "less than or equal"),
])
def test_a_drawings_view_is_validated(view, message):
    from fastapi.testclient import TestClient
    from linkwork.web import create_app

    client = TestClient(create_app(None), raise_server_exceptions=False)
    r = client.post("/api/drawing", json={"source": {"library": "crank-rocker"}, "view": view})
    assert r.status_code == 422 and message in r.json()["error"], r.text
    # a valid one is the panel's box and scale, whatever the frame draws
    view = {"lo": [-50.0, -40.0], "hi": [70.0, 60.0], "per_mm": 1.0}
    r = client.post("/api/drawing", json={"source": {"library": "crank-rocker", "points": {"B": [31, 31]}},
                                          "motion": False, "view": view})
    t = r.json()["transforms"]["mechanism"]
    assert (t["lo"], t["hi"], t["per_mm"]) == (view["lo"], view["hi"], view["per_mm"])


def test_a_dragged_hinge_ends_under_the_pointer_away_from_the_design_position(page):
    """Crank-rocker at 130°, the hinge B dragged about 3 mm: moving B changes the coupler's pose
    (its lengths change), so the design coordinates read through the pose at the drag's start
    put B off the pointer; the page corrects them frame by frame until the engine's B of the
    moved design is where the pointer is (to the screen's pixel, read back exactly)."""
    _go_to(page, 130.0)
    page.check("#edit")
    page.wait_for_timeout(300)
    b = linkwork.solve(MECH, drawn_input(page)).point("B").position[0]
    start = _screen(page, b)
    end = tuple(round(v) for v in _screen(page, b + np.array([2.0, 2.2])))
    target = _world(page, end)  # the world point under the pixel the pointer ends on
    page.mouse.move(*start)
    page.mouse.down()
    for f in np.linspace(0, 1, 6)[1:]:
        page.mouse.move(start[0] + f * (end[0] - start[0]), start[1] + f * (end[1] - start[1]))
        page.wait_for_timeout(40)
    wait_drawn(page, lambda: "B" in _moved(page), "draw the drag")
    _settled(page)
    got = _engine_point(page, "B")
    page.mouse.up()
    assert np.linalg.norm(target - b) == pytest.approx(3.0, abs=0.3)
    assert np.linalg.norm(got - target) < 0.01, (got, target)  # mm


def _time_shown(page) -> float:
    return float(page.get_attribute("#input-time", "data-time") or "nan")


def _played(page, factor: str, seconds: float, times: np.ndarray) -> float:
    """Play at the speed `factor` for `seconds` of the page's own clock (Playwright's clock,
    paused and run forward in steps, each after the drawing asked for is in): how far the time
    shown went from the time of the sample it started at (`times`: the motion's). The page's
    clock, not the wall's: the machine's load does not enter."""
    page.select_option("#speed", factor)
    page.clock.pause_at(datetime.fromtimestamp(page.evaluate("Date.now()") / 1000 + 1.0))
    start = times[int(page.input_value("#input-slider"))]
    page.click("#play")
    steps = round(seconds / 0.02)
    for _ in range(steps):
        page.clock.run_for(20)
        wait_drawn(page, lambda: page.evaluate("!window.linkworkBusy()"), "draw the frame")
    page.clock.run_for(17)  # one more animation frame: the last frame's tick at the end
    shown = _time_shown(page)
    page.click("#play")
    page.clock.resume()
    return shown - start


def test_play_goes_at_the_motions_own_time(page):
    """The crank turns at 60 rpm (the file's driver law, 2π rad/s: a turn a second). Played for
    0.4 s of the page's clock at 1×, the motion's time shown advances 0.4 s; at ½×, 0.2 s (to a
    frame of the page's animation, 17 ms, and a sample). The time shown is the engine's: the
    input turned from the motion's first sample at the driver's speed."""
    speed = MECH.drivers[0].law.speed
    assert speed == pytest.approx(2 * math.pi)
    page.clock.install()
    sol = linkwork.whole_motion(MECH)
    step = float(np.max(np.diff(sol.inputs[:, 0]))) / speed  # the motion's sample spacing (s)
    times = (sol.inputs[:, 0] - sol.inputs[0, 0]) / speed
    # once before: the motion's times fetched (the first play's clock starts when they are in)
    _played(page, "1", 0.1, times)
    for factor, expected in (("1", 0.4), ("0.5", 0.2)):
        went = _played(page, factor, 0.4, times)
        assert went == pytest.approx(expected, abs=(0.017 + 0.02) * float(factor) + step), factor
        k = int(page.input_value("#input-slider"))
        shown = _time_shown(page)
        assert shown == pytest.approx((sol.inputs[k, 0] - sol.inputs[0, 0]) / speed, abs=1e-9)


@pytest.mark.parametrize("name", ["crank-rocker", "heusinger-valve-gear"])
def test_the_structure_panel_shows_the_assur_groups(page, name):
    """Each Assur group of `linkwork.structure.assur_groups`, in order: its name (kind, class,
    order), its links and its pairs."""
    from linkwork.structure import assur_groups

    mech = linkwork.load(f"library:{name}")
    if name != "crank-rocker":
        page.select_option("#mechanism", f"library:{name}")
        wait_drawn(page, lambda: page.inner_text("#title") == mech.name, f"open {name}", timeout=120)
    want = assur_groups(mech)
    wait_drawn(page, lambda: page.locator("#structure dd.group").count() == len(want), "show the groups")
    shown = page.locator("#structure dd.group").evaluate_all(
        "dds => dds.map(d => [d.textContent, {...d.dataset}])")
    for (text, data), g in zip(shown, want):
        assert data["links"].split() == list(g.links) and data["pairs"].split() == list(g.joints)
        assert (data["kind"], int(data["class"]), int(data["order"])) == (g.kind, g.assur_class, g.order)
        assert text.startswith(f"{g.name}: links {', '.join(g.links)}; pairs {', '.join(g.joints)}")
    assert any(g.assur_class == 3 for g in want) == (name == "heusinger-valve-gear")


def test_an_uploaded_file_is_the_mechanism_listed(page):
    """After an upload the Mechanism list shows the uploaded file, so choosing the library entry
    open before opens it again (a change), and the upload's entry opens the upload."""
    text = TEXT.replace("C  = [15, 25]", "C  = [18, 27]").replace("Crank-rocker four-bar", "Uploaded four-bar")
    mech = load_text(text)
    page.set_input_files("#upload", files=[{"name": "mine.toml", "mimeType": "text/plain",
                                             "buffer": text.encode()}])
    wait_drawn(page, lambda: page.inner_text("#title") == mech.name, "open the upload")
    assert page.input_value("#mechanism") != "library:crank-rocker"
    assert "mine.toml" in page.eval_on_selector("#mechanism", "s => s.selectedOptions[0].textContent")

    def c_shown():
        cells = page.locator("#numbers tr[data-point='C'] td").all_inner_texts()
        return float(cells[1]), float(cells[2])

    wait_drawn(page, lambda: c_shown() == pytest.approx(tuple(mech.points["C"]), abs=1e-4), "draw the upload")
    page.select_option("#mechanism", "library:crank-rocker")
    wait_drawn(page, lambda: page.inner_text("#title") == MECH.name, "open the library entry again")
    wait_drawn(page, lambda: c_shown() == pytest.approx(tuple(MECH.points["C"]), abs=1e-4), "draw it")
    page.select_option("#mechanism", label="mine.toml (uploaded)")
    wait_drawn(page, lambda: page.inner_text("#title") == mech.name, "open the upload again")


def test_an_edit_that_does_not_build_stops_the_old_motion(page):
    """An edited file that does not build: the engine's message, the last drawing greyed, and
    nothing moves the old mechanism (play, the slider, the keys are off) until an edit builds."""
    from linkwork.errors import LinkworkError

    page.click("#editor summary")
    bad = TEXT.replace('coupler = ["A", "B", "C"]', 'coupler = ["A", "B", "X"]')
    with pytest.raises(LinkworkError) as exc:
        load_text(bad, source="crank-rocker.toml")
    page.fill("#edit-text", bad)
    page.click("#edit-text-apply")
    wait_drawn(page, lambda: page.get_attribute("#editor", "data-applied") == "error", "apply the edit")
    assert page.inner_text("#error") == str(exc.value)
    assert page.locator("#drawing.stale").count() == 1
    assert page.is_disabled("#play") and page.is_disabled("#input-slider")
    shown = drawn_input(page)
    page.focus("#drawing")
    page.keyboard.press("Space")
    page.keyboard.press("ArrowRight")
    page.wait_for_timeout(600)
    assert page.get_attribute("#play", "aria-pressed") == "false"
    assert drawn_input(page) == shown and page.input_value("#input-slider") == "0"
    assert page.locator("#drawing.stale").count() == 1 and page.inner_text("#error") == str(exc.value)
    # an edit that builds: the page is live again
    page.fill("#edit-text", TEXT)
    page.click("#edit-text-apply")
    wait_drawn(page, lambda: page.get_attribute("#editor", "data-applied") == "ok", "apply the good text")
    wait_drawn(page, lambda: page.locator("#drawing.stale").count() == 0, "draw the good file")
    assert page.is_enabled("#play") and page.is_enabled("#input-slider") and page.is_hidden("#error")
    page.focus("#drawing")
    page.keyboard.press("ArrowRight")
    sol = linkwork.whole_motion(MECH)
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([sol.inputs[1, 0]], abs=1e-15), "step the motion")


def test_a_quantity_constant_over_the_motion_is_plotted_flat_with_its_value(page):
    """The crank pin A turns at a constant speed, so |v_A| = ω·O2A over the whole motion but for
    rounding: plotted as a flat line with that one value, not as its rounding noise scaled to
    the plot's height; the input labels end inside the plot."""
    r = float(np.hypot(*np.subtract(MECH.points["A"], MECH.points["O2"])))
    expected = MECH.drivers[0].law.speed * r
    page.select_option("#quantity", "point:A:v")
    page.wait_for_selector("#plot svg", timeout=30_000)
    svg = page.locator("#plot svg")
    assert float(svg.get_attribute("data-max")) == pytest.approx(expected, rel=1e-12)
    ys = {round(float(p.split(",")[1]), 2)
          for line in svg.locator("polyline.curve").evaluate_all("ls => ls.map(l => l.getAttribute('points'))")
          for p in line.split()}
    assert len(ys) == 1  # one height: flat
    labels = svg.locator("text").evaluate_all("ts => ts.map(t => t.textContent)")
    numbers = [float(t) for t in labels if t.replace(".", "", 1).isdigit()]
    assert numbers == [pytest.approx(expected, rel=1e-4)], labels  # one value on the axis
    box = svg.evaluate("""s => { const f = s.querySelector('rect.frame').getBBox();
        return Array.from(s.querySelectorAll('text')).every(t => {
            const b = t.getBBox(); return b.x >= 0 && b.x + b.width <= s.viewBox.baseVal.width + 0.5; }); }""")
    assert box


def test_a_pairs_numbers_read_as_a_turn_and_in_words(page):
    """The crank's pair O2 half a turn on from its drawing: its relative angle shown in
    (−180°, 180°], equal to the engine's modulo a turn; a sliding pair's fields in words."""
    sol = linkwork.whole_motion(MECH)
    page.select_option("#selection", "joint:O2")
    wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == "joint:O2", "select O2")
    page.focus("#input-slider")
    k = 200
    for _ in range(k):
        page.keyboard.press("ArrowRight")
    want = float(sol.inputs[k, 0])
    wait_drawn(page, lambda: json.loads(page.get_attribute("#selected", "data-input") or "[0]")
               == pytest.approx([want], abs=1e-12), "the numbers at the sample")
    rows = dict(page.locator("#selected tr").evaluate_all(
        "trs => trs.map(r => [r.dataset.quantity, r.cells[1].textContent])"))
    engine = math.degrees(linkwork.solve(MECH, [want]).joint("O2")["angle"][0])
    shown = float(rows["angle"])
    assert -180 < shown <= 180 and abs(engine) > 180  # the engine's is unwrapped here
    assert math.remainder(shown - engine, 360) == pytest.approx(0, abs=1e-3)


def test_a_sliding_pairs_fields_are_named_in_words(page):
    page.select_option("#mechanism", "library:slider-crank-offset")
    wait_drawn(page, lambda: "slider" in page.inner_text("#title").lower(), "open the slider-crank")
    page.select_option("#selection", "joint:guide")
    wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == "joint:guide", "select")
    names = page.locator("#selected tr").evaluate_all("trs => trs.map(r => r.cells[0].textContent)")
    assert "sliding velocity" in names and not any("_" in n for n in names), names


def test_a_drag_keeps_the_vectors_scale(page):
    """With the velocity vectors shown, a drag's frames draw them at the velocity scale of the
    drawing the drag began on (each frame alone would pick another, and the arrows would jump
    in length when the drag begins): the scale the legend states stays."""
    page.check("#show-velocities")
    wait_drawn(page, lambda: page.locator("#drawing svg #layer-velocities").count() == 1, "draw v")

    def velocity_scale() -> str:
        text = page.eval_on_selector("#drawing svg", "s => s.textContent").replace("\u2009", " ")
        found = re.findall(r"≙ ([0-9.e+-]+) mm/s(?!²)", text)
        assert found, text[-300:]
        return found[0]

    before = velocity_scale()
    page.check("#edit")
    page.wait_for_timeout(300)
    start = _screen(page, MECH.points["B"])
    page.mouse.move(*start)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(start[0] + 8 * k, start[1] - 5 * k)
        wait_drawn(page, lambda: "B" in _moved(page), "draw the first frame")
        _settled(page)
        assert velocity_scale() == before, f"the vectors' scale changed at step {k}"
    page.mouse.up()
