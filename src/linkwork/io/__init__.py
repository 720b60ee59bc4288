"""Reading and writing: mechanism files (TOML), the shipped library, solution exports."""

from .dynamics import dynamics_from_text, load_dynamics
from .files import dump_schema, load, load_text, resolve

__all__ = ["dump_schema", "dynamics_from_text", "load", "load_dynamics", "load_text", "resolve"]
