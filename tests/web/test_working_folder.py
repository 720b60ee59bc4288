"""The working folder's mechanism files as the page lists them (`web.sources.working_files`):
the .toml files that state points, down to a few levels, not inside hidden folders or tools'
trees, and at most `_LISTED` of them, so that a large folder is listed quickly."""

from __future__ import annotations

from linkwork.io import resolve
from linkwork.web import sources


def test_only_mechanism_files_are_listed(tmp_path):
    mech = resolve("library:crank-rocker")[1]
    files = {
        "a.toml": mech,
        "pyproject.toml": "[project]\nname = 'x'\n",            # a TOML file, not a mechanism
        "Cargo.toml": "[package]\nname = 'x'\n",
        "inline.toml": 'name = "x"\npoints = { A = [0, 0] }\n',  # points as an inline table
        "sub/b.toml": mech,
        "sub/notes.txt": mech,
        "1/2/3/c.toml": mech,                                     # three levels down: listed
        "1/2/3/4/5/d.toml": mech,                                 # five: not
        ".git/e.toml": mech,
        "node_modules/pkg/f.toml": mech,
        ".venv/lib/g.toml": mech,
    }
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    assert sources.working_files(tmp_path) == ["1/2/3/c.toml", "a.toml", "inline.toml", "sub/b.toml"]


def test_the_list_stops_at_its_length(tmp_path, monkeypatch):
    monkeypatch.setattr(sources, "_LISTED", 5)
    mech = resolve("library:crank-rocker")[1]
    for k in range(12):
        (tmp_path / f"m{k:02}.toml").write_text(mech)
    got = sources.working_files(tmp_path)
    assert len(got) == 5 and got == sorted(got)


def test_no_working_folder_lists_nothing():
    assert sources.working_files(None) == []
