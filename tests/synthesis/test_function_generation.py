"""Function generation (`linkwork.synthesis.function`) against independent closed forms: a
four-bar's input–output relation written out by circle intersection (test four_bar_by_hand)
and an offset slider-crank's s(φ) = a cos φ + √(b² − (e − a sin φ)²) (the library's
slider-crank-offset proportions) must give back their own lengths through Freudenstein's
constants K₁ = d/a, K₂ = d/c, K₃ = (a² − b² + c² + d²)/(2ac) (K₁ = 2a, K₂ = 2ae,
K₃ = a² + e² − b² for the slider); the engine, solving the written file, generates the
prescribed output at the precision points; Chebyshev's points for n = 3 on [1, 10] are
5.5 ∓ 4.5·cos 30° by hand."""

from __future__ import annotations

import numpy as np
import pytest

from four_bar_by_hand import A_LEN, B_LEN, C_LEN, O4, four_bar
from linkwork.errors import InputError
from linkwork.synthesis.function import FunctionTask, chebyshev_spacing, freudenstein, function_generator
from linkwork.synthesis.positions import SynthesisError


def psi_of(phi):
    """The output angle of the four-bar by hand at crank angles phi."""
    _, B = four_bar(np.atleast_1d(phi))
    v = B - O4
    return np.unwrap(np.arctan2(v[:, 1], v[:, 0])).reshape(np.shape(phi))


def test_chebyshev_points_by_hand():
    h = 4.5 * np.sqrt(3) / 2
    assert chebyshev_spacing(1, 10, 3) == pytest.approx([5.5 - h, 5.5, 5.5 + h], rel=1e-15)
    assert chebyshev_spacing(0, 1, 2) == pytest.approx([0.5 - 0.5 / np.sqrt(2), 0.5 + 0.5 / np.sqrt(2)])


def test_freudenstein_constants_of_a_known_four_bar():
    phi = np.radians([20.0, 60.0, 110.0])
    K, res = freudenstein(phi, psi_of(phi))
    a, b, c, d = A_LEN, B_LEN, C_LEN, 4.0
    assert K == pytest.approx([d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)], rel=1e-12)
    assert res < 1e-14


@pytest.mark.parametrize("n", [3, 5, 9])
def test_the_four_bar_is_found_again_and_the_engine_generates_its_function(n):
    """The function ψ(φ) of the four-bar by hand, prescribed through n Chebyshev points (least
    squares beyond three, still exact): the same lengths, and no structural error anywhere."""
    lo, hi = np.radians(15.0), np.radians(150.0)
    task = FunctionTask(lambda x: psi_of(x), (lo, hi), (lo, hi), tuple(psi_of(np.array([lo, hi]))))
    gen = function_generator(task, n, frame=4.0)
    assert gen.lengths == pytest.approx({"frame": 4.0, "input": A_LEN, "coupler": B_LEN, "output": C_LEN}, rel=1e-9)
    x, err = gen.structural_error(121)
    assert np.abs(err).max() < 1e-9


def test_log_function_three_chebyshev_points():
    """y = log₁₀ x on [1, 2], input 30° … 120°, output 60° … 150°: exact at the precision
    points (the engine's answer), an error between them that changes sign at each of them."""
    task = FunctionTask(np.log10, (1.0, 2.0), np.radians([30.0, 120.0]), np.radians([60.0, 150.0]))
    gen = function_generator(task, 3)
    assert gen.residual < 1e-12
    at = gen.generated(gen.precision) - task.output(gen.precision)
    assert np.abs(at).max() < 1e-9
    x, err = gen.structural_error(401)
    assert np.isfinite(err).all()
    assert np.abs(err).max() > 1e-4
    changes = x[np.flatnonzero(np.sign(err[:-1]) != np.sign(err[1:]))]
    for p in gen.precision:
        assert np.abs(changes - p).min() <= (x[1] - x[0]) * 1.01
    # least squares over more points: not exact at them
    ls = function_generator(task, 8)
    assert ls.residual > 1e-9 and ls.kind == "four-bar"


def test_out_of_reach_samples_are_marked():
    """y = log₁₀ x on [1, 10] with input 45° … 105° and output 135° … 225°: the four-bar from
    three Chebyshev points cannot be assembled near x = 1 (the diagonal O₄A is shorter than
    |b − c| there, by hand); those samples are NaN, the others finite."""
    task = FunctionTask(np.log10, (1.0, 10.0), np.radians([45.0, 105.0]), np.radians([135.0, 225.0]))
    gen = function_generator(task, 3)
    x, err = gen.structural_error(101)
    L = gen.lengths
    phi = task.input(x)
    diagonal = np.hypot(L["frame"] - L["input"] * np.cos(phi), L["input"] * np.sin(phi))
    reach = (diagonal >= abs(L["coupler"] - abs(L["output"]))) & (diagonal <= L["coupler"] + abs(L["output"]))
    assert not reach.all()
    assert np.array_equal(np.isfinite(err), reach)


def test_slider_crank_found_again():
    a, b, e = 50.0, 200.0, 20.0

    def s_of(phi):
        return a * np.cos(phi) + np.sqrt(b * b - (e - a * np.sin(phi)) ** 2)
    lo, hi = np.radians(10.0), np.radians(170.0)
    task = FunctionTask(s_of, (lo, hi), (lo, hi), (s_of(lo), s_of(hi)))
    gen = function_generator(task, 3, kind="slider-crank")
    assert gen.K == pytest.approx([2 * a, 2 * a * e, a * a + e * e - b * b], rel=1e-10)
    assert gen.lengths == pytest.approx({"input": a, "coupler": b, "offset": e}, rel=1e-10)
    x, err = gen.structural_error(91)
    assert np.abs(err).max() < 1e-9 * b
    gen6 = function_generator(task, np.linspace(lo, hi, 6), kind="slider-crank")
    assert gen6.lengths == pytest.approx({"input": a, "coupler": b, "offset": e}, rel=1e-9)


def test_bad_tasks_are_refused():
    with pytest.raises(InputError, match="range of x"):
        FunctionTask(np.log10, (2.0, 2.0), (0, 1), (0, 1))
    with pytest.raises(InputError, match="differ"):
        FunctionTask(np.cos, (-1.0, 1.0), (0, 1), (0, 1))
    task = FunctionTask(np.log10, (1.0, 10.0), np.radians([45.0, 105.0]), np.radians([135.0, 225.0]))
    with pytest.raises(SynthesisError, match="coincide"):
        function_generator(task, [2.0, 2.0, 3.0])
    with pytest.raises(InputError, match="at least three"):
        function_generator(task, 2)
    with pytest.raises(InputError, match="unknown function generator"):
        function_generator(task, 3, kind="six-bar")
