// wqmesh: types of the package entry (wasm/index.mjs), written by hand and
// checked with `tsc --noEmit --strict` (tests/node/types.test.mjs compiles
// tests/node/types_check.ts against them).
// SPDX-License-Identifier: GPL-3.0-or-later

/**
 * An input polyhedron: the file's bytes (Uint8Array, Node's Buffer,
 * ArrayBuffer, or any typed array or DataView, read as its bytes), or the
 * text of an OFF or STL file. The format (OFF, ASCII STL, binary STL) is
 * decided by content, never by a name. A string that looks like a file name
 * or a path (one line, no white space, with a dot or a slash), and anything
 * else, is refused with a TypeError saying what was expected: read the file
 * first.
 */
export type WqmeshInput = Uint8Array | ArrayBuffer | ArrayBufferView | string;

/**
 * The stable names of the reasons why an input is rejected: the enumerators of
 * InputErrorKind in core/include/wqmesh/error.h, in order (checked by
 * tests/node/names.test.mjs), and `internal`.
 */
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
  /** Coordinates, extent, bounding box or volume beyond what double precision holds once scaled. */
  | 'out_of_range'
  /** A failure that is not about the input (a bug): please report it. */
  | 'internal';

/**
 * The stable `code` of a {@link WqmeshError}: an input error kind, `options`
 * (an unknown option, a value of the wrong type or out of its range),
 * `limit` (the run needs more memory than `maxMemoryBytes` or the wasm
 * memory holds) or `internal`.
 */
export type WqmeshErrorCode = InputErrorKind | 'options' | 'limit';

/**
 * The one error class of the package, thrown (or rejected with) for bad
 * input, bad options, a memory limit and internal failures; never for a run
 * stopped at its vertex limit (that is a result with `stats.stopped`).
 * Bad argument types are a TypeError, an abort a DOMException named
 * `AbortError`.
 */
export class WqmeshError extends Error {
  constructor(code: WqmeshErrorCode, message: string, options?: { cause?: unknown });
  /** Always `"WqmeshError"`. */
  readonly name: 'WqmeshError';
  /** Stable: what went wrong, e.g. `"open_boundary"` or `"options"`. */
  readonly code: WqmeshErrorCode;
  /** The same as {@link WqmeshError.code} (the name earlier versions used). */
  readonly kind: WqmeshErrorCode;
}

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

/**
 * Sizes of the piecewise linear complex (PLC) built from the input, and the
 * coordinates of its sharp elements (so that a reader can draw them).
 */
export interface PlcCounts {
  /** Input vertices. */
  vertices: number;
  /** Input edges. */
  edges: number;
  /** Facets (planar polygons, possibly with holes). */
  facets: number;
  /** Holes in facets, over all facets. */
  holes: number;
  /**
   * The coordinates [x, y, z] of each sharp vertex (paper, section 2), in the
   * order of `analysis.sharp_vertices`.
   */
  sharp_vertex_points: [number, number, number][];
  /**
   * The two endpoints of each sharp edge (its PLC vertices a then b), in the
   * order of `analysis.sharp_edges`.
   */
  sharp_edge_points: [[number, number, number], [number, number, number]][];
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

/**
 * Options of {@link check}: those of the option table marked for `check`.
 * Every one is optional; unknown names are a {@link WqmeshError} `options`.
 */
export interface CheckOptions {
  /** Margin of the bounding box B, a fraction of the input's largest extent, in [0.001, 1000] (default 0.5). */
  boxMargin?: number;
}

/**
 * Options of {@link mesh}, checked by the module against the option table it
 * shares with the native command line (`wqmesh mesh --rho ...`; the table is
 * exported as {@link options}): the same names (camelCase here, the flags
 * there), ranges and defaults. Every one is optional; an unknown name, a
 * value of the wrong type or out of range is a {@link WqmeshError} `options`
 * naming the known options or the range.
 */
export interface MeshOptions {
  /** rho0 of rule 6: tets with R/l above it are split; in [1, 1e6] (default 2.2; the proof needs above 3.41). `--rho`. */
  rho?: number;
  /** theta of rule 7 and PUMP, degrees: tets with a dihedral angle at most theta are slivers; in [0, 90] (default 3). `--sliver-angle`. */
  sliverAngle?: number;
  /** false: QMESH alone, no rule 7 and no PUMP (default true). `--no-pump`. */
  pump?: boolean;
  /**
   * Beyond the paper: the improvement phase after PUMP (flips, smoothing of
   * interior Steiner vertices, interior insertion; the boundary stays as it
   * is), which raises the smallest dihedral angle (default true); false: the
   * WQMESH output of the paper. `--no-improve`. See `stats.improve`.
   */
  improve?: boolean;
  /**
   * Beyond the paper: with `improve`, after its passes, a polish that raises
   * the smallest dihedral angle further (flips, smoothing, contraction and
   * slides across slanted facets on the tets of the smallest angles; never
   * more tets, no new tet under 5 degrees), then rounds judged by the
   * smallest dihedral angle itself; slit.off 20.15 -> 30.78 degrees.
   * Default false: it costs 3 to 8 times REFINE + PUMP's time on small
   * models. `--polish`. See `stats.improve.polished`.
   */
  polish?: boolean;
  /**
   * The run stops with `stats.stopped: "limit"` at this many vertices, a
   * whole number in [8, 1e9] (default 1000000). A limit below the vertices
   * INITIALIZE alone inserts (the input vertices, the box corners and the
   * vertex-ball points, known in advance) is refused before meshing, with
   * `stopped: "limit"`. `--max-vertices`.
   */
  maxVertices?: number;
  /**
   * Beyond the paper: tets with a larger circumradius are split; in [0, 1e300]
   * (default 0: no bound); next to sharp vertices the bound is the vertex
   * ball's radius f(u)/4 when that is larger. `--max-size`.
   */
  maxSize?: number;
  /** Margin of the bounding box B, a fraction of the largest extent, in [0.001, 1000] (default 0.5). `--box-margin`. */
  boxMargin?: number;
  /** Also time a plain Delaunay triangulation of the final vertex set: `stats.delaunay_floor_s` (default false). `--measure-floor`. */
  measureFloor?: boolean;
  /**
   * wasm only (no command-line flag): the most bytes of wasm memory the call's
   * C++ allocations may hold at once, in [65536, 4294967296] (default
   * 3221225472, 3 GiB). A run that goes beyond it stops (reading the input
   * and making the output arrays refuse the allocation at once; the mesher
   * stops at its next progress call, within 256 insertions) with a
   * {@link WqmeshError} `limit` naming the phase and the vertex count
   * reached; its memory is freed and the module stays usable. The module's
   * memory grows up to 4 GB (or less where the browser gives less): a run
   * that needs more gets the same `limit` error. `stats.peak_memory_mb`
   * tells what a finished run held at most.
   */
  maxMemoryBytes?: number;
}

/** A phase of a run, in the order they come. */
export type Phase = 'initialize' | 'conform' | 'refine' | 'pump' | 'extract' | 'improve';

/** What {@link MeshControl.onProgress} receives. */
export interface Progress {
  /** The phase the run is in. */
  phase: Phase;
  /** Vertices of the triangulation so far (the bounding box included). */
  vertices: number;
  /** Insertions or pump steps of this phase so far. */
  steps: number;
  /**
   * An estimate of the part of the run done, in [0, 1]; it never goes down
   * from one call to the next (refinement has no known end, so it may stay
   * put for a while).
   */
  fraction: number;
}

/** Progress and cancellation of an async call. */
export interface Control {
  /**
   * Aborting it stops the run at once, whatever phase it is in (the worker
   * is terminated; the next call starts a fresh one), and the promise
   * rejects with a DOMException named `AbortError`. Already aborted: rejects
   * without starting.
   */
  signal?: AbortSignal;
}

/** Progress and cancellation of {@link mesh}. */
export interface MeshControl extends Control {
  /**
   * Called on the calling thread as the run goes, at most every 50 ms and at
   * every phase change. What it returns is ignored (use `signal` to stop).
   */
  onProgress?: (progress: Progress) => void;
}

/** Progress and cancellation of {@link meshSync}. */
export interface MeshSyncControl {
  /**
   * Called after a bounded amount of work (every 256 insertions or pump
   * steps, and at each phase change); returning false cancels the run, which
   * then returns at once with `stats.stopped: "cancelled"` and no mesh (its
   * partial mesh is not extracted).
   */
  onProgress?: (progress: Progress) => boolean | void;
}

/** The statistics of a run: the keys of `wqmesh mesh --stats` (the native command line's JSON). */
export interface MeshStats {
  /** Vertices of the PLC. */
  input_points: number;
  /** Sharp vertices plus sharp edges of the input. */
  sharp_elements: number;
  /** Points the mesher inserted (the bounding box's corners excluded). */
  points_inserted: number;
  /** Vertices of the output mesh (used by interior tets). */
  vertices: number;
  /** Interior tets of the output mesh. */
  tets: number;
  /** The smallest dihedral angle of the mesh, degrees (0 without tets). */
  min_dihedral_deg: number;
  /** The largest R/l (circumradius over shortest edge, unweighted) of the mesh. */
  max_radius_edge: number;
  /**
   * Table 2 of the paper: tets by R/l. Like every statistic and class here
   * (but the `orthoradius_*` keys), on the mesh as written, unweighted: a
   * recount from the written mesh and {@link MeshStats.protecting_balls}
   * gives the same numbers (`wqmesh measure MESH --stats STATS`).
   */
  radius_edge_bins: { '0.6-1.4': number; '1.4-2.2': number; '>2.2': number };
  /** Table 2 of the paper: tets by smallest dihedral angle, degrees. */
  dihedral_bins: { '0-3': number; '3-5': number; '5-10': number };
  /** Tets with R/l at most rho0 and a dihedral angle below theta. */
  slivers: number;
  /** Tets with R/l above rho0. */
  skinny: number;
  /**
   * Skinny tets and slivers near a small input angle (allowed there): the
   * circumcenter on or inside a protecting ball (c, r), or a vertex v with
   * |v - c|^2 <= (2r)^2 + L_v^2/9, L_v its shortest edge in the mesh.
   */
  near_small_angle: number;
  /** Skinny tets and slivers not near a small input angle (class 3). */
  violations: number;
  /** near_small_angle over tets (0 without tets). */
  near_small_angle_share: number;
  /**
   * The weighted view (the paper's own measure for a pumped mesh; no class
   * uses it): tets by orthoradius-edge ratio, with PUMP's weights, in Table
   * 2's bins and below 0.6 (a weighted ratio can be).
   */
  orthoradius_edge_bins: { '<0.6': number; '0.6-1.4': number; '1.4-2.2': number; '>2.2': number };
  /** The largest orthoradius-edge ratio of the mesh (weighted view). */
  max_orthoradius_edge: number;
  /** Tets with orthoradius-edge ratio above rho0 (weighted view; the paper's skinny for a pumped mesh). */
  orthoradius_skinny: number;
  /** Interior slivers at the end of REFINE, before PUMP. */
  slivers_before_pump: number;
  /** Vertices PUMP gave a weight. */
  pumped_vertices: number;
  /** The volume enclosed by the input. */
  volume_input: number;
  /** The sum of the tets' volumes. */
  volume_mesh: number;
  /** Every subsegment and subfacet is in the mesh. */
  conforming: boolean;
  /** "" when done, "limit" (the vertex limit), "cancelled" (meshSync's onProgress returned false) or
   * "stalled" (the stuck-step watchdog: one step of the mesher went past its work budget; or the runaway guard:
   * REFINE's rules 4-5 split the boundary without end, stop_message names the input edge or facet). */
  stopped: '' | 'limit' | 'cancelled' | 'stalled';
  /** Why the run stopped, in words (present only when it stopped): the phase
   * that reached the vertex limit, or the two input edges whose small angle
   * needs more vertices than the limit (then the run stops before meshing). */
  stop_message?: string;
  /** Seconds the run took, reading the input included. */
  time_s: number;
  /** Tets per second of time_s. */
  tets_per_second: number;
  /** |V|, the vertices of the whole triangulation (bounding box and outside included). */
  all_vertices: number;
  /** With `measureFloor`: seconds of a plain Delaunay triangulation of the final vertex set. */
  delaunay_floor_s?: number;
  /** With `measureFloor`: time_s over delaunay_floor_s. */
  ratio_to_delaunay?: number;
  /** The options of the run, as the core names them. */
  options: { rho0: number; theta_deg: number; pump: boolean; box_margin: number; max_vertices: number; max_size: number; improve: boolean; polish: boolean };
  /**
   * Beyond the paper: what the improvement phase did ({@link MeshOptions.improve};
   * `ran` false and every count 0 when it did not run: with `improve: false`, or
   * on a stopped or non-conforming run). Counts of accepted operations, the
   * smallest dihedral angle (degrees) before and after, and the class counts
   * of the mesh before it (the top-level counts are those after).
   */
  improve: {
    ran: boolean;
    passes: number;
    flips23: number;
    flips32: number;
    flips44: number;
    flips22: number;
    edge_removals: number;
    smoothed: number;
    inserted: number;
    /** Steiner vertices removed by edge contraction. */
    contractions: number;
    /** Of `smoothed`, moves of boundary vertices (each along a coordinate axis its facets run along, or in the polish across a facet that runs along one axis only). */
    slid: number;
    /** Of `inserted`, points inserted on a facet (with the facet's coordinate off its axes copied exactly). */
    inserted_on_boundary: number;
    /** Multi-face removals of at least two faces (the inverse of edge removal). */
    multi_face_removals: number;
    /** Of the changes above, those the polish made ({@link MeshOptions.polish}; 0 without it). */
    polished: number;
    min_dihedral_before: number;
    min_dihedral_after: number;
    slivers_before: number;
    skinny_before: number;
    near_small_angle_before: number;
    violations_before: number;
    /** The tets of the mesh before it, and the share of them near a small angle. */
    tets_before: number;
    near_small_angle_share_before: number;
  };
  /** Points inserted by each rule: [0] INITIALIZE, [i] rule i (1..7). */
  rule_points: number[];
  /** How often a named loop cap or work budget of the mesher was reached
   * (rule 3 and rule 7 passes, retries of deferred splits, PUMP's label
   * rounds and critical steps, the ray-parity budget of a stopped run's
   * extraction): 0 on every model measured so far. */
  caps_reached: number;
  /** Time and insertions of each phase. */
  phases: { name: string; time_s: number; points_inserted: number }[];
  /** The protecting balls (also as arrays in {@link MeshResult.protectingBalls}). */
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
    /** The weighted view of the same tet. */
    orthoradius_edge: number;
  }[];
}

/**
 * A mesh made by {@link mesh} or {@link meshSync}. The arrays are the
 * result's own (transferred out of the worker, not copied), safe to keep and
 * to transfer again.
 */
export interface MeshResult {
  /** The statistics, as `wqmesh mesh --stats` writes them. */
  stats: MeshStats;
  /** x, y, z per vertex; the input vertices come first, in their order. */
  vertices: Float64Array;
  /** The weight (a squared radius) of each vertex; 0 where PUMP gave none. */
  weights: Float64Array;
  /** Four vertex indices per tet, positively oriented. */
  tets: Uint32Array;
  /** Three vertex indices per boundary triangle, oriented outwards. */
  boundary: Uint32Array;
  /** The input facet (PLC facet index) of each boundary triangle, -1 where unknown. */
  boundaryFacet: Int32Array;
  /** Per tet: 0 good, 1 skinny near a small angle, 2 sliver near a small angle, 3 violation. */
  tetClass: Uint8Array;
  /** Per tet: its smallest dihedral angle in degrees. */
  minDihedral: Float64Array;
  /** Per tet: R/l, circumradius over shortest edge (unweighted, as the classes). */
  radiusEdge: Float64Array;
  /** Per tet: the orthoradius-edge ratio with {@link MeshResult.weights} (the weighted view). */
  orthoradiusEdge: Float64Array;
  /** Four numbers per protecting ball: center x, y, z and radius. */
  protectingBalls: Float64Array;
  /** Per protecting ball: 1 for a vertex ball (radius f(u)/4), 0 for a doubled segment ball. */
  protectingBallIsVertex: Uint8Array;
  /** The module's memory after the call, in the thread that ran it. */
  memory: MemoryStats;
}

/** The wasm module's memory. */
export interface MemoryStats {
  /** The wasm memory's size in bytes (it only grows). */
  heapBytes: number;
  /** The bytes the C++ allocations hold now (between calls: what the module keeps). */
  liveBytes: number;
}

/** What the writers need of a result: {@link MeshResult}'s arrays. */
export type WriterInput = Pick<MeshResult, 'vertices' | 'weights' | 'tets' | 'boundary' | 'boundaryFacet' | 'tetClass'>;

/** Options of the writers. */
export interface WriteOptions {
  /** true: UTF-8 bytes (Uint8Array) instead of a string (default false). */
  bytes?: boolean;
}

/** The four TetGen files of {@link writeTetgen}. */
export interface TetgenFiles<T> {
  /** `.node`: `n 3 0 0` then `i x y z` (0-based). */
  node: T;
  /** `.ele`: `m 4 0` then `i a b c d`, positively oriented. */
  ele: T;
  /** `.face`: `k 1` then `i a b c marker`, the marker the input facet + 1. */
  face: T;
  /** `.edge`: `s 1` then `i a b 1`, the subsegments of the input edges (TetGen's `-rNEFC` checks them). */
  edge: T;
}

/** One option of the table shared by the command line and the module. */
export interface OptionInfo {
  /** The camelCase name, as in {@link MeshOptions}. */
  readonly name: string;
  /** The command-line flag, e.g. `"--sliver-angle"` (a boolean's flag sets the other value), or null: wasm only. */
  readonly flag: string | null;
  /** The value's type; an integer is a whole number. */
  readonly type: 'number' | 'integer' | 'boolean';
  /** The smallest value allowed (numbers and integers). */
  readonly min?: number;
  /** The largest value allowed (numbers and integers). */
  readonly max?: number;
  /** The default. */
  readonly default: number | boolean;
  /** The commands that take it: `"mesh"`, and `"check"` for those check takes too. */
  readonly commands: readonly ('check' | 'mesh')[];
  /** What it does, in one sentence. */
  readonly doc: string;
}

/** The option table (from the module, the same as the native command line's). */
export const options: readonly OptionInfo[];

/** The default of every option, by name. */
export const defaultOptions: Readonly<Required<MeshOptions>>;

/** The version of the wasm module beside index.mjs, e.g. `"0.1.0"`. */
export const version: string;

/**
 * Reads, validates and analyses a polyhedron in a worker (off the calling
 * thread). A broken input is not an error: the report says `valid: false`
 * with the kind and a message naming where.
 * @param input - The polyhedron (see {@link WqmeshInput}).
 * @param options - See {@link CheckOptions}.
 * @param control - An AbortSignal.
 * @returns The report, the same as `wqmesh check FILE` prints.
 * @throws TypeError (the promise rejects) for input that is not bytes or OFF/STL text;
 *   WqmeshError `options`; DOMException `AbortError`.
 */
export function check(input: WqmeshInput, options?: CheckOptions | null, control?: Control): Promise<CheckReport>;

/**
 * Meshes a polyhedron with WQMESH (INITIALIZE, CONFORM, REFINE, PUMP) in a
 * worker: a module Worker in browsers, a worker_threads worker in Node. The
 * result's arrays are transferred out of the worker.
 * @param input - The polyhedron (see {@link WqmeshInput}).
 * @param options - See {@link MeshOptions}.
 * @param control - onProgress and an AbortSignal.
 * @returns The mesh of the interior, its classes and statistics; a run
 *   stopped by `maxVertices` resolves too, with `stats.stopped: "limit"`.
 * @throws TypeError (the promise rejects) for input that is not bytes or
 *   OFF/STL text; {@link WqmeshError} with the input's error kind (as
 *   `check` reports it), `options`, `limit` or `internal`; DOMException
 *   `AbortError` when the signal aborts (within milliseconds, whatever the phase).
 */
export function mesh(input: WqmeshInput, options?: MeshOptions | null, control?: MeshControl): Promise<MeshResult>;

/** The result as a Medit `.mesh` file (the native command line's writer), written in a worker. */
export function writeMedit(result: WriterInput, options?: WriteOptions & { bytes?: false } & Control): Promise<string>;
export function writeMedit(result: WriterInput, options: WriteOptions & { bytes: true } & Control): Promise<Uint8Array>;

/**
 * The result as a VTK `.vtu` file (ASCII XML, the native command line's
 * writer), written in a worker. Every file has the same arrays: cell data
 * `min_dihedral` (degrees), `radius_edge` (R/l, unweighted),
 * `orthoradius_edge` (with the weights), `radius_ratio_R_over_r`
 * (circumradius over inradius, 3 for a regular tet: not VTK's normalised
 * aspect ratio), `volume`, `class` (as {@link MeshResult.tetClass}); point
 * data `weight`.
 */
export function writeVtu(result: WriterInput, options?: WriteOptions & { bytes?: false } & Control): Promise<string>;
export function writeVtu(result: WriterInput, options: WriteOptions & { bytes: true } & Control): Promise<Uint8Array>;

/** The result as TetGen `.node`, `.ele`, `.face` and `.edge` files (the native command line's writer), written in a worker. */
export function writeTetgen(result: WriterInput, options?: WriteOptions & { bytes?: false } & Control): Promise<TetgenFiles<string>>;
export function writeTetgen(result: WriterInput, options: WriteOptions & { bytes: true } & Control): Promise<TetgenFiles<Uint8Array>>;

/**
 * Loads the wasm module in the calling thread, for the *Sync forms (which
 * throw a WqmeshError `internal` until it has resolved).
 */
export function ready(): Promise<void>;

/** {@link check} in the calling thread: blocks it for the whole call. Needs {@link ready}. */
export function checkSync(input: WqmeshInput, options?: CheckOptions | null): CheckReport;

/**
 * {@link mesh} in the calling thread: **blocks it for the whole run**, so
 * use it where that is fine (a worker of your own, a script). Needs
 * {@link ready}. Throws as {@link mesh} rejects (no AbortError: cancel by
 * returning false from onProgress).
 */
export function meshSync(input: WqmeshInput, options?: MeshOptions | null, control?: MeshSyncControl): MeshResult;

/** {@link writeMedit} in the calling thread. Needs {@link ready}. */
export function writeMeditSync(result: WriterInput, options?: WriteOptions & { bytes?: false }): string;
export function writeMeditSync(result: WriterInput, options: WriteOptions & { bytes: true }): Uint8Array;
/** {@link writeVtu} in the calling thread. Needs {@link ready}. */
export function writeVtuSync(result: WriterInput, options?: WriteOptions & { bytes?: false }): string;
export function writeVtuSync(result: WriterInput, options: WriteOptions & { bytes: true }): Uint8Array;
/** {@link writeTetgen} in the calling thread. Needs {@link ready}. */
export function writeTetgenSync(result: WriterInput, options?: WriteOptions & { bytes?: false }): TetgenFiles<string>;
export function writeTetgenSync(result: WriterInput, options: WriteOptions & { bytes: true }): TetgenFiles<Uint8Array>;

/** Options of {@link Wqmesh.checkJson}. */
export interface CheckJsonOptions extends CheckOptions {
  /** Indent the JSON with two spaces (default: one line). */
  pretty?: boolean;
}

/** Options of the earlier {@link Wqmesh.mesh}: the mesh options and a positional progress callback. */
export interface LegacyMeshOptions extends MeshOptions {
  /**
   * Called with the phase, the fraction (never going down) and the vertex
   * count; returning false cancels the run (`stats.stopped: "cancelled"`).
   */
  onProgress?: (phase: string, fraction: number, vertices: number) => boolean | void;
}

/**
 * The module loaded in the calling thread by {@link loadWqmesh}: synchronous
 * functions that block the thread (the form of earlier versions, kept).
 */
export interface Wqmesh {
  /** As {@link checkSync}. */
  check(bytes: WqmeshInput, options?: CheckOptions | null): CheckReport;
  /** Like {@link Wqmesh.check}, but the report as JSON text, exactly as the native command line prints it. */
  checkJson(bytes: WqmeshInput, options?: CheckJsonOptions): string;
  /** As {@link meshSync}; onProgress may also be given among the options, with positional arguments. */
  mesh(bytes: WqmeshInput, options?: LegacyMeshOptions | null, control?: MeshSyncControl): MeshResult;
  /** As {@link writeMeditSync}. */
  writeMedit(result: WriterInput, options?: WriteOptions): string | Uint8Array;
  /** As {@link writeVtuSync}. */
  writeVtu(result: WriterInput, options?: WriteOptions): string | Uint8Array;
  /** As {@link writeTetgenSync}. */
  writeTetgen(result: WriterInput, options?: WriteOptions): TetgenFiles<string> | TetgenFiles<Uint8Array>;
  /** The module's memory now. */
  memoryStats(): MemoryStats;
  /** The version of the wasm module, e.g. `"0.1.0"`. */
  version(): string;
}

/** Options of {@link loadWqmesh}. */
export interface LoadOptions {
  /**
   * Where the Emscripten module is. Default: `wqmesh.mjs` beside index.mjs
   * (in a checkout, `scripts/build.sh wasm` puts it there). Its binary is
   * the file of the same name ending in `.wasm` beside it, compiled once per
   * URL and package instance; without it (or with another build's binary)
   * the promise rejects with a WqmeshError `internal` naming the file.
   */
  moduleUrl?: string | URL;
}

/**
 * Loads and instantiates the wasm module in the calling thread, once per
 * URL: later calls return the same object.
 * @param options - Where the module is, if not beside index.mjs.
 * @returns The module's synchronous functions.
 * @throws WqmeshError `internal` (the promise rejects) when the module is missing or fails to load.
 */
export function loadWqmesh(options?: LoadOptions): Promise<Wqmesh>;

export default loadWqmesh;
