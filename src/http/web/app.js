// The explorer: the impact form and its outcome, the scene, the sweep and
// fit panels, the page's state in its URL. Plain ES modules, no framework,
// no build step; every file is embedded in the binary (src/http/web.rs).

import { CASES, DEFAULTS, caseById, allFields, rangeText, setQuantities } from './cases.js';
import { CaseForm, h } from './form.js';
import { post, apiKey, problemText } from './api.js';
import { drawScene } from './scene.js';
import { renderOutcome, outcomeTsv } from './outcome.js';
import { SweepPanel } from './sweep.js';
import { FitPanel } from './fit.js';
import { copy, curl, python, saveState, loadState, setOperations } from './share.js';

const $ = (id) => document.getElementById(id);

const app = {
  spec: null,
  form: null,
  presets: [],
  outcome: null,
  seq: 0,
  timer: null,
};

const precision = () => document.querySelector('input[name="precision"]:checked')?.value || 'fast';
const currentRequest = () => app.form.request(precision());

function setPrecision(value) {
  document.querySelectorAll('input[name="precision"]').forEach((r) => { r.checked = r.value === (value || 'fast'); });
}

// Shows a case's form, filled from `request`.
function showCase(id, request) {
  app.spec = caseById(id);
  $('case').value = app.spec.id;
  $('case-hint').innerHTML = `${app.spec.about} <code>POST ${app.spec.endpoint}</code> (${app.spec.section})`;
  app.form = new CaseForm(app.spec, $('case-fields'), changed);
  app.form.load(request || DEFAULTS[app.spec.id] || app.presets.find((p) => p.case === app.spec.id)?.request || {});
  setPrecision(request?.precision);
  app.outcome = null;
  renderOutcome($('outcome').querySelector('tbody'), {});
  sweep.refreshChoices(false);
  fit.sceneChanged();
}

function remember() {
  saveState({ case: app.spec.id, request: currentRequest(), sweep: sweep.state() });
}

// An input changed: redraw the scene from the inputs, recompute soon.
function changed() {
  clearTimeout(app.timer);
  app.timer = setTimeout(() => {
    remember();
    drawScene($('scene'), app.spec.id, currentRequest(), null);
    fit.sceneChanged();
    if ($('live').checked) compute();
  }, 250);
}

async function compute() {
  clearTimeout(app.timer);
  const seq = ++app.seq;
  const spec = app.spec;
  const request = currentRequest();
  remember();
  $('outcome-status').textContent = 'Computing…';
  const answer = await post(spec.endpoint, request);
  if (seq !== app.seq) return; // a later request is on its way
  app.form.clearErrors();
  $('impact-problem').hidden = true;
  const tbody = $('outcome').querySelector('tbody');
  if (answer.ok) {
    app.outcome = answer.body;
    renderOutcome(tbody, answer.body);
    const caption = drawScene($('scene'), spec.id, request, answer.body);
    $('scene-caption').textContent = `The scene, lengths to scale: ${caption}.`;
    const regime = answer.body.regime ? `regime ${answer.body.regime}` : '';
    $('outcome-status').textContent = `Outcome of the ${spec.title.toLowerCase()} impact: ${regime}, precision ${answer.body.precision}.`;
    $('outcome-status').dataset.seq = String(seq);
    $('outcome').dataset.seq = String(seq);
    sweep.refreshChoices();
  } else {
    app.outcome = null;
    tbody.replaceChildren();
    drawScene($('scene'), spec.id, request, null);
    showImpactProblem(answer.problem);
    if (answer.status === 401) document.querySelector('.settings').open = true;
    $('outcome-status').textContent = `Refused: ${answer.problem.title || 'error'}.`;
  }
}

function showImpactProblem(problem) {
  const marked = problem.pointer !== undefined && app.form.markError(problem.pointer, problem.detail || problem.title);
  const box = $('impact-problem');
  box.textContent = problemText(problem) + (marked ? ' The field is marked above.' : '');
  box.hidden = false;
}

function fillSelects() {
  $('case').replaceChildren(...CASES.map((c) => new Option(`${c.title} · ${c.endpoint.split('/').pop()}`, c.id)));
  const groups = CASES.map((c) => {
    const list = app.presets.filter((p) => p.case === c.id);
    return list.length ? h('optgroup', { label: c.title }, list.map((p) => new Option(p.label, p.id))) : null;
  }).filter(Boolean);
  $('preset').replaceChildren(new Option('— choose a preset —', ''), ...groups);
}

function applyPreset(id) {
  const preset = app.presets.find((p) => p.id === id);
  if (!preset) return;
  showCase(preset.case, preset.request);
  $('preset').value = id;
  sweep.load(preset.sweep);
  compute();
}

const sweep = new SweepPanel({
  caseId: () => app.spec.id,
  form: () => app.form,
  precision,
  outcome: () => app.outcome,
  onChange: () => remember(),
});

const fit = new FitPanel({
  form: () => app.form,
  planarScene: () => (app.spec.id === 'planar' ? app.form.request() : app.presets.find((p) => p.id === 'cars')?.request),
  // The spatial case's scene, or (on another case) the cube whose e and f a fit finds.
  spatialScene: () => (app.spec?.id === 'spatial' && app.form ? app.form.request() : app.presets.find((p) => p.id === 'cube-corner')?.request),
  showImpactProblem,
});

// A fetched JSON asset of the page, or `fallback` when it cannot be read.
async function readJson(request, fallback) {
  try {
    const response = await request;
    return response.ok ? await response.json() : fallback;
  } catch {
    return fallback;
  }
}

async function start() {
  const [presets, quantities, operations] = await Promise.all([
    readJson(fetch('/assets/presets.json'), []),
    readJson(fetch('/assets/quantities.json'), { cases: [] }),
    readJson(fetch('/assets/operations.json'), {}),
  ]);
  app.presets = presets;
  setQuantities(quantities);
  setOperations(operations);
  fillSelects();
  $('api-key').value = apiKey.get();
  $('api-key').addEventListener('change', (e) => { apiKey.set(e.target.value.trim()); compute(); });
  $('api-key-form').addEventListener('submit', (e) => { e.preventDefault(); apiKey.set($('api-key').value.trim()); compute(); });
  $('case').addEventListener('change', (e) => { showCase(e.target.value); $('preset').value = ''; compute(); });
  $('preset').addEventListener('change', (e) => applyPreset(e.target.value));
  document.querySelectorAll('input[name="precision"]').forEach((r) => r.addEventListener('change', () => compute()));
  $('impact-form').addEventListener('submit', (e) => { e.preventDefault(); compute(); });
  $('copy-table').addEventListener('click', () => app.outcome && copy(outcomeTsv(app.outcome), 'Table copied (tab-separated)'));
  $('copy-json').addEventListener('click', () => app.outcome && copy(JSON.stringify(app.outcome, null, 2), 'Outcome JSON copied'));
  $('copy-curl').addEventListener('click', () => copy(curl(app.spec.endpoint, currentRequest()), 'curl command copied'));
  $('copy-python').addEventListener('click', () => copy(python(app.spec.endpoint, currentRequest()), 'Python program copied'));
  $('copy-link').addEventListener('click', () => { remember(); copy(location.href, 'Link copied'); });

  const state = loadState();
  if (state.preset) {
    applyPreset(state.preset);
  } else if (state.case && CASES.some((c) => c.id === state.case)) {
    showCase(state.case, typeof state.request === 'object' ? state.request : undefined);
    sweep.restore(state.sweep);
    await compute();
    sweep.restore(state.sweep);
  } else {
    applyPreset('maw-oblique');
  }
  document.documentElement.dataset.ready = 'true';
}

// For the browser test: the cases' fields and ranges, and the page's state.
window.explorer = {
  fields: () => CASES.map((c) => ({ id: c.id, endpoint: c.endpoint, fields: allFields(c).map((f) => ({ path: f.path, range: f.range, type: f.type || 'number', text: rangeText(f.range) })) })),
  state: () => ({ case: app.spec.id, request: currentRequest(), outcome: app.outcome }),
};

start();
