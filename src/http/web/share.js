// Sharing: the page's state in the URL, copying to the clipboard, and the
// current request as a curl command or a Python program.

import { apiKey } from './api.js';

let toastTimer;
export function toast(message) {
  const el = document.getElementById('toast');
  el.textContent = message;
  el.classList.add('shown');
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => el.classList.remove('shown'), 2500);
}

// Copies text (the Clipboard API where the page is a secure context, else a
// selected textarea), and says so.
export async function copy(text, message = 'Copied') {
  window.lastCopied = text; // for the browser test, which cannot read the clipboard headless
  try {
    if (navigator.clipboard && window.isSecureContext) {
      await navigator.clipboard.writeText(text);
    } else {
      const area = document.createElement('textarea');
      area.value = text;
      area.setAttribute('readonly', '');
      area.className = 'offscreen';
      document.body.append(area);
      area.select();
      document.execCommand('copy');
      area.remove();
    }
    toast(message);
  } catch (error) {
    toast(`Could not copy: ${error.message}`);
  }
}

// The state in the query string: the case, the request, the sweep.
export function saveState(state) {
  const params = new URLSearchParams();
  for (const [k, v] of Object.entries(state)) {
    if (v === undefined || v === null || v === '') continue;
    params.set(k, typeof v === 'string' ? v : JSON.stringify(v));
  }
  const url = `${location.pathname}?${params}${location.hash}`;
  history.replaceState(null, '', url);
}

export function loadState() {
  const params = new URLSearchParams(location.search);
  const out = {};
  for (const [k, v] of params) {
    try {
      out[k] = v.startsWith('{') || v.startsWith('[') ? JSON.parse(v) : v;
    } catch {
      out[k] = v;
    }
  }
  return out;
}

const shellQuote = (s) => `'${s.replace(/'/g, `'\\''`)}'`;

export function curl(path, body, accept) {
  const lines = [`curl -s ${shellQuote(location.origin + path)}`, `-H 'content-type: application/json'`];
  if (accept && accept !== 'application/json') lines.push(`-H ${shellQuote(`accept: ${accept}`)}`);
  if (apiKey.get()) lines.push(`-H "authorization: Bearer $RESTITUTION_API_KEY"`);
  lines.push(`-d ${shellQuote(JSON.stringify(body))}`);
  return lines.join(' \\\n  ');
}

// A JSON value as a Python literal.
export function pythonLiteral(value, indent = 0) {
  const pad = ' '.repeat(indent + 4);
  const end = ' '.repeat(indent);
  if (value === null) return 'None';
  if (value === true) return 'True';
  if (value === false) return 'False';
  if (typeof value === 'number') return String(value);
  if (typeof value === 'string') return JSON.stringify(value);
  if (Array.isArray(value)) {
    if (value.length === 0) return '[]';
    return `[\n${value.map((v) => pad + pythonLiteral(v, indent + 4)).join(',\n')},\n${end}]`;
  }
  const entries = Object.entries(value);
  if (entries.length === 0) return '{}';
  return `{\n${entries.map(([k, v]) => `${pad}${JSON.stringify(k)}: ${pythonLiteral(v, indent + 4)}`).join(',\n')},\n${end}}`;
}

// The operations of the generated client (openapi-python-client over the
// service's OpenAPI document): module, function and request model per
// path, read from /assets/operations.json (made from that document) at
// start-up by `setOperations`.
let OPERATIONS = {};

export function setOperations(operations) {
  OPERATIONS = operations || {};
}

// The request as a program using the Python client generated from the
// service's OpenAPI document by openapi-python-client (package
// `restitution_client`; .ci/run generates and checks it).
export function python(path, body) {
  const operation = OPERATIONS[path];
  if (!operation) return `# ${path} is not an operation of the service's OpenAPI document\n`;
  const { module, function: fn, model } = operation;
  const keyed = Boolean(apiKey.get());
  const client = keyed
    ? `client = AuthenticatedClient(base_url=${JSON.stringify(location.origin)}, token=os.environ["RESTITUTION_API_KEY"])`
    : `client = Client(base_url=${JSON.stringify(location.origin)})`;
  return [
    '# The client generated from the service\'s OpenAPI document:',
    '#   openapi-python-client generate --path openapi/openapi.json --output-path client && pip install ./client',
    ...(keyed ? ['import os', ''] : []),
    `from restitution_client import ${keyed ? 'AuthenticatedClient' : 'Client'}`,
    `from restitution_client.api.${module} import ${fn}`,
    `from restitution_client.models import ${model}`,
    '',
    client,
    `request = ${model}.from_dict(${pythonLiteral(body)})`,
    `answer = ${fn}.sync(client=client, body=request)`,
    'print(answer.to_dict())',
    '',
  ].join('\n');
}
