// A small SVG chart for the fits: measured points as markers, the fitted
// model as a line, linear axes with readable ticks.

const NS = 'http://www.w3.org/2000/svg';
const s = (tag, attrs = {}, text) => {
  const el = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
  if (text !== undefined) el.textContent = text;
  return el;
};

function ticks(lo, hi, count = 6) {
  const span = hi - lo || Math.abs(lo) || 1;
  const raw = span / count;
  const p = 10 ** Math.floor(Math.log10(raw));
  const m = raw / p;
  const step = (m < 1.5 ? 1 : m < 3 ? 2 : m < 7 ? 5 : 10) * p;
  const out = [];
  for (let t = Math.ceil(lo / step) * step; t <= hi + step * 1e-9; t += step) out.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  return { values: out, step };
}

const label = (t, step) => {
  const digits = Math.max(0, -Math.floor(Math.log10(step)));
  return (Math.abs(t) >= 1e5 ? t.toExponential(1) : t.toFixed(Math.min(digits, 6))).replace('-', '−');
};

// series: [{label, points: [[x, y]], kind: 'line' | 'points', color}]
export function chart({ title, xLabel, yLabel, series }) {
  const W = 720;
  const H = 440;
  const M = { left: 72, right: 20, top: 36, bottom: 56 };
  const all = series.flatMap((s) => s.points).filter(([x, y]) => Number.isFinite(x) && Number.isFinite(y));
  let [x0, x1] = [Math.min(...all.map((p) => p[0])), Math.max(...all.map((p) => p[0]))];
  let [y0, y1] = [Math.min(...all.map((p) => p[1])), Math.max(...all.map((p) => p[1]))];
  if (!all.length) [x0, x1, y0, y1] = [0, 1, 0, 1];
  const padX = (x1 - x0 || 1) * 0.05;
  const padY = (y1 - y0 || 1) * 0.08;
  [x0, x1, y0, y1] = [x0 - padX, x1 + padX, y0 - padY, y1 + padY];
  const X = (x) => M.left + ((x - x0) / (x1 - x0)) * (W - M.left - M.right);
  const Y = (y) => H - M.bottom - ((y - y0) / (y1 - y0)) * (H - M.top - M.bottom);
  const svg = s('svg', { viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': title, class: 'chart' });
  svg.append(s('rect', { x: 0, y: 0, width: W, height: H, fill: '#ffffff' }));
  svg.append(s('text', { x: W / 2, y: 22, 'text-anchor': 'middle', 'font-size': 15, fill: '#1a1a1a' }, title));
  const tx = ticks(x0, x1);
  const ty = ticks(y0, y1);
  for (const t of tx.values) {
    svg.append(s('line', { x1: X(t), x2: X(t), y1: M.top, y2: H - M.bottom, stroke: '#e3e3e3' }));
    svg.append(s('text', { x: X(t), y: H - M.bottom + 18, 'text-anchor': 'middle', 'font-size': 12, fill: '#333333' }, label(t, tx.step)));
  }
  for (const t of ty.values) {
    svg.append(s('line', { x1: M.left, x2: W - M.right, y1: Y(t), y2: Y(t), stroke: '#e3e3e3' }));
    svg.append(s('text', { x: M.left - 8, y: Y(t) + 4, 'text-anchor': 'end', 'font-size': 12, fill: '#333333' }, label(t, ty.step)));
  }
  svg.append(s('rect', { x: M.left, y: M.top, width: W - M.left - M.right, height: H - M.top - M.bottom, fill: 'none', stroke: '#555555' }));
  svg.append(s('text', { x: (M.left + W - M.right) / 2, y: H - 14, 'text-anchor': 'middle', 'font-size': 13, fill: '#1a1a1a' }, xLabel));
  const yl = s('text', { x: 18, y: (M.top + H - M.bottom) / 2, 'text-anchor': 'middle', 'font-size': 13, fill: '#1a1a1a', transform: `rotate(-90 18 ${(M.top + H - M.bottom) / 2})` }, yLabel);
  svg.append(yl);
  svg.append(s('rect', { x: M.left + 6, y: M.top + 4, width: 194, height: 18 * series.length + 6, fill: '#ffffff', 'fill-opacity': 0.92, stroke: '#cccccc' }));
  let ly = M.top + 16;
  for (const one of series) {
    const color = one.color || '#1f5fbf';
    if (one.kind === 'line') {
      const d = one.points.filter(([x, y]) => Number.isFinite(x) && Number.isFinite(y))
        .map(([x, y], i) => `${i ? 'L' : 'M'} ${X(x).toFixed(2)} ${Y(y).toFixed(2)}`).join(' ');
      svg.append(s('path', { d, fill: 'none', stroke: color, 'stroke-width': 2.2 }));
      svg.append(s('line', { x1: M.left + 14, x2: M.left + 38, y1: ly, y2: ly, stroke: color, 'stroke-width': 2.2 }));
    } else {
      for (const [x, y] of one.points) {
        if (Number.isFinite(x) && Number.isFinite(y)) svg.append(s('circle', { cx: X(x), cy: Y(y), r: 3.5, fill: 'none', stroke: color, 'stroke-width': 1.6 }));
      }
      svg.append(s('circle', { cx: M.left + 26, cy: ly, r: 3.5, fill: 'none', stroke: color, 'stroke-width': 1.6 }));
    }
    svg.append(s('text', { x: M.left + 44, y: ly + 4, 'font-size': 12, fill: '#1a1a1a' }, one.label));
    ly += 18;
  }
  return svg;
}
