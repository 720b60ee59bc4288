"""`linkwork structure`: the JSON document, the table, over- and under-constrained mechanisms
reported (exit 0), and user mistakes as one message (exit 2)."""

import json

import pytest
from typer.testing import CliRunner

from linkwork.cli import app
from mechanism_texts import TRIPLE_PARALLEL_CRANKS

runner = CliRunner()


def run(*args):
    return runner.invoke(app, list(args))


def test_json_document_of_a_crank_rocker():
    r = run("structure", "library:crank-rocker", "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["mechanism"] == "Crank-rocker four-bar"
    # four-bar: n = 4, g = 4, 3n − 2g = 4 (Pöschl 97)
    c = doc["counts"]
    assert (c["n"], c["g"], c["grubler_3n_minus_2g"], c["criterion"]) == (4, 4, 4, 0)
    assert doc["count_mobility"] == doc["real_mobility"] == 1
    assert doc["redundant_constraints"] == [] and doc["inputs_needed"] == 0
    assert doc["solution_order"] == [["crank"], ["coupler", "rocker"]]
    assert [g["name"] for g in doc["groups"]] == ["driving link (class I)", "dyad RRR (class II)"]
    assert doc["mechanism_class"] == 2 and doc["mechanism_class_roman"] == "II"
    (lp,) = doc["grashof"]
    assert lp["type"] == "crank-rocker" and lp["grashof"] == "Grashof"
    assert lp["dead_positions"]["time_ratio"] > 1
    assert doc["input_limits"] is None  # the crank turns fully


def test_inversion_name_in_the_json():
    r = run("structure", "library:oscillating-crank-slotted-lever", "--format", "json")
    doc = json.loads(r.output)
    (lp,) = doc["grashof"]
    assert lp["inversion"] == "II" and "schwingende Kurbelschleife" in lp["name"]


FIVE_BAR = """
name = "five-bar"
[points]
O1 = [0, 0]
A = [0, 10]
B = [20, 25]
C = [40, 10]
O2 = [40, 0]
[links]
frame = ["O1", "O2"]
l1 = ["O1", "A"]
l2 = ["A", "B"]
l3 = ["B", "C"]
l4 = ["C", "O2"]
[joints]
O1 = { type = "revolute", links = ["frame", "l1"] }
A = { type = "revolute", links = ["l1", "l2"] }
B = { type = "revolute", links = ["l2", "l3"] }
C = { type = "revolute", links = ["l3", "l4"] }
O2 = { type = "revolute", links = ["l4", "frame"] }
[driver]
joint = "O1"
"""


def test_over_closed_mechanism_is_reported_not_refused(tmp_path):
    f = tmp_path / "triple.toml"
    f.write_text(TRIPLE_PARALLEL_CRANKS)
    r = run("structure", str(f), "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    # n = 5, g = 6: count 0 (001c §101); the parallel cranks move: 1, one redundant equation
    assert doc["count_mobility"] == 0 and doc["real_mobility"] == 1
    assert len(doc["redundant_constraints"]) == 1 and doc["overclosed"] is True
    assert doc["groups"] is None and doc["solution_order"] is None
    assert "over-constrained" in doc["structure_error"]
    r = run("structure", str(f))
    assert r.exit_code == 0
    assert "übergeschlossen" in r.output and "No solution order" in r.output


def test_under_constrained_mechanism_says_how_many_inputs_it_needs(tmp_path):
    f = tmp_path / "five.toml"
    f.write_text(FIVE_BAR)
    r = run("structure", str(f), "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    # hinged pentagon: 2·5 − 15 + 4 = −1 (001c §86): two freedoms, one driver
    assert doc["real_mobility"] == 2 and doc["inputs_needed"] == 1
    assert "needs 1 more input" in doc["verdict"]
    assert doc["groups"] is None and "under-constrained" in doc["structure_error"]


def test_table_output():
    r = run("structure", "library:stephenson-iii-six-bar")
    assert r.exit_code == 0, r.output
    for text in ("counts as the seeds write them", "real mobility", "Assur groups in solution order",
                 "dyad RRR", "Grashof classification", "crank-rocker", "zwangläufig"):
        assert text in r.output


def test_output_file(tmp_path):
    out = tmp_path / "s.json"
    r = run("structure", "library:slider-crank-offset", "--format", "json", "-o", str(out))
    assert r.exit_code == 0 and r.output == ""
    doc = json.loads(out.read_text())
    (lp,) = doc["grashof"]
    assert lp["inversion"] == "I" and lp["lengths"]["offset"] == pytest.approx(20.0)


@pytest.mark.parametrize("args,message", [
    (("structure", "library:no-such-thing"), "no mechanism"),
    (("structure", "missing-file.toml"), "no mechanism file"),
])
def test_user_mistakes_are_one_message(args, message):
    r = run(*args)
    assert r.exit_code == 2
    assert message in r.output
    assert "Traceback" not in r.output


def test_bad_format_is_a_usage_error():
    r = run("structure", "library:crank-rocker", "--format", "csv")
    assert r.exit_code == 2
