// wqmesh: the pieces of a run and the phases in order (class Mesher), and the
// insertion of a point into V with its upkeep (class Inserter).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/mesher.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#if defined(__GLIBC__) && !defined(__EMSCRIPTEN__)
#include <malloc.h>
#endif

#include "mesher/extract.h"
#include "mesher/phases.h"
#include "mesher/pump.h"

namespace wqmesh::mesher {

Mesher::Pieces::Pieces(const Domain& domain, const MeshOptions& options, std::vector<MVertex>& vertices,
                       const ProtectingBalls& balls, WorkMeter& meter)
    : sub(domain, tri, vertices, balls),
      queues(domain, tri, sub, meter),
      ins(options, tri, vertices, sub, queues, meter) {}

Mesher::Mesher(const Domain& domain, const MeshOptions& options, const ProgressCallback& progress)
    : dom_(domain),
      opt_(options),
      balls_(domain.box),
      meter_(options, progress, verts_),
      pieces_(std::make_unique<Pieces>(domain, options, verts_, balls_, meter_)) {}

Mesher::Pieces& Mesher::live() const {
  if (!pieces_) throw std::logic_error("internal error: the mesher's pieces were used after release()");
  return *pieces_;
}

void Mesher::initialize() {
  meter_.set_phase(Phase::initialize);
  Pieces& p = live();
  Initialize(dom_, p.sub, p.queues, p.ins, meter_).run();
}

void Mesher::conform() { make_conform().run(); }

Conform Mesher::make_conform() {
  meter_.set_phase(Phase::conform);
  Pieces& p = live();
  return Conform(dom_, opt_, p.tri, p.sub, p.queues, p.ins, meter_, balls_);
}

void Mesher::refine() {
  meter_.set_phase(Phase::refine);
  Pieces& p = live();
  Refine(dom_, opt_, p.tri, verts_, p.sub, balls_, p.queues, p.ins, meter_).run();
}

Pump Mesher::make_pump() { return Pump(dom_, opt_, live().tri, verts_, live().sub, balls_, meter_); }

void Mesher::pump() {
  meter_.set_phase(Phase::pump);
  Pump p = make_pump();
  if (sliver_scan_vertices_ == static_cast<long>(verts_.size())) {
    if (sliver_scan_in_cells_)
      p.use_cell_labels();
    else
      p.use_scan(std::move(sliver_scan_), std::move(sliver_scan_labels_));
  }
  sliver_scan_ = {};
  std::vector<char>().swap(sliver_scan_labels_);  // freed, not only emptied (see release())
  sliver_scan_vertices_ = -1;
  sliver_scan_in_cells_ = false;
  p.run();
  nn_ = p.nearest_neighbours();
  pumped_vertices_ = p.pumped_vertices();
}

MeshResult Mesher::extract() { return Extract(dom_, opt_, live().tri, verts_, live().sub, balls_, nn_, meter_).run(); }

MeshResult Mesher::extract_mesh() {
  return Extract(dom_, opt_, live().tri, verts_, live().sub, balls_, nn_, meter_).mesh();
}

void trim_heap() {
#if defined(__GLIBC__) && !defined(__EMSCRIPTEN__)
  malloc_trim(0);
#endif
}

void Mesher::freeze_subcomplex() {
  live().sub.freeze();
  trim_heap();
}

void Mesher::release() {
  pieces_.reset();
  // Swapped with empty vectors, so that their blocks are freed: `v = {}` is
  // vector's initializer-list assignment, which empties v and keeps its
  // capacity (V's MVertex list and N(v) stayed allocated, 16 and 8 bytes a
  // vertex of V, through the measures, the classes and the improvement
  // phase: 10 MB of spike.off's 1.15 million tets at --max-size 0.021).
  std::vector<MVertex>().swap(verts_);
  std::vector<double>().swap(nn_);
  sliver_scan_ = {};  // an aggregate: assigned from an empty one, its vectors freed
  std::vector<char>().swap(sliver_scan_labels_);
  sliver_scan_vertices_ = -1;
  sliver_scan_in_cells_ = false;
  released_ = true;
  trim_heap();
}

std::size_t Mesher::count_qmesh_slivers() {
  const std::size_t n = Extract(dom_, opt_, live().tri, verts_, live().sub, balls_, nn_, meter_)
                            .count_qmesh_slivers(sliver_scan_, sliver_scan_labels_, sliver_scan_in_cells_);
  sliver_scan_vertices_ = sliver_scan_.cells.empty() && !sliver_scan_in_cells_ ? -1 : static_cast<long>(verts_.size());
  return n;
}

// ---- insertion into V --------------------------------------------------------------

Inserter::Inserter(const MeshOptions& options, RegularTriangulation& tri, std::vector<MVertex>& vertices,
                   Subcomplex& sub, Queues& queues, WorkMeter& meter)
    : opt_(options), tri_(tri), verts_(vertices), sub_(sub), queues_(queues), meter_(meter) {
  trace_ = std::getenv("WQMESH_TRACE") != nullptr;
}

int Inserter::insert(const Insertion& ins) {
  if (ins.none) return -1;
  const int before = tri_.number_of_vertices();
  const int id = tri_.insert(ins.p, 0, ins.hint);
  if (id < before) return -1;  // hidden or an existing vertex: nothing inserted
  MVertex m;
  m.on = ins.on;
  m.element = ins.element;
  m.sector = ins.sector;
  m.ball = ins.ball;
  verts_.push_back(m);
  std::vector<std::uint64_t> halves;
  sub_.insert_vertex(id, ins, halves);
  for (std::uint64_t k : halves) queues_.push_segment(k);
  queues_.enqueue_around(id);
  if (verts_.size() >= opt_.max_vertices) meter_.stop("limit");
  return id;
}

void Inserter::trace(const Insertion& ins, Rule rule, int id) const {
  double len = 0;
  if (ins.has_segment) {
    const int a = int(ins.split_segment >> 32), b = int(ins.split_segment & 0xFFFFFFFFu);
    len = std::sqrt(dist2(tri_.point(a), tri_.point(b)));
  }
  static const char* kOn[] = {"vertex", "edge", "facet", "free"};
  std::fprintf(stderr, "wqmesh trace: rule %d -> %d on %s %d at (%.17g, %.17g, %.17g) split %s length %g\n",
               rule_number(rule), id, kOn[int(ins.on)], ins.element, ins.p[0], ins.p[1], ins.p[2],
               ins.has_segment ? (ins.sector >= 0 ? "shield" : "subsegment") : "-", len);
}

}  // namespace wqmesh::mesher
