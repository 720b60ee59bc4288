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
