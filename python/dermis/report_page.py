"""The study report's style sheet and script, inlined into every report by report.py.

The script (no libraries) gives the page its interaction:
- every `.zoom` panel shows the same view: the mouse wheel zooms about the cursor, a drag
  pans, a double click resets, and all panels move together (they have the same size);
- flip: a `.flip` panel holds a method's image and the reference's on top of each other;
  a click on it (without dragging) or the key F toggles it to the reference and back;
- exposure: the slider scales the displayed sRGB values of tone-mapped images by
  2^(EV/2.2) (a CSS filter: an exposure change for a gamma-2.2 display; highlights
  clipped in the PNG stay clipped);
- when the page has loaded, every <img> gets `data-natural-width`, and `#status` gets
  `data-loaded="n/m"` (images decoded / images): what the browser test reads.
"""

CSS = r"""
body { font-family: system-ui, sans-serif; margin: 0 1.5em 2em 1.5em; background: #f4f4f2; color: #222; }
h1 { font-size: 1.5em; margin: 0.6em 0 0.2em 0; }
h2 { font-size: 1.2em; margin: 1.4em 0 0.4em 0; border-bottom: 1px solid #ccc; }
p.summary { margin: 0.2em 0 0.6em 0; color: #444; }
.toolbar { position: sticky; top: 0; z-index: 10; background: #e8e8e4; padding: 0.4em 0.6em;
           border-bottom: 1px solid #bbb; display: flex; gap: 1.2em; align-items: center; flex-wrap: wrap; }
.toolbar button { font: inherit; }
.grid { display: flex; flex-wrap: wrap; gap: 12px; }
figure { margin: 0; }
figcaption { font-size: 0.85em; max-width: 100%; margin-top: 3px; }
figcaption b { font-size: 1.05em; }
.zoom { position: relative; overflow: hidden; background: #000; cursor: grab; user-select: none; }
.zoom.dragging { cursor: grabbing; }
.zoom img { position: absolute; left: 0; top: 0; transform-origin: 0 0; image-rendering: pixelated;
            -webkit-user-drag: none; pointer-events: none; }
.flip .ref { visibility: hidden; }
.flip.flipped .ref { visibility: visible; }
.flip .tag { position: absolute; left: 4px; top: 4px; z-index: 2; background: rgba(0,0,0,0.65); color: #fff;
             font-size: 12px; padding: 1px 5px; border-radius: 3px; pointer-events: none;
             max-width: calc(100% - 18px); overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
.flip.flipped .tag { background: rgba(160,20,20,0.85); }
table { border-collapse: collapse; font-size: 0.9em; background: #fff; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: right; }
th { background: #e8e8e4; }
td:first-child, th:first-child { text-align: left; }
img.plot { max-width: 100%; background: #fff; border: 1px solid #ccc; }
pre { background: #fff; border: 1px solid #ccc; padding: 0.6em; white-space: pre-wrap; word-break: break-all; }
.note { color: #555; font-size: 0.9em; max-width: 70em; }
.warning { background: #fff1d6; border: 1px solid #d9a441; padding: 0.4em 0.6em; max-width: 70em; }
#status { color: #777; font-size: 0.8em; }
"""

JS = r"""
(function () {
  // One view for every .zoom panel: scale s, translation (x, y) in panel pixels.
  const view = { s: 1, x: 0, y: 0 };
  const panels = Array.from(document.querySelectorAll('.zoom'));
  function apply() {
    for (const p of panels)
      for (const img of p.querySelectorAll('img'))
        img.style.transform = `translate(${view.x}px, ${view.y}px) scale(${view.s})`;
  }
  function clampView(p) {  // keep the image covering the panel
    const w = p.clientWidth, h = p.clientHeight;
    view.x = Math.min(0, Math.max(w - w * view.s, view.x));
    view.y = Math.min(0, Math.max(h - h * view.s, view.y));
  }
  let drag = null;
  for (const p of panels) {
    p.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = p.getBoundingClientRect();
      const px = e.clientX - r.left, py = e.clientY - r.top;
      const s = Math.min(64, Math.max(1, view.s * Math.exp(-e.deltaY * 0.002)));
      view.x = px - (px - view.x) * s / view.s;
      view.y = py - (py - view.y) * s / view.s;
      view.s = s;
      clampView(p);
      apply();
    }, { passive: false });
    p.addEventListener('mousedown', (e) => {
      e.preventDefault();
      drag = { panel: p, x0: e.clientX, y0: e.clientY, lx: e.clientX, ly: e.clientY };
      p.classList.add('dragging');
    });
    p.addEventListener('dblclick', () => { view.s = 1; view.x = 0; view.y = 0; apply(); });
  }
  window.addEventListener('mousemove', (e) => {
    if (!drag) return;
    view.x += e.clientX - drag.lx;
    view.y += e.clientY - drag.ly;
    drag.lx = e.clientX; drag.ly = e.clientY;
    clampView(drag.panel);
    apply();
  });
  window.addEventListener('mouseup', (e) => {
    if (!drag) return;
    const p = drag.panel;
    const moved = Math.abs(e.clientX - drag.x0) + Math.abs(e.clientY - drag.y0);
    p.classList.remove('dragging');
    drag = null;
    if (moved < 4 && p.classList.contains('flip')) flip([p]);  // a click, not a drag
  });

  // Flip: method <-> reference.
  const flips = Array.from(document.querySelectorAll('.flip'));
  function flip(list) {
    for (const f of list) {
      const on = f.classList.toggle('flipped');
      f.querySelector('.tag').textContent = on ? 'reference' : f.dataset.method;
    }
  }
  document.getElementById('flip-all').addEventListener('click', () => flip(flips));
  document.getElementById('reset-zoom').addEventListener('click', () => {
    view.s = 1; view.x = 0; view.y = 0; apply();
  });
  window.addEventListener('keydown', (e) => {
    if (e.key === 'f' || e.key === 'F') flip(flips);
    if (e.key === '0') { view.s = 1; view.x = 0; view.y = 0; apply(); }
  });

  // Exposure of the tone-mapped images.
  const ev = document.getElementById('exposure'), evText = document.getElementById('exposure-value');
  function exposure() {
    const v = parseFloat(ev.value);
    evText.textContent = (v > 0 ? '+' : '') + v.toFixed(1) + ' EV';
    for (const img of document.querySelectorAll('img.tm'))
      img.style.filter = v === 0 ? '' : `brightness(${Math.pow(2, v / 2.2)})`;
  }
  ev.addEventListener('input', exposure);

  // What the browser test reads: which images decoded.
  window.addEventListener('load', () => {
    const imgs = Array.from(document.images);
    let ok = 0;
    for (const img of imgs) {
      img.dataset.naturalWidth = img.naturalWidth;
      if (img.complete && img.naturalWidth > 0) ok++;
    }
    const st = document.getElementById('status');
    st.dataset.loaded = `${ok}/${imgs.length}`;
    st.textContent = `${ok} of ${imgs.length} images decoded.`;
  });
  apply();
})();
"""
