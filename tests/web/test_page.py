"""The workbench page in a real browser: Debian's Chromium (`/usr/bin/chromium`, installed by
`./run tests` with apt-get) driven by Playwright, against a server on a free local port.

What the page draws is compared with the Python API: a point's SVG position is the engine's
position mapped through the drawing's world-to-paper transform, the slider's samples are those
of `linkwork.whole_motion`, a dragged mechanism is the file with the moved point, solved."""

from __future__ import annotations

import json
import math
import shutil
import socket
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import linkwork
from linkwork.io import load_text, resolve
from linkwork.errors import LinkworkError
from linkwork.web.app import STATIC

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
MECH = linkwork.load("library:crank-rocker")


@pytest.fixture(scope="module")
def server():
    uvicorn = pytest.importorskip("uvicorn")
    from linkwork.web import create_app

    if not (STATIC / "app.js").is_file():
        pytest.fail("the workbench's page is not built: run the tests with ./run tests (it builds "
                    "web/ into src/linkwork/web/static/app.js)")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    srv = uvicorn.Server(uvicorn.Config(create_app(None), host="127.0.0.1", port=port,
                                        log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not srv.started:
        assert time.monotonic() < deadline, "the workbench server did not start"
        time.sleep(0.05)
    yield f"http://127.0.0.1:{port}"
    srv.should_exit = True
    thread.join(10)


@pytest.fixture(scope="module")
def browser():
    if not Path(CHROMIUM).is_file():
        pytest.skip("Debian's chromium is not installed and could not be (./run tests installs it "
                    "with apt-get); the browser tests need it")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        # Debian's browser, never one downloaded by Playwright; no sandbox as root
        b = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        yield b
        b.close()


@pytest.fixture()
def page(browser, server):
    pg = browser.new_page(viewport={"width": 1280, "height": 900})
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(f"{server}/?library=crank-rocker")
    pg.wait_for_selector("body[data-ready=true]", timeout=30_000)
    yield pg
    pg.close()
    assert not errors, errors


def drawn_input(pg) -> list[float]:
    return json.loads(pg.get_attribute("#drawing", "data-input"))


def wait_drawn(pg, predicate, what: str, timeout: float = 20.0) -> None:
    deadline = time.monotonic() + timeout
    while not predicate():
        assert time.monotonic() < deadline, f"the page did not {what}"
        pg.wait_for_timeout(30)


def svg_position(pg, ident: str) -> tuple[float, float]:
    el = pg.locator(f"#drawing svg circle#{ident}")
    return float(el.get_attribute("cx")), float(el.get_attribute("cy"))


def expected_svg(pg, xy) -> tuple[float, float]:
    t = json.loads(pg.get_attribute("#drawing", "data-transform"))
    return (t["origin"][0] + (xy[0] - t["lo"][0]) / t["per_mm"],
            t["origin"][1] + (t["hi"][1] - xy[1]) / t["per_mm"])


def number_row(pg, point: str) -> tuple[float, float]:
    cells = pg.locator(f"#numbers tr[data-point='{point}'] td").all_inner_texts()
    return float(cells[1]), float(cells[2])


def test_page_opens_a_library_mechanism(page):
    assert page.inner_text("#title") == "Crank-rocker four-bar"
    assert page.locator("#drawing svg").count() == 1
    assert page.locator("#drawing svg #layer-mechanism").count() == 1
    # the design position, as written in the file: C = (15, 25), crank up (90°)
    assert number_row(page, "C") == (15.0, 25.0)
    assert page.inner_text("#input-value") == "90.00°"
    assert page.inner_text("#sample-status") == "ok"
    assert page.is_hidden("#error")
    # the structure panel: Grübler's count for four links and four hinges, 3(4 − 1) − 2·4 = 1
    page.wait_for_selector("#structure dd")
    panel = page.inner_text("#structure")
    assert "mobility (count)\n1" in panel.replace("\t", "\n") and "crank-rocker" in panel
    # another mechanism from the list
    page.select_option("#mechanism", "library:slider-crank-centric")
    wait_drawn(page, lambda: page.inner_text("#title") == linkwork.load("library:slider-crank-centric").name,
               "open the slider-crank")


def test_status_strip_is_the_whole_motion(page):
    sol = linkwork.whole_motion(MECH)
    assert int(page.get_attribute("#input-slider", "max")) == len(sol) - 1
    classes = page.locator("#status-strip span").evaluate_all("els => els.map(e => e.className)")
    assert classes == [str(linkwork.kinematics.Status(int(s))) for s in sol.status]


def test_slider_moves_the_mechanism(page):
    sol = linkwork.whole_motion(MECH)
    before = svg_position(page, "point-C")
    page.focus("#input-slider")
    for _ in range(40):  # the keyboard moves it, one sample a press
        page.keyboard.press("ArrowRight")
    assert page.get_attribute("#input-slider", "value") is not None
    k = int(page.eval_on_selector("#input-slider", "e => e.value"))
    assert k == 40
    want_input = float(sol.inputs[k, 0])
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([want_input], abs=1e-15),
               "draw the slider's position")
    xy = linkwork.solve(MECH, [want_input]).point("C").position[0]
    got = svg_position(page, "point-C")
    assert got != before
    assert got == pytest.approx(expected_svg(page, xy), abs=2e-3)  # the SVG has 3 decimals
    assert number_row(page, "C") == pytest.approx(tuple(xy), abs=1e-4)
    assert page.inner_text("#input-value") == f"{math.degrees(want_input):.2f}°"


def test_play_and_pause(page):
    sol = linkwork.whole_motion(MECH)
    start = drawn_input(page)
    page.click("#play")
    assert page.get_attribute("#play", "aria-pressed") == "true"
    wait_drawn(page, lambda: drawn_input(page) != start, "play the motion")
    page.click("#play")
    assert page.get_attribute("#play", "aria-pressed") == "false"
    k = page.eval_on_selector("#input-slider", "e => e.value")
    page.wait_for_timeout(500)
    assert page.eval_on_selector("#input-slider", "e => e.value") == k  # it stopped
    # and what is drawn comes to the sample it stopped at
    want = float(sol.inputs[int(k), 0])
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([want], abs=1e-15), "draw where it stopped")


def _client_of(page, xy):
    """Where on the screen the world point `xy` of the mechanism panel is drawn."""
    sx, sy = expected_svg(page, xy)
    return page.eval_on_selector("#drawing svg", """(svg, p) => {
        const q = new DOMPoint(p[0], p[1]).matrixTransform(svg.getScreenCTM());
        return [q.x, q.y]; }""", [sx, sy])


def test_dragging_a_point_solves_again(page):
    page.check("#edit")
    wait_drawn(page, lambda: page.locator("#drawing.editing").count() == 1, "enter editing")
    page.wait_for_timeout(300)
    a = _client_of(page, (0.0, 10.0))  # the crank's end A at the design position
    b = _client_of(page, (0.0, 13.0))
    page.mouse.move(*a)
    page.mouse.down()
    for f in np.linspace(0, 1, 6)[1:]:
        page.mouse.move(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]))
        page.wait_for_timeout(40)
    page.mouse.up()

    def moved_a():
        return json.loads(page.get_attribute("#drawing", "data-moved")).get("A", [math.nan] * 2)

    wait_drawn(page, lambda: np.hypot(moved_a()[0], moved_a()[1] - 13.0) < 0.2,
               "redraw the dragged point")  # to a pixel of the screen
    wait_drawn(page, lambda: json.loads(page.get_attribute("#input-slider", "data-moved") or "{}")
               .get("A") == moved_a(), "solve the whole motion of the new design")
    page.uncheck("#edit")
    page.focus("#input-slider")
    for _ in range(25):
        page.keyboard.press("ArrowRight")
    wait_drawn(page, lambda: page.eval_on_selector("#input-slider", "e => e.value") == "25", "move the slider")
    page.wait_for_timeout(300)
    # the file with A moved where the drawing says, read by the engine, solved at the same
    # sample of its whole motion
    moved = moved_a()
    text = resolve("library:crank-rocker")[1].replace("A  = [0, 10]", f"A  = [{moved[0]!r}, {moved[1]!r}]")
    mech = load_text(text)
    assert np.allclose(mech.points["A"], moved)
    want = float(linkwork.whole_motion(mech).inputs[25, 0])
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([want], abs=1e-15), "draw the new motion")
    assert moved_a() == moved
    xy = linkwork.solve(mech, [want]).point("C").position[0]
    assert number_row(page, "C") == pytest.approx(tuple(xy), abs=1e-4)
    assert svg_position(page, "point-C") == pytest.approx(expected_svg(page, xy), abs=2e-3)
    # and the crank is longer: A on the circle of radius |moved|
    assert np.hypot(*number_row(page, "A")) == pytest.approx(np.hypot(*moved), abs=1e-4)
    # Save TOML: the file with A's new design coordinates, the rest as it was
    with page.expect_download() as dl:
        page.click("#save")
    saved = Path(dl.value.path()).read_text()
    assert dl.value.suggested_filename == "crank-rocker.toml"
    assert load_text(saved).points["A"] == pytest.approx(moved, abs=1e-6)
    assert [ln for ln in saved.splitlines() if not ln.startswith("A ")] == \
        [ln for ln in resolve("library:crank-rocker")[1].splitlines() if not ln.startswith("A ")]


def _shows_the_last_drawing(page) -> bool:
    """Whether the page shows the SVG the server sent last; a frame may arrive between the
    export and the comparison, so a difference must last (3 s) to count."""
    deadline = time.monotonic() + 3.0
    while not _shown_is(page, _exported(page)):
        if time.monotonic() > deadline:
            return False
        page.wait_for_timeout(100)
    return True


def _shown_is(page, svg: str) -> bool:
    """Whether the drawing in the page is `svg` as the page's parser reads it (the same
    elements, attributes and text, node for node)."""
    return page.eval_on_selector("#drawing svg", """(shown, text) => {
        const t = document.createElement("template");
        t.innerHTML = text.replace(/^<\\?xml[^>]*>\\s*/, "");
        return t.content.firstElementChild.isEqualNode(shown); }""", svg)


def _exported(page) -> str:
    """The SVG drawn last, as the server sent it (the export, clicked without the mouse, which
    may be dragging)."""
    with page.expect_download() as dl:
        page.eval_on_selector("#export-svg", "e => e.click()")
    return Path(dl.value.path()).read_text()


def test_each_frame_shows_the_servers_drawing(page):
    """The page puts a new drawing in by changing what differs from the one shown: after a
    drag's frames, a layer switched on and off again, what it shows is the server's SVG."""
    page.check("#edit")
    page.wait_for_timeout(300)
    a = _client_of(page, (15.0, 25.0))  # C at the design position
    page.mouse.move(*a)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(a[0] + 4 * k, a[1] - 3 * k)
        page.wait_for_timeout(60)
        assert _shows_the_last_drawing(page)
    page.mouse.up()
    wait_drawn(page, lambda: json.loads(page.get_attribute("#input-slider", "data-moved") or "{}")
               .get("C") is not None, "solve the whole motion of the new design")
    assert _shows_the_last_drawing(page)
    page.check("#show-poles")
    wait_drawn(page, lambda: page.locator("#drawing svg #layer-poles").count() == 1, "draw the poles")
    assert _shows_the_last_drawing(page)
    page.uncheck("#show-poles")
    wait_drawn(page, lambda: page.locator("#drawing svg #layer-poles").count() == 0, "hide the poles")
    assert _shows_the_last_drawing(page)
    svg = _exported(page)
    assert 'id="layer-poles"' not in svg
    # and a different drawing is not the same (the comparison sees a difference)
    assert not _shown_is(page, svg.replace('id="layer-mechanism"', 'id="layer-other"'))
    # another mechanism: other names, other texts, other symbols in the same places
    page.select_option("#mechanism", "library:slider-crank-centric")
    wait_drawn(page, lambda: page.inner_text("#title") == linkwork.load("library:slider-crank-centric").name,
               "open the slider-crank")
    assert _shows_the_last_drawing(page)


def test_a_drag_frame_writes_only_the_numbers_that_change(page):
    """A frame of a drag writes into the page, outside the drawing, only the numbers that
    changed (any other write lays out the page and with it the drawing): dragging the coupler
    point C at a fixed input moves C alone, so C's two numbers are all that is written. Each
    number sits whole in its box of fixed size."""
    page.check("#edit")
    page.wait_for_timeout(300)
    a = _client_of(page, (15.0, 25.0))  # C at the design position
    page.mouse.move(*a)
    page.mouse.down()
    page.evaluate("""() => {
        window.written = [];
        new MutationObserver((records) => {
            for (const r of records) {
                const el = r.target.nodeType === Node.ELEMENT_NODE ? r.target : r.target.parentElement;
                if (el.closest('#drawing')) continue;  // the drawing itself
                const row = el.closest('tr');
                window.written.push([el.id || el.className, row ? row.dataset.point : null, r.type]);
            }
        }).observe(document.body, {subtree: true, childList: true, attributes: true, characterData: true});
    }""")
    for k in range(1, 4):
        page.mouse.move(a[0] + 4 * k, a[1] - 3 * k)
        wait_drawn(page, lambda: json.loads(page.get_attribute("#drawing", "data-moved")).get("C")
                   is not None and page.evaluate("window.written.length") >= 2 * k - 1,
                   "draw the frame")
    page.wait_for_timeout(300)
    written = page.evaluate("window.written")
    page.mouse.up()
    assert written and {tuple(w) for w in written} <= {("num", "C", "childList")}, written
    # C's numbers are the engine's position of the moved design at the input shown
    moved = json.loads(page.get_attribute("#drawing", "data-moved"))["C"]
    text = resolve("library:crank-rocker")[1].replace("C  = [15, 25]", f"C  = [{moved[0]!r}, {moved[1]!r}]")
    mech = load_text(text)
    assert np.allclose(mech.points["C"], moved)
    want = linkwork.solve(mech, drawn_input(page)).point("C").position[0]
    assert number_row(page, "C") == pytest.approx(tuple(want), abs=1e-4)
    assert page.eval_on_selector_all("#numbers .num", "es => es.every(e => e.scrollWidth <= e.clientWidth)")


def test_an_unassemblable_drag_shows_the_engines_message(page):
    """At 180° the crank's end A is at (−10, 0); dragged out to (−25, 0) it makes a crank of 25,
    whose chain cannot close there: |A O4| = 65 > coupler + rocker = √925 + √1000 ≈ 62.0."""
    sol = linkwork.whole_motion(MECH)
    k = int(np.argmin(np.abs(sol.inputs[:, 0] - math.pi)))
    assert sol.inputs[k, 0] == pytest.approx(math.pi)
    page.focus("#input-slider")
    for _ in range(k):
        page.keyboard.press("ArrowRight")
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([math.pi]), "go to 180°")
    page.check("#edit")
    # (the screen places of the targets in the drawing the drag starts on: the page reads the
    # pointer in it, while the drawings redrawn meanwhile have layouts of their own)
    a, b, back = (_client_of(page, xy) for xy in ((-10.0, 0.0), (-25.0, 0.0), (-12.0, 0.0)))
    page.mouse.move(*a)
    page.mouse.down()
    for f in np.linspace(0, 1, 8)[1:]:
        page.mouse.move(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]))
        page.wait_for_timeout(40)
    page.wait_for_selector("#error:not([hidden])", timeout=20_000)
    assert "cannot be assembled" in page.inner_text("#error")
    assert page.locator("#drawing.stale").count() == 1  # the last good drawing, greyed
    # back to a crank that closes: the message goes, the drawing is current again
    page.mouse.move(*back)
    page.wait_for_selector("#error[hidden]", state="attached", timeout=20_000)
    page.mouse.up()
    assert math.isclose(drawn_input(page)[0], math.pi, abs_tol=0.05)


def test_a_bad_file_shows_the_error_message(page):
    text = resolve("library:crank-rocker")[1].replace('coupler = ["A", "B", "C"]', 'coupler = ["A", "B", "X"]')
    with pytest.raises(LinkworkError) as exc:
        load_text(text, source="bad.toml")
    page.set_input_files("#upload", files=[{"name": "bad.toml", "mimeType": "text/plain",
                                             "buffer": text.encode()}])
    page.wait_for_selector("#error:not([hidden])", timeout=20_000)
    assert page.inner_text("#error") == str(exc.value)
    # the drawing of the mechanism open before stays
    assert page.inner_text("#title") == "Crank-rocker four-bar"


def test_an_unassemblable_position_shows_the_engines_message(page):
    # a crank of 25: at 180° |A O4| = 65 > coupler + rocker ≈ 62, the chain cannot close
    text = resolve("library:crank-rocker")[1].replace("A  = [0, 10]", "A  = [0, 25]")
    page.set_input_files("#upload", files=[{"name": "long.toml", "mimeType": "text/plain",
                                             "buffer": text.encode()}])
    wait_drawn(page, lambda: page.inner_text("#description") and
               json.loads(page.get_attribute("#drawing", "data-input") or "[0]") == pytest.approx([math.pi / 2]),
               "open the long crank")
    # the whole motion of this rocker stops at its limits: every sample is assembled
    sol = linkwork.whole_motion(load_text(text))
    assert page.locator("#status-strip span.unreachable").count() == int(np.sum(sol.status == 2))


@pytest.mark.parametrize("layer", ["poles", "pole-lines", "centrodes", "inflection", "return",
                                   "bresse", "gamma", "paths", "velocities", "accelerations"])
def test_layer_toggles(page, layer):
    assert page.locator(f"#drawing svg #layer-{layer}").count() == 0
    page.check(f"#show-{layer}")
    wait_drawn(page, lambda: page.locator(f"#drawing svg #layer-{layer}").count() == 1,
               f"draw the {layer} layer")
    assert page.locator(f"#drawing svg #layer-{layer} > *").count() > 0
    page.uncheck(f"#show-{layer}")
    wait_drawn(page, lambda: page.locator(f"#drawing svg #layer-{layer}").count() == 0,
               f"hide the {layer} layer")


def test_velocity_plan(page):
    page.check("#show-velocity-plan")
    wait_drawn(page, lambda: "velocity plan" in page.inner_text("#drawing"), "draw the velocity plan")
    assert page.is_hidden("#error")
    page.check("#show-acceleration-plan")
    wait_drawn(page, lambda: "acceleration plan" in page.inner_text("#drawing"), "draw the acceleration plan")
    assert not page.is_checked("#show-velocity-plan")


def _api(server, path, body):
    import urllib.request
    req = urllib.request.Request(f"{server}{path}", data=json.dumps(body).encode(),
                                 headers={"content-type": "application/json"})
    with urllib.request.urlopen(req, timeout=60) as r:
        return json.loads(r.read())


def test_a_construction_played_step_by_step(page, server):
    from linkwork.constructions import CONSTRUCTIONS
    options = page.locator("#construction option").evaluate_all("els => els.map(e => e.value)")
    assert options == [""] + list(CONSTRUCTIONS)  # every construction the engine offers
    api = _api(server, "/api/construction", {"source": {"library": "crank-rocker"}, "name": "kennedy"})
    page.select_option("#construction", "kennedy")
    wait_drawn(page, lambda: page.inner_text("#step-text") == api["steps"][0], "show the first step")
    assert page.inner_text("#step-count") == f"step 1 of {len(api['steps'])}"
    assert page.is_disabled("#step-back")
    page.click("#step-forward")
    wait_drawn(page, lambda: page.inner_text("#step-text") == api["steps"][1], "show the second step")
    # the drawing is the construction up to that step: the API's drawing for step 1
    want = _api(server, "/api/drawing", {"source": {"library": "crank-rocker"}, "at": [math.pi / 2],
                                         "layers": ["mechanism"], "construction": "kennedy", "step": 1})
    assert page.locator("#drawing svg").evaluate("e => e.outerHTML").count("<path") == \
        want["svg"].count("<path")
    page.click("#step-back")
    wait_drawn(page, lambda: page.inner_text("#step-text") == api["steps"][0], "step back")
    # a construction the mechanism does not allow: the engine's message, the mechanism still drawn
    page.select_option("#construction", "klein")
    page.wait_for_selector("#error:not([hidden])", timeout=20_000)
    assert "klein: " in page.inner_text("#error") and "slider-crank" in page.inner_text("#error")
    assert page.inner_text("#step-text") == ""
    page.select_option("#construction", "")
    wait_drawn(page, lambda: page.is_hidden("#error"), "drop the construction")


@pytest.mark.parametrize("key, values", [
    ("point:C:y", lambda sol: sol.point("C").position[:, 1]),
    ("point:B:v", lambda sol: np.hypot(*sol.point("B").velocity.T)),
    ("link:rocker:angle", lambda sol: np.degrees(sol.link("rocker").angle)),
    ("link:coupler:alpha", lambda sol: sol.link("coupler").alpha),
])
def test_plot_over_the_motion_marks_the_input_and_its_extremes_are_the_engines(page, key, values):
    sol = linkwork.whole_motion(MECH)
    page.select_option("#quantity", key)
    page.wait_for_selector("#plot svg", timeout=30_000)
    svg = page.locator("#plot svg")
    v = values(sol)
    assert float(svg.get_attribute("data-max")) == pytest.approx(np.nanmax(v), rel=1e-12, abs=1e-12)
    assert float(svg.get_attribute("data-min")) == pytest.approx(np.nanmin(v), rel=1e-12, abs=1e-12)
    assert int(svg.get_attribute("data-argmax")) == int(np.nanargmax(v))
    assert svg.locator("polyline.curve").count() >= 1
    assert svg.get_attribute("data-current") == "0"
    # the slider moves the mark
    page.focus("#input-slider")
    for _ in range(10):
        page.keyboard.press("ArrowRight")
    wait_drawn(page, lambda: page.get_attribute("#plot svg", "data-current") == "10", "move the mark")


def selected_rows(pg) -> dict[str, tuple[float, str]]:
    rows = pg.locator("#selected tr").evaluate_all(
        "trs => trs.map(r => [r.dataset.quantity, r.cells[1].textContent, r.cells[2].textContent])")
    return {k: (float(v), unit) for k, v, unit in rows}


def test_clicking_selects_a_point_a_link_or_a_pair(page):
    """(The panel shows four decimals.) At the design position (crank up, 60 rpm = 2π rad/s): the crank's end A moves at
    |v| = 10 mm · 2π/s, its acceleration is centripetal, 10 mm · (2π/s)²."""
    w = 2 * math.pi
    page.mouse.click(*_client_of(page, (0.0, 10.0)))
    wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == "point:A", "select A")
    rows = selected_rows(page)
    assert rows["x"] == (pytest.approx(0.0, abs=1e-9), "mm") and rows["y"] == (pytest.approx(10.0, abs=5e-5), "mm")
    assert rows["|v|"] == (pytest.approx(10 * w, abs=5e-5), "mm/s")
    assert rows["vx"] == (pytest.approx(-10 * w, abs=5e-5), "mm/s")
    assert rows["|a|"] == (pytest.approx(10 * w * w, abs=5e-5), "mm/s²")
    assert page.input_value("#selection") == "point:A"
    # a second click on a point that is a pair selects the pair: O2's relative ω is the crank's
    page.mouse.click(*_client_of(page, (0.0, 0.0)))
    wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == "point:O2", "select O2")
    page.mouse.click(*_client_of(page, (0.0, 0.0)))
    wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == "joint:O2", "select the pair O2")
    assert selected_rows(page)["ω"] == (pytest.approx(w, abs=5e-5), "rad/s")
    # the middle of the crank's bar: the crank, at 90°, turning at 2π rad/s
    page.mouse.click(*_client_of(page, (0.0, 5.0)))
    wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == "link:crank", "select the crank")
    rows = selected_rows(page)
    assert rows["angle"] == (pytest.approx(90.0, abs=5e-5), "°") and rows["ω"] == (pytest.approx(w, abs=5e-5), "rad/s")
    # the numbers follow the input: the coupler point C, 40 samples on, as the engine solves it
    page.select_option("#selection", "point:C")
    page.focus("#input-slider")
    for _ in range(40):
        page.keyboard.press("ArrowRight")
    k = float(linkwork.whole_motion(MECH).inputs[40, 0])
    wait_drawn(page, lambda: json.loads(page.get_attribute("#selected", "data-input") or "[0]") ==
               pytest.approx([k], abs=1e-15) and page.get_attribute("#selected", "data-selected") == "point:C",
               "show C at the new input")
    sol = linkwork.solve(MECH, [k])
    rows = selected_rows(page)
    assert (rows["x"][0], rows["y"][0]) == pytest.approx(tuple(sol.point("C").position[0]), abs=1e-4)
    assert rows["|a|"][0] == pytest.approx(np.hypot(*sol.point("C").acceleration[0]), abs=1e-4)


def test_traced_paths_are_those_chosen(page):
    page.check("#show-paths")
    wait_drawn(page, lambda: page.locator("#drawing svg [id^=path-]").count() == 3, "trace every path")
    page.select_option("#paths-of", ["C"])
    wait_drawn(page, lambda: page.locator("#drawing svg [id^=path-]").evaluate_all("es => es.map(e => e.id)")
               == ["path-C"], "trace C's path only")


def test_exports(page):
    from linkwork.kinematics.export import csv_lines
    page.check("#show-poles")
    wait_drawn(page, lambda: page.locator("#drawing svg #layer-poles").count() == 1, "draw the poles")
    shown = page.locator("#drawing svg").evaluate("e => e.outerHTML")
    with page.expect_download() as dl:
        page.click("#export-svg")
    svg = Path(dl.value.path()).read_text()
    assert dl.value.suggested_filename == "crank-rocker.svg"
    assert 'id="layer-poles"' in svg and svg.count("<circle") == shown.count("<circle")
    with page.expect_download() as dl:
        page.click("#export-png")
    assert dl.value.suggested_filename == "crank-rocker.png"
    assert Path(dl.value.path()).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with page.expect_download(timeout=60_000) as dl:
        page.click("#export-csv")
    assert dl.value.suggested_filename == "crank-rocker-motion.csv"
    assert Path(dl.value.path()).read_text() == "".join(csv_lines(linkwork.whole_motion(MECH), units=True))


def _edit(pg, op, name, **fields):
    pg.select_option("#edit-op", op)
    pg.fill("#edit-name", name)
    for field, value in fields.items():
        pg.fill(f"#edit-{field}", value)
    pg.click("#edit-apply")
    wait_drawn(pg, lambda: pg.get_attribute("#editor", "data-applied") in ("ok", "error"), f"apply {op} {name}")
    return pg.get_attribute("#editor", "data-applied")


def test_editing_adds_and_deletes_points_links_and_joints(page):
    """The crank-rocker becomes a Stephenson six-bar: a dyad C–F–O6 hung between the coupler
    point C and a new frame pivot O6; each edit is read by the engine, and the intermediate files
    that do not build show its message. The expected file is written here by hand."""
    text = resolve("library:crank-rocker")[1]
    want = (text.replace('C  = [15, 25]\n', 'C  = [15, 25]\nO6 = [70, 30]\nF = [45, 45]\n')
            .replace('frame   = ["O2", "O4"]', 'frame = ["O2", "O4", "O6"]')
            .replace('rocker  = ["B", "O4"]\n', 'rocker  = ["B", "O4"]\nl5 = ["C", "F"]\nl6 = ["F", "O6"]\n')
            .replace('O4 = { type = "revolute", links = ["rocker", "frame"] }\n',
                     'O4 = { type = "revolute", links = ["rocker", "frame"] }\n'
                     'C = { type = "revolute", links = ["coupler", "l5"] }\n'
                     'F = { type = "revolute", links = ["l5", "l6"] }\n'
                     'O6 = { type = "revolute", links = ["l6", "frame"] }\n'))
    six = load_text(want)
    assert _edit(page, "add-point", "O6", link="frame", xy="70, 30") == "ok"
    wait_drawn(page, lambda: page.locator("#numbers tr[data-point='O6']").count() == 1, "list O6")
    assert number_row(page, "O6") == (70.0, 30.0)
    # a link whose point does not exist yet: the engine's message, and the text stays for the next edit
    assert _edit(page, "add-link", "l5", members="C, F") == "error"
    msg = page.inner_text("#error")
    with pytest.raises(LinkworkError) as exc:
        load_text(page.input_value("#edit-text"), source="crank-rocker.toml")
    assert msg == str(exc.value) and "F" in msg
    assert page.locator("#drawing.stale").count() == 1
    assert _edit(page, "add-point", "F", link="l5", xy="45, 45") == "error"  # l5 has no pair yet
    assert _edit(page, "add-link", "l6", members="F, O6") == "error"
    assert _edit(page, "add-joint", "C", members="coupler, l5") == "error"
    assert _edit(page, "add-joint", "F", members="l5, l6") == "error"
    assert _edit(page, "add-joint", "O6", members="l6, frame") == "ok"
    assert page.is_hidden("#error")
    got = load_text(page.input_value("#edit-text")).points
    assert {p: tuple(v) for p, v in got.items()} == {p: tuple(v) for p, v in six.points.items()}
    assert page.input_value("#edit-text").replace(" ", "") == want.replace(" ", "")
    # the six-bar is solved where the four-bar was (the design position): F as the engine puts it
    assert number_row(page, "F") == pytest.approx((45.0, 45.0), abs=1e-4)
    page.wait_for_selector("#structure dd")
    wait_drawn(page, lambda: "1" in page.inner_text("#structure"), "the six-bar's structure")
    # and deleting takes it back apart: the pair O6 first (the engine says what is then wrong)
    assert _edit(page, "delete-joint", "O6") == "error"
    assert "O6" in page.inner_text("#error") or "l6" in page.inner_text("#error")
    for op, name in (("delete-joint", "F"), ("delete-joint", "C"), ("delete-link", "l6"),
                     ("delete-link", "l5"), ("delete-point", "F")):
        _edit(page, op, name)
    assert _edit(page, "delete-point", "O6") == "ok", page.inner_text("#error")
    assert page.input_value("#edit-text").replace(" ", "") == text.replace(" ", "")


def test_an_edit_that_is_incomplete_is_refused_by_the_form(page):
    page.select_option("#edit-op", "add-point")
    page.fill("#edit-name", "D")
    page.fill("#edit-link", "coupler")
    page.fill("#edit-xy", "1")
    page.click("#edit-apply")
    page.wait_for_selector("#error:not([hidden])")
    assert page.inner_text("#error") == "edit: give the design coordinates as x, y"


def test_a_mechanism_with_two_drivers(page):
    """Heusinger's valve gear has two drivers (the wheel O and the reversing arm RV): the page
    asks for each drawing with one value per driver and shows both inputs."""
    mech = linkwork.load("library:heusinger-valve-gear")
    page.select_option("#mechanism", "library:heusinger-valve-gear")
    wait_drawn(page, lambda: page.inner_text("#title") == mech.name and
               page.locator("#numbers tr[data-point='P45']").count() == 1, "open the valve gear", timeout=120)
    assert page.is_hidden("#error")
    want = [mech.driver_input_at_design(d) for d in mech.drivers]
    assert drawn_input(page) == pytest.approx(want, abs=1e-12)
    assert page.inner_text("#input-value") == ", ".join(
        f"{d.joint} {math.degrees(v):.2f}°" for d, v in zip(mech.drivers, want))


def test_keyboard_only(page):
    """The main controls are reached with Tab and worked with keys alone."""
    page.focus("#mechanism")
    seen = []
    for _ in range(80):
        seen.append(page.evaluate("document.activeElement.id"))
        page.keyboard.press("Tab")
    for control in ("mechanism", "upload", "export-svg", "export-png", "export-csv", "save", "drawing",
                    "quantity", "play", "speed", "input-slider", "show-poles", "show-velocity-plan",
                    "paths-of", "selection", "edit", "construction", "edit-op", "edit-name", "edit-apply"):
        assert control in seen, control
    # a construction chosen and stepped with keys
    page.focus("#construction")
    page.keyboard.press("ArrowDown")  # the first construction of the list
    first = page.input_value("#construction")
    assert first == "rotated-velocities"
    from linkwork.constructions import construct
    steps = [s.text for s in construct(first, MECH, linkwork.solve(MECH, [math.pi / 2])).steps]
    wait_drawn(page, lambda: page.inner_text("#step-text") == steps[0], "show the first step")
    page.focus("#step-forward")
    page.keyboard.press("Enter")
    wait_drawn(page, lambda: page.inner_text("#step-text") == steps[1], "step with Enter")
    page.focus("#drawing")
    page.keyboard.press(".")
    wait_drawn(page, lambda: page.inner_text("#step-text") == steps[2], "step with the period key")
    page.keyboard.press(",")
    wait_drawn(page, lambda: page.inner_text("#step-text") == steps[1], "step back with the comma key")
    # the motion: arrows go one sample, Space plays and pauses
    page.keyboard.press("ArrowRight")
    page.keyboard.press("ArrowRight")
    assert page.input_value("#input-slider") == "2"
    sol = linkwork.whole_motion(MECH)
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([sol.inputs[2, 0]], abs=1e-15), "draw sample 2")
    page.keyboard.press("Space")
    assert page.get_attribute("#play", "aria-pressed") == "true"
    page.keyboard.press("Space")
    assert page.get_attribute("#play", "aria-pressed") == "false"
    # a design point moved with Alt+arrows: A one step (0.1 mm for this drawing of 40 mm) up
    page.focus("#selection")
    page.select_option("#selection", "point:A")
    page.check("#edit")
    page.focus("#drawing")
    page.keyboard.press("Alt+ArrowUp")
    wait_drawn(page, lambda: json.loads(page.get_attribute("#drawing", "data-moved") or "{}").get("A")
               == pytest.approx([0.0, 10.1]), "move A up")


def test_numbers_carry_units(page):
    assert page.inner_text("#numbers thead").split() == ["point", "x", "[mm]", "y", "[mm]"]
    assert page.inner_text("#input-value").endswith("°")
    for choice in ("point:C", "link:coupler", "joint:B"):
        page.select_option("#selection", choice)
        wait_drawn(page, lambda: page.get_attribute("#selected", "data-selected") == choice, f"select {choice}")
        rows = page.locator("#selected tr").evaluate_all(
            "trs => trs.map(r => [r.cells[0].textContent, r.cells[1].textContent, r.cells[2].textContent])")
        assert rows and all(unit.strip() for _, _, unit in rows), rows
        units = {k: u for k, _, u in rows}
        want = {"point:C": {"x": "mm", "|v|": "mm/s", "|a|": "mm/s²"},
                "link:coupler": {"angle": "°", "ω": "rad/s", "α": "rad/s²"},
                "joint:B": {"angle": "°", "ω": "rad/s", "α": "rad/s²"}}[choice]
        assert {k: units[k] for k in want} == want
    for key, unit in (("point:C:x", "mm"), ("point:C:a", "mm/s²"), ("link:rocker:omega", "rad/s")):
        page.select_option("#quantity", key)
        wait_drawn(page, lambda: page.get_attribute("#plot svg", "data-unit") == unit, f"plot {key}")
        assert f"[{unit}]" in page.inner_text("#plot")
        assert page.locator(f"#quantity option[value='{key}']").inner_text().endswith(f"[{unit}]")


def test_keys_move_a_point_like_a_drag(browser, server):
    """Alt+arrows solve the moved design at the input shown, as a drag's frames do, without the
    whole motion; it is asked for once, when the keys rest (the drawings over HTTP or the
    drawing socket)."""
    page, net, errors = _open(browser, server)
    try:
        _keys_move_a(page, net)
    finally:
        page.close()
    assert not errors, errors


def _keys_move_a(page, net) -> None:
    page.focus("#input-slider")
    for _ in range(30):
        page.keyboard.press("ArrowRight")
    wait_drawn(page, lambda: page.eval_on_selector("#input-slider", "e => e.value") == "30", "move the slider")
    u = float(linkwork.whole_motion(MECH).inputs[30, 0])
    wait_drawn(page, lambda: drawn_input(page) == pytest.approx([u], abs=1e-15), "draw sample 30")
    asked: list[tuple[str, dict]] = []
    page.on("request", lambda r: asked.append((r.url.split("/api/")[-1], json.loads(r.post_data or "{}")))
            if "/api/" in r.url else None)
    sent = len(net.sent)
    page.select_option("#selection", "point:A")
    page.check("#edit")
    page.focus("#drawing")
    for _ in range(3):  # A up by three steps of 0.1 mm, quicker than the keys' rest
        page.keyboard.press("Alt+ArrowUp")
        page.wait_for_timeout(60)

    def moved_a():
        return json.loads(page.get_attribute("#drawing", "data-moved") or "{}").get("A")

    wait_drawn(page, lambda: moved_a() == pytest.approx([0.0, 10.3]), "draw A moved up three times")
    drawings = [body for what, body in asked if what == "drawing"] + \
        [json.loads(t) for t in net.sent[sent:]]
    assert drawings and all(body.get("motion") is False for body in drawings)
    assert all(body["at"] == pytest.approx([u], abs=1e-15) for body in drawings)
    assert not [w for w, _ in asked if w == "motion"] or \
        [body["source"]["points"]["A"] for w, body in asked if w == "motion"] == [moved_a()]
    # the drawn numbers: the moved file solved at the same input
    ax, ay = moved_a()
    text = resolve("library:crank-rocker")[1].replace("A  = [0, 10]", f"A  = [{ax!r}, {ay!r}]")
    want = linkwork.solve(load_text(text), [u]).point("C").position[0]
    assert drawn_input(page) == pytest.approx([u], abs=1e-15)
    assert number_row(page, "C") == pytest.approx(tuple(want), abs=1e-4)
    # the keys rest: the whole motion of the new design, once
    wait_drawn(page, lambda: json.loads(page.get_attribute("#input-slider", "data-moved") or "{}").get("A")
               == pytest.approx([0.0, 10.3]), "load the new design's motion")
    assert [body["source"]["points"]["A"] for w, body in asked if w == "motion"] == [[ax, ay]]


@pytest.mark.parametrize("size", [(1366, 768), (1280, 720)])
def test_drawing_and_plot_fit_a_laptop_screen(browser, server, size):
    pg = browser.new_page(viewport={"width": size[0], "height": size[1]})
    try:
        pg.goto(f"{server}/?library=heusinger-valve-gear")
        pg.wait_for_selector("body[data-ready=true]", timeout=60_000)
        pg.select_option("#quantity", "point:VX:x")
        pg.wait_for_selector("#plot svg", timeout=60_000)
        fit = pg.evaluate("""() => {
            const plot = document.querySelector('#plot svg').getBoundingClientRect();
            const drawing = document.querySelector('#drawing svg').getBoundingClientRect();
            return {page: document.documentElement.scrollHeight, screen: window.innerHeight,
                    plot: plot.bottom, plotHeight: plot.height, drawing: drawing.height}; }""")
        assert fit["page"] <= fit["screen"], fit  # no page scroll
        assert fit["plot"] <= fit["screen"] and fit["plotHeight"] > 100, fit
        assert fit["drawing"] > 250, fit
    finally:
        pg.close()


# ------------------------------------------------------------------ the drawing socket
class _Network:
    """What a page sent and received: the drawing socket's messages, the HTTP drawing requests."""

    def __init__(self, pg) -> None:
        self.sent: list[str] = []
        self.received: list[str] = []
        self.http: list[str] = []
        pg.on("websocket", self._socket)
        pg.on("request", lambda r: self.http.append(r.post_data or "")
              if r.url.endswith("/api/drawing") else None)

    def _socket(self, ws) -> None:
        if ws.url.endswith("/api/drawing/ws"):
            ws.on("framesent", lambda p: self.sent.append(p if isinstance(p, str) else p.decode()))
            ws.on("framereceived", lambda p: self.received.append(p if isinstance(p, str) else p.decode()))


def _open(browser, server, script: str | None = None):
    """The crank-rocker in a new page whose network is watched from the start; `script` runs
    in the page before its own."""
    pg = browser.new_page(viewport={"width": 1280, "height": 900})
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    net = _Network(pg)
    if script:
        pg.add_init_script(script)
    pg.goto(f"{server}/?library=crank-rocker")
    pg.wait_for_selector("body[data-ready=true]", timeout=30_000)
    return pg, net, errors


def _drag_c(pg) -> None:
    """C dragged in five steps, the button held (the drag's frames, without the whole motion)."""
    pg.check("#edit")
    pg.wait_for_timeout(300)
    a = _client_of(pg, (15.0, 25.0))
    pg.mouse.move(*a)
    pg.mouse.down()
    for k in range(1, 6):
        pg.mouse.move(a[0] + 4 * k, a[1] - 3 * k)
        pg.wait_for_timeout(60)


def _frames(pg) -> list[dict]:
    return pg.evaluate("window.linkworkFrames")


def test_a_drag_over_the_socket_shows_the_http_drawing(browser, server):
    """The drag's frames go over the WebSocket; the last shows, element for element, the SVG
    that `POST /api/drawing` answers to the same request."""
    import httpx

    pg, net, errors = _open(browser, server)
    try:
        pg.wait_for_timeout(300)  # the socket opens with the page
        before = len(net.http)
        _drag_c(pg)
        wait_drawn(pg, lambda: len(_frames(pg)) >= 1 and len(net.received) == len(net.sent),
                   "draw the drag's frames")
        pg.wait_for_timeout(300)
        assert len(net.received) == len(net.sent) >= 1
        assert {f["via"] for f in _frames(pg)} == {"socket"}
        assert net.http[before:] == []  # no drawing over HTTP while the socket is open
        last = json.loads(net.sent[-1])
        assert last["source"]["points"]["C"] != [15.0, 25.0] and last["motion"] is False
        http = httpx.post(f"{server}/api/drawing", json=last, timeout=30)
        assert http.status_code == 200
        assert json.loads(net.received[-1])["body"]["svg"] == http.json()["svg"]
        assert _shown_is(pg, http.json()["svg"])
        pg.mouse.up()
    finally:
        pg.close()
    assert not errors, errors


def test_an_unassemblable_drag_over_the_socket_shows_the_engines_message(browser, server):
    pg, net, errors = _open(browser, server)
    try:
        pg.wait_for_timeout(300)  # the socket opens with the page
        test_an_unassemblable_drag_shows_the_engines_message(pg)
        answers = [json.loads(t) for t in net.received]
        refused = [a for a in answers if a["status"] == 400]
        assert refused and all(a["body"]["kind"] == "InputError" for a in refused)
        assert "cannot be assembled" in refused[0]["body"]["error"]
        assert {f["via"] for f in _frames(pg)} == {"socket"}
    finally:
        pg.close()
    assert not errors, errors


# a WebSocket that something between refuses (the server answers the wrong path with 403)
NO_SOCKET = """window.WebSocket = class extends WebSocket {
    constructor(url, protocols) { super(url.replace("/api/drawing/ws", "/api/refused"), protocols); }
};"""


def test_without_the_socket_the_drag_goes_over_http(browser, server):
    pg, net, errors = _open(browser, server, NO_SOCKET)
    try:
        before = len(net.http)
        _drag_c(pg)
        wait_drawn(pg, lambda: len(_frames(pg)) >= 1, "draw the drag's frames")
        assert _shows_the_last_drawing(pg)
        assert {f["via"] for f in _frames(pg)} == {"http"}
        assert len(net.http) - before >= len(_frames(pg))
        assert net.received == []
        pg.mouse.up()
    finally:
        pg.close()
    assert not errors, errors
