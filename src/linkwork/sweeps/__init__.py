"""Design sweeps: vary a mechanism's dimensions over a grid or a random sample, solve each design
over its motion and reduce the motion to metrics (transmission angle, Grashof class, stroke,
time ratio, straightness, …). `plan` parses the arguments, `execute` runs the designs on all
cores (and resumes an interrupted sweep), `write` saves CSV or Parquet with units.
"""

from .designs import Parameter, apply, grid, parameter, random_designs
from .metrics import METRICS, Metric, evaluate, parse_metric
from .run import SweepPlan, execute, plan, run_designs, to_frame, write

__all__ = ["METRICS", "Metric", "Parameter", "SweepPlan", "apply", "evaluate", "execute", "grid",
           "parameter", "parse_metric", "plan", "random_designs", "run_designs", "to_frame", "write"]
