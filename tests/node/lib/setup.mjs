// The set-up the tests in tests/node share: the checkout's root, the native command line, the wasm module to load and temporary work folders.
// SPDX-License-Identifier: GPL-3.0-or-later
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { after } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { loadWqmesh } from '../../../wasm/index.mjs';

/** The checkout's root folder. */
export const root = resolve(dirname(fileURLToPath(import.meta.url)), '../../..');
/** The native command line: WQMESH_CLI, else the native build's. */
export const cli = process.env.WQMESH_CLI ?? join(root, 'build/native/bin/wqmesh');
/** A test's skip reason when the native command line is missing, else false. */
export const skipCli = !existsSync(cli) && 'the native build is missing';

/**
 * The path of the wasm glue to load: WQMESH_MODULE, else build/wasm's glue when `build` is set, else undefined
 * (loadWqmesh then takes the package's own copy beside wasm/index.mjs).
 */
export function modulePath({ build = false } = {}) {
  const path = process.env.WQMESH_MODULE ?? (build ? join(root, 'build/wasm/wasm/wqmesh.mjs') : undefined);
  return path === undefined ? undefined : resolve(path);
}

/** modulePath()'s file as a URL, for loadWqmesh's moduleUrl. */
export function moduleUrl(options) {
  const path = modulePath(options);
  return path === undefined ? undefined : pathToFileURL(path);
}

/** The wasm module loaded from moduleUrl(options). */
export const loadModule = (options) => loadWqmesh({ moduleUrl: moduleUrl(options) });

/** A new temporary folder named wqmesh-NAME-..., removed after the file's tests. */
export function workDir(name) {
  const work = mkdtempSync(join(tmpdir(), `wqmesh-${name}-`));
  after(() => rmSync(work, { recursive: true, force: true }));
  return work;
}
