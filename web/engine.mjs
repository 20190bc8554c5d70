// wqmesh page: checking and meshing through the package (wasm/index.mjs,
// copied into the served folder as pkg/wasm/index.mjs by web/build.mjs).
// The package runs the mesher in a module worker and cancels it through an
// AbortSignal (see wasm/index.d.ts); this file only adapts its errors to
// { code, message } and its progress to one shape for the page.
// While a package without the asynchronous API is served (an older build),
// the page runs the synchronous functions in a worker of its own
// (mesh-worker.mjs) and cancels by terminating that worker.
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

function abortError() {
  return new DOMException('The run was cancelled', 'AbortError');
}

// ---- the stand-in worker, for a package without the asynchronous API ------------------------
let fallbackWorker = null, fallbackSeq = 0;
const pending = new Map();
function fallback() {
  if (!fallbackWorker) {
    fallbackWorker = new Worker(new URL('./mesh-worker.mjs', import.meta.url), { type: 'module' });
    fallbackWorker.onmessage = (ev) => {
      const m = ev.data, p = pending.get(m.id);
      if (!p) return;
      if (m.type === 'progress') { p.onProgress?.(m.progress); return; }
      pending.delete(m.id);
      if (m.type === 'error') p.reject(toError(m.error)); else p.resolve(m.value);
    };
  }
  return fallbackWorker;
}
function callFallback(type, bytes, options, { signal, onProgress } = {}) {
  return new Promise((resolve, reject) => {
    if (signal?.aborted) { reject(abortError()); return; }
    const id = ++fallbackSeq;
    pending.set(id, { resolve, reject, onProgress });
    fallback().postMessage({ type, id, bytes, options });
    signal?.addEventListener('abort', () => {
      if (!pending.has(id)) return;
      // Cancel at once: the synchronous mesher cannot be interrupted, so its worker goes.
      fallbackWorker.terminate();
      fallbackWorker = null;
      for (const [k, p] of pending) p.reject(abortError()), pending.delete(k);
    }, { once: true });
  });
}

/** Validates and analyses the input: the check report (never throws for bad input). */
export async function check(bytes, { signal } = {}) {
  const pkg = await loadPackage();
  try {
    if (typeof pkg.mesh === 'function') return await pkg.check(bytes.slice(), null, { signal });
    return await callFallback('check', bytes.slice(), {}, { signal });
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
    if (typeof pkg.mesh === 'function') {
      return await pkg.mesh(bytes.slice(), options, {
        signal,
        onProgress: (p) => onProgress?.(p),
      });
    }
    return await callFallback('mesh', bytes.slice(), options, { signal, onProgress });
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
