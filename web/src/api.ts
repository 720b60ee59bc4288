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
  joints: { name: string; type: string; links: string[]; point: string | null }[];
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

export interface PointState {
  position: [number | null, number | null];
  velocity: [number | null, number | null] | null;
  acceleration: [number | null, number | null] | null;
}

export interface LinkState {
  angle: number | null;
  omega: number | null;
  alpha: number | null;
}

/** A pair's (joint's) numbers: relative angle, ω, α; a prismatic pair also its slide. */
export type JointState = Record<string, number | [number | null, number | null] | null>;

/** A sample of `analyze --format json` (the full motion document). */
export interface FullSample extends MotionSample {
  time?: number | null; // seconds, where the driver has a time law
  condition: number | null;
  points: Record<string, PointState>;
  links: Record<string, LinkState>;
  joints: Record<string, JointState>;
}

export interface FullMotion {
  mechanism: string;
  drivers: string[];
  samples: FullSample[];
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
  scales?: { length: number | null; velocity: number | null; acceleration: number | null };
  warnings: string[];
}

export interface DrawingRequest {
  source: Source;
  at?: number[] | number[][];
  layers: string[];
  construction?: string;
  step?: number;
  paths?: string[];
  link?: string;
  point?: string;
  fit?: "motion" | "drawing";
  motion?: boolean;
  // the mechanism panel's box and scales, instead of fit (a drag holds those it began with)
  view?: { lo: XY; hi: XY; per_mm: number; velocity_per_mm?: number; acceleration_per_mm?: number };
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

/** When a POST's answer came (performance.now(), ms): its headers, its body parsed; and the
 * server's stages (its Server-Timing header: name → ms). */
export interface Timed<T> {
  body: T;
  headers: number;
  parsed: number;
  server: Record<string, number>;
}

export async function postTimed<T>(path: string, body: unknown): Promise<Timed<T>> {
  const r = await fetch(path, {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify(body),
  });
  const headers = performance.now();
  const out = await answer<T>(r);
  const server: Record<string, number> = {};
  for (const part of (r.headers.get("server-timing") ?? "").split(",")) {
    const m = /^\s*([\w-]+)\s*;\s*dur=([\d.]+)/.exec(part);
    if (m) server[m[1]] = Number(m[2]);
  }
  return { body: out, headers, parsed: performance.now(), server };
}

/** A closed socket's answer: the request goes over HTTP instead. */
class SocketClosed extends Error {}

/** The drawings over the server's WebSocket (`/api/drawing/ws`: the requests and answers of
 * `POST /api/drawing`, without an HTTP round trip each), one request at a time; over HTTP when
 * the socket is not open (not yet, closed, or refused by something between) or is busy. A
 * closed socket is opened again on a later request, at most every 2 s. */
export class DrawingSocket {
  private ws: WebSocket | null = null;
  private waiting: { resolve: (t: Timed<Drawing>) => void; reject: (e: unknown) => void } | null = null;
  private tried = -Infinity;

  constructor(private readonly url: string) {
    this.connect();
  }

  private connect(): void {
    const now = performance.now();
    if (this.ws || typeof WebSocket === "undefined" || now - this.tried < 2000) return;
    this.tried = now;
    const ws = new WebSocket(this.url);
    ws.onmessage = (ev) => {
      const headers = performance.now();
      const w = this.waiting;
      this.waiting = null;
      if (!w) return;
      let a: { status: number; timing: Record<string, number>; body: unknown };
      try {
        a = JSON.parse(ev.data as string);
      } catch {
        w.reject(new ApiError("the server answered without JSON", 500, "Network"));
        return;
      }
      const parsed = performance.now();
      if (a.status >= 200 && a.status < 300) {
        w.resolve({ body: a.body as Drawing, headers, parsed, server: a.timing });
      } else {
        const e = a.body as { error?: string; kind?: string };
        w.reject(new ApiError(e.error ?? `error ${a.status}`, a.status, e.kind ?? "Error"));
      }
    };
    ws.onclose = () => {
      if (this.ws === ws) this.ws = null;
      const w = this.waiting;
      this.waiting = null;
      w?.reject(new SocketClosed());
    };
    this.ws = ws;
  }

  /** The drawing for `req`, and how it came ("socket" or "http"). */
  async drawing(req: DrawingRequest): Promise<Timed<Drawing> & { via: string }> {
    this.connect();
    const ws = this.ws;
    if (ws && ws.readyState === WebSocket.OPEN && !this.waiting) {
      try {
        const answer = await new Promise<Timed<Drawing>>((resolve, reject) => {
          this.waiting = { resolve, reject };
          ws.send(JSON.stringify(req));
        });
        return { ...answer, via: "socket" };
      } catch (e) {
        if (!(e instanceof SocketClosed)) throw e;
      }
    }
    return { ...(await postTimed<Drawing>("/api/drawing", req)), via: "http" };
  }
}

/** A POST whose answer is a file (PNG, CSV); errors come as JSON like every other answer. */
export async function postFile(path: string, body: unknown): Promise<Blob> {
  const r = await fetch(path, {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify(body),
  });
  if (!r.ok) await answer<never>(r);
  return r.blob();
}

/** World coordinates of a panel → SVG user units (mm of paper, y down). */
export function toSvg(t: Transform, p: XY): XY {
  return [t.origin[0] + (p[0] - t.lo[0]) / t.per_mm, t.origin[1] + (t.hi[1] - p[1]) / t.per_mm];
}

/** SVG user units → world coordinates of a panel. */
export function toWorld(t: Transform, q: XY): XY {
  return [t.lo[0] + (q[0] - t.origin[0]) * t.per_mm, t.hi[1] - (q[1] - t.origin[1]) * t.per_mm];
}
