// What the 2D page (demo.js) and the 3D page (demo3d.js) share: colours, parameter names,
// the read-out table and the contract by which tests and tools drive a page. Conversion and
// display only: every value shown comes from Module.answer (web/src/answers.hpp).

export const RED = '#d00', GREEN = '#080', ORANGE = '#d80', BLUE = '#05c', GREY = '#999';

// {k: v} -> {'prefix.k': v}: a body's fields as the library's parameter names.
export function flatten(prefix, obj) {
  const out = {};
  for (const [k, v] of Object.entries(obj)) out[prefix + '.' + k] = v;
  return out;
}

// A value for the table: lists as points of `dim` coordinates.
export function format(v, dim = 2) {
  if (typeof v === 'string') return v;
  if (typeof v === 'number') return Number.isInteger(v) || !Number.isFinite(v) ? String(v) : v.toPrecision(6);
  const parts = [];
  for (let i = 0; i < v.length; i += dim) parts.push('(' + Array.from(v.slice(i, i + dim), (x) => format(x)).join(', ') + ')');
  return parts.join(' ') || '–';
}

// The exact value, as JSON (NaN as null, like the native program's output).
export function exact(v) { return JSON.stringify(typeof v === 'object' ? Array.from(v) : v); }

// Shows an answer in a demo's section: the headline (or the library's error naming the
// field), the table of values not listed in demo.hidden (each with its exact value in
// data-value, for tests), and the inputs sent. The demo: {id, section, table, hidden,
// params(), headline(answer) -> [text, class]}.
export function renderAnswer(demo, answer, dim = 2) {
  const [text, cls] = answer.error !== undefined ? ['invalid input: ' + answer.message, 'failed'] : demo.headline(answer);
  const head = demo.section.querySelector('.headline');
  head.textContent = text;
  head.className = 'headline ' + cls;
  head.dataset.verdict = cls;
  const rows = [];
  for (const [key, value] of Object.entries(answer)) {
    if ((demo.hidden || []).some((h) => key.startsWith(h))) continue;
    const tr = document.createElement('tr'), th = document.createElement('th'), td = document.createElement('td');
    th.textContent = key;
    td.textContent = format(value, dim);
    td.dataset.testid = demo.id + ':' + key;
    td.dataset.value = exact(value);
    tr.append(th, td);
    rows.push(tr);
  }
  demo.table.replaceChildren(...rows);
  demo.section.querySelector('.params').textContent = JSON.stringify(demo.params());
}

// Times a demo's update: the library's part and the whole frame, shown in the header.
export function showTimes(queryMs, frameMs) {
  document.getElementById('query-ms').textContent = queryMs.toFixed(3);
  document.getElementById('frame-ms').textContent = frameMs.toFixed(3);
}

// The page is ready: the library loaded and every demo drawn once.
export function ready() {
  const status = document.getElementById('status');
  status.textContent = 'ready';
  status.dataset.ready = 'true';
}
