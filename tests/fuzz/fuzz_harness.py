"""The fuzz harness of issue 10, shared by the Hypothesis suite (tests/fuzz) and the long run
(tools/fuzz.py): mutated library files through `load` + `solve` + `structure_report`, and
random arguments through the command line.

Every case ends in one `Outcome`:
  result       the input was accepted and every check passed;
  user-error   a `linkwork.errors.LinkworkError` (exit status 2 on the command line);
  crash        any other exception (a bug: the cause is the exception type and where it rose);
  hang         the case ran longer than its deadline;
  wrong-ok     a sample reported `ok` whose revolute pairs do not close (the point computed
               from the two links it joins differs by more than 1e-6 of the drawing's size),
               or whose positions or velocities are not finite.
Mutations draw from a `random.Random`, so a case is reproduced from its seed and Hypothesis
can shrink the choices it feeds in.
"""

from __future__ import annotations

import os
import random
import re
import signal
import tempfile
import traceback
from contextlib import contextmanager
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

import linkwork
from linkwork.errors import LinkworkError
from linkwork.kinematics import solve_at

CLOSURE_TOL = 1e-6  # of the drawing's size: an ok sample's revolute pairs close to this


class Hang(BaseException):
    """Raised by the deadline's alarm (a BaseException, so that no `except Exception` in the
    code under test can swallow it)."""


@contextmanager
def deadline(seconds: float):
    """Raise `Hang` in the main thread after `seconds` of this process's CPU time (SIGPROF;
    Unix only): CPU time, not the clock, so that a loaded machine (the suite's other workers,
    CI) does not turn a slow case into a hang."""
    def alarm(signum, frame):
        raise Hang()

    old = signal.signal(signal.SIGPROF, alarm)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, old)


@dataclass
class Outcome:
    kind: str          # result, user-error, crash, hang, wrong-ok
    cause: str = ""    # exception type and place, or what was wrong
    detail: str = ""   # the message or the case, for the report


def library_texts() -> dict[str, str]:
    root = resources.files("linkwork") / "library"
    return {p.name[:-5]: p.read_text(encoding="utf-8") for p in root.iterdir() if p.name.endswith(".toml")}


def warm_up() -> None:
    """Compile the solver's kernels (numba, seconds on a busy machine) and load the command line
    before the first case, so that its deadline measures the case only."""
    from linkwork.cli import app  # noqa: F401
    from linkwork.structure import structure_report

    from linkwork.kinematics import kernels

    # (the parallelogram: change points, its dyad's signs an array rather than one number)
    for name in ("crank-rocker", "slider-crank-offset", "jansen-linkage", "parallelogram"):
        mech = linkwork.load(f"library:{name}")
        sol = linkwork.solve(mech, _inputs(mech, random.Random(0)))
        check_ok_samples(sol)
        structure_report(mech, limits=False)
        # batches above INTERPRETED_UP_TO run compiled (numba): compiled here, not in a case
        # (the change-point scans take 2049–4097 samples, a path's grid more); an alarm in
        # the middle of numba's compiler leaves its loops broken for the cases after
        u0 = mech.driver_input_at_design(mech.drivers[0])
        many = u0 + np.linspace(-np.pi, np.pi, kernels.INTERPRETED_UP_TO + 1)
        linkwork.solve(mech, many, order=2)
        linkwork.solve(mech, many, order=3)


# ----------------------------------------------------------------------------- mutations
_NUMBER = re.compile(r'(?<![\w."\-])-?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?(?![\w".])')
_STRING = re.compile(r'"([^"\n]*)"')
_POINT = re.compile(r'^\s*"?([\w-]+)"?\s*=\s*\[\s*(-?[\d.eE+-]+)\s*,\s*(-?[\d.eE+-]+)\s*\]', re.M)

NUMBERS = ["nan", "inf", "-inf", "0", "0.0", "-0.0", "1e300", "-1e300", "1e-300", "1e12", "1e13",
           "123456789012345678901234567890", "true", "false", '"10"', '"1e400 deg"', "[]", "[1, 2]",
           "{}", "1e-12", "-1", "3.0e5"]
STRINGS = ["", "9**9**9 rpm", "10**400 deg", "nan rpm", "inf", "[links]", "[bold]x[/bold]",
           "1e400 mm/s", "60 kg", "60 rpm rpm", "(((((", "rad^99", "frame", "revolute",
           "prismatic", "slot", "gear", "cam", "rolling", "polynomial", "table", "circle", "deg",
           "mm", "inch", "-60 rpm", "0 rpm", "1e-300 rad/s", "é", "1 / 0 s"]


def _numbers(text: str) -> list[re.Match]:
    return list(_NUMBER.finditer(text))


def mutate(text: str, rng: random.Random) -> tuple[bytes, list[str]]:
    """`text` with 1–3 random mutations (numbers, strings, lines, bytes); the bytes of the file
    and a description of each mutation."""
    done: list[str] = []
    raw: bytes | None = None
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3])):
        what = rng.choice(["number", "number", "number", "string", "string", "string", "line",
                           "line", "name", "byte", "near", "near"])
        if what == "number" and _numbers(text):
            m = rng.choice(_numbers(text))
            orig = float(m.group())
            new = rng.choice(NUMBERS + [repr(orig * (1 + 1e-9)), repr(-orig), repr(orig + 1e-7),
                                        repr(orig * 1e6), repr(orig * 1e-9), repr(orig + 1e-12)])
            text = text[:m.start()] + new + text[m.end():]
            done.append(f"number {m.group()} -> {new}")
        elif what == "string" and _STRING.search(text):
            m = rng.choice(list(_STRING.finditer(text)))
            s = m.group(1)
            options = STRINGS + [s[:-1], s + "x", s.upper(), s[::-1]]
            new = rng.choice(options)
            text = text[:m.start()] + '"' + new.replace('"', "") + '"' + text[m.end():]
            done.append(f"string {s!r} -> {new!r}")
        elif what == "name" and _STRING.search(text):
            # one name of the file replaced by another of its names: a consistent-looking mistake
            names = [m.group(1) for m in _STRING.finditer(text)]
            m = rng.choice(list(_STRING.finditer(text)))
            new = rng.choice(names)
            text = text[:m.start()] + f'"{new}"' + text[m.end():]
            done.append(f"name {m.group(1)!r} -> {new!r}")
        elif what == "near" and len(_POINT.findall(text)) >= 2:
            # a point drawn onto another, or almost: degenerate and near-singular geometry
            pts = list(_POINT.finditer(text))
            m, other = rng.sample(pts, 2)
            eps = rng.choice([0.0, 1e-12, 1e-9, 1e-6, 1e-3])
            x, y = float(other.group(2)) + eps * rng.uniform(-1, 1), float(other.group(3)) + eps * rng.uniform(-1, 1)
            text = text[:m.start(2)] + repr(x) + ", " + repr(y) + text[m.end(3):]
            done.append(f"point {m.group(1)} -> {other.group(1)} + {eps:g}")
        elif what == "line":
            lines = text.splitlines()
            i = rng.randrange(len(lines))
            op = rng.choice(["delete", "duplicate", "swap"])
            if op == "delete":
                del lines[i]
            elif op == "duplicate":
                lines.insert(i, lines[i])
            else:
                j = rng.randrange(len(lines))
                lines[i], lines[j] = lines[j], lines[i]
            text = "\n".join(lines) + "\n"
            done.append(f"line {i + 1} {op}")
        elif what == "byte":
            data = text.encode()
            i = rng.randrange(len(data) + 1)
            b = bytes([rng.choice([0x00, 0x80, 0xC3, 0xE9, 0xFF, 0x5B, 0x22, 0x0A])])
            raw = data[:i] + b + data[i:]
            done.append(f"byte {b!r} at {i}")
            text = raw.decode("utf-8", errors="replace")
    return (raw if raw is not None and done[-1].startswith("byte") else text.encode()), done


# ----------------------------------------------------------------------------- checks
def check_ok_samples(sol) -> str | None:
    """Why an `ok` sample of `sol` is wrong (None if none is): every revolute pair closes, and
    positions and velocities are finite."""
    mech = sol.mechanism
    ok = np.asarray(sol.status) == 0
    if not ok.any():
        return None
    tol = CLOSURE_TOL * mech.length_scale
    for j in mech.joints:
        if j.kind != "revolute":
            continue
        xy = mech.points[j.point]
        a, b = (sol.point_on(ln, xy) for ln in j.links)
        gap = np.hypot(*(a.position - b.position).T)[ok]
        if not np.all(gap <= tol):
            k = int(np.argmax(np.where(np.isfinite(gap), gap, np.inf)))
            return f"revolute '{j.name}' open by {gap[k]:.3g} (tolerance {tol:.3g}) at an ok sample"
    for p in mech.points:
        m = sol.point(p)
        if not (np.isfinite(m.position[ok]).all() and np.isfinite(m.velocity[ok]).all()):
            return f"point '{p}' not finite at an ok sample"
    return None


def _cause(exc: BaseException) -> str:
    tb = traceback.extract_tb(exc.__traceback__)
    frames = [f for f in tb if "linkwork" in f.filename] or tb
    where = f"{Path(frames[-1].filename).name}:{frames[-1].lineno}" if frames else "?"
    return f"{type(exc).__name__} at {where}"


def _inputs(mech, rng: random.Random) -> np.ndarray:
    """13 input values per driver about the design position, in the drivers' units."""
    cols = []
    for d in mech.drivers:
        u0 = mech.driver_input_at_design(d)
        span = mech.length_scale / 4 if mech.joint(d.joint).kind == "prismatic" else np.pi
        cols.append(u0 + np.linspace(-span, span, 13) * rng.choice([1.0, 0.5, 1e-6]))
    return np.column_stack(cols)


def run_file_case(data: bytes, rng: random.Random, seconds: float = 20.0) -> Outcome:
    """Load the file `data`, solve it at the design position and 13 inputs about it, and
    analyse its structure."""
    from linkwork.structure import structure_report

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "m.toml"
        path.write_bytes(data)
        try:
            with deadline(seconds):
                try:
                    mech = linkwork.load(path)
                    # the design position, then random inputs (a chain moved by given
                    # velocities has its drawn position only)
                    sols = (solve_at(mech),) if mech.given else (
                        solve_at(mech), solve_at(mech, _inputs(mech, rng)))
                    for sol in sols:
                        why = check_ok_samples(sol)
                        if why:
                            cause = "revolute pair open" if " open by " in why else "not finite"
                            return Outcome("wrong-ok", cause, f"{mech.name}: {why}")
                    structure_report(mech, limits=False)
                except LinkworkError as exc:
                    return Outcome("user-error", type(exc).__name__, str(exc))
        except Hang:
            return Outcome("hang", "deadline", f"over {seconds:g} s")
        except Exception as exc:  # noqa: BLE001 - the point of the harness
            return Outcome("crash", _cause(exc), f"{type(exc).__name__}: {exc}"[:300])
    return Outcome("result")


# ----------------------------------------------------------------------------- command line
AT_TOKENS = ["0", "30", "-45", "1.2rad", "0.5s", "nan", "inf", "-inf", "1e400", "9**9**9",
             "10**400 deg", "3 kg", "", "1e9", "360", "2 mm", "1e-300", "(", "1/0", "rpm",
             "90°", "1e12", "45 deg", "0x10", "1_000", "--", "[links]", "O2=30", "=5"]
SWEEP_TOKENS = ["0:360:10", "nan:360:10", "0:inf:10", "0:360:nan", "0:360:0", "360:0:10",
                "0:360:-10", "0:1:0.0001", "0s:1s:0.1s", "0:360", "a:b:c", "0:10mm:1", "0:1e12:1",
                "-1e9:1e9:1e8", "::", "0:360:9**9**9", "0 deg:1 rad:0.1 rad"]
SPEED_TOKENS = ["120 rpm", "nan rpm", "inf", "9**9**9 rpm", "-60 rpm", "0", "2 rad/s", "60 kg",
                "1e400 rad/s", "10 mm/s", "rpm", "[bold]"]
DPI_TOKENS = ["nan", "0", "-1", "1e9", "inf", "72", "abc"]


def cli_args(rng: random.Random, names: list[str]) -> list[str]:
    """Random but plausible `linkwork` arguments: analyze (mostly), poles, curvature or draw."""
    mech = f"library:{rng.choice(names)}" if rng.random() < 0.95 else rng.choice(
        ["library:nope", "missing.toml", "library:", ""])
    cmd = rng.choices(["analyze", "poles", "curvature", "draw", "structure"], [6, 1, 1, 1, 1])[0]
    args = [cmd, mech]
    for _ in range(rng.choice([0, 1, 1, 2, 3])):
        opt = rng.choice(["--at", "--at", "--sweep", "--speed", "--format", "--at"])
        if cmd not in ("analyze",) and opt in ("--sweep", "--speed"):
            opt = "--at"
        if cmd in ("structure",):
            opt = "--format"
        if opt == "--at":
            k = rng.choice([1, 1, 2, 3])
            args += [opt, ",".join(rng.choice(AT_TOKENS) for _ in range(k))]
        elif opt == "--sweep":
            args += [opt, rng.choice(SWEEP_TOKENS)]
        elif opt == "--speed":
            args += [opt, rng.choice(SPEED_TOKENS)]
        else:
            args += [opt, rng.choice(["json", "csv", "jsonl", "table", "xml"])]
    if cmd == "analyze" and "--format" not in args and rng.random() < 0.8:
        args += ["--format", "csv"]  # a table of the whole motion costs a second of Rich's time
    if cmd == "curvature":
        args += ["--link", rng.choice(["coupler", "crank", "nope", "frame"])]
    if cmd == "draw":
        args += ["--dpi", rng.choice(DPI_TOKENS), "-o", "out.svg"]
    return args


def run_cli_case(args: list[str], seconds: float = 30.0) -> Outcome:
    """Run `linkwork ARGS` in-process (in a temporary working directory): exit 0, or exit 2
    with one `error:` line; anything else is a crash."""
    from typer.testing import CliRunner

    from linkwork.cli import app
    from linkwork.cli import inputs

    runner = CliRunner()
    cwd = os.getcwd()
    max_samples = inputs.MAX_SAMPLES
    inputs.MAX_SAMPLES = 20_000  # the fuzz keeps each case short; the limit itself is tested elsewhere
    try:
        with tempfile.TemporaryDirectory() as d:
            os.chdir(d)
            try:
                with deadline(seconds):
                    r = runner.invoke(app, args)
            except Hang:
                return Outcome("hang", "deadline", " ".join(args))
            finally:
                os.chdir(cwd)
    finally:
        inputs.MAX_SAMPLES = max_samples
    if r.exception is not None and not isinstance(r.exception, SystemExit):
        return Outcome("crash", _cause(r.exception), f"{' '.join(args)} -> {type(r.exception).__name__}: {r.exception}"[:300])
    if r.exit_code == 0:
        return Outcome("result")
    text = r.output.strip()
    if r.exit_code == 2 and (text.startswith("error:") or "Usage:" in text):
        return Outcome("user-error", "exit 2", text.splitlines()[-1][:200] if text else "")
    return Outcome("crash", f"exit {r.exit_code}", f"{' '.join(args)} -> {text[:200]}")
