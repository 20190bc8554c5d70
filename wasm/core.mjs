// wqmesh: what the package entry (index.mjs) and its worker (worker.mjs) share:
// the error class, the input check, the loading of the wasm module and the
// calls into the loaded Embind module (wqmesh.mjs, built from bindings.cpp). Options are checked by the
// module itself, with the core's option table (core/src/options.cpp), the
// one the native command line uses.
// SPDX-License-Identifier: GPL-3.0-or-later

/**
 * The one error class of the package. `code` is stable: an input error kind
 * of `check` (`open_boundary`, `truncated`, ...), `options`, `limit` or
 * `internal`. `kind` is the same as `code` (the name of earlier versions).
 */
export class WqmeshError extends Error {
  constructor(code, message, options) {
    super(message, options);
    this.name = 'WqmeshError';
    this.code = code;
  }

  get kind() {
    return this.code;
  }
}

/** The message of an error from the module, naming the kind as the native command line does. */
export function moduleError(error) {
  return new WqmeshError(error.kind, `wqmesh: ${error.kind}: ${error.message}`);
}

function describe(value) {
  if (value === null) return 'null';
  if (Array.isArray(value)) return 'an Array';
  if (typeof value === 'object') return `a ${value.constructor?.name ?? 'object'}`;
  return `a ${typeof value}`;
}

/**
 * True for a string that is a file name or path rather than OFF or STL text:
 * one line, no white space, with a slash, a backslash or a dot (an OFF or STL
 * file has white space between its numbers).
 */
export function looksLikePath(text) {
  return text.length > 0 && text.length < 4096 && !/\s/.test(text) && /[/\\.]/.test(text);
}

/**
 * The bytes of an input as a Uint8Array (no copy when already one): a
 * Uint8Array (Node's Buffer included), an ArrayBuffer, another typed array or
 * DataView (its bytes), or OFF/STL text (encoded as UTF-8). Anything else,
 * and a string that looks like a path, is a TypeError saying what was
 * expected; `fn` names the function in the message.
 */
export function toBytes(input, fn) {
  if (input instanceof Uint8Array) return input;
  if (input instanceof ArrayBuffer) return new Uint8Array(input);
  if (ArrayBuffer.isView(input)) return new Uint8Array(input.buffer, input.byteOffset, input.byteLength);
  const expected = `wqmesh ${fn}(): expected the file's bytes (Uint8Array, ArrayBuffer or Buffer) or its OFF/STL text`;
  if (typeof input === 'string') {
    if (looksLikePath(input))
      throw new TypeError(`${expected}, got the string '${input}', which looks like a file name: ` +
                          'read the file first (e.g. await readFile(path) in Node, await file.arrayBuffer() in a page)');
    return new TextEncoder().encode(input);
  }
  throw new TypeError(`${expected}, got ${describe(input)}`);
}

/**
 * The options as a plain object to hand to the module (or to a worker):
 * undefined and null are no options; anything else but a plain object is a
 * TypeError. Values that cannot be options at all (functions, objects) are a
 * WqmeshError `options`; names, types and ranges are the module's to check.
 */
export function plainOptions(options, fn) {
  if (options === undefined || options === null) return {};
  if (typeof options !== 'object' || Array.isArray(options))
    throw new TypeError(`wqmesh ${fn}(): expected the options as an object, e.g. { rho: 2.2 }, got ${describe(options)}`);
  const out = {};
  for (const [key, value] of Object.entries(options)) {
    if (value === undefined) continue;
    if (typeof value === 'function' || (typeof value === 'object' && value !== null)) {
      const hint = key === 'onProgress' || key === 'signal'
        ? ` (${key} goes in the third argument: ${fn}(input, options, { onProgress, signal }))` : '';
      throw new WqmeshError('options', `wqmesh: options: option '${key}' is ${describe(value)}; ` +
                                       `options are numbers and booleans${hint}`);
    }
    out[key] = value;
  }
  return out;
}

/** The JSON report of `check`, parsed; an options error of the module is thrown. */
export function runCheck(module, bytes, options) {
  const report = JSON.parse(module.check(bytes, options, false));
  if (!report.valid && report.error && (report.error.kind === 'options' || report.error.kind === 'internal'))
    throw moduleError(report.error);
  return report;
}

/** The phases of a run, in order. */
export const PHASES = ['initialize', 'conform', 'refine', 'pump', 'extract', 'improve'];

/**
 * Meshes `bytes`; `onProgress`, when given, receives { phase, vertices,
 * steps, fraction } with a fraction that never goes down, and cancels the run
 * when it returns false. Returns the result (stats parsed) or throws a
 * WqmeshError.
 */
export function runMesh(module, bytes, options, onProgress) {
  let fraction = 0;
  const progress = typeof onProgress === 'function'
    ? (phase, f, vertices, steps) => {
        // The mesher's fraction is an estimate (refinement has no known end):
        // it is reported as the largest so far, so it never goes down.
        fraction = Math.max(fraction, Math.min(1, Number.isFinite(f) ? f : 0));
        return onProgress({ phase, vertices, steps, fraction });
      }
    : undefined;
  const r = module.mesh(bytes, options, progress);
  if (r.error) throw moduleError(r.error);
  r.stats = JSON.parse(r.stats);
  r.memory = module.memoryStats();
  return r;
}

/** The typed arrays of a result, to transfer. */
export function resultBuffers(r) {
  return ['vertices', 'weights', 'tets', 'boundary', 'boundaryFacet', 'tetClass', 'minDihedral', 'radiusEdge', 'orthoradiusEdge',
          'protectingBalls', 'protectingBallIsVertex'].map((k) => r[k]?.buffer).filter((b) => b instanceof ArrayBuffer);
}

/** The arrays of a result the writers read (what a worker is sent). */
export function writerInput(result, fn) {
  if (typeof result !== 'object' || result === null)
    throw new TypeError(`wqmesh ${fn}(): expected the result of mesh(), got ${describe(result)}`);
  const { vertices, weights, tets, boundary, boundaryFacet, tetClass } = result;
  return { vertices, weights, tets, boundary, boundaryFacet, tetClass };
}

export const FORMATS = ['medit', 'vtu', 'tetgen'];

/**
 * Writes a result with the core's writers: a string (UTF-8 bytes when
 * `bytes`), or for tetgen { node, ele, face, edge } of them.
 */
export function runWrite(module, result, format, bytes) {
  const r = module.writeMesh(result, format, Boolean(bytes));
  if (r && typeof r === 'object' && r.error) {
    if (r.error.kind === 'type') throw new TypeError(`wqmesh write: ${r.error.message}`);
    throw moduleError(r.error);
  }
  return r;
}

// ---- Loading the module --------------------------------------------------------

// Node's fs by a computed name, so that bundlers for the browser leave it alone.
const nodeFs = 'node:fs/promises';

/**
 * Compiles the wasm binary at `url` (wqmesh.wasm, the binary of wqmesh.mjs,
 * beside it): in Node from the file; elsewhere with
 * WebAssembly.compileStreaming when the server says application/wasm, which
 * lets Chromium keep the optimized code in its code cache and reuse it on
 * the next page load, as long as the HTTP cache may keep the file (no
 * `Cache-Control: no-store`). Rejects with a WqmeshError `internal` naming
 * the file when it is missing or not wasm.
 */
export async function compileWasm(url) {
  const at = new URL(url);
  try {
    if (at.protocol === 'file:') {
      const { readFile } = await import(nodeFs);
      return await WebAssembly.compile(await readFile(at));
    }
    const response = await fetch(at, { credentials: 'same-origin' });
    if (!response.ok) throw new Error(`HTTP ${response.status}`);
    if (typeof WebAssembly.compileStreaming === 'function' && /^application\/wasm\b/.test(response.headers.get('Content-Type') ?? ''))
      return await WebAssembly.compileStreaming(response);
    return await WebAssembly.compile(await response.arrayBuffer());
  } catch (e) {
    throw new WqmeshError('internal', `wqmesh: cannot load the wasm binary ${at} ` +
                                      `(in a checkout: bash scripts/build.sh wasm): ${e.message}`, { cause: e });
  }
}

/**
 * Instantiates the Emscripten factory (wqmesh.mjs's default export) on the
 * compiled module `wasm` (compileWasm), so that every instance of one
 * package (the calling thread's and each worker's) runs the same compiled
 * code, and V8 compiles and optimizes it once. The glue holds no binary of
 * its own (linked without SINGLE_FILE): a `wasm` that is not its binary
 * (another build's, with other imports or exports) is a WqmeshError
 * `internal`, as is a missing one.
 */
export async function instantiateModule(factory, wasm) {
  if (!(wasm instanceof WebAssembly.Module))
    throw new WqmeshError('internal', 'wqmesh: no compiled wasm binary to instantiate the module on');
  try {
    return await new Promise((resolve, reject) => {
      factory({
        instantiateWasm(imports, receive) {
          WebAssembly.instantiate(wasm, imports).then((instance) => {
            try {
              receive(instance, wasm);
            } catch (e) {
              reject(e);  // a binary without this glue's exports
            }
          }, reject);
          return {};
        },
      }).then(resolve, reject);
    });
  } catch (e) {
    throw new WqmeshError('internal', `wqmesh: the wasm binary is not the one of this module's glue ` +
                                      `(another build's? rebuild: bash scripts/build.sh wasm): ${e?.message ?? e}`, { cause: e });
  }
}
