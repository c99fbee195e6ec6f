// Fits: measured impacts as CSV (a header row of the API's field names
// within one observation, dotted: `initial.normal`), the coefficients the
// service identifies with their standard errors, and the fitted model drawn
// over the points.

import { post, problemText } from './api.js';
import { h, apiName, parseValue, setIn, showError, clearError } from './form.js';
import { outputLabel } from './cases.js';
import { copy, curl } from './share.js';

const $ = (id) => document.getElementById(id);
const XYZ = ['x', 'y', 'z'];

// Per fit: the endpoint, the members shared by every row unless the CSV has
// a column for them, the columns, and how to read the fitted coefficients.
const KINDS = {
  tangential: {
    endpoint: '/v1/fits/tangential',
    common: [
      ['body.mass', 'm', 'kg', 1.0], ['body.inertia', 'I', 'kg m²', 0.00125],
      ['contact.tangential_offset', 'd<sub>c</sub>', 'm', 0.0], ['contact.normal_offset', 'd<sub>d</sub>', 'm', 0.05],
    ],
    columns: ['initial.normal', 'initial.tangential', 'initial.angular', 'final.normal', 'final.tangential', 'final.angular'],
    hint: 'One impact per row: velocities before (initial: v_n, v_t, ω) and after (final: V_n, V_t, Ω). Body and contact from the fields above unless the CSV has body.mass, body.inertia, contact.tangential_offset, contact.normal_offset columns. At least 3 rows.',
    coefficients: [['restitution', 'e'], ['friction', 'f'], ['tangential_restitution', 'e<sub>t</sub>'], ['r_squared', 'R²']],
  },
  torsional: {
    endpoint: '/v1/fits/torsional',
    common: [['body.mass', 'm', 'kg', 0.1], ['body.normal_inertia', 'I<sub>n</sub>', 'kg m²', 0.000036], ['pitch_radius', 'ρ<sub>p</sub>', 'm', 0.005]],
    columns: ['initial.normal', 'initial.spin', 'final.normal', 'final.spin'],
    hint: 'One spinning impact per row: normal velocity and spin before (initial) and after (final). Body and pitch radius from the fields above unless the CSV has those columns. At least 3 rows.',
    coefficients: [['restitution', 'e'], ['torsional_restitution', 'e<sub>z</sub>'], ['torsional_friction', 'μ<sub>z</sub>'], ['r_squared', 'R²']],
  },
  planar: {
    endpoint: '/v1/fits/planar',
    common: [],
    columns: ['velocity_change.x.value', 'velocity_change.x.uncertainty', 'velocity_change.y.value', 'velocity_change.y.uncertainty',
      'angular_velocity_change.value', 'angular_velocity_change.uncertainty'],
    hint: 'One row per body, in the order of the scene\'s bodies: its measured ΔV (x, y) and ΔΩ, each with its standard uncertainty. The scene (bodies before the impact, contact) is the Impact section\'s planar case.',
    coefficients: [['restitution', 'e'], ['impulse_ratio', 'μ'], ['normal/angle', 'angle of n (rad)'], ['chi_squared', 'χ²'], ['degrees_of_freedom', 'degrees of freedom']],
  },
  // The coefficients come back as a list, each named by its member of a
  // spatial impact request: labelled from the quantity table (no list here).
  spatial: {
    endpoint: '/v1/fits/spatial',
    common: [],
    columns: ['impact', ...['velocity_change', 'angular_velocity_change'].flatMap((v) => XYZ.flatMap((c) => [`${v}.${c}.value`, `${v}.${c}.uncertainty`]))],
    hint: 'One row per body per impact, in the order of the scene\'s bodies (A, then B): impact numbers the impact the row belongs to (without it, each run of rows as long as the scene\'s bodies is one impact); ΔV and Δω (x, y, z), each with its standard uncertainty (Δω blank: not measured). Each impact starts from the Impact section\'s spatial scene (bodies before the impact, contact); a column naming a member of a body (velocity.x, angular_velocity.z, position.y, …) or of the contact (contact.normal.z, …) sets it for that row\'s impact. The law fitted is the scene\'s (frictionless is fitted as the impulse ratio μ, 0 when frictionless), with the twist law when the scene has one, at its pitch radius.',
  },
};

// The spatial fit's law: the Impact section's spatial law, as the fit
// request names it (a frictionless scene: the impulse ratio, μ = 0).
function spatialLaw(scene) {
  if (scene && 'kinetic_restitution' in scene) {
    return 'approach_friction' in (scene.kinetic_restitution || {}) ? 'kinetic_friction' : 'kinetic_restitution';
  }
  if (scene && 'tangential_restitution' in scene) return 'tangential_restitution';
  if (scene && 'friction' in scene) return 'friction';
  return 'impulse_ratio'; // a prescribed ratio, or frictionless: μ = 0
}

// Members of one CSV row of the spatial fit: the impact it belongs to, its
// measured change, the contact's and the body's own members.
const MEASURED = /^(velocity_change|angular_velocity_change)(\.|$)/;
const CONTACT = /^contact(\.|$)/;

export function parseCsv(text) {
  const lines = text.split(/\r?\n/).map((l) => l.trim()).filter((l) => l && !l.startsWith('#'));
  if (lines.length === 0) return { header: [], rows: [] };
  const split = (l) => l.split(/[,;\t]/).map((c) => c.trim());
  return { header: split(lines[0]), rows: lines.slice(1).map(split) };
}

export class FitPanel {
  // app: {planarScene(), spatialScene() -> request or null, form(), showImpactProblem()}
  constructor(app) {
    this.app = app;
    $('fit-kind').addEventListener('change', () => this.renderKind(true));
    $('fit-form').addEventListener('submit', (e) => { e.preventDefault(); this.run(); });
    $('fit-sample').addEventListener('click', () => this.sample());
    $('fit-curl').addEventListener('click', () => {
      const built = this.request();
      if (built.request) copy(curl(KINDS[$('fit-kind').value].endpoint, built.request), 'curl command copied');
    });
    $('fit-file').addEventListener('change', async (e) => {
      const file = e.target.files[0];
      if (file) $('fit-csv').value = await file.text();
    });
    this.renderKind(false);
  }

  kind() { return KINDS[$('fit-kind').value]; }

  renderKind(clear) {
    const kind = this.kind();
    const fields = kind.common.map(([name, sym, unit, value]) => {
      const id = `fit-${name.replace(/\./g, '-')}`;
      return h('div', { class: 'field' },
        h('label', { for: id }, h('span', { class: 'sym', html: sym }), ' ', h('code', { text: name }), unit ? h('span', { class: 'unit', text: ` ${unit}` }) : ''),
        h('input', { id, inputmode: 'decimal', autocomplete: 'off', value: String(value), 'aria-describedby': `${id}-error` }),
        h('span', { class: 'error', id: `${id}-error`, hidden: true }));
    });
    if ($('fit-kind').value === 'planar') {
      fields.push(h('div', { class: 'field check' }, h('label', { class: 'inline', for: 'fit-normal' },
        h('input', { type: 'checkbox', id: 'fit-normal' }), ' also fit the normal\'s direction ', h('code', { text: 'fit_normal' }))));
    }
    if ($('fit-kind').value === 'spatial') {
      // The law is the scene's: shown here, where a refusal at `/law` is marked.
      fields.push(h('div', { class: 'field' },
        h('label', { for: 'fit-law' }, h('code', { text: 'law' }), ' (the Impact section\'s spatial law)'),
        h('input', { id: 'fit-law', readonly: true, autocomplete: 'off', 'aria-describedby': 'fit-law-hint fit-law-error' }),
        h('span', { class: 'hint', id: 'fit-law-hint' }),
        h('span', { class: 'error', id: 'fit-law-error', hidden: true })));
    }
    $('fit-fields').replaceChildren(...fields);
    this.sceneChanged();
    $('fit-kind-hint').textContent = `POST ${kind.endpoint}`;
    $('fit-csv-hint').textContent = `Columns: ${kind.columns.join(', ')}. ${kind.hint}`;
    if (clear) {
      $('fit-csv').value = '';
      $('fit-table').hidden = true;
      $('fit-figure').hidden = true;
      $('fit-status').textContent = '';
    }
  }

  // The Impact section changed: the spatial fit's law follows its scene.
  sceneChanged() {
    const law = $('fit-law');
    if (!law) return;
    const scene = this.app.spatialScene() || {};
    law.value = spatialLaw(scene);
    const twist = scene.torsion ? `, and the twist law (torsion.pitch_radius ${scene.torsion.pitch_radius})` : '';
    $('fit-law-hint').textContent = `Its coefficients are fitted${twist}.`;
  }

  // The request from the CSV and the shared fields; {request} or {problem}.
  request() {
    const kindName = $('fit-kind').value;
    const kind = KINDS[kindName];
    const { header, rows } = parseCsv($('fit-csv').value);
    if (header.length === 0) return { problem: 'Paste or upload CSV first (or press “Sample data”).' };
    const items = rows.map((cells) => {
      const item = {};
      header.forEach((name, i) => {
        const v = parseValue(cells[i] ?? '');
        if (v !== undefined) setIn(item, '/' + name.replace(/\./g, '/'), v);
      });
      for (const [name] of kind.common) {
        if (!header.includes(name)) {
          const v = parseValue($(`fit-${name.replace(/\./g, '-')}`).value);
          if (v !== undefined) setIn(item, '/' + name.replace(/\./g, '/'), v);
        }
      }
      return item;
    });
    this.header = header;
    if (kindName === 'spatial') return this.spatialRequest(header, rows);
    if (kindName === 'planar') {
      const scene = this.app.planarScene();
      const request = { bodies: scene.bodies, contact: scene.contact, measured: items };
      if ($('fit-normal').checked) request.fit_normal = true;
      return { request };
    }
    return { request: { observations: items } };
  }

  // The spatial fit's request: the rows grouped into impacts (by the
  // `impact` column, or runs as long as the scene's bodies), each impact the
  // scene with the row's own members set over it. Remembers which CSV row
  // holds each measured change (`this.rowsOf[impact][body]`).
  spatialRequest(header, rows) {
    const scene = this.app.spatialScene();
    if (!scene) return { problem: 'Choose the spatial case in the Impact section first.' };
    this.sceneChanged();
    const byImpact = header.indexOf('impact');
    const groups = new Map();
    rows.forEach((cells, r) => {
      const key = byImpact >= 0 ? String(parseValue(cells[byImpact] ?? '') ?? '') : String(Math.floor(r / Math.max(scene.bodies?.length || 1, 1)));
      if (!groups.has(key)) groups.set(key, []);
      groups.get(key).push(r);
    });
    this.rowsOf = [...groups.values()];
    const impacts = this.rowsOf.map((group) => {
      const impact = { bodies: structuredClone(scene.bodies), contact: structuredClone(scene.contact), measured: [] };
      group.forEach((r, k) => {
        const measured = {};
        header.forEach((name, i) => {
          if (name === 'impact') return;
          const v = parseValue(rows[r][i] ?? '');
          if (v === undefined) return;
          const pointer = '/' + name.replace(/\./g, '/');
          if (MEASURED.test(name)) setIn(measured, pointer, v);
          else if (CONTACT.test(name)) setIn(impact, pointer, v);
          else if (Array.isArray(impact.bodies) && k < impact.bodies.length) setIn(impact.bodies[k], pointer, v);
        });
        impact.measured.push(measured);
      });
      return impact;
    });
    const request = { law: spatialLaw(scene), impacts };
    if (scene.torsion) request.torsion = { pitch_radius: scene.torsion.pitch_radius };
    return { request, rows: rows.length };
  }

  // A refusal of the spatial fit: a row's member on the CSV, the scene's on
  // the Impact section, the law on its field.
  showSpatialProblem(problem, detail) {
    const pointer = problem.pointer || '';
    const at = pointer.match(/^\/impacts\/(\d+)(?:\/(bodies|measured|contact)(?:\/(\d+))?)?(\/.*)?$/);
    const rowsText = (rows) => (rows.length === 1 ? `Row ${rows[0] + 1}` : `Rows ${rows.map((r) => r + 1).join(', ')}`);
    if (at) {
      const impact = Number(at[1]);
      const rows = this.rowsOf?.[impact] || [];
      const [, , part, body, rest] = at;
      const member = (rest || '').slice(1).replace(/\//g, '.');
      const row = body !== undefined ? rows[Number(body)] : undefined;
      // Whether the CSV has a column for the member (or within it).
      const inCsv = (name) => this.header.some((c) => c === name || c.startsWith(`${name}.`) || name.startsWith(`${c}.`));
      if (part === 'measured' && row !== undefined) {
        showError($('fit-csv'), `${rowsText([row])}${member ? ` (${member})` : ''}: ${detail}`);
      } else if (part === 'bodies' && row !== undefined && member && inCsv(member)) {
        showError($('fit-csv'), `${rowsText([row])} (${member}): ${detail}`);
      } else if (part === 'bodies' && body !== undefined) {
        this.app.showImpactProblem({ ...problem, pointer: `/bodies/${body}${rest || ''}` });
      } else if (part === 'contact' && !inCsv(member ? `contact.${member}` : 'contact')) {
        this.app.showImpactProblem({ ...problem, pointer: `/contact${rest || ''}` });
      } else {
        const what = part ? `${part}${body !== undefined ? `[${body}]` : ''}${member ? `.${member}` : ''}` : '';
        showError($('fit-csv'), `${rows.length ? rowsText(rows) : `Impact ${impact + 1}`}${what ? ` (${what})` : ''}: ${detail}`);
      }
    } else if (pointer === '/law' && $('fit-law')) {
      showError($('fit-law'), detail);
    } else if (/^\/(torsion|bodies|contact)(\/|$)/.test(pointer)) {
      this.app.showImpactProblem(problem);
    } else {
      showError($('fit-csv'), detail);
    }
  }

  clearErrors() {
    clearError($('fit-csv'));
    document.querySelectorAll('#fit-fields input').forEach(clearError);
    $('fit-problem').hidden = true;
  }

  showProblem(problem) {
    const pointer = problem.pointer || '';
    const detail = problem.detail || problem.title;
    if ($('fit-kind').value === 'spatial') {
      this.showSpatialProblem(problem, detail);
      $('fit-problem').textContent = problemText(problem);
      $('fit-problem').hidden = false;
      return;
    }
    const row = pointer.match(/^\/(observations|measured)\/(\d+)(\/.*)?$/);
    if (row) {
      const member = (row[3] || '').slice(1).replace(/\//g, '.');
      const shared = this.kind().common.find(([name]) => member === name || member.startsWith(`${name}.`));
      if (shared && !this.header.includes(shared[0])) {
        showError($(`fit-${shared[0].replace(/\./g, '-')}`), detail);
      } else {
        showError($('fit-csv'), `Row ${Number(row[2]) + 1}${member ? ` (${member})` : ''}: ${detail}`);
      }
    } else if (pointer === '/observations' || pointer === '/measured' || pointer === '') {
      showError($('fit-csv'), detail);
    } else if (/^\/(bodies|contact)/.test(pointer)) {
      this.app.showImpactProblem(problem);
    }
    $('fit-problem').textContent = problemText(problem);
    $('fit-problem').hidden = false;
  }

  async run() {
    this.clearErrors();
    const built = this.request();
    if (!built.request) {
      showError($('fit-csv'), built.problem);
      return;
    }
    const kindName = $('fit-kind').value;
    $('fit-status').textContent = 'Fitting…';
    $('fit-table').hidden = true;
    $('fit-figure').hidden = true;
    const answer = await post(this.kind().endpoint, built.request);
    if (!answer.ok) {
      $('fit-status').textContent = 'The service refused the fit.';
      this.showProblem(answer.problem);
      return;
    }
    if (kindName === 'spatial') this.spatialTable(answer.body);
    else this.table(answer.body);
    $('fit-status').textContent = `Fitted ${built.rows ?? (built.request.observations || built.request.measured).length} rows.`;
    await this.draw(kindName, built.request);
  }

  table(fit) {
    const rows = [];
    for (const [path, sym] of this.kind().coefficients) {
      const value = path.split('/').reduce((at, k) => (at == null ? at : at[k]), fit);
      if (value === undefined) {
        rows.push([sym, path, 'not identified', '']);
      } else if (value !== null && typeof value === 'object') {
        rows.push([sym, path, value.value, value.standard_error ?? '—']);
      } else {
        rows.push([sym, path, value ?? '—', '']);
      }
    }
    if (fit.impulse) rows.push(['P<sub>x</sub>, P<sub>y</sub>', 'impulse', `${fit.impulse.x}, ${fit.impulse.y}`, `${fit.impulse_standard_error.x}, ${fit.impulse_standard_error.y}`]);
    if (Array.isArray(fit.regimes)) {
      const counts = {};
      fit.regimes.forEach((r) => { counts[r] = (counts[r] || 0) + 1; });
      rows.push(['regimes', 'regimes', Object.entries(counts).map(([k, n]) => `${k} ${n}`).join(', '), '']);
    }
    if (Array.isArray(fit.residuals)) {
      const flat = fit.residuals.flat().filter((x) => typeof x === 'number');
      const rms = Math.sqrt(flat.reduce((a, x) => a + x * x, 0) / Math.max(flat.length, 1));
      rows.push(['residuals', 'residuals', `RMS ${rms.toPrecision(4)} over ${flat.length}`, '']);
    }
    const tbody = $('fit-table').querySelector('tbody');
    tbody.replaceChildren(...rows.map(([sym, path, value, se]) => h('tr', {},
      h('th', { scope: 'row', html: sym }), h('td', {}, h('code', { text: path.replace(/\//g, '.') })),
      h('td', { class: 'num', text: String(value).replace(/^-/, '−') }), h('td', { class: 'num', text: String(se).replace(/^-/, '−') }))));
    $('fit-table').hidden = false;
  }

  // The spatial fit: each coefficient labelled from the quantity table by its
  // request member, χ² and its degrees of freedom, each impact's regime and
  // residuals; a member the table does not name by its API name.
  spatialTable(fit) {
    const rows = [];
    const row = (pointer, value, se = '', member = apiName(pointer), list = false) => {
      const label = outputLabel(pointer);
      rows.push(h('tr', { 'data-member': member },
        h('th', { scope: 'row' }, label.sym ? h('span', { class: 'sym', html: label.sym }) : '', label.sym ? ' ' : '', h('span', { class: 'words', html: label.text })),
        h('td', {}, h('code', { text: member })),
        h('td', { class: list ? 'num list' : 'num', 'data-value': String(value) }, display(value), label.unit ? h('span', { class: 'unit', text: ` ${label.unit}` }) : ''),
        h('td', { class: 'num', 'data-value': String(se ?? '') }, se === null ? '—' : display(se))));
    };
    for (const c of fit.coefficients) row(c.member, c.value, c.standard_error);
    row('/chi_squared', fit.chi_squared);
    row('/degrees_of_freedom', fit.degrees_of_freedom);
    if (fit.degrees_of_freedom > 0) row('/chi_squared/degrees_of_freedom', fit.chi_squared / fit.degrees_of_freedom, '', 'chi_squared / degrees_of_freedom');
    fit.impacts.forEach((impact, i) => {
      row(`/impacts/${i}/regime`, impact.regime);
      if (impact.torsional_regime) row(`/impacts/${i}/torsional_regime`, impact.torsional_regime);
      row(`/impacts/${i}/residuals`, impact.residuals.map((x) => display(+x.toPrecision(3))).join(', '), '', undefined, true);
    });
    $('fit-table').querySelector('tbody').replaceChildren(...rows);
    $('fit-table').hidden = false;
  }

  // The service's own plot of the fit (image/svg+xml from the fit
  // endpoint), inlined as the sweep's is: the measured points and the fitted
  // model, velocities over the approach speed, for the first row's body.
  async draw(kindName, request) {
    const figure = $('fit-figure');
    if (kindName === 'planar' || kindName === 'spatial') { figure.hidden = true; return; }
    const answer = await post(this.kind().endpoint, request, { accept: 'image/svg+xml' });
    const svg = answer.ok ? new DOMParser().parseFromString(answer.body, 'image/svg+xml').documentElement : null;
    if (!svg || svg.nodeName !== 'svg') {
      figure.hidden = true;
      $('fit-status').textContent += answer.ok ? ' The plot could not be read.' : ` The plot could not be drawn: ${problemText(answer.problem)}.`;
      return;
    }
    svg.querySelectorAll('script, foreignObject').forEach((el) => el.remove());
    const node = document.importNode(svg, true);
    const title = node.querySelector('title')?.textContent || `${kindName} fit`;
    node.setAttribute('role', 'img');
    node.setAttribute('aria-label', title);
    node.removeAttribute('width');
    node.removeAttribute('height');
    $('fit-plot').replaceChildren(node);
    $('fit-caption').textContent = `${title}. The service's own plot (image/svg+xml).`;
    figure.hidden = false;
  }

  // Synthetic measurements from the service itself: the Maw disc (tangential),
  // Figure 4's ball (torsional), the planar scene's own outcome (planar),
  // with a small deterministic wiggle; the spatial scene's own outcome
  // (spatial), exact to 8 digits.
  async sample() {
    const kindName = $('fit-kind').value;
    this.clearErrors();
    $('fit-status').textContent = 'Making sample data with the service…';
    let csv;
    if (kindName === 'tangential') {
      const sweep = {
        case: 'tangential',
        base: { body: { mass: 1, inertia: 0.00125 }, contact: { tangential_offset: 0, normal_offset: 0.05 }, velocity: { normal: -1, tangential: 0, angular: 0 },
          restitution: 0.93, friction: 0.123, tangential_restitution: 0.34 },
        axes: [{ path: '/velocity/tangential', linspace: { start: 0.05, stop: 2.95, count: 30 } }],
        outputs: ['/final_velocity'],
      };
      const answer = await post('/v1/sweeps', sweep);
      if (!answer.ok) { this.showProblem(answer.problem); return; }
      const lines = answer.body.rows.map((r, i) => {
        const w = 1e-3 * Math.sin(i * 2.399);
        return [-1, r[0], 0, r[1] + w, r[2] - w, r[3]].map((x) => +x.toPrecision(8)).join(',');
      });
      csv = [KINDS.tangential.columns.join(','), ...lines].join('\n');
    } else if (kindName === 'torsional') {
      const sweep = {
        case: 'torsional',
        base: { body: { mass: 0.1, normal_inertia: 0.000036 }, velocity: { normal: -3, spin: 0 }, restitution: 0.8,
          torsion: { restitution: 0.2, friction: 0.3, pitch_radius: 0.005 } },
        axes: [{ path: '/velocity/spin', linspace: { start: -50, stop: 54.5, count: 20 } }],
        outputs: ['/final_velocity'],
      };
      const answer = await post('/v1/sweeps', sweep);
      if (!answer.ok) { this.showProblem(answer.problem); return; }
      const lines = answer.body.rows.map((r, i) => [-3, r[0], r[1], r[2] + 0.1 * Math.cos(i)].map((x) => +x.toPrecision(8)).join(','));
      csv = [KINDS.torsional.columns.join(','), ...lines].join('\n');
    } else if (kindName === 'spatial') {
      const scene = this.app.spatialScene();
      const answer = await post('/v1/impacts/spatial', scene);
      if (!answer.ok) {
        // The scene itself is refused: its field is the Impact section's.
        $('fit-status').textContent = 'The service refused the scene.';
        this.app.showImpactProblem(answer.problem);
        $('fit-problem').textContent = problemText(answer.problem);
        $('fit-problem').hidden = false;
        return;
      }
      csv = spatialCsv(scene, answer.body);
      this.sceneChanged();
    } else {
      const scene = this.app.planarScene();
      const answer = await post('/v1/impacts/planar', scene);
      if (!answer.ok) { this.showProblem(answer.problem); return; }
      const lines = answer.body.bodies.map((b) => [b.velocity_change.x, 0.1, b.velocity_change.y, 0.1, b.angular_velocity_change, 0.1]
        .map((x) => +x.toPrecision(8)).join(','));
      csv = [KINDS.planar.columns.join(','), ...lines].join('\n');
    }
    $('fit-csv').value = csv;
    $('fit-status').textContent = 'Sample data ready: press Fit.';
  }
}

const display = (v) => (v === null || v === undefined ? '—' : String(v).replace(/^-/, '−'));

// The spatial scene's outcome as measured rows: one per body, impact 0, its
// ΔV and Δω to 8 digits; the uncertainties 1 % of the largest |ΔV| component,
// and that over body A's lever |C − G| for Δω.
export function spatialCsv(scene, outcome) {
  const round = (x) => +x.toPrecision(8);
  const dv = Math.max(...outcome.bodies.flatMap((b) => XYZ.map((c) => Math.abs(b.velocity_change[c]))));
  const sv = round(0.01 * dv || 1e-3);
  const g = scene.bodies[0].position || {};
  const p = scene.contact.point || {};
  const lever = Math.hypot(...XYZ.map((c) => (p[c] ?? 0) - (g[c] ?? 0)));
  const sw = round(lever > 0 ? sv / lever : sv);
  const lines = outcome.bodies.map((b) => [0,
    ...XYZ.flatMap((c) => [round(b.velocity_change[c]), sv]),
    ...XYZ.flatMap((c) => [round(b.angular_velocity_change[c]), sw])].join(','));
  return [KINDS.spatial.columns.join(','), ...lines].join('\n');
}
