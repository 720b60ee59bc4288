"""Hamilton's construction (Pöschl §57, `synthesis.reflections`): the poles by perpendicular
bisectors, the half angles of the pole triangle and the homologous points by three reflections
of one image point, each compared inside the construction with the analytic values (poles from
the rotation formula, points moved by the displacements); here also checked against points of
a four-bar's coupler solved by hand (four_bar_by_hand) and by the mirror property itself."""

from __future__ import annotations

import numpy as np
import pytest

from four_bar_by_hand import generated, move
from linkwork.errors import InputError
from linkwork.synthesis.positions import Positions
from linkwork.synthesis.reflections import pole_construction


def reflect(p, a, b):
    d = (b - a) / np.hypot(*(b - a))
    f = a + ((p - a) @ d) * d
    return 2 * f - p


@pytest.mark.parametrize("triple", [(0, 1, 2), (1, 2, 3), (0, 2, 3)])
def test_poles_and_homologous_points_of_a_four_bar_coupler(triple):
    pos, A, B = generated([20, 50, 80, 110])
    D1 = np.array([0.7, 2.9])
    con = pole_construction(pos, D1, triple=triple).check()
    assert con.max_error() <= 1e-9
    i, j, k = triple
    el = con.elements
    # the homologous points against the coupler moved by hand
    for t, key in ((j, "D2"), (k, "D3")):
        assert np.allclose(el[key].obj.xy[0], move(pos.poses[i], pos.poses[t], D1), atol=1e-12)
    # D1, D2, D3: the mirror images of one point in the three sides of the pole triangle
    P12, P13, P23 = (el[n].obj.xy[0] for n in ("P12", "P13", "P23"))
    img = reflect(D1, P12, P13)
    assert np.allclose(reflect(img, P12, P23), el["D2"].obj.xy[0], atol=1e-12)
    assert np.allclose(reflect(img, P13, P23), el["D3"].obj.xy[0], atol=1e-12)
    # the triangle's angles: the half rotations (exterior at P13: φ13 = φ12 + φ23 in the book)
    th = pos.angle
    half = lambda a, b: abs(np.sin((th[b] - th[a]) / 2))  # noqa: E731
    def angle(V, U, W):
        u, w = U - V, W - V
        return np.arctan2(abs(u[0] * w[1] - u[1] * w[0]), u @ w)
    assert abs(np.sin(angle(P12, P13, P23))) == pytest.approx(half(i, j), abs=1e-12)
    assert abs(np.sin(angle(P23, P12, P13))) == pytest.approx(half(j, k), abs=1e-12)
    assert abs(np.sin(angle(P13, P12, P23))) == pytest.approx(half(i, k), abs=1e-12)


def test_translation_is_reported_as_degenerate():
    pos = Positions.from_poses(np.array([[0, 0, 0], [1, 0, 0], [2, 1, 0.3]]))
    con = pole_construction(pos)
    assert con.degenerate[0]
    assert any("translation" in m for m in con.messages())


def test_bad_triples_are_refused():
    pos, _, _ = generated([20, 50, 80])
    with pytest.raises(InputError, match="three different"):
        pole_construction(pos, triple=(0, 0, 1))
    with pytest.raises(InputError, match="three different"):
        pole_construction(pos, triple=(0, 1, 3))
