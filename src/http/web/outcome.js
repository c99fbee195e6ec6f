// The outcome as a table: every member of the response, by its pointer, with
// the paper's symbol, words, unit, the value as the service sent it, and a
// copy button.

import { outputLabel } from './cases.js';
import { h, apiName } from './form.js';
import { copy } from './share.js';

// Every leaf of a JSON value, as [pointer, value], in document order.
export function leaves(value, pointer = '') {
  if (value !== null && typeof value === 'object') {
    return Object.entries(value).flatMap(([k, v]) => leaves(v, `${pointer}/${k}`));
  }
  return [[pointer, value]];
}

const display = (v) => (v === null ? 'null' : typeof v === 'number' ? String(v).replace(/^-/, '−') : String(v));

export function renderOutcome(tbody, response) {
  const rows = leaves(response).map(([pointer, value]) => {
    const label = outputLabel(pointer);
    const text = value === null ? 'null' : String(value);
    const name = apiName(pointer);
    return h('tr', { 'data-pointer': pointer },
      h('th', { scope: 'row' }, label.sym ? h('span', { class: 'sym', html: label.sym }) : '', label.sym ? ' ' : '', h('span', { class: 'words', html: label.text })),
      h('td', {}, h('code', { text: name })),
      h('td', { class: 'num', 'data-value': text }, display(value), label.unit ? h('span', { class: 'unit', text: ` ${label.unit}` }) : ''),
      h('td', {}, h('button', { type: 'button', class: 'copy', 'aria-label': `Copy ${name}`, onclick: () => copy(text, `${name} copied`) }, 'Copy')));
  });
  tbody.replaceChildren(...rows);
}

// The table as tab-separated text: pointer, value.
export function outcomeTsv(response) {
  return leaves(response).map(([p, v]) => `${apiName(p)}\t${v === null ? '' : v}`).join('\n');
}
