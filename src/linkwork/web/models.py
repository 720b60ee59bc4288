"""The workbench API's requests and responses (pydantic; the OpenAPI schema is made from them).

Units are those of the Python API and of the command line's JSON: lengths in the mechanism
file's unit, angles in radians, times in seconds. Inputs are given per driver, in driver order.
Every number must be finite and at most 1e12 in size; lists and texts have bounded lengths.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal, Optional

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ..constructions import CONSTRUCTIONS
from ..drawing import LAYERS
from ..units import MAX_MAGNITUDE
from .sources import MAX_TEXT

#: the most samples one request solves (the whole motion has its own step)
MAX_SAMPLES = 20_000

Number = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_MAGNITUDE, le=MAX_MAGNITUDE)]
Name = Annotated[str, Field(min_length=1, max_length=100)]
Layer = Literal[LAYERS]  # type: ignore[valid-type]
ConstructionName = Literal[tuple(CONSTRUCTIONS)]  # type: ignore[valid-type]


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Source(Strict):
    """A mechanism: exactly one of `library` (a library name), `file` (a path relative to the
    working folder) or `text` (the TOML text of a mechanism file, `name` labelling its
    messages); `points` moves design points before the mechanism is built."""

    library: Optional[Annotated[str, Field(max_length=100, pattern=r"^[A-Za-z0-9_.-]+$")]] = None
    file: Optional[Annotated[str, Field(max_length=500)]] = None
    text: Optional[Annotated[str, Field(max_length=MAX_TEXT)]] = None
    name: Optional[Annotated[str, Field(max_length=100, pattern=r"^[^\x00-\x1f]*$")]] = None
    points: Optional[Annotated[dict[Name, tuple[Number, Number]], Field(max_length=1000)]] = None

    @model_validator(mode="after")
    def _one(self) -> "Source":
        given = [k for k in ("library", "file", "text") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of library, file and text"
                             + (f" (got {', '.join(given)})" if given else ""))
        return self


class MechanismRequest(Strict):
    source: Source


class At(Strict):
    """Where to solve: `at` (input values: one number per sample for one driver, or one list
    of a value per driver per sample) or `times` (seconds); neither: the design position."""

    at: Optional[Annotated[list[Number] | list[Annotated[list[Number], Field(min_length=1, max_length=20)]],
                           Field(min_length=1, max_length=MAX_SAMPLES)]] = None
    times: Optional[Annotated[list[Number], Field(min_length=1, max_length=MAX_SAMPLES)]] = None

    @model_validator(mode="after")
    def _either(self) -> "At":
        if self.at is not None and self.times is not None:
            raise ValueError("give either at or times, not both")
        return self


class SolveRequest(At):
    source: Source
    order: int | None = Field(None, ge=1, le=4, description="highest time derivative (default 2, accelerations; a chain driven by given point velocities: as far as its data go)")


class MotionRequest(Strict):
    source: Source
    detail: Literal["full", "status"] = Field(
        "full", description="full: the samples of `analyze --format json`; status: each "
                            "sample's input, status and error bound only")


class PolesRequest(At):
    source: Source
    schedule: bool = False


class CurvatureRequest(At):
    source: Source
    link: Name
    relative_to: Optional[Name] = None
    points: Annotated[list[Name | tuple[Number, Number]], Field(max_length=100)] = []


class ConstructionRequest(At):
    source: Source
    name: ConstructionName
    point: Optional[Name] = None
    link: Optional[Name] = None


class View(Strict):
    """A mechanism panel's world box and scale (a drawing's `transforms["mechanism"]`)."""

    lo: tuple[Number, Number]
    hi: tuple[Number, Number]
    per_mm: float = Field(gt=0, le=MAX_MAGNITUDE, allow_inf_nan=False,
                          description="world length per mm of paper")
    velocity_per_mm: Optional[float] = Field(
        None, gt=0, le=MAX_MAGNITUDE, allow_inf_nan=False,
        description="velocity per mm of a drawn vector (a drawing's `scales`), else this frame's")
    acceleration_per_mm: Optional[float] = Field(
        None, gt=0, le=MAX_MAGNITUDE, allow_inf_nan=False,
        description="acceleration per mm of a drawn vector, else this frame's")

    @model_validator(mode="after")
    def _size(self) -> "View":
        if not (self.hi[0] > self.lo[0] and self.hi[1] > self.lo[1]):
            raise ValueError("hi must exceed lo in x and in y (a box of positive size)")
        return self


class DrawingRequest(At):
    """One position drawn with the layers of `linkwork draw --show` and, optionally, a
    construction up to `step` (0-based; all steps if omitted)."""

    source: Source
    layers: Annotated[list[Layer], Field(max_length=len(LAYERS))] = ["mechanism"]
    construction: Optional[ConstructionName] = None
    point: Optional[Name] = None
    link: Optional[Name] = None
    step: Optional[int] = Field(None, ge=0, le=1000)
    paths: Optional[Annotated[list[Name], Field(max_length=1000)]] = Field(
        None, description="the points whose paths the paths layer traces (default: every "
                          "moving point; an empty list: none)")
    motion: bool = Field(
        True, description="false: leave the whole motion out (no paths; the panel fits the "
                          "position drawn), for the frames of a drag")
    fit: Literal["motion", "drawing"] = Field(
        "motion", description="motion: the panel fits the whole motion, so that frames of an "
                              "animation share one layout; drawing: it fits what is drawn")
    view: Optional[View] = Field(
        None, description="the mechanism panel's box and scale, instead of `fit` (a drag's "
                          "frames keep the view of the drawing the drag began on)")


class PngRequest(DrawingRequest):
    """The drawing of a `DrawingRequest` as PNG (converted from the same SVG by cairo)."""

    dpi: float = Field(200.0, ge=30.0, le=600.0, description="pixels per inch of paper")


# ---------------------------------------------------------------------------- responses
class Error(BaseModel):
    error: str = Field(description="the message, naming the part and the reason")
    kind: str = Field(description="the error's type, e.g. MechanismFileError")


class LibraryEntry(BaseModel):
    name: str
    title: str


class LibraryList(BaseModel):
    mechanisms: list[LibraryEntry]
    files: list[str] = Field(description="mechanism files of the working folder (relative)")


class MechanismText(BaseModel):
    name: str
    text: str


class JointInfo(BaseModel):
    name: str
    type: str
    links: list[str]
    point: Optional[str] = None


class DriverInfo(BaseModel):
    joint: str
    kind: Literal["revolute", "prismatic"]
    design_input: float = Field(description="the input at the design position (rad or length)")


class MechanismInfo(BaseModel):
    name: str
    description: str
    source: str
    text: str
    units: dict[str, str]
    frame: str
    points: dict[str, list[float]]
    links: dict[str, list[str]]
    owners: dict[str, str] = Field(description="the link each point's design coordinates belong to")
    joints: list[JointInfo]
    drivers: list[DriverInfo]
    layers: list[str]
    constructions: list[str]
    warnings: list[str] = []


class SolutionDocument(BaseModel):
    """The document of `linkwork analyze --format json`."""

    mechanism: str
    units: dict[str, str]
    drivers: list[str]
    samples: list[dict[str, Any]]
    warnings: list[str] = []


class Document(BaseModel):
    """A JSON document as the command line writes it (`poles`, `curvature`, `structure`
    with `--format json`)."""

    model_config = ConfigDict(extra="allow")
    mechanism: Any


class ConstructionResult(BaseModel):
    name: str
    title: str
    steps: list[str]
    description: str
    warnings: list[str] = []


class Drawing(BaseModel):
    svg: str = Field(description="the SVG of `linkwork draw` for the same request")
    status: str
    input: list[Optional[float]]
    time: Optional[float] = None
    points: dict[str, Optional[list[float]]] = Field(description="point positions drawn")
    poses: dict[str, Optional[list[float]]] = Field(
        description="each link's pose [x, y, θ]: a point's position is R(θ)·design + (x, y)")
    transforms: dict[str, dict[str, Any]] = Field(
        description="per panel: x_svg = origin[0] + (x − lo[0])/per_mm, "
                    "y_svg = origin[1] + (hi[1] − y)/per_mm")
    steps: list[str] = []
    scales: dict[str, Optional[float]] = Field(
        default_factory=dict, description="the drawing's scales, units per mm of paper: length, "
                                          "velocity, acceleration (null: none drawn)")
    march: Optional[str] = Field(
        None, description="a moved mechanism with Newton-solved groups: whether their march "
                          "was carried over from the drag's previous frame, or marched again "
                          "from the design position's branch and why")
    warnings: list[str] = []
