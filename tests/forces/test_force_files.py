"""[masses] and [loads] in mechanism files: units, errors that name key and line, mass data
required only when forces are computed, and the library's PMKS Stephenson III file reproducing
the reference reactions from its own mass data."""

import numpy as np
import pytest

import linkwork
import pmks_cases as P
from linkwork.errors import MechanismFileError, ModelError
from linkwork.forces import kinetostatics
from linkwork.io import dynamics_from_text, load_dynamics



def crank_rocker_text(extra: str) -> str:
    """The library's crank-rocker drawing without its [masses], plus `extra`."""
    from importlib import resources
    text = (resources.files("linkwork") / "library" / "crank-rocker.toml").read_text()
    return text.split("\n# Mass data")[0] + "\n" + extra


FULL = crank_rocker_text('''
[masses.crank]
mass = "200 g"
center = "A"
inertia = "20 g*cm^2"
[masses.coupler]
mass = 0.5
center = [15, 20]
[masses.rocker]
mass = 0.25
center = "B"
inertia = 1e-5
[loads]
gravity = true
[[loads.forces]]
link = "rocker"
point = "B"
force = { of = "input", at = [0, 180, 360], values = [[0, 1], [2, 3], [0, 1]], periodic = true }
[[loads.torques]]
link = "coupler"
torque = "300 N*mm"
[[loads.springs]]
links = ["frame", "coupler"]
points = [[0, 40], "C"]
stiffness = "2 N/mm"
free_length = "1 cm"
damping = "3 N*s/m"
[[loads.torsion_springs]]
joint = "B"
stiffness = 1
free_angle = 10
''')


def test_units_are_converted():
    dyn = dynamics_from_text(FULL)
    assert dyn.metres_per_unit == pytest.approx(1e-3)
    crank = dyn.masses["crank"]
    assert crank.mass == pytest.approx(0.2) and crank.inertia == pytest.approx(2e-6)
    np.testing.assert_array_equal(crank.center, [0, 10])
    assert dyn.loads.gravity.tolist() == [0, -9.80665]
    assert dyn.loads.couples[0].torque == pytest.approx(0.3)
    s = dyn.loads.springs[0]
    assert (s.stiffness, s.free_length, s.damping) == pytest.approx((2000.0, 10.0, 3.0))
    assert dyn.loads.torsion_springs[0].free_angle == pytest.approx(np.radians(10))
    table = dyn.loads.forces[0].force
    np.testing.assert_allclose(table(np.array([np.pi / 2, 2 * np.pi + np.pi / 2])), [[1, 2], [1, 2]])


def test_forces_from_a_file_balance_power():
    dyn = dynamics_from_text(FULL)
    fa = kinetostatics(dyn, linkwork.whole_motion(dyn.mechanism, step=np.radians(10)))
    assert fa.solved.all()
    assert np.abs(fa.power_residual / fa.power_scale).max() < 1e-9


@pytest.mark.parametrize("old, new, key, words", [
    ('center = "A"', 'center = "Q"', "masses.crank.center", "point 'Q'"),
    ('mass = 0.5', 'mass = "0.5 m"', "masses.coupler.mass", "cannot be converted to 'kg'"),
    ('mass = 0.5', 'mas = 0.5', "masses.coupler.mas", "did you mean 'mass'"),
    ('mass = 0.5', 'mass = -0.5', "masses.coupler.mass", "must not be negative"),
    ('mass = 0.5', 'mass = nan', "masses.coupler.mass", "finite"),
    ('mass = 0.5', 'mass = true', "masses.coupler.mass", "number"),
    ('[masses.rocker]', '[masses.rocket]', "masses.rocket", "link 'rocket'"),
    ('[0, 1]]', '[0, 1], [4, 4]]', "loads.forces[0].force", "3 abscissae but 4 values"),
    ('periodic = true', 'periodic = 1', "loads.forces[0].force.periodic", "boolean"),
    ('torque = "300 N*mm"', 'torque = [1, 2]', "loads.torques[0].torque", "number"),
    ('joint = "B"', 'joint = "X"', "loads.torsion_springs[0].joint", "joint 'X'"),
])
def test_errors_name_key_and_line(old, new, key, words):
    assert old in FULL
    text = FULL.replace(old, new, 1)
    line = next(i for i, ln in enumerate(text.splitlines(), 1) if new in ln)  # the changed line
    with pytest.raises(MechanismFileError) as exc:
        dynamics_from_text(text)
    assert exc.value.key == key and exc.value.line == line and words in str(exc.value)


def test_mass_data_needed_only_for_forces():
    text = crank_rocker_text("")
    assert linkwork.load_text(text).name  # the mechanism alone
    dyn = dynamics_from_text(text)  # no masses: fine until forces are asked for
    sol = linkwork.solve(dyn.mechanism, [0.5])
    with pytest.raises(ModelError, match="no mass data for link.*'crank'.*'coupler'.*'rocker'"):
        kinetostatics(dyn, sol)
    assert np.all(kinetostatics(dyn, sol, inertia=False).effort == 0)  # static, no loads
    grav = dynamics_from_text(text + "[loads]\ngravity = true\n")
    with pytest.raises(ModelError, match="gravity need"):
        kinetostatics(grav, sol, inertia=False)


def test_library_stephenson_reproduces_the_reference():
    # the library's own [masses] and [loads]; its pairs name their links in another order than
    # the reference reports (A: ground on AB, as here; B, C, D the other way round)
    meta, _, _ = P.case("stephenson_iii_example_2")
    dyn = load_dynamics("library:pmks-stephenson-iii")
    _, sol = P.motion(meta, dyn.mechanism, "stephenson_iii_example_2")
    ref = P.table(P.ROOT / "stephenson_iii_example_2" / "newton_gravity.csv")
    fa = kinetostatics(dyn, sol)
    np.testing.assert_allclose(fa.effort, ref["input_torque"], rtol=1e-9)
    scale = np.abs(np.stack([ref[k] for k in ref if k.endswith(("_fx", "_fy"))], 1)).max(axis=1)
    for j in meta["joints"]:
        jn, (first, second) = j["id"], dyn.mechanism.joint(j["id"]).links
        on = j["reported_force"].split(" on ")[1].split(" by ")[0]
        sign = 1.0 if on == second else -1.0
        err = np.abs(sign * fa.reactions[jn].force - np.c_[ref[f"{jn}_fx"], ref[f"{jn}_fy"]]).max(axis=1)
        assert (err / scale).max() < 1e-9, jn


def test_readme_example_loads_and_balances():
    from pathlib import Path
    from importlib import resources
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    block = readme.split("## Forces")[1].split("```toml\n")[1].split("```")[0]
    base = (resources.files("linkwork") / "library" / "slider-crank-centric.toml").read_text()
    dyn = dynamics_from_text(base.split("\n# Mass data")[0] + "\n" + block)
    fa = kinetostatics(dyn, linkwork.whole_motion(dyn.mechanism, step=np.radians(10)))
    assert fa.solved.all() and np.abs(fa.power_residual / fa.power_scale).max() < 1e-9
