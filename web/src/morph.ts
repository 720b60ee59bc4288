// The drawing of a new frame put into the page by changing only what differs from the one shown:
// most of a drag's frame is the same (the frame's pivots, the legend, the labels of points that
// did not move), and an element whose attributes did not change keeps its style and layout.

function sameKind(a: Node, b: Node): boolean {
  return a.nodeType === b.nodeType && a.nodeName === b.nodeName;
}

/** Make `old` equal to `neu` — the same elements, attributes and text, node for node, as if
 * `neu` had replaced it — changing only what differs. `neu`'s nodes may be moved into `old`. */
export function morph(old: Element, neu: Element): void {
  const na = neu.attributes;
  for (let i = 0; i < na.length; i++) {
    const a = na[i];
    if (old.getAttributeNS(a.namespaceURI, a.localName) !== a.value) {
      old.setAttributeNS(a.namespaceURI, a.name, a.value);
    }
  }
  const oa = old.attributes;
  for (let i = oa.length - 1; i >= 0; i--) {
    const a = oa[i];
    if (!neu.hasAttributeNS(a.namespaceURI, a.localName)) old.removeAttributeNS(a.namespaceURI, a.localName);
  }
  let o = old.firstChild;
  let n = neu.firstChild;
  while (n) {
    const next = n.nextSibling;
    if (!o) {
      old.appendChild(n);
    } else if (sameKind(o, n)) {
      // a subtree that did not change (the browser compares it natively) is left alone; an
      // element without elements inside (a line, a circle, a label) that changed is replaced
      // by its new one, parsed already: writing its attributes one by one costs more (each
      // parsed again) when many move, as in a frame whose drawing is scaled anew
      if (o.nodeType === Node.ELEMENT_NODE) {
        if (!o.isEqualNode(n)) {
          if ((n as Element).firstElementChild === null) {
            old.replaceChild(n, o);
            o = n;
          } else morph(o as Element, n as Element);
        }
      } else if (o.nodeValue !== n.nodeValue) o.nodeValue = n.nodeValue;
      o = o.nextSibling;
    } else {
      const after = o.nextSibling;
      old.replaceChild(n, o);
      o = after;
    }
    n = next;
  }
  while (o) {
    const after = o.nextSibling;
    old.removeChild(o);
    o = after;
  }
}

/** Show the SVG document `svg` in `host` (whose only element is the drawing shown before, if
 * any): parsed as the page parses it, then morphed into the drawing shown. */
export function showSvg(host: HTMLElement, svg: string): void {
  const text = svg.replace(/^<\?xml[^>]*>\s*/, "");
  const old = host.firstElementChild;
  const parsed = document.createElement("template");
  parsed.innerHTML = text;
  const neu = parsed.content.firstElementChild;
  if (!old || !neu || host.children.length !== 1 || parsed.content.children.length !== 1) {
    host.innerHTML = text;
    return;
  }
  morph(old, neu);
}
