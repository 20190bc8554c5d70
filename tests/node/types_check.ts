// wqmesh: compiled by tests/node/types.test.mjs with `tsc --noEmit --strict`
// to check the hand-written wasm/index.d.ts against typical uses.
// SPDX-License-Identifier: GPL-3.0-or-later
import loadWqmesh, { CheckReport, MeshResult, Wqmesh } from '../../wasm/index.js';

async function use(bytes: Uint8Array): Promise<number> {
  const w: Wqmesh = await loadWqmesh();
  const report: CheckReport = w.check(bytes);
  if (!report.valid) return report.error.message.length;
  const mesh: MeshResult = w.mesh(bytes, {
    rho: 2.2,
    sliverAngle: 3,
    pump: true,
    maxVertices: 100000,
    maxMemoryBytes: 2 ** 30,
    onProgress: (phase: string, fraction: number, vertices: number) => fraction < 1 && phase !== '' && vertices >= 0,
  });
  const bins: number = mesh.stats.dihedral_bins['0-3'] + mesh.stats.radius_edge_bins['>2.2'];
  const peak: number = mesh.stats.peak_memory_mb ?? 0;
  return bins + peak + mesh.tets.length + mesh.vertices.length + mesh.tetClass.length + w.version().length;
}

export default use;
