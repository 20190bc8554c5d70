// wqmesh: types of the package entry (wasm/index.mjs), written by hand.
// SPDX-License-Identifier: GPL-3.0-or-later

/**
 * The bytes of an input file (OFF or STL, ASCII or binary; the format is
 * decided by content). A string is encoded as UTF-8 first.
 */
export type WqmeshInput = Uint8Array | ArrayBuffer | ArrayBufferView | string;

/** The stable names of the reasons why an input is rejected. */
export type InputErrorKind =
  | 'io'
  | 'empty'
  | 'syntax'
  | 'truncated'
  | 'too_large'
  | 'non_finite'
  | 'bad_index'
  | 'too_few_faces'
  | 'degenerate_face'
  | 'duplicate_face'
  | 'open_boundary'
  | 'non_manifold_edge'
  | 'non_manifold_vertex'
  | 'not_orientable'
  | 'self_intersection'
  | 'zero_volume'
  /** A failure that is not about the input (a bug): please report it. */
  | 'internal';

/** Why an input was rejected. */
export interface InputErrorReport {
  /** What kind of defect, e.g. `"open_boundary"`. */
  kind: InputErrorKind;
  /** A sentence that names the defect and where it is (line, face, edge, vertex). */
  message: string;
}

/** What reading and merging did: counts as read and after building the PLC. */
export interface MergeReport {
  /** Points in the file. */
  points_read: number;
  /** Vertices after merging identical points. */
  vertices: number;
  /** Faces (polygons or triangles) in the file. */
  faces_read: number;
  /** Facets of the PLC, after merging adjacent exactly coplanar faces. */
  facets: number;
  /** Edges of the input polygons. */
  edges_before: number;
  /** Input edges of the PLC, after joining exactly collinear chains. */
  edges: number;
  /** Vertices dropped because they lie inside a facet or an edge. */
  vertices_removed: number;
  /** Non-planar polygons split into triangles. */
  faces_split: number;
  /** Faces whose orientation was reversed to make the surface point outwards. */
  faces_flipped: number;
}

/** Sizes of the piecewise linear complex (PLC) built from the input. */
export interface PlcCounts {
  /** Input vertices. */
  vertices: number;
  /** Input edges. */
  edges: number;
  /** Facets (planar polygons, possibly with holes). */
  facets: number;
  /** Holes in facets, over all facets. */
  holes: number;
}

/** An axis-aligned box. */
export interface BoxReport {
  /** The smallest corner, [x, y, z]. */
  lo: [number, number, number];
  /** The largest corner, [x, y, z]. */
  hi: [number, number, number];
}

/** The local feature size f(u) at a sharp vertex u. */
export interface LocalFeatureSize {
  /** The sharp vertex (PLC vertex index). */
  vertex: number;
  /** Distance from u to the nearest input element not containing u. */
  f: number;
}

/** The dihedral angles at one input edge. */
export interface DihedralReport {
  /** The input edge (PLC edge index). */
  edge: number;
  /** Angle inside the polyhedron, degrees, in (0, 360). */
  internal: number;
  /** 360 minus the internal angle, degrees. */
  external: number;
  /** Whether the internal or the external angle is acute (decided exactly). */
  sharp: boolean;
}

/** The angle between two input edges at a common vertex. */
export interface EdgeEdgeReport {
  /** The common vertex (PLC vertex index). */
  vertex: number;
  /** The first edge (PLC edge index). */
  edge1: number;
  /** The second edge (PLC edge index). */
  edge2: number;
  /** The angle in degrees. */
  degrees: number;
  /** Whether the angle is acute (decided exactly; a right angle is not). */
  acute: boolean;
}

/** The angle between an edge and a facet that meet at a vertex. */
export interface EdgeFacetReport {
  /** The common vertex (PLC vertex index). */
  vertex: number;
  /** The edge, which is neither an edge of the facet nor in its plane. */
  edge: number;
  /** The facet (PLC facet index). */
  facet: number;
  /** The angle in degrees. */
  degrees: number;
  /** Whether the angle is acute (decided exactly). */
  acute: boolean;
}

/** The input analysis: angles, sharp elements, local feature sizes, boxes. */
export interface AnalysisReport {
  /** How many of each element the lists below hold. */
  counts: {
    /** Sharp vertices. */
    sharp_vertices: number;
    /** Sharp edges. */
    sharp_edges: number;
    /** Edge-edge angles. */
    edge_edge_angles: number;
    /** Acute edge-edge angles. */
    acute_edge_edge_angles: number;
    /** Edge-facet angles. */
    edge_facet_angles: number;
    /** Acute edge-facet angles. */
    acute_edge_facet_angles: number;
    /** Dihedral angles (one per input edge). */
    dihedral_angles: number;
  };
  /** The smallest input angle, degrees. */
  phi_m_degrees: number;
  /** Sharp vertices (PLC vertex indices), increasing. */
  sharp_vertices: number[];
  /** Sharp edges (PLC edge indices), increasing. */
  sharp_edges: number[];
  /** f(u) for each sharp vertex, in the order of `sharp_vertices`. */
  lfs: LocalFeatureSize[];
  /** The dihedral angles, one per input edge. */
  dihedral: DihedralReport[];
  /** The edge-edge angles. */
  edge_edge: EdgeEdgeReport[];
  /** The edge-facet angles. */
  edge_facet: EdgeFacetReport[];
  /** The bounding box of the input. */
  input_box: BoxReport;
  /** The box B that encloses the input, grown by `box_margin`. */
  bounding_box: BoxReport;
  /** The margin of B, as a fraction of the input's largest extent. */
  box_margin: number;
}

/** The report for an input that was read, validated and analysed. */
export interface ValidReport {
  /** The input can be meshed. */
  valid: true;
  /** The format read: `"OFF"`, `"STL-ascii"` or `"STL-binary"`. */
  format: string;
  /** Repairs made while reading (e.g. orientation fixed), one sentence each. */
  warnings: string[];
  /** What reading and merging did. */
  merge: MergeReport;
  /** Sizes of the PLC. */
  plc: PlcCounts;
  /** Angles, sharp elements and local feature sizes. */
  analysis: AnalysisReport;
}

/** The report for an input that was rejected. */
export interface InvalidReport {
  /** The input cannot be meshed. */
  valid: false;
  /** The format, when the file could be read. */
  format?: string;
  /** Warnings collected before the error, one sentence each. */
  warnings?: string[];
  /** Why the input was rejected. */
  error: InputErrorReport;
}

/** The report of {@link Wqmesh.check}: tell the two apart by `valid`. */
export type CheckReport = ValidReport | InvalidReport;

/** Options of {@link Wqmesh.check}. */
export interface CheckOptions {}

/** Options of {@link Wqmesh.mesh}; every one is optional. */
export interface MeshOptions {
  /** rho0 of rule 6, in [1, 1e6] (default 2.2; the proof needs above 3.41). */
  rho?: number;
  /** theta of rule 7 and PUMP in degrees, in [0, 90] (default 3). */
  sliverAngle?: number;
  /** false: QMESH alone, no rule 7 and no PUMP (default true). */
  pump?: boolean;
  /**
   * The run stops with `stopped: "limit"` at this many vertices, in [8, 1e9]
   * (default 1000000). A limit below the vertices INITIALIZE alone inserts
   * (the input vertices, the box corners and the vertex-ball points, known in
   * advance) is refused before meshing, with `stopped: "limit"`.
   */
  maxVertices?: number;
  /**
   * Tets with a larger circumradius are split, finite, at least 0 (default 0:
   * no bound); next to sharp vertices the bound is the vertex ball's radius
   * f(u)/4 when that is larger.
   */
  maxSize?: number;
  /** Margin of the bounding box B, a fraction of the largest extent, in [0.001, 1000] (default 0.5). */
  boxMargin?: number;
  /**
   * The most bytes of wasm memory the call's C++ allocations may hold at once,
   * in [65536, 4294967296] (default 3221225472, 3 GiB). A run that goes
   * beyond it stops (reading the input and making the output arrays refuse
   * the allocation at once; the mesher stops at its next progress call, within
   * 256 insertions) and {@link Wqmesh.mesh} throws an Error of kind `"limit"`
   * naming the phase and the vertex count reached; its memory is freed and the
   * module stays usable. The module's memory grows up to 4 GB (or less where
   * the browser gives less): a run that needs more throws the same `"limit"`
   * error. `stats.peak_memory_mb` tells what a finished run held at most.
   */
  maxMemoryBytes?: number;
  /**
   * Called after a bounded amount of work with the phase ("initialize",
   * "conform", "refine", "pump"), an estimated fraction of the run in [0, 1]
   * and the vertex count; returning false cancels the run.
   */
  onProgress?: (phase: string, fraction: number, vertices: number) => boolean | void;
}

/** The statistics of a run, as `wqmesh mesh --stats` writes them. */
export interface MeshStats {
  input_points: number;
  sharp_elements: number;
  points_inserted: number;
  vertices: number;
  tets: number;
  min_dihedral_deg: number;
  radius_edge_bins: { '0.6-1.4': number; '1.4-2.2': number; '>2.2': number };
  dihedral_bins: { '0-3': number; '3-5': number; '5-10': number };
  slivers: number;
  skinny: number;
  near_small_angle: number;
  violations: number;
  slivers_before_pump: number;
  pumped_vertices: number;
  volume_input: number;
  volume_mesh: number;
  conforming: boolean;
  /** "" when done, "limit" or "cancelled". */
  stopped: '' | 'limit' | 'cancelled';
  /** Why the run stopped, in words (present only when it stopped): the phase
   * that reached the vertex limit, or the two input edges whose small angle
   * needs more vertices than the limit (then the run stops before meshing). */
  stop_message?: string;
  time_s: number;
  tets_per_second: number;
  rule_points: number[];
  phases: { name: string; time_s: number; points_inserted: number }[];
  protecting_balls: { center: [number, number, number]; radius: number; vertex_ball: boolean }[];
  /**
   * Memory, megabytes: the command line's peak resident set; the wasm
   * module's peak of the call's live C++ allocations (compare with
   * {@link MeshOptions.maxMemoryBytes}).
   */
  peak_memory_mb?: number;
  /** Every violation (up to 1000): tet index, its vertex indices, kind, quality. */
  violation_tets: {
    tet: number;
    vertices: [number, number, number, number];
    kind: 'skinny' | 'sliver';
    min_dihedral_deg: number;
    radius_edge: number;
  }[];
}

/** A mesh made by {@link Wqmesh.mesh}: copies, safe to keep and transfer. */
export interface MeshResult {
  stats: MeshStats;
  /** x, y, z per vertex; the input vertices come first, in their order. */
  vertices: Float64Array;
  /** The weight (a squared radius) of each vertex; 0 where not pumped. */
  weights: Float64Array;
  /** Four vertex indices per tet, positively oriented. */
  tets: Uint32Array;
  /** Three vertex indices per boundary triangle, oriented outwards. */
  boundary: Uint32Array;
  /** The input facet of each boundary triangle. */
  boundaryFacet: Int32Array;
  /** Per tet: 0 good, 1 skinny near a small angle, 2 sliver near a small angle, 3 violation. */
  tetClass: Uint8Array;
  /** Per tet: its smallest dihedral angle in degrees. */
  minDihedral: Float64Array;
}

/** Options of {@link Wqmesh.checkJson}. */
export interface CheckJsonOptions extends CheckOptions {
  /** Indent the JSON with two spaces (default: one line). */
  pretty?: boolean;
}

/** The loaded wasm module. */
export interface Wqmesh {
  /**
   * Reads, validates and analyses a polyhedron. Never throws for bad input:
   * a broken file gives `{ valid: false, error: { kind, message } }`.
   * @param bytes - The file's bytes (OFF or STL, decided by content).
   * @param options - Reserved for later options.
   * @returns The parsed report, the same as `wqmesh check FILE` prints.
   * @throws TypeError when `bytes` is not bytes or a string.
   */
  check(bytes: WqmeshInput, options?: CheckOptions): CheckReport;

  /**
   * Like {@link Wqmesh.check}, but returns the report as JSON text, exactly
   * as the native command line prints it.
   * @param bytes - The file's bytes (OFF or STL, decided by content).
   * @param options - `pretty` indents the JSON.
   * @returns The JSON report.
   * @throws TypeError when `bytes` is not bytes or a string.
   */
  checkJson(bytes: WqmeshInput, options?: CheckJsonOptions): string;

  /**
   * Meshes a polyhedron with WQMESH (INITIALIZE, CONFORM, REFINE, PUMP).
   * @param bytes The OFF or STL file's bytes.
   * @param options See {@link MeshOptions}.
   * @returns The mesh of the interior, its classes and statistics.
   * @throws Error with a `kind`: an input error kind (as in {@link InputErrorKind};
   *   "too_large" for more than 1 GiB of input or more points or faces than
   *   the readers accept), "options" (an option out of its range), "limit"
   *   (the run needs more memory than `maxMemoryBytes` or the wasm memory
   *   holds; the module stays usable) or "internal".
   */
  mesh(bytes: WqmeshInput, options?: MeshOptions): MeshResult;

  /**
   * The version of the wasm module, e.g. `"0.1.0"`.
   * @returns The version string.
   */
  version(): string;
}

/** Options of {@link loadWqmesh}. */
export interface LoadOptions {
  /**
   * Where the Emscripten module (`wqmesh.mjs`) is. Default: the build tree,
   * `build/wasm/wasm/wqmesh.mjs` next to this package's `wasm/` folder.
   */
  moduleUrl?: string | URL;
}

/**
 * Loads and instantiates the wasm module. The module is loaded once per URL:
 * later calls return the same object.
 * @param options - Where the module is, if not in the build tree.
 * @returns The module's functions.
 * @throws Error (the promise rejects) when the module is not built or fails to load.
 */
export function loadWqmesh(options?: LoadOptions): Promise<Wqmesh>;

export default loadWqmesh;
