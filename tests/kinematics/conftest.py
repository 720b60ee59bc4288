"""Fixtures of the kinematics tests."""

import pytest

from linkwork.kinematics import groups, solver


def _newton_kind(mech, group):
    return ("driver", {}) if group.drivers and group.size == 1 else ("generic", {})


@pytest.fixture
def newton(monkeypatch):
    """Every group but the driver's solved by Newton's method (a dyad by the continuation, as a
    group without a closed form); the solution orders planned before and after are forgotten."""
    monkeypatch.setattr(groups, "_classify", _newton_kind)
    solver.plan.cache_clear()
    yield
    solver.plan.cache_clear()
