// A plot of one quantity over the whole motion, drawn as SVG by the page from the motion's JSON:
// the samples in their order along the motion (a rocker's back and forth included), gaps where a
// sample is unreachable, the current sample marked.

export interface Series {
  label: string; // e.g. "C |v|"
  unit: string; // e.g. "mm/s"
  values: (number | null)[]; // one per sample of the whole motion, null where unreachable
  inputs: string[]; // each sample's input as text, for the axis
}

const W = 460, H = 190, L = 62, R = 10, T = 16, B = 34;

function fmt(v: number): string {
  const a = Math.abs(v);
  return a !== 0 && (a >= 1e5 || a < 1e-3) ? v.toExponential(3) : String(+v.toPrecision(5));
}

/** The extremes of the finite values (null if there are none). */
export function extremes(values: (number | null)[]): { min: number; max: number; argmin: number; argmax: number } | null {
  let min = Infinity, max = -Infinity, argmin = -1, argmax = -1;
  values.forEach((v, k) => {
    if (v === null || !Number.isFinite(v)) return;
    if (v < min) { min = v; argmin = k; }
    if (v > max) { max = v; argmax = k; }
  });
  return argmin < 0 ? null : { min, max, argmin, argmax };
}

export function plotSvg(s: Series, current: number): string {
  const n = s.values.length;
  const e = extremes(s.values);
  const esc = (t: string) => t.replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);
  if (!e || n < 2) return `<p>${esc(s.label)}: no values over the motion</p>`;
  // a quantity constant over the motion but for rounding (|v| of a crank pin at a uniform speed)
  // is drawn as the constant it is, not scaled up to its rounding noise
  const flat = e.max - e.min <= 1e-9 * Math.max(Math.abs(e.max), Math.abs(e.min));
  const mid = (e.max + e.min) / 2;
  const span = flat ? Math.max(Math.abs(mid), 1) : e.max - e.min;
  const lo = flat ? mid - span / 2 : e.min, hi = lo + span;
  const x = (k: number) => L + ((W - L - R) * k) / (n - 1);
  const y = (v: number) => T + ((H - T - B) * (hi - v)) / (hi - lo);
  // one polyline per run of reachable samples
  const runs: string[] = [];
  let run: string[] = [];
  s.values.forEach((v, k) => {
    if (v === null || !Number.isFinite(v)) {
      if (run.length) runs.push(run.join(" "));
      run = [];
    } else run.push(`${x(k).toFixed(2)},${y(v).toFixed(2)}`);
  });
  if (run.length) runs.push(run.join(" "));
  const lines = runs.map((r) => `<polyline class="curve" points="${r}"/>`).join("");
  const k = Math.min(Math.max(current, 0), n - 1);
  const vk = s.values[k];
  const marker = `<line class="now" x1="${x(k)}" y1="${T}" x2="${x(k)}" y2="${H - B}"/>` +
    (vk === null ? "" : `<circle class="now" cx="${x(k)}" cy="${y(vk)}" r="3"/>`);
  // the first and last input labels end inside the plot (centred, half of each was cut off)
  const anchors = ["start", "middle", "end"];
  const ticks = [0, Math.round((n - 1) / 2), n - 1].map((j, i) =>
    `<text x="${x(j)}" y="${H - B + 14}" text-anchor="${anchors[i]}">${esc(s.inputs[j] ?? "")}</text>`).join("");
  const yTicks = (flat ? [mid] : [e.max, e.min]).map((v) =>
    `<text x="${L - 4}" y="${y(v) + 4}" text-anchor="end">${fmt(v)}</text>` +
    `<line class="grid" x1="${L}" y1="${y(v)}" x2="${W - R}" y2="${y(v)}"/>`).join("");
  const now = vk === null ? "unreachable" : `${fmt(vk)} ${s.unit}`;
  return `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 ${W} ${H}" role="img" ` +
    `aria-label="${esc(s.label)} over the motion" data-min="${e.min}" data-max="${e.max}" ` +
    `data-argmin="${e.argmin}" data-argmax="${e.argmax}" data-current="${k}" data-unit="${esc(s.unit)}">` +
    `<rect class="frame" x="${L}" y="${T}" width="${W - L - R}" height="${H - T - B}"/>` +
    yTicks + ticks + lines + marker +
    `<text x="${L}" y="${T - 4}">${esc(s.label)} [${esc(s.unit)}] — here ${esc(now)}</text>` +
    `<text x="${(L + W - R) / 2}" y="${H - 4}" text-anchor="middle">input, along the whole motion</text>` +
    `</svg>`;
}
