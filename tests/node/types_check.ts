// wqmesh: compiled by tests/node/types.test.mjs with `tsc --noEmit --strict`
// to check the hand-written wasm/index.d.ts against typical uses.
// SPDX-License-Identifier: GPL-3.0-or-later
import loadWqmesh, {
  CheckReport, MeshResult, Progress, Wqmesh, WqmeshError, check, checkSync, defaultOptions, mesh, meshSync,
  options, ready, version, writeMedit, writeTetgen, writeVtu, writeVtuSync,
} from '../../wasm/index.js';

async function useAsync(bytes: Uint8Array, text: string): Promise<number> {
  const report: CheckReport = await check(bytes, { boxMargin: 0.5 }, { signal: new AbortController().signal });
  if (!report.valid) return report.error.message.length;
  const controller = new AbortController();
  const fractions: number[] = [];
  let result: MeshResult;
  try {
    result = await mesh(text, { rho: 2.2, sliverAngle: 3, pump: true, maxVertices: 100000, maxSize: 0 }, {
      signal: controller.signal,
      onProgress: (p: Progress) => { fractions.push(p.fraction + p.vertices + p.steps + p.phase.length); },
    });
  } catch (e) {
    if (e instanceof WqmeshError) return e.code.length + e.kind.length;
    throw e;
  }
  const vtu: string = await writeVtu(result);
  const bytesOut: Uint8Array = await writeMedit(result, { bytes: true });
  const tetgen = await writeTetgen(result);
  const edge: string = tetgen.edge;
  const names: string[] = options.map((o) => o.name + (o.flag ?? ''));
  const rho: number = defaultOptions.rho;
  return vtu.length + bytesOut.length + edge.length + names.length + rho + result.radiusEdge.length +
         result.protectingBalls.length + result.memory.liveBytes + version.length + fractions.length;
}

async function useSync(bytes: Uint8Array): Promise<number> {
  await ready();
  const r: MeshResult = meshSync(bytes, { maxMemoryBytes: 2 ** 30 }, { onProgress: (p) => p.fraction < 1 });
  const s: CheckReport = checkSync(bytes);
  const vtu: string = writeVtuSync(r);
  const w: Wqmesh = await loadWqmesh();
  const legacy: MeshResult = w.mesh(bytes, {
    rho: 2.2,
    onProgress: (phase: string, fraction: number, vertices: number) => fraction < 1 && phase !== '' && vertices >= 0,
  });
  const bins: number = legacy.stats.dihedral_bins['0-3'] + legacy.stats.radius_edge_bins['>2.2'];
  const peak: number = legacy.stats.peak_memory_mb ?? 0;
  return bins + peak + vtu.length + (s.valid ? 1 : 0) + w.checkJson(bytes, { pretty: true }).length + w.version().length;
}

export { useAsync, useSync };
