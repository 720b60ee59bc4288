"""The PMKS kinetostatics reference cases (../shared/reference/pmks-kinetostatics-v1) as
linkwork mechanisms with mass data, built from each case.json alone (its joints' first-sample
positions are the design drawing)."""

import csv
import json

import numpy as np

import linkwork
from linkwork.model import Mechanism, Revolute
from linkwork.model.inertia import Dynamics, Loads, MassProperties, PointForce

from conftest import SHARED

ROOT = SHARED / "reference" / "pmks-kinetostatics-v1" / "cases"
CASES = ("stephenson_iii_example_2", "teaching_four_bar", "watt_i")


def table(path) -> dict[str, np.ndarray]:
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0] if k != "sample_id"}


def case(case_id: str):
    """(meta, mechanism, masses, loads builder) of a reference case."""
    meta = json.loads((ROOT / case_id / "case.json").read_text())
    points = {j["id"]: j["position_first_sample"] for j in meta["joints"]}
    links = {"ground": [j["id"] for j in meta["joints"] if "ground" in j["links"]]}
    receiver = {}  # joint -> the link whose reaction sign is +1 (the reported force acts on it)
    for ln in meta["links"]:
        links[ln["id"]] = list(ln["joints"])
        for jn, sign in ln["reaction_signs"].items():
            if sign == 1:
                receiver.setdefault(jn, ln["id"])
    joints = []
    for j in meta["joints"]:
        on = receiver[j["id"]]
        other = next(x for x in j["links"] if x != on)
        joints.append(Revolute(j["id"], j["id"], (other, on)))  # links[0] acts on links[1]
    inp = meta["input"]
    input_link = next(ln for ln in meta["links"] if ln["id"] == inp["link"])
    ref = next(p for p in input_link["joints"] if p != inp["joint"])
    mech = Mechanism.build(name=case_id, points=points, links=links, joints=joints,
                           drivers=[{"joint": inp["joint"], "reference": ref}], frame="ground",
                           length_unit="m")
    masses = {ln["id"]: MassProperties(float(ln["mass"]), np.array(ln["com_first_sample"], float),
                                       float(ln["inertia_about_com"]))
              for ln in meta["links"]}
    return meta, mech, masses


def dynamics(case_id: str, gravity: bool) -> tuple[dict, Dynamics]:
    meta, mech, masses = case(case_id)
    forces = tuple(
        PointForce(ld["link"], np.mean([mech.points[p] for p in ld["application_point_mean_of"]], axis=0),
                   np.array(ld["force"], float), name=f"load{i}")
        for i, ld in enumerate(meta.get("external_loads", [])))
    g = np.array(meta["gravity"]["vector"], float) if gravity else np.zeros(2)
    return meta, Dynamics.build(mech, masses, Loads(gravity=g, forces=forces), metres_per_unit=1.0)


def motion(meta: dict, mech: Mechanism, case_id: str):
    kin = table(ROOT / case_id / "kinematics.csv")
    speed = meta["input"]["speed_rad_s"]
    return kin, linkwork.solve(mech, kin["input_angle_rad"], velocities=speed * kin["input_direction"])
