// wqmesh: the rules of WQMESH by name (private; paper, section 4.3). CONFORM
// applies rules 1-3, REFINE rules 4-7; a rule runs only when no rule with a
// smaller number applies. Rule::initialize counts INITIALIZE's insertions.
// The numbers are the paper's: MeshResult::rule_points[rule_number(r)].
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace wqmesh::mesher {

enum class Rule : int {
  initialize = 0,
  /// Rule 1: an encroached subsegment e: SPLITE(e).
  rule1_split_encroached_subsegment = 1,
  /// Rule 2: a subfacet of B that is encroached, or one of the input that
  /// is missing from Del V: SPLITF(h).
  rule2_split_missing_subfacet = 2,
  /// Rule 3: the midpoint of a sharp subsegment on edge e encroaches a
  /// subsegment or subfacet h in an element of P disjoint from e: split h.
  rule3_split_near_sharp_subsegment = 3,
  /// Rule 4: an encroached subsegment e: SPLITE(e).
  rule4_split_encroached_subsegment = 4,
  /// Rule 5: a non-guarded subfacet that is encroached, or a guarded one
  /// missing from Del V: SPLITF(h).
  rule5_split_encroached_subfacet = 5,
  /// Rule 6: a tet with circumradius-edge ratio above rho0: ENCROACH of its
  /// circumcenter, unless that lies in a protecting ball.
  rule6_split_skinny_tet = 6,
  /// Rule 7: a sliver vertex whose weighted point threatens the subcomplex:
  /// split what it encroaches or removes.
  rule7_split_for_pumping = 7,
};
constexpr int kRules = 8;  ///< Rule::initialize and rules 1..7

constexpr int rule_number(Rule r) { return static_cast<int>(r); }

/// The loop caps of the mesher (beyond the paper: each bounds a loop the
/// paper lets run to its end). Reaching one is counted in caps_reached.
struct Caps {
  /// Rule 3 passes in CONFORM, until one inserts nothing.
  static constexpr int kRule3Passes = 1000;
  /// Rule 7 passes in REFINE, until one inserts nothing.
  static constexpr int kRule7Passes = 100;
  /// Times a subfacet (or a tet, by three of its vertices) is looked at again
  /// after its split was deferred to another feature.
  static constexpr int kRetries = 16;
  /// REFINE's insertions by rules 4 and 5 in a row, with no rule-6 or rule-7
  /// insertion between them: at most kBoundaryRunFactor times the vertex
  /// count of V before the first of them, plus kBoundaryRunSlack; past it the
  /// run stops as a runaway (WorkMeter::refine_insertion). In a terminating
  /// run such a run of splits answers the points inserted before it: the
  /// longest on the 16 meshable models of examples/models and the shared
  /// models (BENCHMARKS.md, session 9, h4) was wedge-1's, 2,013 points from 240 vertices (8.4 times; part 333 from
  /// 4,400, anchor 71 from 27,639), 12 times below its cap. Where a pair of
  /// elements at an angle below 90 degrees is left unprotected (a sharp edge
  /// missed), their subfacets encroach each other's and rule 5 splits them
  /// without end: section 5.1 assumes every such pair protected (Lemma 5.1
  /// (ii)); the cap turns that into a stop with a message.
  static constexpr int kBoundaryRunFactor = 16;
  static constexpr int kBoundaryRunSlack = 20000;
  /// Past that cap a run goes on while every insertion keeps its distance to
  /// its nearest neighbour at least kRunawaySpacing times the smallest
  /// protecting ball's radius (B's extent without balls), up to
  /// kBoundaryRunBackstop times the cap. A pair of facets at a small angle
  /// next to a sharp edge whose protecting balls CONFORM made small (a nearly
  /// flat facet fan at a 1.2-1.5-degree edge: BENCHMARKS.md, session 16, h2)
  /// needs a long but finite run graded by the facets' gap outside the balls
  /// (41,849-73,923 insertions from about 500 vertices, every point at least
  /// 0.018 of the smallest ball's radius from its neighbours), while the
  /// cascade of a missed sharp edge works at a fixed tiny scale.
  static constexpr double kRunawaySpacing = 1e-4;
  static constexpr int kBoundaryRunBackstop = 8;
};

}  // namespace wqmesh::mesher
