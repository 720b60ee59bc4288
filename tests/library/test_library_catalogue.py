"""`linkwork library`: the shipped mechanisms grouped by category, searched by name and
description, every seed machine the library promises present and described with its source."""

from __future__ import annotations

import json
import re
import tomllib
from importlib import resources

import pytest
from typer.testing import CliRunner

from linkwork.cli import app
from linkwork.io.library import CATEGORIES, library_entries, library_names, search_library

runner = CliRunner()

SEED_MACHINES = {
    "heusinger-valve-gear": "valve gears", "heusinger-hinge-chain": "valve gears",
    "stephenson-link-motion": "valve gears", "kley-governor": "governors",
    "proell-governor": "governors", "holst-mechanism": "slider mechanisms",
    "rosenauer-shaping-machine": "slider mechanisms", "poeschl-quick-return-shaper": "slider mechanisms",
    "watt-straight-line": "straight-line linkages", "evans-straight-line": "straight-line linkages",
    "chebyshev-straight-line": "straight-line linkages", "peaucellier-inversor": "straight-line linkages",
    "hart-inversor": "straight-line linkages", "hart-straight-line": "straight-line linkages",
    "elliptic-straight-line": "straight-line linkages", "conchoidograph": "slider mechanisms",
    "swinging-block": "slider mechanisms", "alt-eight-link": "six-bars and multi-loop linkages",
    "alt-ten-link": "six-bars and multi-loop linkages", "galloway-kite": "four-bars",
    "roberval-balance": "over-closed chains", "pantograph": "over-closed chains",
    "five-bar": "several drivers", "crank-slider": "several drivers",
    "roemer-mechanism": "gears", "rosenauer-eight-link-chain": "six-bars and multi-loop linkages",
}


def test_the_library_holds_at_least_sixty_mechanisms_and_the_seed_machines():
    names = library_names()
    assert len(names) >= 60
    cat = {e["name"]: e["category"] for e in library_entries()}
    for n, c in SEED_MACHINES.items():
        assert cat[n] == c, n


@pytest.mark.parametrize("name", sorted(SEED_MACHINES))
def test_seed_files_name_their_section_and_a_german_or_latvian_name(name):
    doc = tomllib.loads((resources.files("linkwork") / "library" / f"{name}.toml").read_text())
    d = doc["description"]
    assert re.search(r"(Rosenauer|Pöschl)[^.]*(§|paper|Fig)", d), d
    assert re.search(r"German|Latvian", d), d
    assert doc["category"] in CATEGORIES


def test_every_mechanism_has_a_known_group_and_groups_come_in_order():
    entries = library_entries()
    assert {e["category"] for e in entries} <= set(CATEGORIES) - {"other"}
    ranks = [CATEGORIES.index(e["category"]) for e in entries]
    assert ranks == sorted(ranks)
    # files without the key are grouped by their pairs: a Geneva wheel is intermittent, a cam a cam
    cat = {e["name"]: e["category"] for e in entries}
    assert cat["geneva-4"] == "intermittent" and cat["radial-roller-cam"] == "cams"
    assert cat["elliptical-gears"] == "gears" and cat["proell-schwabe-valve-gear"] == "valve gears"


def test_search_matches_every_word_folding_umlauts():
    assert {e["name"] for e in search_library("proll")} >= {"proell-governor", "proell-schwabe-valve-gear"}
    assert {e["name"] for e in search_library("Pröll governor")} == {"proell-governor"}
    assert {e["name"] for e in search_library("inversor")} == {"peaucellier-inversor", "hart-inversor"}
    assert {e["name"] for e in search_library(None, "straight")} >= {
        "watt-straight-line", "chebyshev-straight-line", "peaucellier-inversor"}
    assert search_library("no such machine anywhere") == []


def test_cli_lists_groups_searches_and_refuses_an_unknown_group():
    r = runner.invoke(app, ["library", "--category", "governors", "--format", "json"])
    assert r.exit_code == 0, r.output
    assert [e["name"] for e in json.loads(r.output)] == ["kley-governor", "proell-governor"]
    r = runner.invoke(app, ["library", "--search", "Walschaerts"])
    assert r.exit_code == 0 and "heusinger-valve-gear" in r.output and "valve gears" in r.output
    r = runner.invoke(app, ["library"])
    assert r.exit_code == 0 and all(g in r.output for g in ("four-bars", "straight-line linkages"))
    r = runner.invoke(app, ["library", "--category", "spaceships"])
    assert r.exit_code != 0 and "no group 'spaceships'" in r.output
    r = runner.invoke(app, ["library", "--search", "zzzz"])
    assert r.exit_code == 1 and "no library mechanism matches 'zzzz'" in r.output


def test_catalogue_page_names_only_shipped_mechanisms_with_their_drawings():
    """docs/library.md (tools/library_catalogue.py) shows existing mechanisms and pictures."""
    from pathlib import Path
    docs = Path(__file__).resolve().parents[2] / "docs"
    text = (docs / "library.md").read_text()
    shown = set(re.findall(r"`library:([\w-]+)`", text)) - {"NAME"}
    assert shown and shown <= set(library_names())
    for name in re.findall(r"\(library/([\w-]+)\.svg\)", text):
        assert (docs / "library" / f"{name}.svg").read_text().lstrip().startswith("<")
