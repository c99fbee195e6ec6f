// A case's form: built from its spec (cases.js), read into a request, filled
// from one (presets, shared links), and marked where the service refused it.

import { rangeText } from './cases.js';

// Creates an element: h('div', {class: 'x'}, child, 'text').
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k === 'html') el.innerHTML = v; // only the page's own constants
    else if (k === 'text') el.textContent = v;
    else if (k.startsWith('on')) el.addEventListener(k.slice(2), v);
    else el.setAttribute(k, v === true ? '' : v);
  }
  for (const c of children.flat()) {
    if (c !== undefined && c !== null && c !== false) el.append(c);
  }
  return el;
}

export const idOf = (path) => 'f' + path.replace(/\//g, '-');
// The API's name of a member: `/bodies/0/mass` reads `bodies[0].mass`.
export const apiName = (path) => path.slice(1).replace(/\/(\d+)(?=\/|$)/g, '[$1]').replace(/\//g, '.');

// A number when the text is one, the text itself otherwise (the service
// then refuses it and names the member), nothing when blank.
export function parseValue(text) {
  const t = text.trim().replace(/\u2212/g, '-');
  if (t === '') return undefined;
  if (/^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(t)) {
    const x = Number(t);
    return Number.isFinite(x) ? x : t;
  }
  return t;
}

// Sets `value` at a JSON pointer, creating objects and arrays on the way.
export function setIn(target, pointer, value) {
  const keys = pointer.split('/').slice(1);
  let at = target;
  keys.forEach((key, i) => {
    const last = i === keys.length - 1;
    const k = Array.isArray(at) ? Number(key) : key;
    if (last) {
      at[k] = value;
    } else {
      if (at[k] === undefined || at[k] === null || typeof at[k] !== 'object') {
        at[k] = /^\d+$/.test(keys[i + 1]) ? [] : {};
      }
      at = at[k];
    }
  });
}

export function getIn(source, pointer) {
  let at = source;
  for (const key of pointer.split('/').slice(1)) {
    if (at === undefined || at === null) return undefined;
    at = at[key];
  }
  return at;
}

export const formatNumber = (x) => (typeof x === 'number' ? String(x) : String(x ?? ''));

export class CaseForm {
  constructor(spec, container, onChange) {
    this.spec = spec;
    this.container = container;
    this.onChange = onChange;
    this.inputs = new Map(); // path -> [inputs] (a coefficient may sit in several options)
    this.radios = new Map(); // choice id -> [radio inputs]
    this.toggles = new Map(); // toggle id -> checkbox
    this.groups = []; // {parts, el} for errors on a whole member
    container.replaceChildren(...spec.parts.map((p) => this.render(p)));
    this.refresh();
  }

  render(part) {
    switch (part.kind) {
      case 'field': return this.renderField(part);
      case 'vector': {
        const legendId = idOf(part.path) + '-legend';
        const fs = h('fieldset', { class: 'vector', 'data-path': part.path },
          h('legend', { id: legendId },
            h('span', { class: 'sym', html: part.sym }), ' ', h('code', { text: apiName(part.path) }),
            part.unit ? h('span', { class: 'unit', text: ` ${part.unit}` }) : '',
            h('span', { class: 'hint', html: ` · ${part.text}` })),
          h('div', { class: 'components' }, part.fields.map((f) => this.renderField(f, part))),
          h('span', { class: 'error', id: idOf(part.path) + '-error', hidden: true }));
        this.groups.push({ path: part.path, el: fs });
        return fs;
      }
      case 'group': {
        const fs = h('fieldset', { class: 'group' }, h('legend', { text: part.legend }),
          part.note ? h('p', { class: 'note', text: part.note }) : '',
          part.parts.map((p) => this.render(p)));
        return fs;
      }
      case 'choice': {
        const name = part.id;
        const radios = part.options.map((o, i) => h('input', {
          type: 'radio', name, value: o.id, id: `${name}-${o.id}`, checked: i === 0,
          onchange: () => { this.refresh(); this.onChange(); },
        }));
        this.radios.set(name, radios);
        const fs = h('fieldset', { class: 'choice' },
          h('legend', { text: part.legend }),
          h('div', { class: 'options' }, part.options.map((o, i) => h('label', { class: 'option', for: `${name}-${o.id}` }, radios[i], h('span', { html: o.label })))),
          part.options.map((o) => h('div', { class: 'option-parts', 'data-choice': name, 'data-option': o.id }, o.parts.map((p) => this.render(p)))));
        return fs;
      }
      case 'toggle': {
        const box = h('input', { type: 'checkbox', id: `toggle-${part.id}`, onchange: () => { this.refresh(); this.onChange(); } });
        this.toggles.set(part.id, box);
        return h('div', { class: 'toggle' },
          h('label', { class: 'inline', for: `toggle-${part.id}` }, box, ' ', part.label),
          h('div', { class: 'toggle-parts', 'data-toggle': part.id }, part.parts.map((p) => this.render(p))));
      }
      default: throw new Error(`unknown part ${part.kind}`);
    }
  }

  // Registers an input under its path; inputs of one path share their value.
  register(path, input) {
    const list = this.inputs.get(path) || [];
    list.push(input);
    this.inputs.set(path, list);
    input.addEventListener('input', () => {
      for (const other of list) {
        if (other === input) continue;
        if (input.type === 'checkbox') other.checked = input.checked;
        else other.value = input.value;
      }
      this.onChange();
    });
  }

  renderField(f, vector) {
    const seen = (this.inputs.get(f.path) || []).length;
    const id = idOf(f.path) + (seen ? `-${seen}` : '');
    const hintId = `${id}-hint`;
    const errorId = `${id}-error`;
    if (f.type === 'checkbox') {
      const input = h('input', { type: 'checkbox', id, name: f.path });
      this.register(f.path, input);
      return h('div', { class: 'field check' },
        h('label', { class: 'inline', for: id }, input, ' ', f.text, ' ', h('code', { text: apiName(f.path) })),
        h('span', { class: 'error', id: errorId, hidden: true }));
    }
    const range = rangeText(f.range);
    const input = h('input', {
      id, name: f.path, type: 'text', inputmode: 'decimal', autocomplete: 'off', spellcheck: 'false',
      'aria-describedby': vector ? errorId : hintId,
    });
    this.register(f.path, input);
    if (vector) {
      // A component: its label is the component; the legend names the vector.
      return h('div', { class: 'field component' },
        h('label', { for: id }, h('span', { class: 'vh', html: `${vector.sym} ` }), f.component),
        input,
        h('span', { class: 'error', id: errorId, hidden: true }));
    }
    return h('div', { class: 'field' },
      h('label', { for: id },
        h('span', { class: 'sym', html: f.sym }), ' ', h('code', { text: apiName(f.path) }),
        f.unit ? h('span', { class: 'unit', text: ` ${f.unit}` }) : ''),
      input,
      h('span', { class: 'hint', id: hintId, html: (range ? `${range} · ` : '') + f.text }),
      h('span', { class: 'error', id: errorId, hidden: true }));
  }

  // Shows the chosen options and present toggles; disables what is hidden
  // (so it is neither sent nor reached by Tab).
  refresh() {
    for (const [name, radios] of this.radios) {
      const chosen = radios.find((r) => r.checked)?.value;
      this.container.querySelectorAll(`.option-parts[data-choice="${name}"]`).forEach((el) => {
        el.hidden = el.dataset.option !== chosen;
      });
    }
    for (const [id, box] of this.toggles) {
      this.container.querySelectorAll(`.toggle-parts[data-toggle="${id}"]`).forEach((el) => { el.hidden = !box.checked; });
    }
    for (const input of this.allInputs()) {
      input.disabled = input.closest('[hidden]') !== null;
    }
  }

  allInputs() { return [...this.inputs.values()].flat(); }

  // The input of `path` the form shows now (none when hidden).
  input(path) { return (this.inputs.get(path) || []).find((el) => !el.disabled); }

  // The active fields, in form order.
  activeFields() {
    const out = [];
    const walk = (parts) => {
      for (const p of parts) {
        if (p.kind === 'field') out.push(p);
        else if (p.kind === 'vector') out.push(...p.fields);
        else if (p.kind === 'group') walk(p.parts);
        else if (p.kind === 'toggle') { if (this.toggles.get(p.id).checked) walk(p.parts); }
        else if (p.kind === 'choice') {
          const chosen = this.radios.get(p.id).find((r) => r.checked)?.value;
          walk(p.options.find((o) => o.id === chosen).parts);
        }
      }
    };
    walk(this.spec.parts);
    return out;
  }

  request(precision) {
    const request = {};
    for (const f of this.activeFields()) {
      const input = this.input(f.path);
      if (!input) continue;
      const value = f.type === 'checkbox' ? (input.checked ? true : undefined) : parseValue(input.value);
      if (value !== undefined) setIn(request, f.path, value);
    }
    if (precision && precision !== 'fast') request.precision = precision;
    return request;
  }

  load(request) {
    const visit = (parts) => {
      for (const p of parts) {
        if (p.kind === 'choice') {
          const chosen = p.detect(request);
          this.radios.get(p.id).forEach((r) => { r.checked = r.value === chosen; });
          p.options.forEach((o) => visit(o.parts));
        } else if (p.kind === 'toggle') {
          this.toggles.get(p.id).checked = Boolean(p.present(request));
          visit(p.parts);
        } else if (p.kind === 'group') visit(p.parts);
      }
    };
    visit(this.spec.parts);
    for (const [path, inputs] of this.inputs) {
      const value = getIn(request, path);
      for (const input of inputs) {
        if (input.type === 'checkbox') input.checked = value === true;
        else input.value = value === undefined || value === null || typeof value === 'object' ? '' : formatNumber(value);
      }
    }
    this.refresh();
  }

  clearErrors() {
    this.container.querySelectorAll('[aria-invalid]').forEach((el) => el.removeAttribute('aria-invalid'));
    this.container.querySelectorAll('.error').forEach((el) => { el.hidden = true; el.textContent = ''; });
    this.container.querySelectorAll('.invalid').forEach((el) => el.classList.remove('invalid'));
    for (const input of this.allInputs()) {
      const described = (input.getAttribute('aria-describedby') || '').split(' ').filter((x) => x && !x.endsWith('-error'));
      described.push(`${input.id}-error`);
      input.setAttribute('aria-describedby', described.join(' '));
    }
  }

  // Marks the member a problem's pointer names: the input itself, or the
  // inputs under it (a vector, a body). Returns whether anything was marked.
  markError(pointer, detail) {
    const exact = this.input(pointer);
    if (exact) {
      showError(exact, detail);
      return true;
    }
    if (pointer === '') return false;
    const under = [...this.inputs.keys()].filter((p) => p.startsWith(pointer + '/'))
      .map((p) => [p, this.input(p)]).filter(([, el]) => el);
    if (under.length === 0) return false;
    under.forEach(([, el]) => el.setAttribute('aria-invalid', 'true'));
    const group = this.groups.find((g) => g.path === pointer);
    const target = (group && group.el.querySelector(`#${CSS.escape(idOf(pointer) + '-error')}`))
      || document.getElementById(`${under[0][1].id}-error`);
    target.textContent = detail;
    target.hidden = false;
    under.forEach(([, el]) => {
      const described = new Set((el.getAttribute('aria-describedby') || '').split(' ').filter(Boolean));
      described.add(target.id);
      el.setAttribute('aria-describedby', [...described].join(' '));
    });
    return true;
  }
}

// Marks one input invalid with the message next to it.
export function showError(input, detail) {
  input.setAttribute('aria-invalid', 'true');
  const error = document.getElementById(`${input.id}-error`);
  if (error) {
    error.textContent = detail;
    error.hidden = false;
    const described = new Set((input.getAttribute('aria-describedby') || '').split(' ').filter(Boolean));
    described.add(error.id);
    input.setAttribute('aria-describedby', [...described].join(' '));
  }
}

export function clearError(input) {
  input.removeAttribute('aria-invalid');
  const error = document.getElementById(`${input.id}-error`);
  if (error) { error.hidden = true; error.textContent = ''; }
}
