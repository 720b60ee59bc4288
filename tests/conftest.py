"""Shared test fixtures: where the project's shared reference material lives."""

from pathlib import Path

import pytest

import os

# ../shared beside the checkout (as on developer machines and in CI), or LINKWORK_SHARED
SHARED = Path(os.environ.get("LINKWORK_SHARED", Path(__file__).resolve().parents[1].parent / "shared"))
REFERENCE = SHARED / "reference" / "pmks-verification-v1" / "cases"


@pytest.fixture(scope="session")
def reference_root() -> Path:
    if not REFERENCE.is_dir():
        pytest.fail(f"the reference suite is missing: {REFERENCE}")
    return REFERENCE
