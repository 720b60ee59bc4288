// The workbench page: open a mechanism, see it drawn by the server (the SVG of `linkwork draw`),
// animate its input, drag its design points, toggle the layers. All numbers come from the API;
// the page only asks, shows and maps the pointer into the drawing's world coordinates.

import {
  ApiError, Drawing, DrawingRequest, LibraryList, MechanismInfo, Motion, Source, Transform, XY,
  get, post, toSvg, toWorld,
} from "./api";

const $ = <T extends HTMLElement>(id: string): T => {
  const el = document.getElementById(id);
  if (!el) throw new Error(`the page has no #${id}`);
  return el as T;
};

const ui = {
  mechanism: $<HTMLSelectElement>("mechanism"),
  upload: $<HTMLInputElement>("upload"),
  save: $<HTMLButtonElement>("save"),
  error: $<HTMLDivElement>("error"),
  drawing: $<HTMLDivElement>("drawing"),
  title: $<HTMLHeadingElement>("title"),
  description: $<HTMLParagraphElement>("description"),
  play: $<HTMLButtonElement>("play"),
  speed: $<HTMLSelectElement>("speed"),
  slider: $<HTMLInputElement>("input-slider"),
  strip: $<HTMLDivElement>("status-strip"),
  inputValue: $<HTMLOutputElement>("input-value"),
  sampleStatus: $<HTMLOutputElement>("sample-status"),
  layers: $<HTMLFieldSetElement>("layers"),
  edit: $<HTMLInputElement>("edit"),
  numbers: $<HTMLTableElement>("numbers"),
  structure: $<HTMLDListElement>("structure"),
};

/** Layers drawn over the mechanism, and the plans (constructions drawn beside it). */
const PLANS: Record<string, string> = { "velocity-plan": "velocity plan", "acceleration-plan": "acceleration plan" };

interface State {
  base: Source | null; // the mechanism as opened (library, file or text)
  moved: Record<string, XY>; // design points dragged since
  info: MechanismInfo | null;
  motion: Motion | null;
  index: number;
  playing: boolean;
  layers: Set<string>;
  plan: string | null;
  drawn: Drawing | null;
  busy: boolean;
  again: boolean;
  generation: number; // drawings asked for a mechanism that is no longer open are dropped
}

const state: State = {
  base: null, moved: {}, info: null, motion: null, index: 0, playing: false,
  layers: new Set(), plan: null, drawn: null, busy: false, again: false, generation: 0,
};

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
  if (state.motion) req.at = sampleInput(state.index);
  if (state.plan) req.construction = state.plan;
  // while dragging, the frames leave the whole motion out: they follow the pointer sooner
  if (dragging) req.motion = false;
  return req;
}

/** Ask for the drawing of the current state; while one is on its way, only the latest wish
 * is sent after it (dragging and playing never queue up). */
async function redraw(): Promise<void> {
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
      try {
        const d = await post<Drawing>("/api/drawing", req);
        if (generation !== state.generation) continue;
        show(d, req);
        clearError();
      } catch (e) {
        if (generation !== state.generation) continue;
        if (req.construction && e instanceof ApiError && e.status === 400) {
          // a plan that cannot be drawn here: say why, draw the rest
          showError(`${PLANS[req.construction]}: ${e.message}`);
          const plain = { ...req, construction: undefined };
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
  ui.drawing.innerHTML = d.svg.replace(/^<\?xml[^>]*>\s*/, "");
  ui.drawing.classList.remove("stale");
  const t = d.transforms["mechanism"];
  ui.drawing.dataset.transform = JSON.stringify(t);
  ui.drawing.dataset.input = JSON.stringify(d.input);
  ui.drawing.dataset.moved = JSON.stringify(req.source.points ?? {});
  ui.inputValue.textContent = inputText(d.input);
  ui.sampleStatus.textContent = d.status;
  ui.sampleStatus.className = d.status;
  numbers(d);
}

function numbers(d: Drawing): void {
  const unit = state.info?.units.length ?? "";
  const head = ui.numbers.tHead as HTMLTableSectionElement;
  head.innerHTML = `<tr><th>point</th><th>x [${unit}]</th><th>y [${unit}]</th></tr>`;
  const body = ui.numbers.tBodies[0];
  body.innerHTML = "";
  for (const [name, xy] of Object.entries(d.points)) {
    const row = body.insertRow();
    row.dataset.point = name;
    row.insertCell().textContent = name;
    row.insertCell().textContent = xy ? xy[0].toFixed(4) : "—";
    row.insertCell().textContent = xy ? xy[1].toFixed(4) : "—";
  }
}

// ------------------------------------------------------------------ opening
async function open(base: Source): Promise<void> {
  state.generation += 1;
  pause();
  clearError();
  try {
    const info = await post<MechanismInfo>("/api/mechanism", { source: base });
    state.base = base;
    state.moved = {};
    state.info = info;
    ui.title.textContent = info.name;
    ui.description.textContent = info.description;
    buildLayers(info);
    void structure(base);
    await loadMotion();
    if (info.warnings.length) showError(info.warnings.join("\n"));
  } catch (e) {
    showError(messageOf(e));
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
  } catch (e) {
    ui.structure.textContent = messageOf(e);
  }
}

async function loadMotion(keep = false): Promise<void> {
  const generation = state.generation;
  const before = keep ? sampleInput(state.index) : [];
  const src = source();
  const motion = await post<Motion>("/api/motion", { source: src, detail: "status" });
  if (generation !== state.generation) return;
  state.motion = motion;
  ui.slider.dataset.moved = JSON.stringify(src.points ?? {}); // the design the motion is of
  const n = motion.samples.length;
  ui.slider.max = String(Math.max(n - 1, 0));
  ui.strip.innerHTML = motion.samples.map((s) => `<span class="${s.status}" title="${s.status}"></span>`).join("");
  // a new mechanism starts at its design position (the whole motion starts there); an edited
  // one stays where it was
  state.index = nearestSample(motion, before);
  ui.slider.value = String(state.index);
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

function sourceOf(value: string): Source {
  if (value.startsWith("library:")) return { library: value.slice(8) };
  return { file: value.slice(5) };
}

// ------------------------------------------------------------------ motion
let timer: number | undefined;

function play(): void {
  if (!state.motion) return;
  state.playing = true;
  ui.play.textContent = "Pause";
  ui.play.setAttribute("aria-pressed", "true");
  tick();
}

function pause(): void {
  state.playing = false;
  ui.play.textContent = "Play";
  ui.play.setAttribute("aria-pressed", "false");
  if (timer !== undefined) window.clearTimeout(timer);
  timer = undefined;
}

function tick(): void {
  if (!state.playing || !state.motion) return;
  const n = state.motion.samples.length;
  // the whole motion of a rocker already runs to one limit, back to the other and forward:
  // going round its samples plays it back and forth
  const step = Math.max(1, Math.round(Number(ui.speed.value) * Math.max(1, n / 240)));
  setIndex((state.index + step) % n);
  const wait = () => {
    if (state.busy) timer = window.setTimeout(wait, 8);
    else timer = window.setTimeout(tick, 33);
  };
  wait();
}

function setIndex(k: number): void {
  state.index = k;
  ui.slider.value = String(k);
  void redraw();
}

// ------------------------------------------------------------------ editing
// a drag reads the pointer in the drawing it started on (its screen placement and its world
// transform), whatever layouts the drawings redrawn meanwhile have; the point's new design
// coordinates put it under the pointer in the pose its link had when the drag started
let dragging: { name: string; transform: Transform; screen: DOMMatrix; pose: [number, number, number] } | null = null;

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
  if (!ui.edit.checked || !state.drawn) return;
  const t = state.drawn.transforms["mechanism"];
  const screen = screenToSvg();
  if (!t || !screen) return;
  const name = nearestPoint(svgPoint(ev, screen), t);
  const pose = name && state.info ? state.drawn.poses[state.info.owners[name]] : null;
  if (!name || !pose) return;
  pause();
  dragging = { name, transform: t, screen, pose };
  ui.drawing.setPointerCapture(ev.pointerId);
  ev.preventDefault();
});

ui.drawing.addEventListener("pointermove", (ev) => {
  if (!dragging) return;
  const w = toWorld(dragging.transform, svgPoint(ev, dragging.screen));
  const [x, y, th] = dragging.pose;
  const c = Math.cos(th), s = Math.sin(th);
  state.moved[dragging.name] = [c * (w[0] - x) + s * (w[1] - y), -s * (w[0] - x) + c * (w[1] - y)];
  void redraw();
});

const endDrag = () => {
  if (!dragging) return;
  dragging = null;
  state.generation += 1;
  void loadMotion(true).catch((e) => showError(messageOf(e)));
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

// ------------------------------------------------------------------ wiring
ui.play.addEventListener("click", () => (state.playing ? pause() : play()));
ui.slider.addEventListener("input", () => {
  pause();
  setIndex(Number(ui.slider.value));
});
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
ui.save.addEventListener("click", () => {
  const text = savedText();
  if (!text) return;
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type: "text/plain" }));
  a.download = `${(state.info?.source ?? "mechanism").replace(/^library:/, "").replace(/\.toml$/, "").split("/").pop()}.toml`;
  a.click();
  URL.revokeObjectURL(a.href);
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
