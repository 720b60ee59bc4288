"""Reading and writing: mechanism files (TOML), the shipped library, solution exports."""

from .files import dump_schema, load, load_text, resolve

__all__ = ["dump_schema", "load", "load_text", "resolve"]
