// Calls to the service's API, from the page's own origin, with the API key
// the user typed (kept in this tab's session storage) when there is one.

const KEY = 'restitution.api-key';

export const apiKey = {
  get: () => sessionStorage.getItem(KEY) || '',
  set: (value) => (value ? sessionStorage.setItem(KEY, value) : sessionStorage.removeItem(KEY)),
};

// POSTs JSON; answers {ok, status, type, body, problem}: `body` is parsed
// JSON, text (SVG) or a Blob (`as: 'blob'`), `problem` the RFC 9457 object.
export async function post(path, payload, { accept = 'application/json', as = 'auto' } = {}) {
  const headers = { 'content-type': 'application/json', accept };
  const key = apiKey.get();
  if (key) headers.authorization = `Bearer ${key}`;
  let response;
  try {
    response = await fetch(path, { method: 'POST', headers, body: JSON.stringify(payload) });
  } catch (error) {
    return { ok: false, status: 0, problem: { title: 'Network error', detail: `the service did not answer: ${error.message}` } };
  }
  const type = response.headers.get('content-type') || '';
  if (!response.ok) {
    let problem;
    try {
      problem = await response.json();
    } catch {
      problem = { title: `HTTP ${response.status}`, detail: response.statusText };
    }
    return { ok: false, status: response.status, type, problem };
  }
  let body;
  if (as === 'blob') body = await response.blob();
  else if (type.includes('json')) body = await response.json();
  else body = await response.text();
  return { ok: true, status: response.status, type, body, headers: response.headers };
}

// The problem as one line of text.
export const problemText = (p) => [p.title, p.detail].filter(Boolean).join(': ') + (p.pointer ? ` (at ${p.pointer})` : '');
