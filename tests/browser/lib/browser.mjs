// wqmesh: the browser of the browser tests: Debian's Chromium
// (/usr/bin/chromium, or $WQMESH_CHROMIUM) driven by playwright-core, headless,
// with a fresh profile (--user-data-dir in a new temporary folder, removed on
// close), recording every console message (pages and workers), page error,
// request and failed request.
//   const b = await launchBrowser();
//   await b.page.goto(url); ... b.consoleMessages, b.requests, b.pageErrors
//   await b.close();
// `browserSkipReason()` says why the tests cannot run here ('' when they can):
// with env CI set, a missing browser is an error instead (see the README).
// SPDX-License-Identifier: GPL-3.0-or-later
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export const CHROMIUM = process.env.WQMESH_CHROMIUM || '/usr/bin/chromium';

// The flags of the toolchain notes: headless, no sandbox (root in a
// container), nothing that reaches the network on its own.
export const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
                              '--disable-component-update', '--disable-sync', '--no-first-run'];

function playwrightInstalled() {
  try {
    createRequire(import.meta.url).resolve('playwright-core');
    return true;
  } catch {
    return false;
  }
}

/** '' when Chromium and playwright-core are there, else why not (a test's skip reason). */
export function browserSkipReason() {
  let reason = '';
  if (!existsSync(CHROMIUM)) reason = `${CHROMIUM} is missing (Debian package chromium; scripts/setup.sh installs it)`;
  else if (!playwrightInstalled()) reason = 'playwright-core is not installed (npm ci)';
  if (reason && process.env.CI) throw new Error(`browser tests cannot run under CI: ${reason}`);
  return reason;
}

/**
 * Launches Chromium with a fresh profile and opens one page. Returns
 * { context, page, consoleMessages, pageErrors, requests, failedRequests,
 *   newPage(), close() }: consoleMessages holds { type, text, where } from
 * pages and their workers ('page' or 'worker: URL'), requests { method, url,
 * resourceType }, failedRequests { url, error }.
 */
export async function launchBrowser({ timeout = 60000 } = {}) {
  const { chromium } = await import('playwright-core');
  const profile = mkdtempSync(join(tmpdir(), 'wqmesh-chromium-'));
  let context;
  try {
    context = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM,
      headless: true,
      args: CHROMIUM_ARGS,
      timeout,
    });
  } catch (e) {
    rmSync(profile, { recursive: true, force: true });
    throw e;
  }
  const record = {
    context,
    consoleMessages: [],
    pageErrors: [],
    requests: [],
    failedRequests: [],
  };
  const watch = (page) => {
    page.on('console', (m) => record.consoleMessages.push({ type: m.type(), text: m.text(), where: 'page' }));
    page.on('pageerror', (e) => record.pageErrors.push(String(e?.message ?? e)));
    page.on('request', (r) => record.requests.push({ method: r.method(), url: r.url(), resourceType: r.resourceType() }));
    page.on('requestfailed', (r) => record.failedRequests.push({ url: r.url(), error: r.failure()?.errorText ?? '' }));
    page.on('worker', (w) => {
      w.on('console', (m) => record.consoleMessages.push({ type: m.type(), text: m.text(), where: `worker: ${w.url()}` }));
    });
    page.setDefaultTimeout(timeout);
    return page;
  };
  context.on('page', watch);
  record.page = context.pages()[0] ? watch(context.pages()[0]) : await context.newPage();
  record.newPage = () => context.newPage();
  record.close = async () => {
    try {
      await context.close();
    } finally {
      rmSync(profile, { recursive: true, force: true });
    }
  };
  return record;
}
