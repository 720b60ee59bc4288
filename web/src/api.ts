// The workbench API's shapes (src/linkwork/web/models.py) and one function to call it.
// Units as in the Python API: the file's length unit, radians, seconds.

export type XY = [number, number];

export interface Source {
  library?: string;
  file?: string;
  text?: string;
  name?: string;
  points?: Record<string, XY>;
}

export interface DriverInfo {
  joint: string;
  kind: "revolute" | "prismatic";
  design_input: number;
}

export interface MechanismInfo {
  name: string;
  description: string;
  source: string;
  text: string;
  units: { length: string; angle: string; time: string };
  frame: string;
  points: Record<string, XY>;
  links: Record<string, string[]>;
  owners: Record<string, string>;
  drivers: DriverInfo[];
  layers: string[];
  constructions: string[];
  warnings: string[];
}

export interface LibraryList {
  mechanisms: { name: string; title: string }[];
  files: string[];
}

export type Status = "ok" | "singular" | "unreachable";

export interface MotionSample {
  input: number | number[];
  status: Status;
  error: number | null;
}

export interface Motion {
  mechanism: string;
  drivers: string[];
  samples: MotionSample[];
  warnings: string[];
}

export interface Transform {
  origin: XY;
  lo: XY;
  hi: XY;
  per_mm: number;
}

export interface Drawing {
  svg: string;
  status: Status;
  input: (number | null)[];
  points: Record<string, XY | null>;
  poses: Record<string, [number, number, number] | null>;
  transforms: Record<string, Transform>;
  steps: string[];
  warnings: string[];
}

export interface DrawingRequest {
  source: Source;
  at?: number[];
  layers: string[];
  construction?: string;
  fit?: "motion" | "drawing";
  motion?: boolean;
}

/** An answer of the API that is not 2xx: its message, as the server wrote it. */
export class ApiError extends Error {
  constructor(message: string, readonly status: number, readonly kind: string) {
    super(message);
  }
}

async function answer<T>(r: Response): Promise<T> {
  let body: unknown;
  try {
    body = await r.json();
  } catch {
    throw new ApiError(`the server answered ${r.status} without JSON`, r.status, "Network");
  }
  if (!r.ok) {
    const e = body as { error?: string; kind?: string };
    throw new ApiError(e.error ?? `error ${r.status}`, r.status, e.kind ?? "Error");
  }
  return body as T;
}

export async function get<T>(path: string): Promise<T> {
  return answer<T>(await fetch(path));
}

export async function post<T>(path: string, body: unknown): Promise<T> {
  return answer<T>(await fetch(path, {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify(body),
  }));
}

/** World coordinates of a panel → SVG user units (mm of paper, y down). */
export function toSvg(t: Transform, p: XY): XY {
  return [t.origin[0] + (p[0] - t.lo[0]) / t.per_mm, t.origin[1] + (t.hi[1] - p[1]) / t.per_mm];
}

/** SVG user units → world coordinates of a panel. */
export function toWorld(t: Transform, q: XY): XY {
  return [t.lo[0] + (q[0] - t.origin[0]) * t.per_mm, t.hi[1] - (q[1] - t.origin[1]) * t.per_mm];
}
