"""The `linkwork` command line (Typer + Rich). `main.app` is the entry point."""

from .main import app

__all__ = ["app"]
