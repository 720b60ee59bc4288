"""`[profiles.NAME]` tables of mechanism files: every type builds the same profile as the Python
constructor (compared by its derivatives, domain and breaks), angles in degrees unless the file
says radians, CSV point files read by their rules and kept inside the file's folder, and every
bad table a MechanismFileError naming its key."""

from __future__ import annotations

import os

import numpy as np
import pytest

import linkwork
from linkwork.errors import MechanismFileError
from linkwork.geometry.profiles import (
    ArchimedeanSpiral,
    ArcTo,
    CircleProfile,
    EllipseProfile,
    InvoluteProfile,
    LineProfile,
    LineTo,
    LogarithmicSpiral,
    PathProfile,
    SplineProfile,
)
from linkwork.io.profiles import build_profile, read_points_csv
from linkwork.model.disc_cams import DiscCam
from linkwork.model.motion_programs import MotionProgram, Segment

DEG = np.pi / 180


def mechanism(profile_toml: str, units: str = "") -> str:
    """A crank on the frame (the smallest mechanism a file describes) with one profile `p`."""
    return f"""
name = "profile table"
{units}
[points]
O = [0, 0]
A = [10, 0]
[profiles.p]
{profile_toml}
[links]
frame = ["O"]
crank = ["O", "A"]
[joints]
O = {{ type = "revolute", links = ["frame", "crank"] }}
[driver]
joint = "O"
"""


def loaded(profile_toml: str, units: str = "", base_dir=None):
    return linkwork.load_text(mechanism(profile_toml, units), base_dir=base_dir).profiles["p"]


def assert_same_profile(a, b, order=3):
    assert type(a) is type(b)
    assert a.closed == b.closed
    np.testing.assert_allclose(a.domain, b.domain, rtol=1e-14)
    np.testing.assert_allclose(a.breaks, b.breaks, rtol=1e-14)
    lo = max(a.domain[0], -50.0)
    hi = min(a.domain[1], 50.0)
    u = np.linspace(lo, hi, 23)
    np.testing.assert_allclose(a.derivatives(u, order), b.derivatives(u, order), rtol=1e-13, atol=1e-12)


CASES = {
    "circle": ('type = "circle"\ncenter = [10, -2]\nradius = 40',
               lambda: CircleProfile((10.0, -2.0), 40.0)),
    "ellipse": ('type = "ellipse"\ncenter = [1, 2]\nsemi_axes = [40, 25]\nangle = 30',
                lambda: EllipseProfile((1.0, 2.0), (40.0, 25.0), 30 * DEG)),
    "ellipse-default-angle": ('type = "ellipse"\ncenter = [0, 0]\nsemi_axes = [4, 2.5]',
                              lambda: EllipseProfile((0.0, 0.0), (4.0, 2.5))),
    "path": ('type = "path"\nstart = [40, 0]\nclosed = true\nsegments = [\n'
             '  { arc_to = [0, 40], center = [0, 0] },\n  { line_to = [-30, 10] },\n'
             '  { arc_to = [-30, -10], radius = 10, sense = "ccw" },\n'
             '  { arc_to = [40, 0], radius = 50, sense = "ccw", large = false },\n]',
             lambda: PathProfile((40.0, 0.0), [ArcTo((0.0, 40.0), center=(0.0, 0.0)), LineTo((-30.0, 10.0)),
                                               ArcTo((-30.0, -10.0), radius=10.0, sense="ccw"),
                                               ArcTo((40.0, 0.0), radius=50.0)], closed=True)),
    "path-cw-large-smooth": ('type = "path"\nstart = [1, 0]\nsmooth = true\nsegments = [\n'
                             '  { arc_to = [0, 1], radius = 1, sense = "cw", large = true },\n'
                             '  { line_to = [5, 1] },\n]',
                             lambda: PathProfile((1.0, 0.0), [ArcTo((0.0, 1.0), radius=1.0, sense=-1, large=True),
                                                              LineTo((5.0, 1.0))], smooth=True)),
    "spline": ('type = "spline"\npoints = [[0, 0], [10, 5], [20, 0], [10, -5]]\nclosed = true',
               lambda: SplineProfile([[0, 0], [10, 5], [20, 0], [10, -5]], closed=True)),
    "spline-cubic-open": ('type = "spline"\npoints = [[0, 0], [1, 2], [3, 3], [4, 1], [6, 0]]\ndegree = 3',
                          lambda: SplineProfile([[0, 0], [1, 2], [3, 3], [4, 1], [6, 0]], degree=3)),
    "line": ('type = "line"\npoint = [1, 2]\ndirection = [3, 4]',
             lambda: LineProfile((1.0, 2.0), (3.0, 4.0))),
    "involute": ('type = "involute"\ncenter = [1, 1]\nbase_radius = 20\nstart_angle = 15\nroll = [10, 200]\nsense = "cw"',
                 lambda: InvoluteProfile((1.0, 1.0), 20.0, 15 * DEG, (10 * DEG, 200 * DEG), -1)),
    "involute-defaults": ('type = "involute"\ncenter = [0, 0]\nbase_radius = 20',
                          lambda: InvoluteProfile((0.0, 0.0), 20.0, 0.0, (0.0, 2 * np.pi), 1)),
    "archimedean-spiral": ('type = "archimedean-spiral"\ncenter = [0, 0]\nstart_radius = 20\npitch = 10\nangles = [0, 360]',
                           lambda: ArchimedeanSpiral((0.0, 0.0), 20.0, 10.0, (0.0, 2 * np.pi))),
    "logarithmic-spiral": ('type = "logarithmic-spiral"\ncenter = [2, 0]\nstart_radius = 20\npitch_angle = 10\n'
                           'angles = [-90, 270]',
                           lambda: LogarithmicSpiral((2.0, 0.0), 20.0, 10 * DEG, (-np.pi / 2, 1.5 * np.pi))),
}


@pytest.mark.parametrize("name", list(CASES))
def test_table_builds_the_python_profile(name):
    text, python = CASES[name]
    assert_same_profile(loaded(text), python())


def test_cam_design_table_builds_the_disc_cams_profile():
    text = ('type = "cam-design"\nfollower = "roller"\nbase_radius = 40\nroller_radius = 10\noffset = 5\n'
            'segments = [\n  { rise = 20, over = 120, law = "cycloidal" },\n  { dwell = 60 },\n'
            '  { return = 20, over = 120, law = "3-4-5" },\n  { dwell = 60 },\n]')
    program = MotionProgram([Segment("rise", 120 * DEG, 20.0, "cycloidal"), Segment("dwell", 60 * DEG),
                             Segment("return", 120 * DEG, 20.0, "3-4-5"), Segment("dwell", 60 * DEG)])
    cam = DiscCam(program, "roller", 40.0, roller_radius=10.0, offset=5.0)
    a, b = loaded(text), cam.profile
    u = np.linspace(0, 2 * np.pi, 19)
    np.testing.assert_allclose(a.derivatives(u, 2), b.derivatives(u, 2), rtol=1e-12, atol=1e-10)
    assert a.closed == b.closed


def test_angles_in_radians_when_the_file_says_so():
    units = '[units]\nangle = "rad"'
    a = loaded('type = "ellipse"\ncenter = [0, 0]\nsemi_axes = [4, 2]\nangle = 0.5', units)
    assert_same_profile(a, EllipseProfile((0.0, 0.0), (4.0, 2.0), 0.5))
    b = loaded('type = "involute"\ncenter = [0, 0]\nbase_radius = 3\nstart_angle = 1\nroll = [0.5, 2]', units)
    assert_same_profile(b, InvoluteProfile((0.0, 0.0), 3.0, 1.0, (0.5, 2.0)))
    c = loaded('type = "archimedean-spiral"\ncenter = [0, 0]\nstart_radius = 5\npitch = 2\nangles = [0, 3]', units)
    assert_same_profile(c, ArchimedeanSpiral((0.0, 0.0), 5.0, 2.0, (0.0, 3.0)))
    # degrees spelt out are the default
    d = loaded('type = "ellipse"\ncenter = [0, 0]\nsemi_axes = [4, 2]\nangle = 90', '[units]\nangle = "degree"')
    assert_same_profile(d, EllipseProfile((0.0, 0.0), (4.0, 2.0), np.pi / 2))
    with pytest.raises(MechanismFileError, match="unknown angle unit 'grad'"):
        build_profile("p", {"type": "circle", "center": [0, 0], "radius": 1}, angle_unit="grad")


# -- CSV point files ----------------------------------------------------------------------------

STAR = [(10.0, 0.0), (6.0, 8.0), (-7.5, 9.0), (-11.0, -1.5), (-3.0, -9.5), (8.0, -6.0)]


def csv_table(file: str, closed: bool = True) -> str:
    return f'type = "points"\nfile = "{file}"\nclosed = {str(closed).lower()}'


@pytest.mark.parametrize("text", [
    "x,y\n" + "\n".join(f"{x},{y}" for x, y in STAR) + "\n",
    "# a cam\n\nx y  # header\n" + "\n".join(f"  {x}   {y}  # point" for x, y in STAR) + "\n\n",
    "\n".join(f"{x}, {y}" for x, y in STAR),
    "\n".join(f"{x};{y}" for x, y in STAR) + "\n# end\n",
    "\r\n".join(f"{x}\t{y}" for x, y in STAR) + "\r\n",
])
def test_csv_rules(tmp_path, text):
    (tmp_path / "cam.csv").write_text(text)
    profile = loaded(csv_table("cam.csv"), base_dir=tmp_path)
    assert_same_profile(profile, SplineProfile(STAR, closed=True))


def test_csv_beside_the_file_in_a_subfolder_and_via_load(tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "cam.csv").write_text("\n".join(f"{x},{y}" for x, y in STAR))
    (tmp_path / "cam.toml").write_text(mechanism(csv_table("data/cam.csv") + "\ndegree = 3"))
    profile = linkwork.load(tmp_path / "cam.toml").profiles["p"]
    assert_same_profile(profile, SplineProfile(STAR, closed=True, degree=3))
    # `..` that stays inside the folder is fine
    (tmp_path / "cam2.toml").write_text(mechanism(csv_table("data/../data/cam.csv", closed=False)))
    assert_same_profile(linkwork.load(tmp_path / "cam2.toml").profiles["p"], SplineProfile(STAR))
    # relative to the working directory when no folder is given
    cwd = os.getcwd()
    try:
        os.chdir(tmp_path / "data")
        assert_same_profile(build_profile("p", {"type": "points", "file": "cam.csv"}), SplineProfile(STAR))
    finally:
        os.chdir(cwd)


def test_csv_outside_the_folder_is_refused(tmp_path):
    inner = tmp_path / "mech"
    inner.mkdir()
    (tmp_path / "cam.csv").write_text("\n".join(f"{x},{y}" for x, y in STAR))
    with pytest.raises(MechanismFileError, match=r"key 'profiles.p.file'.*lies outside the mechanism file's folder"):
        loaded(csv_table("../cam.csv"), base_dir=inner)
    with pytest.raises(MechanismFileError, match=r"key 'profiles.p.file'.*relative to the mechanism file's folder"):
        loaded(csv_table((tmp_path / "cam.csv").as_posix()), base_dir=inner)
    with pytest.raises(MechanismFileError, match=r"key 'profiles.p.file'.*relative to the mechanism file's folder"):
        loaded(csv_table(" "), base_dir=inner)
    # a link inside the folder pointing out of it is outside too
    try:
        (inner / "link.csv").symlink_to(tmp_path / "cam.csv")
    except OSError:
        pytest.skip("no symbolic links here")
    with pytest.raises(MechanismFileError, match="lies outside"):
        loaded(csv_table("link.csv"), base_dir=inner)


@pytest.mark.parametrize("text,message,line", [
    ("x,y\n1,2\nfoo,bar\n", r"not a point 'x, y': 'foo,bar'", 3),
    ("1,2\nx,y\n", r"not a point 'x, y': 'x,y'", 2),
    ("1,2\n3,4,5\n", "a point has two coordinates x, y; this line has 3", 2),
    ("1,2\n3\n", "this line has 1", 2),
    ("1,2\nnan,4\n", "coordinates must be finite", 2),
    ("1,2\n3,inf\n", "coordinates must be finite", 2),
    ("1,2\n3,1e300\n", "coordinates must be finite numbers of at most", 2),
    ("# only a comment\n\nx,y\n", "the CSV holds no points", None),
    ("", "the CSV holds no points", None),
])
def test_malformed_csv_names_file_key_and_line(tmp_path, text, message, line):
    (tmp_path / "cam.csv").write_text(text)
    with pytest.raises(MechanismFileError, match=message) as e:
        loaded(csv_table("cam.csv"), base_dir=tmp_path)
    assert e.value.key == "profiles.p.file"
    assert e.value.line == line
    assert str(tmp_path / "cam.csv") in str(e.value)


def test_csv_points_the_spline_refuses_name_their_line(tmp_path):
    # line 1 a header, line 2 a comment, the repeated point on line 5
    (tmp_path / "cam.csv").write_text("x,y\n# cam\n0,0\n4,0\n4,0\n0,3\n")
    with pytest.raises(MechanismFileError, match="point 2: repeats point 1") as e:
        loaded(csv_table("cam.csv"), base_dir=tmp_path)
    assert e.value.key == "profiles.p.file" and e.value.line == 5
    (tmp_path / "few.csv").write_text("0,0\n1,0\n1,1\n")
    with pytest.raises(MechanismFileError, match="needs at least 6 distinct points, got 3"):
        loaded(csv_table("few.csv", closed=False), base_dir=tmp_path)


def test_missing_or_unreadable_csv(tmp_path):
    with pytest.raises(MechanismFileError, match=r"key 'profiles.p.file'.*no such CSV file"):
        loaded(csv_table("nothere.csv"), base_dir=tmp_path)
    (tmp_path / "folder.csv").mkdir()
    with pytest.raises(MechanismFileError, match="no such CSV file"):
        loaded(csv_table("folder.csv"), base_dir=tmp_path)
    (tmp_path / "latin.csv").write_bytes(b"x\xe9,y\n1,2\n")
    with pytest.raises(MechanismFileError, match="cannot read the CSV") as e:
        read_points_csv(tmp_path / "latin.csv", key="profiles.p.file")
    assert e.value.key == "profiles.p.file"


def test_read_points_csv_returns_points_and_their_lines(tmp_path):
    (tmp_path / "p.csv").write_text("# t\nx y\n\n1 2\n 3,4 # c\n5;6\n")
    pts, lines = read_points_csv(tmp_path / "p.csv")
    np.testing.assert_array_equal(pts, [[1, 2], [3, 4], [5, 6]])
    assert lines == [4, 5, 6]


# -- errors naming the key ----------------------------------------------------------------------

@pytest.mark.parametrize("table,key,message", [
    ('type = "circle"\ncenter = [0, 0]\nradus = 2', "profiles.p.radus", "unknown key \\(did you mean 'radius'\\?\\)"),
    ('type = "circle"\ncenter = [0, 0]\nradius = 1\nradus = 2', "profiles.p.radus", "unknown key"),
    ('center = [0, 0]\nradius = 1', "profiles.p", "a profile needs a 'type'"),
    ('type = "oval"\ncenter = [0, 0]', "profiles.p", "unknown profile type 'oval'"),
    ('type = "circle"\ncenter = [0, 0]', "profiles.p.radius", "required key is missing"),
    ('type = "circle"\ncenter = [0, 0]\nradius = -1', "profiles.p.radius", "expected a positive number, got -1"),
    ('type = "circle"\ncenter = [0, 0, 0]\nradius = 1', "profiles.p.center", "at most 2 items"),
    ('type = "ellipse"\ncenter = [0, 0]\nsemi_axes = [1, 0]', "profiles.p.semi_axes[1]", "expected a positive number, got 0"),
    ('type = "line"\npoint = [0, 0]\ndirection = [0, 0]', "profiles.p", "zero vector"),
    ('type = "path"\nstart = [0, 0]\nsegments = [{ line_to = [1, 0] }, { line_to = [1, 0] }]',
     "profiles.p.segments[1]", "a line of zero length"),
    ('type = "path"\nstart = [0, 0]\nsegments = [{ line_to = [1, 0] }, { arc_to = [3, 0], radius = 0.5 }]',
     "profiles.p.segments[1]", "longer than the diameter"),
    ('type = "path"\nstart = [0, 0]\nsegments = [{ line_to = [1, 0] }, { arc_to = [3, 0] }]',
     "profiles.p.segments[1]", "either its centre or its radius"),
    ('type = "path"\nstart = [0, 0]\nsegments = [{ line_to = [1, 0] }, { arc_to = [3, 0], radius = 2, sense = "up" }]',
     "profiles.p.segments[1].sense", "'ccw' or 'cw'"),
    ('type = "path"\nstart = [0, 0]\nsegments = [{ move_to = [1, 0] }]', "profiles.p.segments[0]",
     "a segment is"),
    ('type = "path"\nstart = [0, 0]\nsegments = [{ line_to = [1, 0], center = [0, 0] }]',
     "profiles.p.segments[0].center", "unknown key"),
    ('type = "path"\nstart = [0, 0]\nclosed = true\nsegments = [{ line_to = [1, 0] }, { line_to = [1, 1] }]',
     "profiles.p.segments[1]", "must end at its start"),
    ('type = "path"\nstart = [0, 0]\nsmooth = true\nsegments = [{ line_to = [1, 0] }, { line_to = [1, 1] }]',
     "profiles.p.segments[1]", "corner of 90°"),
    ('type = "path"\nstart = [0, 0]\nsegments = []', "profiles.p.segments", "at least 1 item"),
    ('type = "spline"\npoints = [[0, 0], [1, 0], [1, 0], [2, 1], [3, 0], [4, 1]]',
     "profiles.p.points[2]", "repeats point 1"),
    ('type = "spline"\npoints = [[0, 0], [1, 0], [2, 1]]', "profiles.p", "at least 6 distinct points"),
    ('type = "spline"\npoints = [[0, 0], [1, 0], [2, 1], [3, 3]]\ndegree = 4', "profiles.p.degree", "3 or 5"),
    ('type = "spline"\npoints = [[0, 0], [1, 0], [2, 1]]\nclosed = "yes"', "profiles.p.closed", "valid boolean"),
    ('type = "involute"\ncenter = [0, 0]\nbase_radius = 2\nroll = [-10, 90]', "profiles.p", "start at 0 or later"),
    ('type = "involute"\ncenter = [0, 0]\nbase_radius = 2\nsense = "left"', "profiles.p.sense", "'ccw' or 'cw'"),
    ('type = "archimedean-spiral"\ncenter = [0, 0]\nstart_radius = 5\npitch = -10\nangles = [0, 360]',
     "profiles.p", "radius must stay positive"),
    ('type = "logarithmic-spiral"\ncenter = [0, 0]\nstart_radius = 5\npitch_angle = 90\nangles = [0, 360]',
     "profiles.p", "between -90° and 90°"),
    ('type = "logarithmic-spiral"\ncenter = [0, 0]\nstart_radius = 5\npitch_angle = 10\nangles = [90, 0]',
     "profiles.p", "two finite increasing"),
    ('type = "points"\nfile = "x.csv"\ndegree = 2', "profiles.p.degree", "3 or 5"),
])
def test_bad_tables_name_their_key(table, key, message):
    with pytest.raises(MechanismFileError, match=message) as e:
        loaded(table)
    assert e.value.key == key, str(e.value)
    assert f"key '{key}'" in str(e.value)


def test_a_profile_that_is_not_a_table():
    with pytest.raises(MechanismFileError) as e:
        build_profile("p", 3)
    assert e.value.key == "profiles.p"
