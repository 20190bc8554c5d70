// wqmesh: the one list of input error kinds, read from its C++ source
// (core/include/wqmesh/error.h, enum class InputErrorKind; names.cpp's
// all_error_kinds() lists the same enumerators, checked by
// tests/native/facade_test.cpp), and the unions of wasm/index.d.ts, so the
// tests compare every other list with it instead of keeping a copy.
// SPDX-License-Identifier: GPL-3.0-or-later
import { readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../../..');

/** The enumerators of InputErrorKind in error.h, in order (their names are the stable strings). */
export function errorKinds() {
  const header = readFileSync(join(root, 'core/include/wqmesh/error.h'), 'utf8');
  const body = /enum class InputErrorKind\s*\{([^}]*)\}/.exec(header);
  if (!body) throw new Error('error.h: enum class InputErrorKind not found');
  const names = body[1].replace(/\/\/[^\n]*/g, '').split(',').map((s) => s.trim()).filter(Boolean);
  for (const n of names) if (!/^[a-z_]+$/.test(n)) throw new Error(`error.h: unexpected enumerator '${n}'`);
  return names;
}

/** The string members of `export type NAME = 'a' | 'b' ...;` in wasm/index.d.ts (comments dropped). */
export function dtsUnion(name) {
  const dts = readFileSync(join(root, 'wasm/index.d.ts'), 'utf8');
  const m = new RegExp(`export type ${name}\\s*=([^;]*);`).exec(dts);
  if (!m) throw new Error(`index.d.ts: type ${name} not found`);
  const text = m[1].replace(/\/\*[\s\S]*?\*\//g, '').replace(/\/\/[^\n]*/g, '');
  return [...text.matchAll(/'([^']*)'/g)].map((x) => x[1]);
}

/** The version of project(wqmesh VERSION x.y.z) in CMakeLists.txt. */
export function cmakeVersion() {
  const m = /project\(\s*wqmesh\s+VERSION\s+([0-9.]+)/.exec(readFileSync(join(root, 'CMakeLists.txt'), 'utf8'));
  if (!m) throw new Error('CMakeLists.txt: project(wqmesh VERSION ...) not found');
  return m[1];
}
