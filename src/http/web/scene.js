// The scene as SVG: the bodies and the barrier with lengths to scale, the
// contact point with its normal and tangent, the velocities and spins before
// (blue) and after (orange) the impact, and the impulse (green). Velocity
// arrows share one scale (and the impulse is drawn as the velocity change it
// gives body A, P/m), shown by the scale bars.

const NS = 'http://www.w3.org/2000/svg';
const COLORS = { before: '#1f5fbf', after: '#b54a00', impulse: '#17803d', axis: '#4a4a4a', body: '#dfe7f3', bodyB: '#efe3d3', stroke: '#2b3440', barrier: '#6b6b6b' };
const BODY_PX = 150; // the largest body dimension, in px
const ARROW_PX = 120; // the longest velocity arrow, in px

function s(tag, attrs = {}, text) {
  const el = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== undefined && v !== null) el.setAttribute(k, v);
  if (text !== undefined) el.textContent = text;
  return el;
}

const num = (x) => (typeof x === 'number' && Number.isFinite(x) ? x : 0);
const isNum = (x) => typeof x === 'number' && Number.isFinite(x);
const fmt = (x) => {
  if (!isNum(x)) return '–';
  if (x === 0) return '0';
  const a = Math.abs(x);
  const text = a >= 1e4 || a < 1e-3 ? x.toExponential(2) : x.toPrecision(3);
  return (text.includes('.') && !text.includes('e') ? text.replace(/\.?0+$/, '') : text).replace('-', '−');
};
const hypot = Math.hypot;

// A drawing in px, y up (world-like); rendered into the svg with a viewBox
// that fits everything drawn.
class Drawing {
  constructor() {
    this.items = [];
    this.box = [Infinity, Infinity, -Infinity, -Infinity];
    this.notes = []; // [colour kind, text]: lines under the legend
  }
  grow(x, y, pad = 0) {
    const b = this.box;
    b[0] = Math.min(b[0], x - pad); b[1] = Math.min(b[1], y - pad);
    b[2] = Math.max(b[2], x + pad); b[3] = Math.max(b[3], y + pad);
  }
  add(el, points, pad = 0) {
    this.items.push(el);
    points.forEach(([x, y]) => this.grow(x, y, pad));
    return el;
  }
  // Screen y is −y.
  line(a, b, attrs) { return this.add(s('line', { x1: a[0], y1: -a[1], x2: b[0], y2: -b[1], ...attrs }), [a, b]); }
  arrow(from, vec, kind, label, opts = {}) {
    const len = hypot(vec[0], vec[1]);
    if (!(len > 0.5)) return;
    const to = [from[0] + vec[0], from[1] + vec[1]];
    this.line(from, to, { stroke: COLORS[kind], 'stroke-width': opts.width || 2.5, 'marker-end': `url(#head-${kind})`, 'stroke-dasharray': opts.dash });
    if (label && opts.side) {
      // Beside the arrow's middle, left or right.
      const mid = [from[0] + vec[0] / 2, from[1] + vec[1] / 2];
      this.text([mid[0] + (opts.side === 'left' ? -8 : 8), mid[1]], label, { fill: COLORS[kind], anchor: opts.side === 'left' ? 'end' : 'start' });
    } else if (label) {
      const ux = vec[0] / len;
      const uy = vec[1] / len;
      this.text([to[0] + ux * 12, to[1] + uy * 12], label, { fill: COLORS[kind], anchor: ux > 0.3 ? 'start' : ux < -0.3 ? 'end' : 'middle' });
    }
  }
  text(at, content, { fill = '#1a1a1a', anchor = 'start', size = 13, weight } = {}) {
    const width = content.length * size * 0.55;
    const x0 = anchor === 'start' ? at[0] : anchor === 'end' ? at[0] - width : at[0] - width / 2;
    this.add(s('text', { x: at[0], y: -at[1] + size * 0.35, 'text-anchor': anchor, 'font-size': size, fill, 'font-weight': weight }, content),
      [[x0, at[1] - size * 0.6], [x0 + width, at[1] + size * 0.6]]);
  }
  circle(c, r, attrs) { return this.add(s('circle', { cx: c[0], cy: -c[1], r, ...attrs }), [[c[0] - r, c[1] - r], [c[0] + r, c[1] + r]]); }
  polygon(points, attrs) {
    return this.add(s('polygon', { points: points.map(([x, y]) => `${x},${-y}`).join(' '), ...attrs }), points);
  }
  // A spin arrow around `c`: counter-clockwise on screen when `ccw`.
  spin(c, r, ccw, kind, label) {
    const span = (250 * Math.PI) / 180;
    const a0 = ccw ? -Math.PI / 3 : (4 * Math.PI) / 3;
    const a1 = ccw ? a0 + span : a0 - span;
    const p0 = [c[0] + r * Math.cos(a0), c[1] + r * Math.sin(a0)];
    const p1 = [c[0] + r * Math.cos(a1), c[1] + r * Math.sin(a1)];
    // SVG's sweep flag 1 turns clockwise on screen.
    const d = `M ${p0[0]} ${-p0[1]} A ${r} ${r} 0 1 ${ccw ? 0 : 1} ${p1[0]} ${-p1[1]}`;
    this.add(s('path', { d, fill: 'none', stroke: COLORS[kind], 'stroke-width': 2, 'marker-end': `url(#head-${kind})` }),
      [[c[0] - r, c[1] - r], [c[0] + r, c[1] + r]]);
    if (label) this.notes.push([kind, label]);
  }
  point(c, label, dx = 8, dy = -14) {
    this.circle(c, 4, { fill: '#111' });
    if (label) this.text([c[0] + dx, c[1] + dy], label, { weight: 'bold' });
  }
  // A hatched barrier: the line through `c` along `along`, hatches on the side `away`.
  barrier(c, along, away, half) {
    const a = [c[0] - along[0] * half, c[1] - along[1] * half];
    const b = [c[0] + along[0] * half, c[1] + along[1] * half];
    this.line(a, b, { stroke: COLORS.barrier, 'stroke-width': 3 });
    for (let i = 0; i <= 16; i += 1) {
      const t = -half + (2 * half * i) / 16;
      const p = [c[0] + along[0] * t, c[1] + along[1] * t];
      const q = [p[0] + away[0] * 10 - along[0] * 8, p[1] + away[1] * 10 - along[1] * 8];
      this.line(p, q, { stroke: COLORS.barrier, 'stroke-width': 1 });
    }
  }
  render(svg, caption) {
    const keep = [...svg.children].filter((el) => el.tagName === 'title' || el.tagName === 'desc');
    svg.replaceChildren(...keep, defs(), ...this.items);
    const pad = 16;
    let [x0, y0, x1, y1] = this.box;
    if (!Number.isFinite(x0)) [x0, y0, x1, y1] = [-100, -100, 100, 100];
    const w = Math.max(x1 - x0, 200) + 2 * pad;
    const h = Math.max(y1 - y0, 160) + 2 * pad;
    const cx = (x0 + x1) / 2;
    const cy = (y0 + y1) / 2;
    svg.setAttribute('viewBox', `${cx - w / 2} ${-cy - h / 2} ${w} ${h}`);
    const desc = svg.querySelector('desc');
    if (desc) desc.textContent = caption;
  }
}

function defs() {
  const d = s('defs');
  for (const kind of ['before', 'after', 'impulse', 'axis']) {
    const m = s('marker', { id: `head-${kind}`, viewBox: '0 0 10 10', refX: 8, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse', markerUnits: 'userSpaceOnUse' });
    m.setAttribute('markerWidth', 12);
    m.setAttribute('markerHeight', 12);
    m.append(s('path', { d: 'M 0 0 L 10 5 L 0 10 z', fill: COLORS[kind] }));
    d.append(m);
  }
  return d;
}

// Scale bars and the legend, under the drawing.
function legend(dr, lengthScale, lengthUnit, speedScale) {
  const [x0, y0] = [dr.box[0], dr.box[1] - 26];
  let x = x0;
  for (const [kind, label] of [['before', 'before'], ['after', 'after'], ['impulse', 'impulse P/m']]) {
    dr.line([x, y0], [x + 22, y0], { stroke: COLORS[kind], 'stroke-width': 3 });
    dr.text([x + 27, y0], label, { size: 12 });
    x += 40 + label.length * 7;
  }
  const bar = (value, unit, scale, at) => {
    const px = value * scale;
    dr.line([at, y0 - 22], [at + px, y0 - 22], { stroke: '#1a1a1a', 'stroke-width': 2 });
    dr.line([at, y0 - 27], [at, y0 - 17], { stroke: '#1a1a1a', 'stroke-width': 1.5 });
    dr.line([at + px, y0 - 27], [at + px, y0 - 17], { stroke: '#1a1a1a', 'stroke-width': 1.5 });
    dr.text([at + px + 6, y0 - 22], `${fmt(value)} ${unit}`, { size: 12 });
    return at + px + 20 + (fmt(value).length + unit.length) * 7;
  };
  let at = x0;
  if (lengthScale > 0) at = bar(niceLength(60 / lengthScale), lengthUnit, lengthScale, at);
  if (speedScale > 0) bar(niceLength(60 / speedScale), 'm/s', speedScale, at + 10);
  dr.notes.forEach(([kind, text], i) => dr.text([x0, y0 - 48 - 18 * i], text, { size: 12.5, fill: kind === 'plain' ? '#1a1a1a' : COLORS[kind] }));
}

// 1, 2 or 5 times a power of ten, near x.
function niceLength(x) {
  const p = 10 ** Math.floor(Math.log10(x));
  const m = x / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : 5) * p;
}

// Velocity scale: px per m/s, the longest arrow ARROW_PX.
function speedScale(vectors) {
  const longest = Math.max(...vectors.map(([x, y]) => hypot(num(x), num(y))), 0);
  return longest > 0 ? ARROW_PX / longest : 0;
}

// One body against a barrier in the paper's frame: t along x, n along y,
// C at the origin, G at (d_c, d_d).
function paperScene(request, outcome, caseId) {
  const dr = new Drawing();
  const m = num(request.body?.mass) || 1;
  const inertia = request.body?.inertia;
  const pointMass = !isNum(inertia);
  const dc = num(request.contact?.tangential_offset);
  const dd = num(request.contact?.normal_offset);
  const k = pointMass ? 0 : Math.sqrt(Math.max(inertia / m, 0));
  const disc = Math.abs(dc) === 0;
  const radius = disc ? Math.abs(dd) || k : 0;
  const halfW = disc ? radius : Math.abs(dc);
  const halfH = disc ? radius : Math.abs(dd) || k / 2;
  const extent = Math.max(2 * halfW, 2 * halfH);
  const L = pointMass || !(extent > 0) ? 0 : BODY_PX / extent; // px per m
  const G = pointMass ? [0, 14] : [dc * L, (disc && dd === 0 ? radius : dd) * L];
  const v = [num(request.velocity?.tangential), num(request.velocity?.normal)];
  const fv = outcome?.final_velocity;
  const V = fv ? [num(fv.tangential), num(fv.normal)] : null;
  const P = outcome?.impulse ? [num(outcome.impulse.tangential) / m, num(outcome.impulse.normal) / m] : null;
  const S = speedScale([v, V || [0, 0], P || [0, 0]]);

  const half = Math.max(halfW * L, 60) + 90;
  dr.barrier([0, 0], [1, 0], [0, -1], half);
  if (pointMass) {
    dr.circle(G, 14, { fill: COLORS.body, stroke: COLORS.stroke, 'stroke-width': 1.5 });
  } else if (disc) {
    dr.circle(G, radius * L, { fill: COLORS.body, stroke: COLORS.stroke, 'stroke-width': 1.5 });
  } else {
    const [gx, gy] = G;
    const [w, h] = [halfW * L, halfH * L];
    dr.polygon([[gx - w, gy - h], [gx + w, gy - h], [gx + w, gy + h], [gx - w, gy + h]], { fill: COLORS.body, stroke: COLORS.stroke, 'stroke-width': 1.5 });
  }
  // The frame at C.
  dr.arrow([0, 0], [0, 44], 'axis', 'n', { width: 1.5 });
  dr.arrow([0, 0], [44, 0], 'axis', 't', { width: 1.5 });
  dr.point([0, 0], 'C', -16, -16);
  if (!pointMass) {
    dr.circle(G, 3.5, { fill: '#111' });
    dr.text([G[0] + 8, G[1] + 12], 'G', { weight: 'bold' });
  }
  // A point mass's arrows side by side (they are along n).
  const [gv, gV] = pointMass ? [[G[0] - 22, G[1]], [G[0] + 22, G[1]]] : [G, G];
  const side = (k) => (pointMass ? { side: k } : {});
  dr.arrow(gv, [v[0] * S, v[1] * S], 'before', `v ${fmt(hypot(...v))} m/s`, side('left'));
  if (V) dr.arrow(gV, [V[0] * S, V[1] * S], 'after', `V ${fmt(hypot(...V))} m/s`, side('right'));
  if (P) dr.arrow([0, 0], [P[0] * S, P[1] * S], 'impulse', 'P');
  // ω turns n toward t: clockwise on screen.
  const w0 = num(request.velocity?.angular);
  const r = Math.max((disc ? radius : Math.min(halfW, halfH)) * L * 0.55, 18);
  if (!pointMass && w0 !== 0) dr.spin(G, r, w0 < 0, 'before');
  if (!pointMass && fv && num(fv.angular) !== 0) dr.spin(G, r + 9, num(fv.angular) < 0, 'after');
  if (!pointMass) dr.notes.push(['plain', `spin ω ${fmt(w0)}${fv ? ` → Ω ${fmt(fv.angular)}` : ''} rad/s (positive turns n toward t)`]);
  if (P) dr.notes.push(['impulse', `impulse P = (${fmt(outcome.impulse.tangential)}, ${fmt(outcome.impulse.normal)}) N s (t, n), μ = ${fmt(outcome.impulse_ratio)}, ${outcome.regime}`]);
  legend(dr, L, 'm', S);
  const shape = pointMass ? 'a point mass' : disc ? `a disc of radius ${fmt(radius)} m` : `a box ${fmt(2 * halfW)} × ${fmt(2 * halfH)} m`;
  return [dr, `${caseId} impact: ${shape} on a barrier; before, v = (${fmt(v[0])}, ${fmt(v[1])}) m/s (t, n)` +
    (V ? `; after, V = (${fmt(V[0])}, ${fmt(V[1])}) m/s, regime ${outcome.regime}` : '')];
}

// A ball spinning about the normal: side view (normal velocities) and the
// view down the normal (spins, the pitch circle).
function torsionalScene(request, outcome) {
  const dr = new Drawing();
  const m = num(request.body?.mass) || 1;
  const In = num(request.body?.normal_inertia);
  const radius = Math.sqrt(Math.max((2.5 * In) / m, 0)) || 0.05; // a solid sphere of the same I_n/m
  const L = BODY_PX / (2 * radius);
  const R = radius * L;
  const vn = num(request.velocity?.normal);
  const Vn = outcome ? num(outcome.final_velocity?.normal) : null;
  const S = speedScale([[0, vn], [0, Vn || 0], [0, outcome ? num(outcome.impulse?.normal) / m : 0]]);
  // Side view.
  dr.barrier([0, 0], [1, 0], [0, -1], R + 50);
  const G = [0, R];
  dr.circle(G, R, { fill: COLORS.body, stroke: COLORS.stroke, 'stroke-width': 1.5 });
  dr.point([0, 0], 'C', 10, -14);
  dr.circle(G, 3.5, { fill: '#111' });
  dr.arrow([-R * 0.35, G[1]], [0, vn * S], 'before', `v_n ${fmt(vn)}`, { side: 'left' });
  if (outcome) dr.arrow([R * 0.35, G[1]], [0, Vn * S], 'after', `V_n ${fmt(Vn)}`, { side: 'right' });
  if (outcome) dr.arrow([0, 0], [0, (num(outcome.impulse?.normal) / m) * S], 'impulse', '');
  dr.text([0, 2 * R + 18], 'side view', { anchor: 'middle', size: 12 });
  // View down the normal: spin positive counter-clockwise.
  const T = [2 * R + 90, R];
  const rp = num(request.torsion?.pitch_radius) * L;
  dr.circle(T, R, { fill: COLORS.body, stroke: COLORS.stroke, 'stroke-width': 1.5 });
  if (rp > 0) dr.circle(T, Math.min(rp, R * 1.5), { fill: 'none', stroke: COLORS.stroke, 'stroke-dasharray': '4 3' });
  dr.text([T[0], T[1] - Math.min(rp, R * 1.5) - 12], `ρ_p ${fmt(request.torsion?.pitch_radius)} m`, { anchor: 'middle', size: 12 });
  const w0 = num(request.velocity?.spin);
  if (w0 !== 0) dr.spin(T, R * 0.55, w0 > 0, 'before');
  if (outcome && num(outcome.final_velocity?.spin) !== 0) dr.spin(T, R * 0.75, outcome.final_velocity.spin > 0, 'after');
  dr.notes.push(['plain', `spin ω_n ${fmt(w0)}${outcome ? ` → Ω_n ${fmt(outcome.final_velocity?.spin)}` : ''} rad/s (counter-clockwise seen down the normal)`]);
  if (outcome) dr.notes.push(['impulse', `P_n ${fmt(outcome.impulse?.normal)} N s, M_n ${fmt(outcome.impulse?.torsional)} N m s, ${outcome.regime} (switch at ω_s ${fmt(outcome.switch_spin)})`]);
  dr.text([T[0], 2 * R + 18], 'seen down the normal', { anchor: 'middle', size: 12 });
  legend(dr, L, 'm', S);
  return [dr, `torsional impact: a ball (drawn as a solid sphere of the same I_n/m, radius ${fmt(radius)} m) spinning at ${fmt(w0)} rad/s` +
    (outcome ? `; after, ${fmt(outcome.final_velocity?.spin)} rad/s, regime ${outcome.regime}` : '')];
}

const sub = (a, b) => a.map((x, i) => x - b[i]);
const dot = (a, b) => a.reduce((acc, x, i) => acc + x * b[i], 0);
const scale = (a, k) => a.map((x) => x * k);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = (a) => { const n = Math.hypot(...a); return n > 0 ? scale(a, 1 / n) : a; };

// A body in a world drawing (2-D, px): a disc when the contact is central
// (C − G along n), else a box whose face through C is normal to n, sized by
// the radius of gyration (a uniform box of that I/m where it can).
function bodyShape(G, C, n, k, outward) {
  // `outward`: the body's outward normal at C (−n for A, +n for B).
  const d = dot(sub(G, C), scale(outward, -1));
  const t = [-outward[1], outward[0]];
  const e = dot(sub(C, G), t);
  const r = Math.hypot(...sub(G, C));
  if (Math.abs(e) <= 1e-9 * Math.max(r, 1e-300)) return { kind: 'disc', radius: r };
  const a = Math.abs(d) || k;
  const b = Math.max(Math.sqrt(Math.max(3 * k * k - a * a, 0)), Math.abs(e) * 1.1, 0.3 * a);
  const nA = scale(outward, -1);
  const corners = [[a, b], [a, -b], [-a, -b], [-a, b]].map(([u, w]) => [G[0] + nA[0] * u + t[0] * w, G[1] + nA[1] * u + t[1] * w]);
  return { kind: 'box', corners };
}

// Two laminae (or one and a barrier) in world axes.
function planarScene(request, outcome) {
  const dr = new Drawing();
  const bodies = Array.isArray(request.bodies) ? request.bodies : [];
  const C = [num(request.contact?.point?.x), num(request.contact?.point?.y)];
  const n = unit([num(request.contact?.normal?.x), num(request.contact?.normal?.y)]);
  const pos = (b) => [num(b?.position?.x), num(b?.position?.y)];
  const shapes = bodies.map((b, i) => {
    const k = Math.sqrt(Math.max(num(b.inertia) / (num(b.mass) || 1), 0));
    return bodyShape(pos(b), C, n, k, i === 0 ? scale(n, -1) : n);
  });
  // Length scale: everything drawn in world metres fits BODY_PX * 2.
  const pts = [C];
  shapes.forEach((sh, i) => {
    if (sh.kind === 'box') pts.push(...sh.corners);
    else { const G = pos(bodies[i]); pts.push([G[0] - sh.radius, G[1] - sh.radius], [G[0] + sh.radius, G[1] + sh.radius]); }
  });
  const span = Math.max(...[0, 1].map((j) => Math.max(...pts.map((p) => p[j])) - Math.min(...pts.map((p) => p[j]))), 1e-300);
  const L = (2 * BODY_PX) / span;
  const px = (p) => [(p[0] - C[0]) * L, (p[1] - C[1]) * L];
  const vOf = (b) => [num(b?.velocity?.x), num(b?.velocity?.y)];
  const finals = outcome?.bodies || [];
  const m0 = num(bodies[0]?.mass) || 1;
  const P = outcome?.impulse ? [num(outcome.impulse.x) / m0, num(outcome.impulse.y) / m0] : null;
  const S = speedScale([...bodies.map(vOf), ...finals.map((f) => [num(f.velocity?.x), num(f.velocity?.y)]), P || [0, 0]]);
  if (bodies.length === 1) dr.barrier([0, 0], [-n[1], n[0]], scale(n, -1), BODY_PX);
  shapes.forEach((sh, i) => {
    const fill = i === 0 ? COLORS.body : COLORS.bodyB;
    if (sh.kind === 'disc') dr.circle(px(pos(bodies[i])), sh.radius * L, { fill, stroke: COLORS.stroke, 'stroke-width': 1.5, 'fill-opacity': 0.85 });
    else dr.polygon(sh.corners.map(px), { fill, stroke: COLORS.stroke, 'stroke-width': 1.5, 'fill-opacity': 0.85 });
  });
  dr.arrow([0, 0], scale(n, 44), 'axis', 'n', { width: 1.5 });
  dr.arrow([0, 0], scale([-n[1], n[0]], 44), 'axis', 't', { width: 1.5 });
  dr.point([0, 0], 'C', 8, 10);
  bodies.forEach((b, i) => {
    const G = px(pos(b));
    dr.circle(G, 3.5, { fill: '#111' });
    dr.text([G[0] - 8, G[1] + 12], i === 0 ? 'A' : 'B', { weight: 'bold', anchor: 'end' });
    const v = vOf(b);
    dr.arrow(G, scale(v, S), 'before', `${fmt(hypot(...v))} m/s`);
    const f = finals[i];
    if (f) {
      const V = [num(f.velocity?.x), num(f.velocity?.y)];
      dr.arrow(G, scale(V, S), 'after', `${fmt(hypot(...V))} m/s`);
    }
    const w0 = num(b.angular_velocity);
    if (w0 !== 0) dr.spin(G, 20, w0 > 0, 'before');
    if (f && num(f.angular_velocity) !== 0) dr.spin(G, 28, f.angular_velocity > 0, 'after');
    dr.notes.push(['plain', `${i === 0 ? 'A' : 'B'}: spin ω ${fmt(w0)}${f ? ` → Ω ${fmt(f.angular_velocity)}` : ''} rad/s (counter-clockwise)${f ? `, delta-V ${fmt(f.delta_v)} m/s` : ''}`]);
  });
  if (P) dr.arrow([0, 0], scale(P, S), 'impulse', 'P');
  if (P) dr.notes.push(['impulse', `impulse on A P = (${fmt(outcome.impulse.x)}, ${fmt(outcome.impulse.y)}) N s, μ = ${fmt(outcome.impulse_ratio)}, ${outcome.regime}`]);
  legend(dr, L, 'm', S);
  return [dr, `planar impact, ${bodies.length === 2 ? 'two bodies' : 'one body on a barrier'}, world axes` +
    (outcome ? `; regime ${outcome.regime}, delta-V of A ${fmt(finals[0]?.delta_v)} m/s` : '')];
}

// Bodies in space, seen along the axis normal to n and to the slip: n up,
// the initial slip to the right; spins about the viewing axis as arcs.
function spatialScene(request, outcome) {
  const dr = new Drawing();
  const bodies = Array.isArray(request.bodies) ? request.bodies : [];
  const v3 = (o) => [num(o?.x), num(o?.y), num(o?.z)];
  const C = v3(request.contact?.point);
  const n = unit(v3(request.contact?.normal));
  let right = outcome?.contact_velocity?.initial?.tangential ? v3(outcome.contact_velocity.initial.tangential) : sub(v3(bodies[0]?.velocity), v3(bodies[1]?.velocity));
  right = sub(right, scale(n, dot(right, n)));
  if (Math.hypot(...right) < 1e-12 * (1 + Math.hypot(...v3(bodies[0]?.velocity)))) {
    const trial = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    right = sub(trial, scale(n, dot(trial, n)));
  }
  right = unit(right);
  const depth = cross(right, n); // toward the viewer
  const proj = (p) => [dot(p, right), dot(p, n)];
  const radiusOf = (b) => {
    const m = num(b.mass) || 1;
    const inertia = b.inertia || {};
    if (inertia.sphere) return num(inertia.sphere.radius);
    const mean = inertia.principal ? (num(inertia.principal.moments?.x) + num(inertia.principal.moments?.y) + num(inertia.principal.moments?.z)) / 3
      : (num(inertia.xx) + num(inertia.yy) + num(inertia.zz)) / 3;
    return Math.sqrt(Math.max((2.5 * mean) / m, 0)) || Math.hypot(...sub(v3(b.position), C));
  };
  const radii = bodies.map(radiusOf);
  const pts = [proj(C)];
  bodies.forEach((b, i) => { const G = proj(v3(b.position)); pts.push([G[0] - radii[i], G[1] - radii[i]], [G[0] + radii[i], G[1] + radii[i]]); });
  const span = Math.max(...[0, 1].map((j) => Math.max(...pts.map((p) => p[j])) - Math.min(...pts.map((p) => p[j]))), 1e-300);
  const L = (bodies.length > 1 ? 2 : 1) * BODY_PX / span;
  const c0 = proj(C);
  const px = (p) => { const q = proj(p); return [(q[0] - c0[0]) * L, (q[1] - c0[1]) * L]; };
  const finals = outcome?.bodies || [];
  const m0 = num(bodies[0]?.mass) || 1;
  const P = outcome?.impulse ? scale([num(outcome.impulse.x), num(outcome.impulse.y), num(outcome.impulse.z)], 1 / m0) : null;
  const S = speedScale([...bodies.map((b) => proj(v3(b.velocity))), ...finals.map((f) => proj(v3(f.velocity))), P ? proj(P) : [0, 0]]);
  if (bodies.length === 1) dr.barrier([0, 0], [1, 0], [0, -1], Math.max(radii[0] * L, 60) + 80);
  bodies.forEach((b, i) => {
    dr.circle(px(v3(b.position)), radii[i] * L, { fill: i === 0 ? COLORS.body : COLORS.bodyB, stroke: COLORS.stroke, 'stroke-width': 1.5, 'fill-opacity': 0.85 });
  });
  dr.arrow([0, 0], [0, 44], 'axis', 'n', { width: 1.5 });
  dr.arrow([0, 0], [44, 0], 'axis', 'slip', { width: 1.5 });
  dr.point([0, 0], 'C', -18, -16);
  const notes = [];
  bodies.forEach((b, i) => {
    const G = px(v3(b.position));
    dr.circle(G, 3.5, { fill: '#111' });
    if (bodies.length > 1) dr.text([G[0] - 8, G[1] + 12], i === 0 ? 'A' : 'B', { weight: 'bold', anchor: 'end' });
    const v = v3(b.velocity);
    dr.arrow(G, scale(proj(v), S), 'before', `${fmt(Math.hypot(...v))} m/s`);
    const f = finals[i];
    if (f) { const V = v3(f.velocity); dr.arrow(G, scale(proj(V), S), 'after', `${fmt(Math.hypot(...V))} m/s`); }
    const w = v3(b.angular_velocity);
    const wd = dot(w, depth);
    const r = Math.max(radii[i] * L * 0.55, 18);
    const W = f ? dot(v3(f.angular_velocity), depth) : 0;
    if (Math.abs(wd) > 1e-12) dr.spin(G, r, wd > 0, 'before');
    if (f && Math.abs(W) > 1e-12) dr.spin(G, r + 9, W > 0, 'after');
    const who = bodies.length > 1 ? (i === 0 ? 'A: ' : 'B: ') : '';
    notes.push(`${who}spin in view ${fmt(wd)}${f ? ` → ${fmt(W)}` : ''}, about n ${fmt(dot(w, n))}${f ? ` → ${fmt(dot(v3(f.angular_velocity), n))}` : ''} rad/s`);
  });
  if (P) dr.arrow([0, 0], scale(proj(P), S), 'impulse', 'P');
  notes.forEach((t) => dr.notes.push(['plain', t]));
  if (P) dr.notes.push(['impulse', `impulse on A P = (${fmt(outcome.impulse.x)}, ${fmt(outcome.impulse.y)}, ${fmt(outcome.impulse.z)}) N s, μ = ${fmt(outcome.impulse_ratio)}, ${outcome.regime}`]);
  legend(dr, L, 'm', S);
  const drawnAsSphere = bodies.some((b) => !b.inertia?.sphere) ? '; a body given by its tensor or principal moments is drawn as the solid sphere of its mean moment' : '';
  return [dr, `spatial impact seen with n up and the initial slip to the right${drawnAsSphere}; ${notes.join('; ')}` +
    (outcome ? `; regime ${outcome.regime}` : '')];
}

export function drawScene(svg, caseId, request, outcome) {
  let made;
  try {
    if (caseId === 'torsional') made = torsionalScene(request, outcome);
    else if (caseId === 'planar') made = planarScene(request, outcome);
    else if (caseId === 'spatial') made = spatialScene(request, outcome);
    else made = paperScene(request, outcome, caseId);
  } catch (error) {
    const dr = new Drawing();
    dr.text([0, 0], 'The scene cannot be drawn from these inputs.', {});
    made = [dr, String(error)];
  }
  const [dr, caption] = made;
  dr.render(svg, caption);
  return caption;
}
