// wqmesh page: the rows of the numbers table (keys of the stats of a run, as
// `wqmesh mesh --stats` writes them; see wasm/index.d.ts, MeshStats) and how
// the page formats each value. Every shown value carries data-stat="KEY"
// with this text, so tests compare it with formatStat of the package's result.
// Pure functions: no DOM.
// SPDX-License-Identifier: GPL-3.0-or-later

/** Groups of rows: [group title, [[key, label], ...]]. Nested keys use dots. */
export const STAT_GROUPS = [
  ['Counts', [
    ['vertices', 'vertices'], ['tets', 'tets'], ['min_dihedral_deg', 'smallest dihedral (deg)'],
    ['slivers', 'slivers'], ['skinny', 'skinny'], ['near_small_angle', 'near a small angle'],
    ['near_small_angle_share', 'share near a small angle'],
    ['violations', 'violations'], ['pumped_vertices', 'pumped vertices'], ['conforming', 'conforming'],
    ['stopped', 'stopped'], ['volume_input', 'volume of the input'], ['volume_mesh', 'volume of the mesh'],
  ]],
  ['Table 2 (paper): input and output', [
    ['input_points', 'input points'], ['sharp_elements', 'sharp elements'], ['points_inserted', 'points inserted'],
    ['radius_edge_bins.0.6-1.4', 'tets with R/l 0.6-1.4'], ['radius_edge_bins.1.4-2.2', 'R/l 1.4-2.2'],
    ['radius_edge_bins.>2.2', 'R/l > 2.2'], ['dihedral_bins.0-3', 'tets, min dihedral 0-3 deg'],
    ['dihedral_bins.3-5', 'min dihedral 3-5 deg'], ['dihedral_bins.5-10', 'min dihedral 5-10 deg'],
  ]],
  ['Weighted view (orthoradius with PUMP\'s weights; no class uses it)', [
    ['orthoradius_edge_bins.0.6-1.4', 'tets with orthoradius/l 0.6-1.4'],
    ['orthoradius_edge_bins.1.4-2.2', 'orthoradius/l 1.4-2.2'], ['orthoradius_edge_bins.>2.2', 'orthoradius/l > 2.2'],
    ['orthoradius_edge_bins.<0.6', 'orthoradius/l < 0.6'],
  ]],
  ['Before the improvement phase (the counts above are after it)', [
    ['improve.skinny_before', 'skinny'], ['improve.slivers_before', 'slivers'],
    ['improve.near_small_angle_before', 'near a small angle'], ['improve.violations_before', 'violations'],
    ['improve.near_small_angle_share_before', 'share near a small angle'],
    ['improve.min_dihedral_before', 'smallest dihedral (deg)'],
  ]],
  ['Table 1 (paper): effect of sliver exudation', [
    ['slivers_before_pump', 'slivers after QMESH'], ['slivers', 'slivers after WQMESH'],
  ]],
  ['Time', [
    ['time_s', 'time (s)'], ['tets_per_second', 'tets per second'], ['peak_memory_mb', 'peak memory (MB)'],
  ]],
];

/** The value of a (possibly dotted) key; the first dot splits, bin names keep theirs. */
export function statValue(stats, key) {
  if (!stats) return undefined;
  if (key in stats) return stats[key];
  const i = key.indexOf('.');
  if (i < 0) return undefined;
  const sub = stats[key.slice(0, i)];
  return sub ? sub[key.slice(i + 1)] : undefined;
}

/** The text the page shows for a value. */
export function formatStat(key, v) {
  if (v === undefined || v === null) return '–';
  if (key === 'stopped') return v ? String(v) : 'no';
  if (typeof v === 'boolean') return v ? 'yes' : 'no';
  if (typeof v !== 'number') return String(v);
  if (key === 'min_dihedral_deg') return v.toFixed(2);
  if (key === 'time_s') return v.toFixed(2);
  if (key === 'peak_memory_mb') return v.toFixed(1);
  if (key === 'tets_per_second') return String(Math.round(v));
  if (key.startsWith('volume')) return v.toPrecision(6);
  return Number.isInteger(v) ? String(v) : v.toPrecision(4);
}
