// wqmesh: the package entry, the same in Node 20+ and in browsers. The async
// functions (check, mesh, the writers) run in a worker (worker.mjs: a module
// Worker in browsers, a worker_threads worker in Node); the *Sync forms and
// loadWqmesh run in the calling thread. The wasm module (wqmesh.mjs, the
// Emscripten glue, and wqmesh.wasm, its binary: the package ships the binary
// once) and the option table (options.mjs, written from the module's own
// table) sit beside this file: scripts/build.sh wasm
// copies them here from the build tree, and `npm pack` does the same in its
// prepack step. See index.d.ts for the documentation.
// SPDX-License-Identifier: GPL-3.0-or-later
import optionTable, { version as moduleVersion } from './options.mjs';
import { WqmeshError, compileWasm, instantiateModule, plainOptions, runCheck, runMesh, runWrite, toBytes,
         writerInput } from './core.mjs';

export { WqmeshError };

/** The option table of the native command line and the module: name, flag, type, range, default, doc. */
export const options = Object.freeze(optionTable.map((o) => Object.freeze({ ...o, commands: Object.freeze([...o.commands]) })));

/** The default of every option, by name. */
export const defaultOptions = Object.freeze(Object.fromEntries(options.map((o) => [o.name, o.default])));

const MODULE_URL = new URL('./wqmesh.mjs', import.meta.url);
// The binary of wqmesh.mjs (linked without SINGLE_FILE: the glue holds no
// copy), compiled once per package instance: the calling thread and every
// worker instantiate the same compiled module (posted to each worker with
// its requests), so V8 compiles and optimizes the code once per process or
// page, not once per worker. In Node the calling thread compiles it from the
// import of this file on. In a browser the first worker compiles it
// (WebAssembly.compileStreaming) and sends it back: Chromium may then keep
// the optimized code in its code cache for the next page load, and it
// serializes that code on the thread that compiled, which must not be the
// page's (a long task of about 0.1 s per caching event during a run).
// Without the file (e.g. a bundle that left it out) every call rejects with a
// WqmeshError `internal` naming it.
const WASM_URL = new URL('./wqmesh.wasm', import.meta.url);
const compiled = new Map();  // wasm URL -> Promise<WebAssembly.Module>

function compiledModule(url) {
  const key = String(url);
  if (!compiled.has(key)) {
    const promise = compileWasm(url);
    // Handled here (no unhandled rejection at import), and forgotten: a failed load may be retried.
    promise.catch(() => { if (compiled.get(key) === promise) compiled.delete(key); });
    compiled.set(key, promise);
  }
  return compiled.get(key);
}
/** The wasm binary beside the Emscripten module at `url`: x.mjs -> x.wasm. */
function wasmUrlOf(url) {
  return String(url) === String(MODULE_URL) ? WASM_URL : new URL(String(url).replace(/\.m?js(?=$|[?#])/, '.wasm'));
}
const isNode = typeof process === 'object' && typeof process.versions?.node === 'string';
if (isNode) compiledModule(WASM_URL);  // from the import on (see WASM_URL)
// By a computed name, so that bundlers for the browser leave it alone.
const nodeWorkerThreads = 'node:worker_threads';

// ---- Workers -----------------------------------------------------------------

/**
 * One worker behind a small interface common to both platforms: post, a
 * message listener, a failure listener (the worker died or its script did
 * not load), terminate, and ref/unref (Node: an idle worker does not keep
 * the process alive).
 */
async function startWorker() {
  if (isNode) {
    const { Worker } = await import(nodeWorkerThreads);
    // execArgv: [] rather than the caller's: a worker inherits the process's
    // flags by default, and some are refused in a worker script (e.g.
    // `node --input-type=module -e ...`: "--input-type can only be used with
    // string input"). The worker needs no flags of its own.
    const w = new Worker(new URL('./worker.mjs', import.meta.url), { execArgv: [] });
    return {
      post: (m) => w.postMessage(m),
      onMessage: (f) => w.on('message', f),
      onFailure: (f) => {
        w.on('error', (e) => f(e));
        w.on('exit', (code) => f(new Error(`the worker exited with code ${code}`)));
      },
      terminate: () => { w.terminate(); },
      ref: () => w.ref(),
      unref: () => w.unref(),
    };
  }
  // The literal `new URL('./worker.mjs', import.meta.url)` inside `new Worker`
  // lets Vite find and bundle the worker.
  const w = new Worker(new URL('./worker.mjs', import.meta.url), { type: 'module' });
  return {
    post: (m) => w.postMessage(m),
    onMessage: (f) => w.addEventListener('message', (e) => f(e.data)),
    onFailure: (f) => {
      w.addEventListener('error', (e) => { e.preventDefault?.(); f(new Error(e.message || 'the worker script failed to load')); });
      w.addEventListener('messageerror', () => f(new Error('a message from the worker could not be read')));
    },
    terminate: () => w.terminate(),
    ref: () => {},
    unref: () => {},
  };
}

let idleWorker = null;  // at most one worker waits for the next call
let nextId = 1;

async function takeWorker() {
  if (idleWorker && !idleWorker.failed) {
    const w = idleWorker;
    idleWorker = null;
    return w;
  }
  const handle = await startWorker();
  const w = { handle, listener: null, failed: null };
  handle.onMessage((m) => {
    if (m && m.id !== undefined) w.listener?.(m);
    // A worker that compiled wqmesh.wasm itself: the module for the next workers.
    else if (m?.type === 'compiled' && m.wasm instanceof WebAssembly.Module && !compiled.has(m.wasmUrl))
      compiled.set(m.wasmUrl, Promise.resolve(m.wasm));
  });
  handle.onFailure((e) => { w.failed = e; w.onFailure?.(e); });
  return w;
}

function releaseWorker(w) {
  w.listener = null;
  w.onFailure = null;
  if (w.failed || idleWorker) {
    w.handle.terminate();
  } else {
    w.handle.unref();
    idleWorker = w;
  }
}

function abortError() {
  return new DOMException('wqmesh: the run was aborted', 'AbortError');
}

function errorFromWorker(m) {
  if (m.name === 'TypeError') return new TypeError(m.message);
  return new WqmeshError(m.code ?? 'internal', m.message);
}

/**
 * Runs one request in a worker. An abort of `signal` terminates the worker
 * at once (whatever the run is doing) and rejects with an AbortError; the
 * next call starts a fresh worker.
 */
async function inWorker(request, { signal, onProgress } = {}) {
  if (signal !== undefined && !(signal && typeof signal.aborted === 'boolean' && typeof signal.addEventListener === 'function'))
    throw new TypeError('wqmesh: signal must be an AbortSignal');
  if (onProgress !== undefined && typeof onProgress !== 'function')
    throw new TypeError('wqmesh: onProgress must be a function');
  if (signal?.aborted) throw abortError();
  const wasmUrl = String(WASM_URL);
  const wasm = compiled.has(wasmUrl) ? await compiled.get(wasmUrl) : null;
  const w = await takeWorker();
  if (signal?.aborted) {
    releaseWorker(w);
    throw abortError();
  }
  w.handle.ref();
  const id = nextId++;
  return new Promise((resolve, reject) => {
    let settled = false;
    const finish = (fn, value, keep) => {
      if (settled) return;
      settled = true;
      signal?.removeEventListener('abort', onAbort);
      if (keep) {
        releaseWorker(w);
      } else {
        w.listener = null;
        w.handle.terminate();
      }
      fn(value);
    };
    const onAbort = () => finish(reject, abortError(), false);
    signal?.addEventListener('abort', onAbort, { once: true });
    w.onFailure = (e) => finish(reject, new WqmeshError('internal', `wqmesh: the worker failed: ${e.message}`), false);
    w.listener = (m) => {
      if (m.id !== id) return;
      if (m.type === 'progress') {
        if (onProgress && !settled) {
          try {
            onProgress(m.progress);
          } catch (e) {
            finish(reject, e, false);
          }
        }
      } else if (m.type === 'done') {
        finish(resolve, m.value, true);
      } else if (m.type === 'error') {
        finish(reject, errorFromWorker(m), true);
      }
    };
    if (w.failed) w.onFailure(w.failed);
    else w.handle.post({ ...request, id, wasm, wasmUrl });
  });
}

// ---- The async API (in a worker) ---------------------------------------------

/**
 * The bytes to post to the worker: a copy of just the view when it is part
 * of a larger buffer (posting a view clones its whole buffer, e.g. Node's
 * 8 kB Buffer pool). The caller's bytes are never transferred away.
 */
function ownBytes(bytes) {
  return bytes.byteOffset === 0 && bytes.byteLength === bytes.buffer.byteLength ? bytes : bytes.slice();
}

/** Validates and analyses a polyhedron in a worker. See index.d.ts. */
export async function check(input, checkOptions, control = {}) {
  const bytes = ownBytes(toBytes(input, 'check'));
  const opts = plainOptions(checkOptions, 'check');
  return inWorker({ op: 'check', bytes, options: opts }, { signal: control?.signal });
}

/** Meshes a polyhedron in a worker. See index.d.ts. */
export async function mesh(input, meshOptions, control = {}) {
  const bytes = ownBytes(toBytes(input, 'mesh'));
  const opts = plainOptions(meshOptions, 'mesh');
  const onProgress = control?.onProgress;
  return inWorker({ op: 'mesh', bytes, options: opts, progress: typeof onProgress === 'function' },
                  { signal: control?.signal, onProgress });
}

async function write(result, format, writeOptions, fn) {
  const input = writerInput(result, fn);
  return inWorker({ op: 'write', result: input, format, asBytes: Boolean(writeOptions?.bytes) },
                  { signal: writeOptions?.signal });
}

/** The result as a Medit .mesh file. See index.d.ts. */
export const writeMedit = (result, writeOptions) => write(result, 'medit', writeOptions, 'writeMedit');
/** The result as a VTK .vtu file. See index.d.ts. */
export const writeVtu = (result, writeOptions) => write(result, 'vtu', writeOptions, 'writeVtu');
/** The result as TetGen files { node, ele, face, edge }. See index.d.ts. */
export const writeTetgen = (result, writeOptions) => write(result, 'tetgen', writeOptions, 'writeTetgen');

// ---- The calling thread: loadWqmesh, ready and the *Sync forms -----------------

const loaded = new Map();  // module URL -> Promise<instance>

async function instantiate(url) {
  let factory;
  try {
    factory = String(url) === String(MODULE_URL)
      ? (await import('./wqmesh.mjs')).default   // a literal: bundlers include the module
      : (await import(String(url))).default;
  } catch (e) {
    throw new WqmeshError('internal', `wqmesh: cannot load the wasm module ${url} ` +
                                      `(in a checkout: bash scripts/build.sh wasm): ${e.message}`, { cause: e });
  }
  return instantiateModule(factory, await compiledModule(wasmUrlOf(url)));
}

function wrap(module) {
  const sync = {
    check: (input, opts) => runCheck(module, toBytes(input, 'check'), plainOptions(opts, 'check')),
    mesh: (input, opts, control) => {
      const bytes = toBytes(input, 'meshSync');
      // Earlier versions took onProgress(phase, fraction, vertices) among the options.
      let onProgress = control?.onProgress;
      let rest = opts;
      if (opts && typeof opts === 'object' && typeof opts.onProgress === 'function' && onProgress === undefined) {
        const { onProgress: legacy, ...others } = opts;
        onProgress = (p) => legacy(p.phase, p.fraction, p.vertices);
        rest = others;
      }
      if (onProgress !== undefined && typeof onProgress !== 'function')
        throw new TypeError('wqmesh: onProgress must be a function');
      return runMesh(module, bytes, plainOptions(rest, 'meshSync'), onProgress);
    },
    write: (result, format, writeOptions) => runWrite(module, writerInput(result, 'write'), format, writeOptions?.bytes),
  };
  return {
    check: sync.check,
    checkJson: (input, opts = {}) => {
      const { pretty, ...rest } = opts ?? {};
      return module.check(toBytes(input, 'checkJson'), plainOptions(rest, 'checkJson'), Boolean(pretty));
    },
    mesh: sync.mesh,
    writeMedit: (result, o) => sync.write(result, 'medit', o),
    writeVtu: (result, o) => sync.write(result, 'vtu', o),
    writeTetgen: (result, o) => sync.write(result, 'tetgen', o),
    memoryStats: () => module.memoryStats(),
    version: () => module.version(),
  };
}

/**
 * Loads and instantiates the wasm module in the calling thread, once per
 * module URL; later calls return the same object (blocking, synchronous
 * functions). See index.d.ts.
 */
export function loadWqmesh(loadOptions = {}) {
  const url = String(loadOptions?.moduleUrl ?? MODULE_URL);
  if (!loaded.has(url)) {
    const promise = instantiate(url).then(wrap);
    promise.catch(() => loaded.delete(url));  // a failed load may be retried
    loaded.set(url, promise);
  }
  return loaded.get(url);
}

export default loadWqmesh;

let instance = null;

/** Loads the module in the calling thread for the *Sync forms. See index.d.ts. */
export async function ready() {
  instance = await loadWqmesh();
}

function syncInstance(fn) {
  if (!instance)
    throw new WqmeshError('internal', `wqmesh ${fn}(): the module is not loaded in this thread: await ready() first`);
  return instance;
}

/** check in the calling thread, blocking it. See index.d.ts. */
export const checkSync = (input, opts) => syncInstance('checkSync').check(input, opts);
/** mesh in the calling thread, blocking it. See index.d.ts. */
export const meshSync = (input, opts, control) => syncInstance('meshSync').mesh(input, opts, control);
/** writeMedit in the calling thread. See index.d.ts. */
export const writeMeditSync = (result, o) => syncInstance('writeMeditSync').writeMedit(result, o);
/** writeVtu in the calling thread. See index.d.ts. */
export const writeVtuSync = (result, o) => syncInstance('writeVtuSync').writeVtu(result, o);
/** writeTetgen in the calling thread. See index.d.ts. */
export const writeTetgenSync = (result, o) => syncInstance('writeTetgenSync').writeTetgen(result, o);

/** The version of the wasm module beside this file (the project's version), e.g. "0.1.0". */
export const version = moduleVersion;
