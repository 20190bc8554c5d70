// wqmesh: the hand-written TypeScript types (wasm/index.d.ts) compile, under
// `tsc --noEmit --strict`, against typical uses (tests/node/types_check.ts).
// Skipped when TypeScript is not installed (npm ci installs it).
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const tsc = join(root, 'node_modules/typescript/bin/tsc');

test('index.d.ts compiles with tsc --strict', { skip: !existsSync(tsc) && 'typescript is not installed' }, () => {
  const r = spawnSync(process.execPath, [tsc, '--noEmit', '--strict', '--target', 'es2022', '--module', 'es2022',
    '--moduleResolution', 'node', join(root, 'tests/node/types_check.ts')], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stdout + r.stderr);
});
