// wqmesh: the worker that runs check, mesh and the writers off the calling
// thread: a module Worker in browsers, a worker_threads worker in Node (the
// same file). It loads the wasm module (wqmesh.mjs, beside this file) once and
// answers one request at a time:
//   in:  { id, op: 'check'|'mesh'|'write', bytes?, options?, progress?, result?, format?, asBytes? }
//   out: { id, type: 'progress', progress: { phase, vertices, steps, fraction } }
//        { id, type: 'done', value }          (mesh: its typed arrays transferred)
//        { id, type: 'error', name, code?, message }
// wasm/index.mjs starts, reuses and terminates these workers.
// SPDX-License-Identifier: GPL-3.0-or-later
import { WqmeshError, resultBuffers, runCheck, runMesh, runWrite } from './core.mjs';

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
function loadModule() {
  modulePromise ??= (async () => {
    let factory;
    try {
      factory = (await import('./wqmesh.mjs')).default;
    } catch (e) {
      throw new WqmeshError('internal', 'wqmesh: cannot load the wasm module wqmesh.mjs beside worker.mjs ' +
                                        `(in a checkout: bash scripts/build.sh wasm): ${e.message}`);
    }
    return factory();
  })();
  return modulePromise;
}

// Progress messages: at most one per 50 ms, and at every phase change.
const PROGRESS_INTERVAL_MS = 50;

async function handle(request) {
  const { id, op } = request;
  try {
    const module = await loadModule();
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
