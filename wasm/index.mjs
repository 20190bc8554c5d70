// wqmesh: the package entry. Loads the wasm module (one ES module file with the
// wasm inlined, written by the build to build/wasm/wasm/wqmesh.mjs) and wraps
// its Embind functions.
// SPDX-License-Identifier: GPL-3.0-or-later

/** Where `scripts/build.sh` writes the module, relative to this file. */
const DEFAULT_MODULE_URL = new URL('../build/wasm/wasm/wqmesh.mjs', import.meta.url);

const loaded = new Map();  // module URL -> Promise<Wqmesh>

/** The bytes of an input as a Uint8Array (no copy when already one). */
function toBytes(input) {
  if (input instanceof Uint8Array) return input;  // Node's Buffer included
  if (input instanceof ArrayBuffer) return new Uint8Array(input);
  if (ArrayBuffer.isView(input)) return new Uint8Array(input.buffer, input.byteOffset, input.byteLength);
  if (typeof input === 'string') return new TextEncoder().encode(input);
  throw new TypeError('wqmesh check(): expected a Uint8Array, ArrayBuffer, typed array, DataView or string, ' +
                      `got ${input === null ? 'null' : typeof input}`);
}

function wrap(module) {
  const checkJson = (bytes, options = {}) => module.check(toBytes(bytes), Boolean(options.pretty));
  return {
    check: (bytes, options = {}) => JSON.parse(checkJson(bytes, { ...options, pretty: false })),
    checkJson,
    mesh: (bytes, options = {}) => {
      const { onProgress, ...rest } = options;
      const r = module.mesh(toBytes(bytes), rest, typeof onProgress === 'function' ? onProgress : undefined);
      if (r.error) {
        const error = new Error(`wqmesh: ${r.error.kind}: ${r.error.message}`);
        error.kind = r.error.kind;
        throw error;
      }
      return { ...r, stats: JSON.parse(r.stats) };
    },
    version: () => module.version(),
  };
}

/**
 * Loads and instantiates the wasm module once per module URL; later calls
 * return the same object. See index.d.ts for the documentation.
 */
export function loadWqmesh(options = {}) {
  const url = String(options.moduleUrl ?? DEFAULT_MODULE_URL);
  if (!loaded.has(url)) {
    const promise = (async () => {
      let factory;
      try {
        factory = (await import(url)).default;
      } catch (e) {
        const error = new Error(`wqmesh: cannot load the wasm module ${url} ` +
                                `(build it with 'bash scripts/build.sh wasm'): ${e.message}`);
        error.cause = e;
        throw error;
      }
      return wrap(await factory());
    })();
    promise.catch(() => loaded.delete(url));  // a failed load may be retried
    loaded.set(url, promise);
  }
  return loaded.get(url);
}

export default loadWqmesh;
