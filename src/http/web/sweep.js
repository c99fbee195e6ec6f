// Sweeps: one input of the impact form over a range (and optionally a second
// over a few values, one curve each), the service's own SVG plot of one
// output, and the whole table as CSV, NDJSON or Arrow.

import { post, problemText } from './api.js';
import { outputLabel } from './cases.js';
import { apiName, parseValue, showError, clearError } from './form.js';
import { copy, curl, python } from './share.js';
import { leaves } from './outcome.js';

const $ = (id) => document.getElementById(id);
export const plainSymbol = (html) => html.replace(/<sub>(.*?)<\/sub>/g, '_$1').replace(/<sup>(.*?)<\/sup>/g, '^$1').replace(/<[^>]+>/g, '');

const EXTENSIONS = { 'text/csv': 'csv', 'application/x-ndjson': 'ndjson', 'application/vnd.apache.arrow.stream': 'arrow' };

export class SweepPanel {
  // app: {caseId(), form(), precision(), outcome(), onChange()}
  constructor(app) {
    this.app = app;
    this.outputs = [];
    $('sweep-form').addEventListener('submit', (e) => { e.preventDefault(); this.plot(); });
    $('sweep-axis').addEventListener('change', () => { this.defaultRange(); app.onChange(); });
    for (const id of ['sweep-spacing', 'sweep-start', 'sweep-stop', 'sweep-count', 'sweep-output', 'sweep-series', 'sweep-series-values']) {
      $(id).addEventListener('change', () => app.onChange());
    }
    document.querySelectorAll('[data-download]').forEach((b) => b.addEventListener('click', () => this.download(b.dataset.download)));
    $('sweep-curl').addEventListener('click', () => {
      const r = this.request(false);
      if (r) copy(curl('/v1/sweeps', r, 'image/svg+xml'), 'curl command copied');
    });
    $('sweep-python').addEventListener('click', () => {
      const r = this.request(false);
      if (r) copy(python('/v1/sweeps', r), 'Python program copied');
    });
  }

  // The inputs and outputs of the current case as choices.
  refreshChoices(keep = true) {
    const form = this.app.form();
    const fields = form.activeFields().filter((f) => f.type !== 'checkbox');
    const axis = $('sweep-axis');
    const series = $('sweep-series');
    const [oldAxis, oldSeries] = [axis.value, series.value];
    const options = (list) => list.map((f) => new Option(`${plainSymbol(f.sym)} · ${apiName(f.path)}${f.unit ? ` (${f.unit})` : ''}`, f.path));
    axis.replaceChildren(...options(fields));
    series.replaceChildren(new Option('none', ''), ...options(fields));
    if (keep && fields.some((f) => f.path === oldAxis)) axis.value = oldAxis;
    if (keep && fields.some((f) => f.path === oldSeries)) series.value = oldSeries;
    const outcome = this.app.outcome();
    if (outcome) {
      this.outputs = leaves(outcome).filter(([, v]) => typeof v === 'number').map(([p]) => p);
    }
    const output = $('sweep-output');
    const oldOutput = output.value;
    output.replaceChildren(...this.outputs.map((p) => {
      const l = outputLabel(p);
      return new Option(`${l.sym ? plainSymbol(l.sym) + ' · ' : ''}${apiName(p)}${l.unit ? ` (${l.unit})` : ''}`, p);
    }));
    if (this.pendingOutput && this.outputs.includes(this.pendingOutput)) {
      output.value = this.pendingOutput;
      this.pendingOutput = null;
    } else if (this.outputs.includes(oldOutput)) {
      output.value = oldOutput;
    }
    if (!$('sweep-start').value) this.defaultRange();
  }

  // A range around the axis's current value, within its API range.
  defaultRange() {
    const path = $('sweep-axis').value;
    const field = this.app.form().activeFields().find((f) => f.path === path);
    if (!field) return;
    const value = parseValue(this.app.form().input(path)?.value || '');
    const v = typeof value === 'number' ? value : 1;
    let [a, b] = v > 0 ? [0, 2 * v] : v < 0 ? [2 * v, 0] : [-1, 1];
    const { min, max, exclusiveMin, exclusiveMax } = field.range;
    if (min !== undefined && max !== undefined) {
      [a, b] = [min, max];
    } else {
      if (min !== undefined && a <= min) a = exclusiveMin ? min + (b - min) / 100 : min;
      if (max !== undefined && b >= max) b = exclusiveMax ? max - (max - a) / 100 : max;
    }
    $('sweep-start').value = String(Number(a.toPrecision(6)));
    $('sweep-stop').value = String(Number(b.toPrecision(6)));
    if (!$('sweep-count').value) $('sweep-count').value = '101';
  }

  // Sets the panel from a preset's sweep ({axes, outputs}).
  load(sweep) {
    if (!sweep) return;
    this.refreshChoices(false);
    const [first, second] = sweep.axes || [];
    if (first) {
      $('sweep-axis').value = first.path;
      const spacing = first.logspace ? 'logspace' : 'linspace';
      const range = first[spacing];
      $('sweep-spacing').value = spacing;
      if (range) {
        $('sweep-start').value = String(range.start);
        $('sweep-stop').value = String(range.stop);
        $('sweep-count').value = String(range.count);
      } else if (first.values) {
        $('sweep-start').value = String(Math.min(...first.values));
        $('sweep-stop').value = String(Math.max(...first.values));
        $('sweep-count').value = String(first.values.length);
      }
    }
    $('sweep-series').value = second?.values ? second.path : '';
    $('sweep-series-values').value = second?.values ? second.values.join(', ') : '';
    // The outputs are known once the preset's outcome is in.
    this.pendingOutput = (sweep.outputs || []).find((p) => p !== '/regime') || null;
    if (this.outputs.includes(this.pendingOutput)) $('sweep-output').value = this.pendingOutput;
  }

  state() {
    return {
      axis: $('sweep-axis').value, spacing: $('sweep-spacing').value, start: $('sweep-start').value, stop: $('sweep-stop').value,
      count: $('sweep-count').value, output: $('sweep-output').value, series: $('sweep-series').value, values: $('sweep-series-values').value,
    };
  }

  restore(state) {
    if (!state || typeof state !== 'object') return;
    this.refreshChoices(false);
    const set = (id, v) => { if (v !== undefined && v !== null) $(id).value = v; };
    set('sweep-axis', state.axis); set('sweep-spacing', state.spacing); set('sweep-start', state.start); set('sweep-stop', state.stop);
    set('sweep-count', state.count); set('sweep-output', state.output);
    set('sweep-series', state.series); set('sweep-series-values', state.values);
    if (state.output) this.pendingOutput = state.output;
  }

  // The sweep request; `forPlot`: just the plotted output.
  request(forPlot = true) {
    const spacing = $('sweep-spacing').value;
    const axis = { path: $('sweep-axis').value, [spacing]: { start: parseValue($('sweep-start').value), stop: parseValue($('sweep-stop').value), count: parseValue($('sweep-count').value) } };
    const axes = [axis];
    const series = $('sweep-series').value;
    if (series) {
      const values = $('sweep-series-values').value.split(',').map((t) => parseValue(t)).filter((v) => v !== undefined);
      axes.push({ path: series, values });
    }
    const request = { case: this.app.caseId(), base: this.app.form().request(), axes };
    const output = $('sweep-output').value;
    if (forPlot && output) request.outputs = [output];
    const precision = this.app.precision();
    if (precision !== 'fast') request.precision = precision;
    return request;
  }

  clearErrors() {
    for (const id of ['sweep-axis', 'sweep-start', 'sweep-stop', 'sweep-count', 'sweep-output', 'sweep-series-values']) clearError($(id));
    $('sweep-problem').hidden = true;
  }

  // Marks what a refusal names: the impact form for `/base/…`, the panel's
  // own fields for the axes and outputs.
  showProblem(problem) {
    const pointer = problem.pointer || '';
    const detail = problem.detail || problem.title;
    let marked = false;
    if (pointer.startsWith('/base/')) {
      marked = this.app.form().markError(pointer.slice(5), detail);
    } else if (/^\/axes\/0\/(linspace|logspace)\/(start|stop|count)/.test(pointer)) {
      showError($(`sweep-${pointer.split('/')[4]}`), detail); marked = true;
    } else if (/^\/axes\/0/.test(pointer)) {
      showError($('sweep-axis'), detail); marked = true;
    } else if (/^\/axes\/1/.test(pointer)) {
      showError($('sweep-series-values'), detail); marked = true;
    } else if (pointer.startsWith('/outputs')) {
      showError($('sweep-output'), detail); marked = true;
    }
    const box = $('sweep-problem');
    box.textContent = problemText(problem) + (marked ? '' : '');
    box.hidden = false;
  }

  async plot() {
    this.clearErrors();
    this.app.form().clearErrors();
    const request = this.request(true);
    $('sweep-status').textContent = 'Computing the sweep…';
    const answer = await post('/v1/sweeps', request, { accept: 'image/svg+xml' });
    if (!answer.ok) {
      $('sweep-status').textContent = 'The service refused the sweep.';
      this.showProblem(answer.problem);
      return;
    }
    const doc = new DOMParser().parseFromString(answer.body, 'image/svg+xml');
    const svg = doc.documentElement;
    if (svg.nodeName !== 'svg') {
      $('sweep-status').textContent = 'The plot could not be read.';
      return;
    }
    svg.querySelectorAll('script, foreignObject').forEach((el) => el.remove());
    const node = document.importNode(svg, true);
    const l = outputLabel(request.outputs[0]);
    const title = `${plainSymbol(l.sym) || apiName(request.outputs[0])} against ${apiName(request.axes[0].path)}`;
    node.setAttribute('role', 'img');
    node.setAttribute('aria-label', `Sweep plot: ${title}`);
    node.removeAttribute('width');
    node.removeAttribute('height');
    $('sweep-plot').replaceChildren(node);
    $('sweep-figure').hidden = false;
    const points = answer.headers.get('x-sweep-points');
    $('sweep-caption').textContent = `${title}: ${points} points, the service's own plot (image/svg+xml).`;
    $('sweep-status').textContent = `Plotted ${points} points.`;
  }

  async download(accept) {
    this.clearErrors();
    const request = this.request(false);
    $('sweep-status').textContent = `Computing the sweep as ${accept}…`;
    const answer = await post('/v1/sweeps', request, { accept, as: 'blob' });
    if (!answer.ok) {
      $('sweep-status').textContent = 'The service refused the sweep.';
      this.showProblem(answer.problem);
      return;
    }
    const url = URL.createObjectURL(answer.body);
    const a = document.createElement('a');
    a.href = url;
    a.download = `sweep-${request.case}.${EXTENSIONS[accept]}`;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
    $('sweep-status').textContent = `Downloaded ${a.download} (${answer.body.size} bytes, ${answer.headers.get('x-sweep-points')} points).`;
  }
}
