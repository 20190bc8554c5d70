// wqmesh page: a stand-in worker for a package without the asynchronous API
// (engine.mjs uses it only then): runs the synchronous check and mesh of
// loadWqmesh() off the main thread and posts progress. Cancelled by
// terminating it.
// SPDX-License-Identifier: GPL-3.0-or-later
import { loadWqmesh } from './pkg/wasm/index.mjs';

const ready = loadWqmesh();

self.onmessage = async (ev) => {
  const { type, id, bytes, options } = ev.data;
  try {
    const w = await ready;
    if (type === 'check') {
      self.postMessage({ type: 'done', id, value: w.check(bytes) });
      return;
    }
    let last = 0;
    const r = w.mesh(bytes, {
      ...options,
      onProgress: (phase, fraction, vertices) => {
        const now = Date.now();
        if (now - last > 50) {
          last = now;
          self.postMessage({ type: 'progress', id, progress: { phase, fraction, vertices } });
        }
        return true;
      },
    });
    const transfer = Object.values(r).filter((v) => ArrayBuffer.isView(v)).map((v) => v.buffer);
    self.postMessage({ type: 'done', id, value: r }, transfer);
  } catch (e) {
    self.postMessage({ type: 'error', id, error: { code: e.code || e.kind || 'internal', message: e.message } });
  }
};
