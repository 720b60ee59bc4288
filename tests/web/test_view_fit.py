"""The workbench's view of the whole motion holds every element drawn: a Geneva or star wheel's
cross turns within its rim, which the view must hold at every position (the audit saw a third
of the Geneva wheel cut off: the fit knew cam profiles, not indexing wheels)."""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

import linkwork
from linkwork.web import create_app


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(None), raise_server_exceptions=False)


@pytest.mark.parametrize("name", ["geneva-4", "geneva-6"])
def test_the_view_holds_the_wheel_at_every_position(client, name):
    mech = linkwork.load(f"library:{name}")
    r = client.post("/api/drawing", json={"source": {"library": name}, "layers": ["mechanism"],
                                           "motion": True, "fit": "motion"})
    assert r.status_code == 200, r.text
    t = r.json()["transforms"]["mechanism"]
    lo, hi = np.array(t["lo"]), np.array(t["hi"])
    # the cross's rim passes through the slots' mouths, where the pin enters them at right
    # angles to the driver's crank (shock-free entry, Pöschl §25a): at sqrt(D² − r²) from the
    # wheel's centre C (D = MC the centre distance, r = MB the pin's radius); the cross turns
    # within that circle
    M, B, C = (np.asarray(mech.points[p], float) for p in ("M", "B", "C"))
    reach = np.sqrt(np.sum((C - M) ** 2) - np.sum((B - M) ** 2))
    assert np.all(lo <= C - reach) and np.all(C + reach <= hi), (lo, hi, C, reach)
