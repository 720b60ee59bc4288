// The workbench page: open a mechanism, see it drawn by the server (the SVG of `linkwork draw`),
// animate its input, drag its design points, toggle the layers. All numbers come from the API;
// the page only asks, shows and maps the pointer into the drawing's world coordinates.

import {
  ApiError, Drawing, DrawingSocket, DrawingRequest, FullMotion, FullSample, LibraryList, MechanismInfo, Motion,
  Source, Transform, XY, get, post, postFile, toSvg, toWorld,
} from "./api";
import { EditError, addEntry, addToLink, removeEntry, removeFromLinks } from "./edit";
import { showSvg } from "./morph";
import { plotSvg } from "./plot";

const $ = <T extends HTMLElement>(id: string): T => {
  const el = document.getElementById(id);
  if (!el) throw new Error(`the page has no #${id}`);
  return el as T;
};

const ui = {
  mechanism: $<HTMLSelectElement>("mechanism"),
  upload: $<HTMLInputElement>("upload"),
  save: $<HTMLButtonElement>("save"),
  exportSvg: $<HTMLButtonElement>("export-svg"),
  exportPng: $<HTMLButtonElement>("export-png"),
  exportCsv: $<HTMLButtonElement>("export-csv"),
  editOp: $<HTMLSelectElement>("edit-op"),
  editName: $<HTMLInputElement>("edit-name"),
  editLink: $<HTMLInputElement>("edit-link"),
  editXy: $<HTMLInputElement>("edit-xy"),
  editMembers: $<HTMLInputElement>("edit-members"),
  editMembersWhat: $<HTMLSpanElement>("edit-members-what"),
  editApply: $<HTMLButtonElement>("edit-apply"),
  editText: $<HTMLTextAreaElement>("edit-text"),
  editTextApply: $<HTMLButtonElement>("edit-text-apply"),
  editor: $<HTMLFieldSetElement>("editor"),
  error: $<HTMLDivElement>("error"),
  drawing: $<HTMLDivElement>("drawing"),
  title: $<HTMLHeadingElement>("title"),
  description: $<HTMLParagraphElement>("description"),
  play: $<HTMLButtonElement>("play"),
  speed: $<HTMLSelectElement>("speed"),
  slider: $<HTMLInputElement>("input-slider"),
  strip: $<HTMLDivElement>("status-strip"),
  inputValue: $<HTMLOutputElement>("input-value"),
  inputTime: $<HTMLOutputElement>("input-time"),
  sampleStatus: $<HTMLOutputElement>("sample-status"),
  layers: $<HTMLFieldSetElement>("layers"),
  edit: $<HTMLInputElement>("edit"),
  numbers: $<HTMLTableElement>("numbers"),
  structure: $<HTMLDListElement>("structure"),
  construction: $<HTMLSelectElement>("construction"),
  constructionLink: $<HTMLSelectElement>("construction-link"),
  constructionPoint: $<HTMLSelectElement>("construction-point"),
  stepBack: $<HTMLButtonElement>("step-back"),
  stepForward: $<HTMLButtonElement>("step-forward"),
  stepCount: $<HTMLOutputElement>("step-count"),
  stepText: $<HTMLParagraphElement>("step-text"),
  quantity: $<HTMLSelectElement>("quantity"),
  plot: $<HTMLDivElement>("plot"),
  pathsOf: $<HTMLSelectElement>("paths-of"),
  selection: $<HTMLSelectElement>("selection"),
  selected: $<HTMLTableElement>("selected"),
};

/** Layers drawn over the mechanism, and the plans (constructions drawn beside it). */
const PLANS: Record<string, string> = { "velocity-plan": "velocity plan", "acceleration-plan": "acceleration plan" };

interface State {
  base: Source | null; // the mechanism as opened (library, file or text)
  moved: Record<string, XY>; // design points dragged since
  info: MechanismInfo | null;
  motion: Motion | null;
  full: Promise<FullMotion> | null; // the whole motion with every number, asked for when needed
  motionSource: Source | null; // the design the motion is of
  index: number;
  playing: boolean;
  layers: Set<string>;
  plan: string | null;
  // the construction played step by step (0-based step; its link and point, if chosen)
  construction: { name: string; link: string; point: string; step: number } | null;
  drawn: Drawing | null;
  busy: boolean;
  again: boolean;
  generation: number; // drawings asked for a mechanism that is no longer open are dropped
  broken: string | null; // the engine's message on an edited file that does not build
}

const state: State = {
  base: null, moved: {}, info: null, motion: null, full: null, motionSource: null, index: 0, playing: false,
  layers: new Set(), plan: null, construction: null, drawn: null, busy: false, again: false, generation: 0,
  broken: null,
};

/** A drag's frame as it went (performance.now(), ms): the pointer's move (the event's own time
 * stamp, and when its handler ran), the request sent, its answer's headers and body, the drawing
 * in the page, the first paint after it; and the server's stages (its Server-Timing, ms). */
interface Frame {
  event: number;
  handler: number;
  sent: number;
  headers: number;
  parsed: number;
  shown: number;
  painted: number;
  server: Record<string, number>;
  via: string; // "socket" or "http"
}

// every drawing of a drag, as it went (a "linkworkframe" event on the window says when one is
// added); bench/bench_workbench.py reads them
const frames: Frame[] = [];
// for the bench and the browser tests: the frames of drags, and whether a drawing is on its way
Object.assign(window, { linkworkFrames: frames, linkworkBusy: () => state.busy });
// the drawings over a WebSocket while it is open (a drag's frames skip an HTTP round trip each)
const drawings = new DrawingSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/api/drawing/ws`);
let movedAt: { event: number; handler: number } | null = null; // the pointer's last move of a drag

function source(): Source {
  const s: Source = { ...(state.base as Source) };
  if (Object.keys(state.moved).length) s.points = { ...state.moved };
  return s;
}

// ------------------------------------------------------------------ messages
function showError(message: string): void {
  ui.error.textContent = message;
  ui.error.hidden = false;
}

function clearError(): void {
  if (ui.error.hidden) return; // every drawing clears it: no write when there is nothing to clear
  ui.error.textContent = "";
  ui.error.hidden = true;
}

function messageOf(e: unknown): string {
  return e instanceof ApiError || e instanceof Error ? e.message : String(e);
}

// ------------------------------------------------------------------ inputs
function sampleInput(k: number): number[] {
  const s = state.motion?.samples[k];
  if (!s) return [];
  return Array.isArray(s.input) ? s.input : [s.input];
}

function inputText(values: (number | null)[]): string {
  const info = state.info;
  if (!info) return "";
  return values.map((v, i) => {
    if (v === null) return "—";
    const d = info.drivers[i];
    const text = d.kind === "prismatic" ? `${v.toFixed(3)} ${info.units.length}` : `${((v * 180) / Math.PI).toFixed(2)}°`;
    return info.drivers.length > 1 ? `${d.joint} ${text}` : text;
  }).join(", ");
}

// ------------------------------------------------------------------ drawing
function drawingRequest(): DrawingRequest {
  const layers = ["mechanism", ...Array.from(state.layers)];
  const req: DrawingRequest = { source: source(), layers };
  if (state.motion) {
    // one sample: a number per driver, as one list of them when there are several
    const at = sampleInput(state.index);
    req.at = at.length > 1 ? [at] : at;
  }
  const c = state.construction;
  if (c) {
    req.construction = c.name;
    req.step = c.step;
    if (c.link) req.link = c.link;
    if (c.point) req.point = c.point;
  } else if (state.plan) req.construction = state.plan;
  // while dragging (or moving a point by keys), the frames leave the whole motion out: they
  // follow the pointer sooner; and they keep the view (box and scale) of the drawing the drag
  // began on, which the pointer is read in (fitted to the frame alone, the view would zoom)
  if (dragging || settling !== undefined) {
    req.motion = false;
    if (held) {
      req.view = { lo: held.lo, hi: held.hi, per_mm: held.per_mm };
      // the vectors keep the length they had when the drag began
      if (heldScales?.velocity) req.view.velocity_per_mm = heldScales.velocity;
      if (heldScales?.acceleration) req.view.acceleration_per_mm = heldScales.acceleration;
    }
  }
  const traced = Array.from(ui.pathsOf.selectedOptions).map((o) => o.value);
  if (traced.length) req.paths = traced;
  return req;
}

/** Ask for the drawing of the current state; while one is on its way, only the latest wish
 * is sent after it (dragging and playing never queue up). */
async function redraw(): Promise<void> {
  if (state.broken) return; // the last drawing of the file that built stays, greyed
  if (state.busy) {
    state.again = true;
    return;
  }
  state.busy = true;
  try {
    do {
      state.again = false;
      const generation = state.generation;
      const req = drawingRequest();
      const asked = req.motion === false ? movedAt : null;
      movedAt = null;
      try {
        const sent = performance.now();
        const answer = await drawings.drawing(req);
        if (generation !== state.generation) continue;
        show(answer.body, req);
        if (dragging && answer.body.status !== "unreachable" && aim()) state.again = true;
        if (asked) {
          const frame: Frame = { ...asked, sent, headers: answer.headers, parsed: answer.parsed,
            shown: performance.now(), painted: NaN, server: answer.server, via: answer.via };
          // after the next paint: a task queued in the frame callback runs after it
          requestAnimationFrame(() => window.setTimeout(() => {
            frame.painted = performance.now();
            frames.push(frame);
            window.dispatchEvent(new Event("linkworkframe"));
          }, 0));
        }
        clearError();
      } catch (e) {
        if (generation !== state.generation) continue;
        if (req.construction && e instanceof ApiError && e.status === 400) {
          // a plan that cannot be drawn here: say why, draw the rest
          showError(`${PLANS[req.construction] ?? req.construction}: ${e.message}`);
          if (state.construction) stepShown([], 0);
          const plain = { ...req, construction: undefined, step: undefined };
          const rest = await post<Drawing>("/api/drawing", plain).catch(() => null);
          if (rest && generation === state.generation) show(rest, plain);
        } else {
          // the last good drawing stays, greyed, with the engine's message above it
          ui.drawing.classList.add("stale");
          showError(messageOf(e));
          ui.sampleStatus.textContent = e instanceof ApiError && /assembled/.test(e.message) ? "unreachable" : "error";
        }
      }
    } while (state.again);
  } finally {
    state.busy = false;
  }
}

function show(d: Drawing, req: DrawingRequest): void {
  state.drawn = d;
  showSvg(ui.drawing, d.svg);
  ui.drawing.classList.remove("stale");
  const t = d.transforms["mechanism"];
  ui.drawing.dataset.transform = JSON.stringify(t);
  ui.drawing.dataset.input = JSON.stringify(d.input);
  ui.drawing.dataset.moved = JSON.stringify(req.source.points ?? {});
  setText(ui.inputValue, inputText(d.input));
  setText(ui.sampleStatus, d.status);
  if (ui.sampleStatus.className !== d.status) ui.sampleStatus.className = d.status;
  numbers(d);
  void plot();
  void selected(d, req);
  if (req.construction && state.construction && req.construction === state.construction.name) {
    stepShown(d.steps, req.step ?? 0);
  }
}

/** The step drawn and its text (as the engine words it), and which way one can step. */
function stepShown(steps: string[], k: number): void {
  const n = steps.length;
  ui.stepCount.textContent = n ? `step ${k + 1} of ${n}` : "";
  ui.stepText.textContent = n ? steps[k] : "";
  ui.stepText.dataset.step = String(k);
  ui.stepBack.disabled = !n || k <= 0;
  ui.stepForward.disabled = !n || k >= n - 1;
}

function step(by: number): void {
  const c = state.construction;
  const n = state.drawn?.steps.length ?? 0;
  if (!c || !n) return;
  const k = Math.min(Math.max(c.step + by, 0), n - 1);
  if (k === c.step) return;
  c.step = k;
  void redraw();
}

function chooseConstruction(): void {
  const name = ui.construction.value;
  state.construction = name ? {
    name, link: ui.constructionLink.value, point: ui.constructionPoint.value, step: 0,
  } : null;
  if (name) { // one construction is drawn at a time: the plans' toggles give way
    state.plan = null;
    for (const other of Object.keys(PLANS)) {
      const box = document.getElementById(`show-${other}`) as HTMLInputElement | null;
      if (box) box.checked = false;
    }
  }
  stepShown([], 0);
  void redraw();
}

function buildConstructions(info: MechanismInfo): void {
  const keep = ui.construction.value;
  ui.construction.innerHTML = `<option value="">none</option>` + info.constructions
    .map((c) => `<option value="${c}">${c}</option>`).join("");
  ui.construction.value = info.constructions.includes(keep) ? keep : "";
  const moving = Object.keys(info.links).filter((l) => l !== info.frame);
  ui.constructionLink.innerHTML = `<option value="">default</option>` + moving
    .map((l) => `<option value="${escapeHtml(l)}">${escapeHtml(l)}</option>`).join("");
  ui.constructionPoint.innerHTML = `<option value="">default</option>` + Object.keys(info.points)
    .map((p) => `<option value="${escapeHtml(p)}">${escapeHtml(p)}</option>`).join("");
  state.construction = null;
  if (ui.construction.value) chooseConstruction();
  else stepShown([], 0);
}

function numbers(d: Drawing): void {
  const unit = state.info?.units.length ?? "";
  const head = ui.numbers.tHead as HTMLTableSectionElement;
  if (head.dataset.unit !== unit) {
    head.innerHTML = `<tr><th>point</th><th>x [${unit}]</th><th>y [${unit}]</th></tr>`;
    head.dataset.unit = unit;
  }
  const body = ui.numbers.tBodies[0];
  const points = Object.entries(d.points);
  // the same points as shown (a frame of a drag): only the numbers that changed are written
  const rows = body.rows;
  if (rows.length !== points.length || points.some(([name], k) => rows[k].dataset.point !== name)) {
    body.innerHTML = "";
    for (const [name] of points) {
      const row = body.insertRow();
      row.dataset.point = name;
      row.insertCell().textContent = name;
      // each number in a box of its own size (class num): a number that changes is laid out
      // in its box alone, not the page (which would lay the drawing out again too)
      for (const _ of [0, 1]) row.insertCell().innerHTML = `<span class="num"></span>`;
    }
  }
  points.forEach(([, xy], k) => {
    const cells = rows[k].cells;
    for (const i of [0, 1]) setText(cells[i + 1].firstElementChild as HTMLElement, xy ? xy[i].toFixed(4) : "—");
  });
}

/** Write `text` into `el` if it shows another: an unchanged text is left alone (writing it
 * again would replace its text node and lay the page out again). */
function setText(el: HTMLElement, text: string): void {
  if (el.textContent !== text) el.textContent = text;
}

// ------------------------------------------------------------------ quantities and plots
/** What can be read off a sample: a point's x, y, speed and acceleration magnitude, a link's
 * angle, angular velocity and acceleration, in the file's length unit, degrees and radians. */
interface Quantity {
  label: string;
  unit: string;
  of: (s: FullSample) => number | null;
}

const hyp = (v: [number | null, number | null] | null | undefined): number | null =>
  v && v[0] !== null && v[1] !== null ? Math.hypot(v[0], v[1]) : null;

function quantities(info: MechanismInfo): Map<string, Quantity> {
  const u = info.units.length;
  const out = new Map<string, Quantity>();
  for (const p of Object.keys(info.points)) {
    out.set(`point:${p}:x`, { label: `${p} x`, unit: u, of: (s) => s.points[p]?.position[0] ?? null });
    out.set(`point:${p}:y`, { label: `${p} y`, unit: u, of: (s) => s.points[p]?.position[1] ?? null });
    out.set(`point:${p}:v`, { label: `${p} |v|`, unit: `${u}/s`, of: (s) => hyp(s.points[p]?.velocity) });
    out.set(`point:${p}:a`, { label: `${p} |a|`, unit: `${u}/s²`, of: (s) => hyp(s.points[p]?.acceleration) });
  }
  for (const l of Object.keys(info.links)) {
    if (l === info.frame) continue;
    const deg = (v: number | null | undefined) => (v === null || v === undefined ? null : (v * 180) / Math.PI);
    out.set(`link:${l}:angle`, { label: `${l} angle`, unit: "°", of: (s) => deg(s.links[l]?.angle) });
    out.set(`link:${l}:omega`, { label: `${l} ω`, unit: "rad/s", of: (s) => s.links[l]?.omega ?? null });
    out.set(`link:${l}:alpha`, { label: `${l} α`, unit: "rad/s²", of: (s) => s.links[l]?.alpha ?? null });
  }
  return out;
}

function buildQuantities(info: MechanismInfo): void {
  const keep = ui.quantity.value;
  const qs = quantities(info);
  ui.quantity.innerHTML = `<option value="">none</option>` + Array.from(qs.entries())
    .map(([k, q]) => `<option value="${escapeHtml(k)}">${escapeHtml(q.label)} [${escapeHtml(q.unit)}]</option>`).join("");
  ui.quantity.value = qs.has(keep) ? keep : "";
}

/** The whole motion with every number (asked for once per design, when a panel needs it). */
function fullMotion(): Promise<FullMotion> {
  if (!state.full) {
    state.full = post<FullMotion>("/api/motion", { source: state.motionSource ?? source(), detail: "full" });
    state.full.catch(() => { state.full = null; });
  }
  return state.full;
}

let plotted = ""; // the quantity and sample drawn last (a plot is redrawn when either changes)

async function plot(): Promise<void> {
  const key = ui.quantity.value;
  const info = state.info;
  if (!key || !info || !state.motion) {
    ui.plot.replaceChildren(); // every drawing comes here: emptied without running the parser
    plotted = "";
    return;
  }
  const q = quantities(info).get(key);
  if (!q) return;
  const generation = state.generation;
  let full: FullMotion;
  try {
    full = await fullMotion();
  } catch (e) {
    ui.plot.textContent = messageOf(e);
    return;
  }
  if (generation !== state.generation || key !== ui.quantity.value) return;
  const wish = `${key}@${state.index}#${generation}`;
  if (wish === plotted) return;
  plotted = wish;
  ui.plot.innerHTML = plotSvg({
    label: q.label, unit: q.unit, values: full.samples.map(q.of),
    inputs: full.samples.map((s) => inputText(Array.isArray(s.input) ? s.input : [s.input])),
  }, state.index);
  ui.plot.dataset.quantity = key;
}

// ------------------------------------------------------------------ selection
/** The units of a pair's numbers (the names of the JSON of `analyze`). */
function jointUnit(field: string, u: string): string {
  return ({
    angle: "°", omega: "rad/s", alpha: "rad/s²", slide: u, sliding_velocity: `${u}/s`,
    sliding_acceleration: `${u}/s²`, velocity: `${u}/s`, acceleration: `${u}/s²`, coriolis: `${u}/s²`,
  } as Record<string, string>)[field] ?? "";
}

const wrapDegrees = (d: number): number => { const w = ((d % 360) + 360) % 360; return w > 180 ? w - 360 : w; };

const num = (v: number | null | undefined, digits = 4): string =>
  v === null || v === undefined || !Number.isFinite(v) ? "—" : v.toFixed(digits);

let selectedFor = ""; // the request whose numbers the panel shows

/** The numbers of the selected point, link or pair at the drawn input (`linkwork.solve`). */
async function selected(d: Drawing, req: DrawingRequest): Promise<void> {
  const choice = ui.selection.value;
  const info = state.info;
  const body = ui.selected.tBodies[0];
  if (!choice || !info) {
    body.replaceChildren();
    selectedFor = "";
    return;
  }
  if (d.input.some((v) => v === null)) return;
  const at = info.drivers.length === 1 ? [d.input[0] as number] : [d.input as number[]];
  const ask = JSON.stringify({ source: req.source, at, choice });
  if (ask === selectedFor) return;
  selectedFor = ask;
  let doc: { samples: FullSample[] };
  try {
    doc = await post<{ samples: FullSample[] }>("/api/solve", { source: req.source, at, order: 2 });
  } catch (e) {
    body.innerHTML = `<tr><td>${escapeHtml(messageOf(e))}</td></tr>`;
    return;
  }
  if (ask !== selectedFor) return;
  const s = doc.samples[0];
  const u = info.units.length;
  const rows: [string, string, string][] = [];
  const [kind, name] = [choice.slice(0, choice.indexOf(":")), choice.slice(choice.indexOf(":") + 1)];
  const vec = (label: string, v: [number | null, number | null] | null | undefined, unit: string, size = true) => {
    rows.push([`${label}x`, num(v?.[0]), unit], [`${label}y`, num(v?.[1]), unit]);
    if (size) rows.push([`|${label}|`, num(hyp(v ?? null)), unit]);
  };
  if (kind === "point") {
    const p = s.points[name];
    rows.push(["x", num(p?.position[0]), u], ["y", num(p?.position[1]), u]);
    vec("v", p?.velocity, `${u}/s`);
    vec("a", p?.acceleration, `${u}/s²`);
  } else if (kind === "link") {
    const l = s.links[name];
    rows.push(["angle", num(l ? (l.angle === null ? null : (l.angle * 180) / Math.PI) : null), "°"],
      ["ω", num(l?.omega), "rad/s"], ["α", num(l?.alpha), "rad/s²"]);
  } else {
    for (const [field, v] of Object.entries(s.joints[name] ?? {})) {
      const unit = jointUnit(field, u);
      const label = ({ omega: "ω", alpha: "α" } as Record<string, string>)[field] ?? field.replace(/_/g, " ");
      if (Array.isArray(v)) vec(`${label} `, v, unit, false);
      // a pair's angle as a turn reads it, in (−180°, 180°] (the engine's is unwrapped)
      else rows.push([label, num(field === "angle" && v !== null ? wrapDegrees((v * 180) / Math.PI) : v), unit]);
    }
  }
  body.innerHTML = rows.map(([k, v, unit]) =>
    `<tr data-quantity="${escapeHtml(k)}"><th>${escapeHtml(k)}</th><td>${v}</td><td class="unit">${escapeHtml(unit)}</td></tr>`).join("");
  ui.selected.dataset.selected = choice;
  ui.selected.dataset.input = JSON.stringify(d.input);
}

function select(choice: string): void {
  ui.selection.value = choice;
  selectedFor = "";
  if (state.drawn) void selected(state.drawn, drawingRequest());
}

function buildSelection(info: MechanismInfo): void {
  const keep = ui.selection.value;
  const opt = (v: string, t: string) => `<option value="${escapeHtml(v)}">${escapeHtml(t)}</option>`;
  const moving = Object.keys(info.points).filter((p) => info.owners[p] !== info.frame);
  ui.selection.innerHTML = opt("", "none (click the drawing)") +
    Object.keys(info.points).map((p) => opt(`point:${p}`, `point ${p}`)).join("") +
    Object.keys(info.links).filter((l) => l !== info.frame).map((l) => opt(`link:${l}`, `link ${l}`)).join("") +
    info.joints.map((j) => opt(`joint:${j.name}`, `pair ${j.name} (${j.type})`)).join("");
  ui.selection.value = Array.from(ui.selection.options).some((o) => o.value === keep) ? keep : "";
  const traced = new Set(Array.from(ui.pathsOf.selectedOptions).map((o) => o.value));
  ui.pathsOf.innerHTML = moving.map((p) => opt(p, p)).join("");
  for (const o of Array.from(ui.pathsOf.options)) o.selected = traced.has(o.value);
  selectedFor = "";
}

/** What a click at `q` (SVG units of the mechanism panel) hits: a point, else a link's bar. */
function hit(q: XY, t: Transform): string | null {
  const point = nearestPoint(q, t);
  const info = state.info;
  if (point) {
    // a pair drawn at this point is chosen by a second click on it
    const pair = info?.joints.find((j) => j.point === point || j.name === point);
    if (pair && ui.selection.value === `point:${point}`) return `joint:${pair.name}`;
    return `point:${point}`;
  }
  let best: string | null = null;
  let bestDist = 2.5; // mm of paper
  for (const [link, names] of Object.entries(info?.links ?? {})) {
    if (link === info?.frame) continue;
    const xy = names.map((n) => state.drawn?.points[n]).filter((p): p is XY => !!p).map((p) => toSvg(t, p));
    for (let i = 0; i < xy.length; i++) {
      for (let j = i + 1; j < xy.length; j++) {
        const d = segmentDistance(q, xy[i], xy[j]);
        if (d < bestDist) {
          best = `link:${link}`;
          bestDist = d;
        }
      }
    }
  }
  return best;
}

function segmentDistance(q: XY, a: XY, b: XY): number {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  const u = len2 ? Math.min(Math.max(((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len2, 0), 1) : 0;
  return Math.hypot(q[0] - a[0] - u * dx, q[1] - a[1] - u * dy);
}

// ------------------------------------------------------------------ opening
async function open(base: Source, keep = false): Promise<boolean> {
  state.generation += 1;
  pause();
  clearError();
  const before = keep ? sampleInput(state.index) : [];
  try {
    const info = await post<MechanismInfo>("/api/mechanism", { source: base });
    state.base = base;
    state.moved = {};
    state.info = info;
    broken(null);
    listOpened(base, keep);
    ui.editText.value = info.text;
    ui.title.textContent = info.name;
    ui.description.textContent = info.description;
    buildLayers(info);
    buildConstructions(info);
    buildQuantities(info);
    buildSelection(info);
    void structure(base);
    await loadMotion(before);
    if (info.warnings.length) showError(info.warnings.join("\n"));
    return true;
  } catch (e) {
    showError(messageOf(e));
    ui.drawing.classList.add("stale");
    return false;
  }
}

/** The sample of the motion nearest to `values` (angles compared round the circle). */
function nearestSample(motion: Motion, values: number[]): number {
  if (!values.length || !state.info) return 0;
  const kinds = state.info.drivers.map((d) => d.kind);
  let best = 0;
  let bestDist = Infinity;
  motion.samples.forEach((s, k) => {
    const v = Array.isArray(s.input) ? s.input : [s.input];
    let d = 0;
    v.forEach((x, i) => {
      const e = x - values[i];
      d += kinds[i] === "revolute" ? Math.abs(Math.atan2(Math.sin(e), Math.cos(e))) : Math.abs(e);
    });
    if (d < bestDist - 1e-9) { // the first of equals: a full turn's last sample is its first
      best = k;
      bestDist = d;
    }
  });
  return best;
}

interface StructureDoc {
  count_mobility: number;
  real_mobility: number;
  verdict: string;
  mechanism_class_roman: string | null;
  grashof: { name: string }[] | null;
  groups: { links: string[]; joints: string[]; kind: string; name: string; class: number; order: number;
    notes: string[] }[];
}

/** Mobility by the count and by the Jacobian, Assur class, Grashof type (`linkwork structure`). */
async function structure(base: Source): Promise<void> {
  ui.structure.innerHTML = "";
  try {
    const d = await post<StructureDoc>("/api/structure", { source: base });
    const rows: [string, string][] = [
      ["mobility (count)", String(d.count_mobility)],
      ["mobility (real)", String(d.real_mobility)],
      ["verdict", d.verdict],
    ];
    if (d.mechanism_class_roman) rows.push(["Assur class", d.mechanism_class_roman]);
    for (const loop of d.grashof ?? []) rows.push(["type", loop.name]);
    for (const [k, v] of rows) {
      const dt = document.createElement("dt");
      const dd = document.createElement("dd");
      dt.textContent = k;
      dd.textContent = v;
      ui.structure.append(dt, dd);
    }
    // the Assur groups in the order they are solved: the driving links, then each group
    // (Strukturgruppe) with its class and kind, its links and its pairs
    d.groups.forEach((g, k) => {
      const dt = document.createElement("dt");
      const dd = document.createElement("dd");
      dt.textContent = `group ${k + 1}`;
      dd.className = "group";
      Object.assign(dd.dataset, { kind: g.kind, class: String(g.class), order: String(g.order),
        links: g.links.join(" "), pairs: g.joints.join(" ") });
      dd.textContent = `${g.name}: links ${g.links.join(", ")}; pairs ${g.joints.join(", ")}` +
        (g.notes.length ? ` (${g.notes.join("; ")})` : "");
      ui.structure.append(dt, dd);
    });
  } catch (e) {
    ui.structure.textContent = messageOf(e);
  }
}

/** The whole motion of the design; the slider goes to the sample nearest `before` (the input
 * shown before an edit), else to the start. */
async function loadMotion(before: number[] = []): Promise<void> {
  const generation = state.generation;
  const src = source();
  const motion = await post<Motion>("/api/motion", { source: src, detail: "status" });
  if (generation !== state.generation) return;
  state.motion = motion;
  state.full = null;
  state.motionSource = src;
  ui.slider.dataset.moved = JSON.stringify(src.points ?? {}); // the design the motion is of
  const n = motion.samples.length;
  ui.slider.max = String(Math.max(n - 1, 0));
  ui.strip.innerHTML = motion.samples.map((s) => `<span class="${s.status}" title="${s.status}"></span>`).join("");
  // a new mechanism starts at its design position (the whole motion starts there); an edited
  // one stays where it was
  state.index = nearestSample(motion, before);
  ui.slider.value = String(state.index);
  showTime();
  await redraw();
}

function buildLayers(info: MechanismInfo): void {
  ui.layers.querySelectorAll("label").forEach((l) => l.remove());
  const keep = new Set(Array.from(state.layers).filter((l) => info.layers.includes(l)));
  state.layers = keep;
  const names = info.layers.filter((l) => l !== "mechanism");
  for (const name of names) {
    addToggle(`show-${name}`, name, keep.has(name), (on) => {
      if (on) state.layers.add(name);
      else state.layers.delete(name);
      void redraw();
    });
  }
  for (const [name, label] of Object.entries(PLANS)) {
    if (!info.constructions.includes(name)) continue;
    addToggle(`show-${name}`, label, state.plan === name, (on) => {
      state.plan = on ? name : null;
      if (on && state.construction) {
        state.construction = null;
        ui.construction.value = "";
        stepShown([], 0);
      }
      for (const other of Object.keys(PLANS)) {
        const box = document.getElementById(`show-${other}`) as HTMLInputElement | null;
        if (box && other !== name) box.checked = false;
      }
      void redraw();
    });
  }
}

function addToggle(id: string, text: string, checked: boolean, changed: (on: boolean) => void): void {
  const label = document.createElement("label");
  const box = document.createElement("input");
  box.type = "checkbox";
  box.id = id;
  box.checked = checked;
  box.addEventListener("change", () => changed(box.checked));
  label.append(box, ` ${text}`);
  ui.layers.append(label);
}

async function fillMechanisms(): Promise<void> {
  const list = await get<LibraryList>("/api/library");
  const options: string[] = [];
  for (const m of list.mechanisms) options.push(`<option value="library:${m.name}">${escapeHtml(m.title || m.name)} (${m.name})</option>`);
  for (const f of list.files) options.push(`<option value="file:${escapeHtml(f)}">${escapeHtml(f)}</option>`);
  ui.mechanism.innerHTML = options.join("");
}

function escapeHtml(s: string): string {
  return s.replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);
}

// the mechanism open from text (a file uploaded, an edit applied): the Mechanism list's entry
// "text:" opens it again
let fromText: Source | null = null;

function sourceOf(value: string): Source {
  if (value.startsWith("library:")) return { library: value.slice(8) };
  if (value === "text:" && fromText) return fromText;
  return { file: value.slice(5) };
}

/** The Mechanism list shows what is open: its library entry or working file, else an entry of
 * its own for the text opened (choosing any other entry is then a change, and opens it). */
function listOpened(base: Source, edited: boolean): void {
  let value = base.library !== undefined ? `library:${base.library}` : `file:${base.file}`;
  if (base.text !== undefined) {
    value = "text:";
    fromText = base;
    let own = ui.mechanism.querySelector<HTMLOptionElement>('option[value="text:"]');
    if (!own) {
      own = document.createElement("option");
      own.value = value;
      ui.mechanism.append(own);
    }
    own.textContent = `${base.name ?? "mechanism"} (${edited ? "edited" : "uploaded"})`;
  }
  if (Array.from(ui.mechanism.options).some((o) => o.value === value)) ui.mechanism.value = value;
}

// ------------------------------------------------------------------ motion
let timer: number | undefined;
// play's clock: the wall clock (performance.now(), ms) and the motion's time (s) it started at
let clock: { wall: number; time: number } | null = null;
let run = 0; // each play's number: the frames of one paused before stop
// the motion's time at each sample (s), for the motion it was made for
let timeline: { motion: Motion; times: Promise<number[]>; known: number[] | null } | null = null;

/** The motion's own time at each sample: the samples' times where the driver has a time law,
 * else the input's travel over the driver's speed (the driving pair's ω or sliding velocity,
 * from the whole motion), summed from the first sample. */
function motionTimes(): Promise<number[]> {
  const motion = state.motion as Motion;
  if (timeline?.motion === motion) return timeline.times;
  const driver = state.info?.drivers[0];
  const times = fullMotion().then((full) => {
    const s = full.samples;
    if (s.length && s.every((x) => typeof x.time === "number")) return s.map((x) => x.time as number);
    const rate = (x: FullSample): number => {
      const j = driver ? x.joints[driver.joint] : undefined;
      const v = j?.[driver?.kind === "prismatic" ? "sliding_velocity" : "omega"];
      return typeof v === "number" ? Math.abs(v) : NaN;
    };
    const out = [0];
    for (let k = 1; k < s.length; k++) {
      const du = Math.abs(Number(s[k].input) - Number(s[k - 1].input));
      const w = (rate(s[k]) + rate(s[k - 1])) / 2;
      out.push(out[k - 1] + (Number.isFinite(w) && w > 0 ? du / w : 1 / 30));
    }
    return out;
  }).catch(() => motion.samples.map((_, k) => k / 30)); // without the numbers: 30 samples a second
  const entry = { motion, times, known: null as number[] | null };
  void times.then((t) => { entry.known = t; if (timeline === entry) showTime(); });
  timeline = entry;
  return times;
}

function showTime(): void {
  const t = timeline?.motion === state.motion ? timeline?.known?.[state.index] : undefined;
  setText(ui.inputTime, t === undefined ? "" : `${t.toFixed(3)} s`);
  ui.inputTime.dataset.time = t === undefined ? "" : String(t);
}

function play(): void {
  if (!state.motion || state.broken) return;
  clock = null;
  run += 1;
  state.playing = true;
  ui.play.textContent = "Pause";
  ui.play.setAttribute("aria-pressed", "true");
  void tick(run);
}

function pause(): void {
  state.playing = false;
  ui.play.textContent = "Play";
  ui.play.setAttribute("aria-pressed", "false");
  if (timer !== undefined) window.clearTimeout(timer);
  timer = undefined;
}

/** A frame of play: the sample at the motion's time the wall clock has come to (scaled by the
 * speed), whatever samples that skips; the next frame when this one's drawing is back. */
async function tick(playing: number): Promise<void> {
  const motion = state.motion;
  if (!state.playing || playing !== run || !motion) return;
  const times = await motionTimes();
  if (!state.playing || playing !== run || state.motion !== motion) return;
  const n = times.length;
  const now = performance.now();
  if (!clock) clock = { wall: now, time: times[state.index] };
  // the whole motion of a rocker already runs to one limit, back to the other and forward
  // (a crank's, a turn): going round its samples plays it back and forth
  const period = times[n - 1] - times[0];
  let t = clock.time + ((now - clock.wall) / 1000) * Number(ui.speed.value);
  if (period > 0) t = times[0] + ((((t - times[0]) % period) + period) % period);
  let lo = 0, hi = n - 1; // the last sample at or before t
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid;
    else hi = mid - 1;
  }
  if (lo !== state.index) setIndex(lo);
  const wait = () => {
    if (!state.playing || playing !== run) return;
    if (state.busy) timer = window.setTimeout(wait, 4);
    else requestAnimationFrame(() => void tick(playing));
  };
  wait();
}

function setIndex(k: number): void {
  if (state.broken) return;
  state.index = k;
  ui.slider.value = String(k);
  showTime();
  void redraw();
}

// ------------------------------------------------------------------ editing
// a drag reads the pointer in the drawing it started on (its screen placement and its world
// transform); the point's new design coordinates put it under the pointer in the pose its link
// has in the latest frame drawn. Moving the point moves its link (a hinge changes the lengths
// of the chain): each frame drawn corrects the design coordinates by its own pose, until the
// point is drawn under the pointer (a fixed-point iteration, a few frames)
let dragging: { name: string; transform: Transform; screen: DOMMatrix; pointer: XY | null; corrections: number } | null = null;
// the mechanism panel's view while a drag or the keys move points: that of the drawing they began on
let held: Transform | null = null;
let heldScales: Drawing["scales"] | null = null; // … and its vectors' scales

function screenToSvg(): DOMMatrix | null {
  const ctm = ui.drawing.querySelector("svg")?.getScreenCTM();
  return ctm ? ctm.inverse() : null;
}

function svgPoint(ev: PointerEvent, screen: DOMMatrix): XY {
  const p = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(screen);
  return [p.x, p.y];
}

function nearestPoint(q: XY, t: Transform): string | null {
  let best: string | null = null;
  let bestDist = 4.0; // mm of paper
  for (const [name, xy] of Object.entries(state.drawn?.points ?? {})) {
    if (!xy) continue;
    const s = toSvg(t, xy);
    const d = Math.hypot(s[0] - q[0], s[1] - q[1]);
    if (d < bestDist) {
      best = name;
      bestDist = d;
    }
  }
  return best;
}

ui.drawing.addEventListener("pointerdown", (ev) => {
  if (!state.drawn || state.broken) return;
  if (!ui.edit.checked) { // a click selects what it hits
    const t = state.drawn.transforms["mechanism"];
    const screen = screenToSvg();
    if (!t || !screen) return;
    const what = hit(svgPoint(ev, screen), t);
    if (what) select(what);
    return;
  }
  const t = state.drawn.transforms["mechanism"];
  const screen = screenToSvg();
  if (!t || !screen) return;
  const name = nearestPoint(svgPoint(ev, screen), t);
  const pose = name && state.info ? state.drawn.poses[state.info.owners[name]] : null;
  if (!name || !pose) return;
  pause();
  dragging = { name, transform: t, screen, pointer: null, corrections: 0 };
  held = t;
  heldScales = state.drawn.scales ?? null;
  ui.drawing.setPointerCapture(ev.pointerId);
  ev.preventDefault();
});

ui.drawing.addEventListener("pointermove", (ev) => {
  if (!dragging) return;
  movedAt = { event: ev.timeStamp, handler: performance.now() };
  dragging.pointer = toWorld(dragging.transform, svgPoint(ev, dragging.screen));
  dragging.corrections = 0;
  aim();
  void redraw();
});

/** While dragging: the dragged point's design coordinates that put it under the pointer in the
 * pose its link has in the drawing shown; whether they differ from those asked for by more than
 * a hundredth of a mm of paper (a frame is then due, at most 12 for a place of the pointer). */
function aim(): boolean {
  const d = dragging, info = state.info, drawn = state.drawn;
  if (!d || !d.pointer || !info || !drawn) return false;
  const pose = drawn.poses[info.owners[d.name]];
  if (!pose) return false; // not assembled: the pointer's next move asks again
  const [x, y, th] = pose;
  const c = Math.cos(th), s = Math.sin(th);
  const w = d.pointer;
  const want: XY = [c * (w[0] - x) + s * (w[1] - y), -s * (w[0] - x) + c * (w[1] - y)];
  const had = state.moved[d.name];
  state.moved[d.name] = want;
  const off = had ? Math.hypot(want[0] - had[0], want[1] - had[1]) : Infinity;
  return off > 0.01 * d.transform.per_mm && d.corrections++ < 12;
}

const endDrag = () => {
  if (!dragging) return;
  dragging = null;
  held = null;
  state.generation += 1;
  void loadMotion(sampleInput(state.index)).catch((e) => showError(messageOf(e)));
};
ui.drawing.addEventListener("pointerup", endDrag);
ui.drawing.addEventListener("pointercancel", endDrag);

/** The mechanism file with the dragged points written into its [points] table. */
function savedText(): string {
  const info = state.info;
  if (!info) return "";
  const lines = info.text.split("\n");
  let table = "";
  const left = new Set(Object.keys(state.moved));
  const out = lines.map((line) => {
    const header = /^\s*\[+\s*([^\]]+?)\s*\]+/.exec(line);
    if (header) table = header[1];
    if (table !== "points") return line;
    for (const name of left) {
      const esc = name.replace(/[.*+?^${}()|[\]\\]/g, "\\$&");
      const m = new RegExp(`^(\\s*"?${esc}"?\\s*=\\s*)\\[[^\\]]*\\](.*)$`).exec(line);
      if (m) {
        const [x, y] = state.moved[name];
        left.delete(name);
        return `${m[1]}[${+x.toFixed(6)}, ${+y.toFixed(6)}]${m[2]}`;
      }
    }
    return line;
  });
  if (left.size) showError(`could not write the moved point(s) ${Array.from(left).join(", ")} into the file's [points] table`);
  return out.join("\n");
}

/** The text the edits apply to: the file being edited (which may not build yet), else the
 * file open, with the dragged points written in. */
function editorText(): string {
  const info = state.info;
  if (info && ui.editText.value === info.text) return savedText();
  return ui.editText.value;
}

const names = (s: string): string[] => s.split(/[\s,;]+/).map((x) => x.trim()).filter(Boolean);

/** The file's text after the form's action (a clear message if the form is incomplete). */
function edited(text: string): string {
  const op = ui.editOp.value;
  const name = ui.editName.value.trim();
  if (!name) throw new EditError("give a name");
  switch (op) {
    case "add-point": {
      const xy = names(ui.editXy.value).map(Number);
      if (xy.length !== 2 || !xy.every(Number.isFinite)) throw new EditError("give the design coordinates as x, y");
      const link = ui.editLink.value.trim();
      if (!link) throw new EditError("give the link the point belongs to");
      return addToLink(addEntry(text, "points", name, `[${xy[0]}, ${xy[1]}]`), link, name);
    }
    case "delete-point":
      return removeFromLinks(removeEntry(text, "points", name), name);
    case "add-link": {
      const pts = names(ui.editMembers.value);
      return addEntry(text, "links", name, `[${pts.map((p) => JSON.stringify(p)).join(", ")}]`);
    }
    case "delete-link":
      return removeEntry(text, "links", name);
    case "add-joint": {
      const links = names(ui.editMembers.value);
      if (links.length !== 2) throw new EditError("a hinge joins two links: give both");
      return addEntry(text, "joints", name, `{ type = "revolute", links = [${links.map((l) => JSON.stringify(l)).join(", ")}] }`);
    }
    case "delete-joint":
      return removeEntry(text, "joints", name);
  }
  throw new EditError(`unknown action ${op}`);
}

/** Open the edited text; when it does not build, the engine's message is shown and the text
 * stays in the editor for the next edit. */
async function applyText(text: string): Promise<void> {
  const label = `${stem()}.toml`;
  ui.editText.value = text;
  ui.editor.dataset.applied = "pending";
  const ok = await open({ text, name: label }, true);
  if (!ok) {
    ui.editText.value = text;
    broken(ui.error.textContent ?? "");
  }
  ui.editor.dataset.applied = ok ? "ok" : "error";
}

/** An edited file that does not build (`message`: the engine's), or none (null). Until a file
 * builds, the page shows the last good drawing greyed with the message, and nothing moves or
 * draws the old mechanism: play, the slider and dragging are off. */
function broken(message: string | null): void {
  state.broken = message;
  ui.play.disabled = ui.slider.disabled = message !== null;
  if (message === null) return;
  pause();
  state.generation += 1; // (a drawing of the old mechanism on its way is dropped)
  dragging = null;
  held = null;
  if (settling !== undefined) window.clearTimeout(settling);
  settling = undefined;
  ui.drawing.classList.add("stale");
  showError(message);
  ui.sampleStatus.textContent = "error";
}

function showEditFields(): void {
  const op = ui.editOp.value;
  document.querySelectorAll<HTMLElement>("#editor label[class^=for-]").forEach((l) => {
    l.hidden = !l.className.split(" ").includes(`for-${op}`);
  });
  ui.editMembersWhat.textContent = op === "add-joint" ? "two links" : "points";
}

// ------------------------------------------------------------------ keyboard
/** The whole motion of a design whose points were moved by keys is asked for once the keys
 * have rested this long (ms): each key is solved like a drag's frame, at the input shown. */
const SETTLE = 800;
let settling: number | undefined; // the timer of that, while keys move points

/** A design point moved by the keyboard: `by` in the file's length unit, in the design
 * coordinates of the point's link (those the file holds). Drawn again at once like a frame of
 * a drag; the whole motion of the new design follows when the keys rest. */
function nudge(name: string, by: XY): void {
  const info = state.info;
  if (!info || state.broken) return;
  const at = state.moved[name] ?? info.points[name];
  state.moved[name] = [at[0] + by[0], at[1] + by[1]];
  pause();
  if (settling !== undefined) window.clearTimeout(settling);
  else {
    held = state.drawn?.transforms["mechanism"] ?? null;
    heldScales = state.drawn?.scales ?? null;
  }
  settling = window.setTimeout(() => {
    settling = undefined;
    held = null;
    state.generation += 1;
    void loadMotion(sampleInput(state.index)).catch((e) => showError(messageOf(e)));
  }, SETTLE);
  void redraw();
}

const ARROWS: Record<string, XY> = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };

document.addEventListener("keydown", (ev) => {
  const target = ev.target as HTMLElement;
  const typing = !!target.closest("input[type=text], input:not([type]), textarea");
  if (ev.altKey && ARROWS[ev.key] && !typing && ui.edit.checked && ui.selection.value.startsWith("point:")) {
    const info = state.info;
    if (!info) return;
    // a step of 1/200 of the drawing's size (Shift: ten times that), in round numbers
    const xs = Object.values(info.points);
    const size = Math.max(...xs.map((p) => p[0])) - Math.min(...xs.map((p) => p[0])) || 1;
    const unit = 10 ** Math.floor(Math.log10(size / 200)) * (ev.shiftKey ? 10 : 1);
    const [dx, dy] = ARROWS[ev.key];
    nudge(ui.selection.value.slice(6), [dx * unit, dy * unit]);
    ev.preventDefault();
    return;
  }
  // the form's own controls keep their keys (a slider's arrows, a button's Space)
  if (typing || ev.altKey || ev.ctrlKey || ev.metaKey || target.closest("input, select, textarea, button, summary")) return;
  if (ev.key === " ") {
    if (state.playing) pause();
    else play();
  } else if ((ev.key === "ArrowRight" || ev.key === "ArrowLeft") && state.motion) {
    pause();
    const n = state.motion.samples.length;
    setIndex((state.index + (ev.key === "ArrowRight" ? 1 : n - 1)) % n);
  } else if (ev.key === "." || ev.key === ",") {
    step(ev.key === "." ? 1 : -1);
  } else return;
  ev.preventDefault();
});

// ------------------------------------------------------------------ wiring
ui.editOp.addEventListener("change", showEditFields);
ui.editApply.addEventListener("click", () => {
  let text: string;
  try {
    text = edited(editorText());
  } catch (e) {
    showError(`edit: ${messageOf(e)}`);
    return;
  }
  void applyText(text);
});
ui.editTextApply.addEventListener("click", () => void applyText(ui.editText.value));
ui.play.addEventListener("click", () => (state.playing ? pause() : play()));
ui.speed.addEventListener("change", () => { clock = null; }); // play's clock starts again where it is
ui.slider.addEventListener("input", () => {
  pause();
  setIndex(Number(ui.slider.value));
});
ui.construction.addEventListener("change", chooseConstruction);
ui.constructionLink.addEventListener("change", chooseConstruction);
ui.constructionPoint.addEventListener("change", chooseConstruction);
ui.quantity.addEventListener("change", () => void plot());
ui.selection.addEventListener("change", () => select(ui.selection.value));
ui.pathsOf.addEventListener("change", () => void redraw());
ui.stepBack.addEventListener("click", () => step(-1));
ui.stepForward.addEventListener("click", () => step(1));
ui.edit.addEventListener("change", () => {
  ui.drawing.classList.toggle("editing", ui.edit.checked);
});
ui.mechanism.addEventListener("change", () => void open(sourceOf(ui.mechanism.value)));
ui.upload.addEventListener("change", async () => {
  const file = ui.upload.files?.[0];
  if (!file) return;
  const text = await file.text();
  void open({ text, name: file.name });
  ui.upload.value = "";
});
/** The file name the downloads start with: the mechanism's file or library name. */
function stem(): string {
  return `${(state.info?.source ?? "mechanism").replace(/^library:/, "").replace(/\.toml$/, "").split("/").pop()}`;
}

function download(blob: Blob, name: string): void {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.click();
  window.setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

ui.save.addEventListener("click", () => {
  const text = savedText();
  if (text) download(new Blob([text], { type: "text/plain" }), `${stem()}.toml`);
});
ui.exportSvg.addEventListener("click", () => {
  // the very SVG the server drew (that of `linkwork draw`), as shown
  if (state.drawn) download(new Blob([state.drawn.svg], { type: "image/svg+xml" }), `${stem()}.svg`);
});
ui.exportPng.addEventListener("click", async () => {
  try {
    download(await postFile("/api/drawing.png", drawingRequest()), `${stem()}.png`);
  } catch (e) {
    showError(messageOf(e));
  }
});
ui.exportCsv.addEventListener("click", async () => {
  try {
    download(await postFile("/api/motion.csv", { source: state.motionSource ?? source() }), `${stem()}-motion.csv`);
  } catch (e) {
    showError(messageOf(e));
  }
});

async function start(): Promise<void> {
  try {
    await fillMechanisms();
  } catch (e) {
    showError(messageOf(e));
    return;
  }
  const q = new URLSearchParams(location.search);
  const first: Source = q.get("file") ? { file: q.get("file") as string }
    : { library: q.get("library") ?? "crank-rocker" };
  const value = first.file ? `file:${first.file}` : `library:${first.library}`;
  if (Array.from(ui.mechanism.options).some((o) => o.value === value)) ui.mechanism.value = value;
  await open(first);
  document.body.dataset.ready = "true";
}

void start();
