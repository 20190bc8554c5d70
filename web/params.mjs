// wqmesh page: the run parameters and the view options, their defaults, their
// one-line explanations, and their round trip through the page URL (so that a
// link reproduces a run). Pure functions: no DOM, usable in Node tests.
// SPDX-License-Identifier: GPL-3.0-or-later

/**
 * The run parameters shown on the page, in the package's option names
 * (wasm/index.d.ts, MeshOptions). Ranges are those the module accepts; the
 * defaults are the module's defaults (rho0 = 2.2 and theta = 3 degrees, as in
 * the paper's experiments, section 6).
 */
export const RUN_PARAMS = [
  { key: 'rho', label: 'rho0', type: 'number', def: 2.2, min: 1, max: 1e6, step: 0.1,
    help: 'Radius-edge bound of rule 6: tets with a larger R/l are refined (paper: 2.2).' },
  { key: 'sliverAngle', label: 'theta (deg)', type: 'number', def: 3, min: 0, max: 90, step: 0.5,
    help: 'Sliver angle of rule 7 and PUMP: a tet with a dihedral angle below it is a sliver.' },
  { key: 'pump', label: 'PUMP', type: 'bool', def: true,
    help: 'Sliver exudation by weight pumping (off: QMESH alone, no rule 7).' },
  { key: 'improve', label: 'improve', type: 'bool', def: true,
    help: 'Flips, smoothing and insertion after PUMP raise the smallest dihedral angle; the boundary stays exact (beyond the paper; off: the paper\'s WQMESH output).' },
  { key: 'polish', label: 'polish', type: 'bool', def: false,
    help: 'With improve: a polish after its passes raises the smallest dihedral angle further (beyond the paper; 3-8 times the refinement\'s time on small models).' },
  { key: 'maxSize', label: 'size bound', type: 'number', def: 0, min: 0, max: 1e300, step: 'any',
    help: 'Largest circumradius allowed, in model units (0: no bound; beyond the paper).' },
  { key: 'maxVertices', label: 'vertex limit', type: 'number', def: 1000000, min: 8, max: 1e9, step: 1,
    help: 'The run stops with "limit" when the mesh reaches this many vertices.' },
];

/** View options kept in the URL too (short keys, since links get long). */
export const VIEW_PARAMS = [
  { key: 'clip', type: 'bool', def: true },           // clipping plane on
  { key: 'axis', type: 'enum', def: 'x', values: ['x', 'y', 'z'] },
  { key: 'cut', type: 'number', def: 0.5, min: 0, max: 1 },   // plane position, fraction of the box
  { key: 'flip', type: 'bool', def: false },          // keep the other side
  { key: 'shrink', type: 'number', def: 1, min: 0.3, max: 1 },
  { key: 'bound', type: 'number', def: 10, min: 0, max: 90 },  // user dihedral bound, degrees
  { key: 'rest', type: 'enum', def: 'show', values: ['show', 'fade', 'hide'] },
  { key: 'balls', type: 'bool', def: false },
  { key: 'pumped', type: 'bool', def: false },
];

/** The default state: every run parameter and view option, plus no example. */
export function defaultState() {
  const s = { example: '' };
  for (const p of [...RUN_PARAMS, ...VIEW_PARAMS]) s[p.key] = p.def;
  return s;
}

/**
 * Validates one value against its parameter; returns the value to use, or
 * the default when the text is not a valid value (a hand-edited URL).
 */
export function coerce(p, raw) {
  if (p.type === 'bool') {
    if (raw === true || raw === '1' || raw === 'true' || raw === 'on') return true;
    if (raw === false || raw === '0' || raw === 'false' || raw === 'off') return false;
    return p.def;
  }
  if (p.type === 'enum') return p.values.includes(raw) ? raw : p.def;
  const x = typeof raw === 'number' ? raw : Number(raw);
  if (raw === '' || raw === null || !Number.isFinite(x) || x < p.min || x > p.max) return p.def;
  return x;
}

/** Reads the state from a URL query string (e.g. location.search). */
export function stateFromQuery(query) {
  const q = new URLSearchParams(query);
  const s = defaultState();
  for (const p of [...RUN_PARAMS, ...VIEW_PARAMS]) if (q.has(p.key)) s[p.key] = coerce(p, q.get(p.key));
  const ex = q.get('example');
  if (ex && /^[\w.-]+\.(off|stl)$/i.test(ex)) s.example = ex;
  return s;
}

/** Writes the state as a query string; values at their default are left out. */
export function queryFromState(s) {
  const q = new URLSearchParams();
  if (s.example) q.set('example', s.example);
  for (const p of [...RUN_PARAMS, ...VIEW_PARAMS]) {
    const v = s[p.key];
    if (v === p.def) continue;
    q.set(p.key, p.type === 'bool' ? (v ? '1' : '0') : String(v));
  }
  const t = q.toString();
  return t ? `?${t}` : '';
}

/** The package options of a state (only the run parameters). */
export function meshOptions(s) {
  const o = {};
  for (const p of RUN_PARAMS) o[p.key] = s[p.key];
  return o;
}
