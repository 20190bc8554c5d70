// wqmesh: the test environment itself. The Node tests of ../shared/models skip
// when that folder is absent; under CI (the environment variable CI set to
// anything but '', 'false' or '0') it must be there, since a skip would hide
// those tests.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { existsSync, readdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const shared = join(root, '../shared/models');
const ci = process.env.CI !== undefined && !['', 'false', '0'].includes(process.env.CI);
const present = existsSync(shared) && readdirSync(shared).some((n) => /\.(off|stl)$/i.test(n));

test('../shared/models is present under CI', { skip: !ci && !present && '../shared/models is absent' }, () => {
  assert.ok(present, `CI is set but ${shared} is missing or holds no model: the tests that read it would all skip`);
});
