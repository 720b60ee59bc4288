// Edits of a mechanism file's text that keep the rest of it as written (comments, order,
// spacing): an entry added at the end of its table, an entry removed, a name added to or
// removed from a link's list of points. Only the file's text is changed here; the engine reads
// the result and says what is wrong with it.

export type Table = "points" | "links" | "joints";

/** A TOML key as written: bare when it can be, else quoted. */
export function key(name: string): string {
  return /^[A-Za-z0-9_-]+$/.test(name) ? name : JSON.stringify(name);
}

const headerOf = (line: string): string | null => {
  const m = /^\s*\[+\s*([^\]]+?)\s*\]+\s*(#.*)?$/.exec(line);
  return m ? m[1] : null;
};

/** The lines [start, end) of a table's entries (after its header, before the next one). */
function range(lines: string[], table: Table): [number, number] | null {
  const start = lines.findIndex((l) => headerOf(l) === table);
  if (start < 0) return null;
  let end = start + 1;
  while (end < lines.length && headerOf(lines[end]) === null) end++;
  // entries end at the last line that is not blank or a comment
  let last = end;
  while (last > start + 1 && /^\s*(#.*)?$/.test(lines[last - 1])) last--;
  return [start + 1, last];
}

function entryLine(lines: string[], r: [number, number], name: string): number {
  const esc = name.replace(/[.*+?^${}()|[\]\\]/g, "\\$&");
  const re = new RegExp(`^\\s*("${esc}"|${esc})\\s*=`);
  for (let i = r[0]; i < r[1]; i++) if (re.test(lines[i])) return i;
  return -1;
}

export class EditError extends Error {}

export function addEntry(text: string, table: Table, name: string, value: string): string {
  const lines = text.split("\n");
  const r = range(lines, table);
  if (!r) return `${text.replace(/\n*$/, "")}\n\n[${table}]\n${key(name)} = ${value}\n`;
  if (entryLine(lines, r, name) >= 0) throw new EditError(`[${table}] already has '${name}'`);
  lines.splice(r[1], 0, `${key(name)} = ${value}`);
  return lines.join("\n");
}

export function removeEntry(text: string, table: Table, name: string): string {
  const lines = text.split("\n");
  const r = range(lines, table);
  const i = r ? entryLine(lines, r, name) : -1;
  if (!r || i < 0) throw new EditError(`[${table}] has no '${name}'`);
  // an entry may run over several lines (an array written one element a line)
  let end = i + 1;
  let depth = 0;
  for (const c of lines[i].replace(/#.*$/, "")) depth += c === "[" || c === "{" ? 1 : c === "]" || c === "}" ? -1 : 0;
  while (depth > 0 && end < r[1]) {
    for (const c of lines[end].replace(/#.*$/, "")) depth += c === "[" || c === "{" ? 1 : c === "]" || c === "}" ? -1 : 0;
    end++;
  }
  lines.splice(i, end - i);
  return lines.join("\n");
}

/** The names of a one-line list entry `name = ["A", "B"]` of `table`, and its line. */
function listOf(lines: string[], table: Table, name: string): { line: number; names: string[]; rest: string } {
  const r = range(lines, table);
  const i = r ? entryLine(lines, r, name) : -1;
  if (!r || i < 0) throw new EditError(`[${table}] has no '${name}'`);
  const m = /=\s*\[([^\]]*)\](.*)$/.exec(lines[i]);
  if (!m) throw new EditError(`[${table}] ${name}: its list is not written on one line; edit the text`);
  const names = Array.from(m[1].matchAll(/"([^"]*)"|'([^']*)'/g), (x) => x[1] ?? x[2]);
  return { line: i, names, rest: m[2] };
}

function writeList(lines: string[], at: { line: number; rest: string }, name: string, names: string[]): void {
  lines[at.line] = `${key(name)} = [${names.map((n) => JSON.stringify(n)).join(", ")}]${at.rest}`;
}

export function addToLink(text: string, link: string, point: string): string {
  const lines = text.split("\n");
  const at = listOf(lines, "links", link);
  if (!at.names.includes(point)) writeList(lines, at, link, [...at.names, point]);
  return lines.join("\n");
}

/** `point` taken out of every link's list (of the links the text has). */
export function removeFromLinks(text: string, point: string): string {
  const lines = text.split("\n");
  const r = range(lines, "links");
  if (!r) return text;
  for (let i = r[0]; i < r[1]; i++) {
    const m = /^\s*("[^"]*"|[A-Za-z0-9_-]+)\s*=\s*\[/.exec(lines[i]);
    if (!m) continue;
    const link = m[1].startsWith('"') ? JSON.parse(m[1]) as string : m[1];
    const at = listOf(lines, "links", link);
    if (at.names.includes(point)) writeList(lines, at, link, at.names.filter((n) => n !== point));
  }
  return lines.join("\n");
}
