"""The browser workbench: an ASGI application (FastAPI) whose JSON API is the Python API — load
and validate, solve, whole motion, poles, curvature, structure, constructions, drawings — and
the page (TypeScript, built from `web/` into `static/`) that opens a mechanism, animates it,
lets its design points be dragged and its layers toggled. `linkwork serve` starts it."""

from .app import create_app

__all__ = ["create_app"]
