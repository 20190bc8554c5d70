// wqmesh page: checking and meshing through the package (wasm/index.mjs,
// copied into the served folder as pkg/wasm/index.mjs by web/build.mjs).
// The package runs the mesher in a module worker and cancels it through an
// AbortSignal (see wasm/index.d.ts); this file only adapts its errors to
// { code, message } for the page.
// SPDX-License-Identifier: GPL-3.0-or-later

const PKG_URL = new URL('./pkg/wasm/index.mjs', import.meta.url);

let pkgPromise = null;
/** The package module (imported once). */
export function loadPackage() {
  if (!pkgPromise) pkgPromise = import(PKG_URL.href);
  return pkgPromise;
}

/** An error of the package as { code, message }; an AbortError keeps its name. */
export function toError(e) {
  if (e && e.name === 'AbortError') return e;
  const code = (e && (e.code || e.kind)) || 'internal';
  let message = String((e && e.message) || e);
  message = message.replace(/^wqmesh: [a-z_]+: /, '');
  const err = new Error(message);
  err.code = code;
  return err;
}

/** Validates and analyses the input: the check report (never throws for bad input). */
export async function check(bytes, { signal } = {}) {
  const pkg = await loadPackage();
  try {
    return await pkg.check(bytes.slice(), null, { signal });
  } catch (e) {
    throw toError(e);
  }
}

/**
 * Meshes the input. onProgress receives { phase, fraction, vertices, steps }.
 * Rejects with an AbortError when `signal` aborts, else with { code, message }.
 */
export async function mesh(bytes, options, { signal, onProgress } = {}) {
  const pkg = await loadPackage();
  try {
    return await pkg.mesh(bytes.slice(), options, { signal, onProgress: (p) => onProgress?.(p) });
  } catch (e) {
    throw toError(e);
  }
}

/** The package's version string, or '' when it has none. */
export async function version() {
  const pkg = await loadPackage();
  try {
    if (typeof pkg.version === 'string') return pkg.version;
    if (typeof pkg.version === 'function') return String(await pkg.version());
  } catch { /* no version */ }
  return '';
}
