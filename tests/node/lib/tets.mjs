// wqmesh: a check the Node and browser tests share: the signed volumes of a
// mesh's tets (vertices: x, y, z per vertex; tets: four indices per tet).
// SPDX-License-Identifier: GPL-3.0-or-later

/**
 * The sum of the tets' signed volumes, the smallest one and the index of the
 * first tet that is not positively oriented (-1 when every one is).
 */
export function tetVolumes(v, t) {
  let total = 0;
  let smallest = Infinity;
  let firstBad = -1;
  for (let i = 0; i < t.length; i += 4) {
    const p = [0, 1, 2, 3].map((k) => [v[3 * t[i + k]], v[3 * t[i + k] + 1], v[3 * t[i + k] + 2]]);
    const a = [0, 1, 2].map((c) => p[1][c] - p[0][c]);
    const b = [0, 1, 2].map((c) => p[2][c] - p[0][c]);
    const d = [0, 1, 2].map((c) => p[3][c] - p[0][c]);
    const o = (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
               a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
    if (!(o > 0) && firstBad < 0) firstBad = i / 4;
    total += o;
    smallest = Math.min(smallest, o);
  }
  return { total, smallest, firstBad };
}
