"""Command-line arguments at the boundary (issue 10): NaN, infinities and giant quantities are
refused with a message naming the option and the part; messages are printed as they are."""

import pytest
from typer.testing import CliRunner

from linkwork.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, list(args))


def _error(r) -> str:
    assert r.exit_code == 2, r.output
    assert r.exception is None or isinstance(r.exception, SystemExit), r.exception
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.output
    return lines[0]


@pytest.mark.parametrize("args,message", [
    (["--sweep", "nan:360:10"], "--sweep START: cannot read 'nan': not a finite number"),
    (["--sweep", "0:inf:10"], "--sweep STOP: cannot read 'inf': not a finite number"),
    (["--sweep", "0:360:nan"], "--sweep STEP: cannot read 'nan': not a finite number"),
    (["--sweep", "0:360:0"], "the step must not be zero"),
    (["--sweep", "0:1e12:1e-3"], "at most 10 000 000"),
    (["--at", "nan"], "--at: cannot read 'nan': not a finite number"),
    (["--at", "-inf"], "not a finite number"),
    (["--at", "1e400"], "is not a finite number"),
    (["--at", "9**9**9"], "exponents go up to 4"),
    (["--at", "10**400 deg"], "exponents go up to 4"),
    (["--at", "3 kg"], "give an angle"),
    (["--speed", "nan rpm", "--at", "0"], "not a finite number"),
    (["--speed", "9**9**9 rpm", "--at", "0"], "exponents go up to 4"),
])
def test_bad_input_values(args, message):
    assert message in _error(run("analyze", "library:crank-rocker", *args))


@pytest.mark.parametrize("args,message", [
    (["--dpi", "nan"], "--dpi nan: give a finite number greater than 0"),
    (["--dpi", "0"], "--dpi 0: give a finite number greater than 0"),
    (["--dpi", "-5"], "greater than 0"),
    (["--dpi", "1e9"], "at most 2400"),
    (["--length-scale", "inf"], "--length-scale inf"),
    (["--animate", "nan"], "--animate nan"),
])
def test_bad_draw_options(args, message, tmp_path):
    out = tmp_path / "m.png"
    assert message in _error(run("draw", "library:crank-rocker", "-o", str(out), *args))
    assert not out.exists()


def test_section_names_in_messages_are_printed_literally(tmp_path):
    text = runner.invoke(app, ["library", "crank-rocker"]).output
    bad = tmp_path / "m.toml"
    bad.write_text(text.replace('coupler = ["A", "B", "C"]', 'coupler = ["A", "X", "C"]'))
    msg = _error(run("analyze", str(bad)))
    assert msg.endswith("link 'coupler' lists point 'X', which is not in [points] (defined: A, B, C, O2, O4)")


def test_names_with_brackets_survive_in_tables(tmp_path):
    text = runner.invoke(app, ["library", "crank-rocker"]).output
    f = tmp_path / "m.toml"
    f.write_text(text.replace('name = "Crank-rocker four-bar"', 'name = "four-bar [bold]test[/bold]"'))
    r = run("analyze", str(f), "--at", "30")
    assert r.exit_code == 0 and "four-bar [bold]test[/bold]" in r.output


def test_structure_of_forty_loose_links_is_immediate():
    """40 links joined to nothing: named at once as undetermined (was: every subset tried)."""
    lines = ['name = "loose"', "[points]", "O = [0, 0]", "A = [0, 10]"]
    lines += [f"P{i} = [{i}, 1]\nQ{i} = [{i}, 2]" for i in range(40)]
    lines += ["[links]", 'frame = ["O"]', 'crank = ["O", "A"]']
    lines += [f'l{i} = ["P{i}", "Q{i}"]' for i in range(40)]
    lines += ["[joints]", 'O = { type = "revolute", links = ["frame", "crank"] }', "[driver]", 'joint = "O"']
    import tempfile, os
    with tempfile.TemporaryDirectory() as d:
        p = os.path.join(d, "loose.toml")
        open(p, "w").write("\n".join(lines) + "\n")
        r = run("structure", p, "--format", "json")
    assert r.exit_code == 0, r.output
    assert "no chain of pairs joins them to the frame" in r.output


def test_long_open_chain_orders_quickly_enough_to_finish():
    """An under-constrained chain of 25 links in a row: only connected sets are tried."""
    from linkwork.errors import StructureError
    from linkwork.model import Mechanism, Revolute
    from linkwork.topology.groups import solution_order
    n = 25
    pts = {f"P{i}": [10.0 * i, 0.0] for i in range(n + 1)}
    links = {"frame": ["P0"], **{f"l{i}": [f"P{i}", f"P{i + 1}"] for i in range(n)}}
    joints = [Revolute(f"P{i}", f"P{i}", ("frame" if i == 0 else f"l{i - 1}", f"l{i}")) for i in range(n)]
    mech = Mechanism.build(name="chain", points=pts, links=links, joints=joints,
                           drivers=[{"joint": "P0"}])
    with pytest.raises(StructureError, match="under-constrained"):
        solution_order(mech)
