// wqmesh: the worker that runs check, mesh and the writers off the calling
// thread: a module Worker in browsers, a worker_threads worker in Node (the
// same file). It loads the wasm module (wqmesh.mjs, beside this file) once and
// answers one request at a time:
//   in:  { id, op: 'check'|'mesh'|'write', wasm, wasmUrl, bytes?, options?, progress?, result?, format?, asBytes? }
//        (wasm: the compiled WebAssembly.Module of wqmesh.wasm, or null; wasmUrl: where wqmesh.wasm is)
//   out: { id, type: 'progress', progress: { phase, vertices, steps, fraction } }
//        { id, type: 'done', value }          (mesh: its typed arrays transferred)
//        { id, type: 'error', name, code?, message }
//        { type: 'compiled', wasm, wasmUrl }   (this worker compiled wasmUrl: the module for the next ones)
// wasm/index.mjs starts, reuses and terminates these workers.
// SPDX-License-Identifier: GPL-3.0-or-later
import { WqmeshError, compileWasm, instantiateModule, resultBuffers, runCheck, runMesh, runWrite } from './core.mjs';

// Node's worker_threads by a computed name, so that bundlers for the browser
// leave it alone.
const nodeWorkerThreads = 'node:worker_threads';
const port = typeof self === 'object' && typeof self.postMessage === 'function' && typeof WorkerGlobalScope === 'function'
  ? { post: (m, t) => self.postMessage(m, t), listen: (f) => self.addEventListener('message', (e) => f(e.data)) }
  : await (async () => {
    const { parentPort } = await import(nodeWorkerThreads);
    return { post: (m, t) => parentPort.postMessage(m, t), listen: (f) => parentPort.on('message', f) };
  })();

let modulePromise = null;
/**
 * The module of this worker, instantiated once, on the compiled module the
 * calling thread sends with each request (`wasm`: index.mjs compiles
 * wqmesh.wasm once per package instance); when it sends none, this worker
 * compiles `wasmUrl` itself and sends the module back for the next workers.
 * A failure (no wqmesh.wasm, a binary of another build) rejects this request
 * with a WqmeshError `internal`; the next request tries again.
 */
function loadModule({ wasm, wasmUrl }) {
  modulePromise ??= (async () => {
    let factory;
    try {
      factory = (await import('./wqmesh.mjs')).default;
    } catch (e) {
      throw new WqmeshError('internal', 'wqmesh: cannot load the wasm module wqmesh.mjs beside worker.mjs ' +
                                        `(in a checkout: bash scripts/build.sh wasm): ${e.message}`);
    }
    let compiled = wasm ?? null;
    if (!compiled) {
      if (!wasmUrl) throw new WqmeshError('internal', 'wqmesh worker: a request without the wasm binary or its URL');
      compiled = await compileWasm(wasmUrl);
      port.post({ type: 'compiled', wasm: compiled, wasmUrl });
    }
    return instantiateModule(factory, compiled);
  })();
  modulePromise.catch(() => { modulePromise = null; });
  return modulePromise;
}

// Progress messages: at most one per 50 ms, and at every phase change.
const PROGRESS_INTERVAL_MS = 50;

async function handle(request) {
  const { id, op } = request;
  try {
    const module = await loadModule(request);
    if (op === 'check') {
      port.post({ id, type: 'done', value: runCheck(module, request.bytes, request.options) });
    } else if (op === 'mesh') {
      let lastPhase = '';
      let lastTime = 0;
      const onProgress = request.progress ? (p) => {
        const now = Date.now();
        if (p.phase !== lastPhase || now - lastTime >= PROGRESS_INTERVAL_MS) {
          lastPhase = p.phase;
          lastTime = now;
          port.post({ id, type: 'progress', progress: p });
        }
        return true;
      } : undefined;
      const r = runMesh(module, request.bytes, request.options, onProgress);
      port.post({ id, type: 'done', value: r }, resultBuffers(r));
    } else if (op === 'write') {
      const value = runWrite(module, request.result, request.format, request.asBytes);
      const buffers = value instanceof Uint8Array ? [value.buffer]
        : Object.values(value).filter((v) => v instanceof Uint8Array).map((v) => v.buffer);
      port.post({ id, type: 'done', value }, buffers);
    } else {
      throw new WqmeshError('internal', `wqmesh worker: unknown request '${op}'`);
    }
  } catch (e) {
    port.post({ id, type: 'error', name: e?.name ?? 'Error', code: e?.code, message: String(e?.message ?? e) });
  }
}

port.listen(handle);
port.post({ type: 'ready' });
