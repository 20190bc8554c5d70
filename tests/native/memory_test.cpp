// The peak memory of a run (issue 15, item 3): the mesher's large pieces (V's
// triangulation, the subcomplex, the queues) are freed once the mesh is
// extracted, before the per-tet measures, the classes and the improvement
// phase are built; the extraction split in two (the mesh, then
// classify_tets) gives the same result as the whole extraction, and so does
// a run whose subcomplex was frozen after REFINE; the labels kept in the
// cells are the cell graph's; PUMP's compact label table answers as a map
// does; the planar triangulations' pool is emptied with the last of them.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>
#include <malloc.h>

#include <algorithm>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh_invariants.h"
#include "mesher/classify.h"
#include "mesher/extract.h"
#include "mesher/mesher.h"
#include "mesher/pump.h"
#include "triangulation.h"
#include "wqmesh/mesher.h"

namespace wqmesh {
namespace {

using invariants::Input;
using invariants::load;

const std::string kSpike = std::string(WQMESH_EXAMPLE_MODELS) + "/spike.off";

// The heap glibc has handed out (mmapped blocks included).
std::size_t heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

// Whether heap_in_use sees this process's allocations (not under a
// sanitizer's allocator, which glibc's counters do not see).
bool heap_is_measurable() {
  const std::size_t before = heap_in_use();
  std::vector<char> block(8 << 20, 1);
  const std::size_t during = heap_in_use();
  return block[12345] == 1 && during >= before + (8u << 20);
}

// One example model, loaded, with its domain, default options and no
// progress callback: the set-up of each test below (built in place, never
// copied: the domain refers to the loaded input).
struct LoadedModel {
  explicit LoadedModel(const std::string& name)
      : in(load(std::string(WQMESH_EXAMPLE_MODELS) + "/" + name)), dom(in.plc, in.analysis) {}
  LoadedModel(const LoadedModel&) = delete;
  LoadedModel& operator=(const LoadedModel&) = delete;
  const Input in;
  const mesher::Domain dom;
  const MeshOptions o;
  const ProgressCallback none;
};

// INITIALIZE, CONFORM and REFINE (section 4.3) on m.
void refine(mesher::Mesher& m) {
  m.initialize();
  m.conform();
  m.refine();
}

// The mesh and its per-vertex data of r are those of `expected`.
void expect_same_mesh(const MeshResult& r, const MeshResult& expected) {
  EXPECT_EQ(r.mesh.vertices, expected.mesh.vertices);
  EXPECT_EQ(r.mesh.weights, expected.mesh.weights);
  EXPECT_EQ(r.mesh.tets, expected.mesh.tets);
  EXPECT_EQ(r.mesh.boundary, expected.mesh.boundary);
  EXPECT_EQ(r.mesh.boundary_facet, expected.mesh.boundary_facet);
  EXPECT_EQ(r.nearest_neighbour, expected.nearest_neighbour);
  EXPECT_EQ(r.input_vertex, expected.input_vertex);
}

// Extract::mesh then classify_tets, with the mesher released in between, is
// the whole extraction (Extract::run), field by field; after release() the
// pieces are refused and the balls stay.
TEST(Memory, ReleasedMesherGivesTheWholeExtractionsResult) {
  for (const std::string name : {"spike.off", "slit.off", "edge_facet.off"}) {
    SCOPED_TRACE(name);
    const LoadedModel s(name);
    const mesher::Domain& dom = s.dom;
    const MeshOptions& o = s.o;
    const ProgressCallback& none = s.none;
    auto run_phases = [&](mesher::Mesher& m) {
      refine(m);
      m.count_qmesh_slivers();
      m.pump();
    };
    mesher::Mesher whole(dom, o, none);
    run_phases(whole);
    const MeshResult expected = whole.extract();

    mesher::Mesher m(dom, o, none);
    run_phases(m);
    MeshResult r = m.extract_mesh();
    EXPECT_TRUE(r.quality.empty());
    EXPECT_TRUE(r.tet_class.empty());
    const mesher::ProtectingBalls balls = m.balls();
    EXPECT_FALSE(m.released());
    m.release();
    EXPECT_TRUE(m.released());
    EXPECT_THROW(m.triangulation(), std::logic_error);
    EXPECT_THROW(m.subcomplex(), std::logic_error);
    EXPECT_THROW(m.extract_mesh(), std::logic_error);
    EXPECT_TRUE(m.vertices().empty());
    EXPECT_EQ(m.vertices().capacity(), 0u);  // freed, not only emptied
    EXPECT_EQ(m.balls().all().size(), expected.protecting_balls.size());
    ASSERT_TRUE(mesher::classify_tets(r, balls, o));

    expect_same_mesh(r, expected);
    EXPECT_EQ(r.orthoradius_edge, expected.orthoradius_edge);
    EXPECT_EQ(r.tet_class, expected.tet_class);
    ASSERT_EQ(r.quality.size(), expected.quality.size());
    for (std::size_t t = 0; t < r.quality.size(); ++t) {
      EXPECT_EQ(r.quality[t].min_dihedral_deg, expected.quality[t].min_dihedral_deg) << "tet " << t;
      EXPECT_EQ(r.quality[t].radius_edge, expected.quality[t].radius_edge) << "tet " << t;
      EXPECT_EQ(r.quality[t].volume, expected.quality[t].volume) << "tet " << t;
    }
    EXPECT_EQ(r.conforming, expected.conforming);
    EXPECT_EQ(r.stopped, expected.stopped);
    EXPECT_EQ(r.slivers, expected.slivers);
    EXPECT_EQ(r.skinny, expected.skinny);
    EXPECT_EQ(r.near_small_angle, expected.near_small_angle);
    EXPECT_EQ(r.violations, expected.violations);
    EXPECT_EQ(r.orthoradius_skinny, expected.orthoradius_skinny);
  }
}

// classify_tets on a changed mesh (the improvement phase's final classes)
// frees the old measures and classes before making new ones: the new arrays
// are exactly the new mesh's size, not the old arrays' blocks kept (issue 15,
// the peak memory).
TEST(Memory, ClassesOfAChangedMeshReplaceTheOldArrays) {
  const LoadedModel s("spike.off");
  mesher::Mesher m(s.dom, s.o, s.none);
  refine(m);
  m.count_qmesh_slivers();
  m.pump();
  MeshResult r = m.extract();
  const mesher::ProtectingBalls balls = m.balls();
  m.release();
  ASSERT_GT(r.mesh.tets.size(), 8u);
  ASSERT_EQ(r.orthoradius_edge.size(), r.mesh.tets.size());
  r.mesh.tets.resize(r.mesh.tets.size() / 2);  // fewer tets, as the improvement phase may leave
  ASSERT_TRUE(mesher::classify_tets(r, balls, s.o));
  EXPECT_EQ(r.quality.size(), r.mesh.tets.size());
  EXPECT_EQ(r.orthoradius_edge.size(), r.mesh.tets.size());
  EXPECT_EQ(r.orthoradius_edge.capacity(), r.mesh.tets.size());
  EXPECT_EQ(r.tet_class.size(), r.mesh.tets.size());
  EXPECT_EQ(r.tet_class.capacity(), r.mesh.tets.size());
}

// Subcomplex::freeze (Mesher::freeze_subcomplex, as mesh_polyhedron calls it
// after REFINE): the subfacets come from the kept list exactly as from the
// facets' planar triangulations, the run conforms as before, PUMP and the
// extraction give the same result field by field, and what needs the freed
// planar triangulations is refused.
TEST(Memory, FrozenSubcomplexGivesTheSameRunAfterRefine) {
  for (const std::string name : {"spike.off", "slit.off", "edge_facet.off"}) {
    SCOPED_TRACE(name);
    const LoadedModel s(name);
    const mesher::Domain& dom = s.dom;
    const MeshOptions& o = s.o;
    const ProgressCallback& none = s.none;
    mesher::Mesher live(dom, o, none), frozen(dom, o, none);
    refine(live);
    refine(frozen);
    const std::vector<mesher::Subfacet> expected = live.subcomplex().subfacets();
    ASSERT_FALSE(expected.empty());
    frozen.freeze_subcomplex();
    ASSERT_TRUE(frozen.subcomplex().frozen());
    EXPECT_FALSE(live.subcomplex().frozen());
    const std::vector<mesher::Subfacet> kept = frozen.subcomplex().subfacets();
    ASSERT_EQ(kept.size(), expected.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
      EXPECT_EQ(kept[i].facet, expected[i].facet) << "subfacet " << i;
      EXPECT_EQ(kept[i].v, expected[i].v) << "subfacet " << i;
    }
    EXPECT_EQ(frozen.subcomplex().conforms(), live.subcomplex().conforms());
    EXPECT_THROW(frozen.subcomplex().facet_triangulation(0), std::logic_error);
    std::vector<mesher::Tri> around;
    EXPECT_THROW(frozen.subcomplex().subfacets_at(0, 0, around), std::logic_error);
    EXPECT_THROW(frozen.subcomplex().is_subfacet(kept[0].facet, kept[0].v), std::logic_error);
    for (mesher::Mesher* m : {&live, &frozen}) {
      m->count_qmesh_slivers();
      m->pump();
    }
    EXPECT_EQ(frozen.pumped_vertices(), live.pumped_vertices());
    const MeshResult a = live.extract(), b = frozen.extract();
    expect_same_mesh(b, a);
    EXPECT_EQ(b.tet_class, a.tet_class);
    EXPECT_EQ(b.conforming, a.conforming);
    EXPECT_EQ(b.slivers, a.slivers);
    EXPECT_EQ(b.violations, a.violations);
  }
}

// The vertex order of a cell in the output (extract.cpp): sorted, then the
// last two swapped if that took an odd permutation (orientation kept).
Tet canonical_order(const Tet& t) {
  Tet s = t;
  std::sort(s.begin(), s.end());
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += t[i] > t[j];
  if (inversions % 2) std::swap(s[2], s[3]);
  return s;
}

// The labels kept in the cells (label_cells_in_place, no cell graph) are
// interior_labels' on the cell graph, cell by cell, wherever it says they
// are free of the order, with each cell's neighbours' labels in
// visit_labelled, after REFINE (rule 7's scans) and after PUMP (the sliver
// count's and the extraction's); and the extraction built on them is the
// one a cell graph gives: the interior cells in canonical order, each in its
// canonical vertex order (compared by coordinates), with one boundary
// triangle per face between an inside and an outside cell.
TEST(Memory, LabelsInTheCellsAreTheCellGraphsLabels) {
  int in_place = 0;
  for (const std::string name : {"spike.off", "slit.off", "edge_facet.off", "thin_wedge.off", "bracket.off"}) {
    SCOPED_TRACE(name);
    const LoadedModel s(name);
    const mesher::Domain& dom = s.dom;
    const MeshOptions& o = s.o;
    mesher::Mesher m(dom, o, s.none);
    refine(m);
    for (int stage = 0; stage < 2; ++stage) {
      SCOPED_TRACE(stage ? "after PUMP" : "after REFINE");
      if (stage) {
        m.count_qmesh_slivers();
        m.pump();
      }
      const RegularTriangulation& tri = m.triangulation();
      const RegularTriangulation::CellGraph g = tri.cell_graph();
      bool order_free = false;
      const std::vector<char> expected = mesher::interior_labels(dom, m.subcomplex(), g, m.meter(), false, &order_free);
      const bool kept = mesher::label_cells_in_place(dom, m.subcomplex(), tri, m.meter(), false);
      EXPECT_EQ(kept, order_free && m.subcomplex().conforms());
      if (!kept) continue;
      ++in_place;
      std::vector<Tet> cells;
      std::vector<char> labels;
      tri.visit_labels([&](const Tet& t, char& label) {
        cells.push_back(t);
        labels.push_back(label == RegularTriangulation::kExcludedOdd ? char(0) : label);
      });
      ASSERT_EQ(cells, g.cells);
      ASSERT_EQ(labels, expected);
      std::size_t c = 0, inside = 0;
      tri.visit_labelled(1, [&](const Tet& t, const std::array<char, 4>& across) {
        while (c < g.cells.size() && expected[c] != 1) ++c;
        ASSERT_LT(c, g.cells.size());
        EXPECT_EQ(t, g.cells[c]);
        for (int k = 0; k < 4; ++k)
          EXPECT_EQ(across[k] == 1, expected[g.neighbor[c][k]] == 1) << "cell " << c << " face " << k;
        ++c;
        ++inside;
      });
      EXPECT_EQ(inside, static_cast<std::size_t>(std::count(expected.begin(), expected.end(), char(1))));
      if (!stage) continue;
      // The extraction against the cell graph's labels.
      std::vector<Tet> interior;
      std::size_t faces = 0;
      for (std::size_t i = 0; i < g.cells.size(); ++i) {
        if (expected[i] != 1) continue;
        interior.push_back(canonical_order(g.cells[i]));
        for (int k = 0; k < 4; ++k) faces += expected[g.neighbor[i][k]] != 1;
      }
      std::sort(interior.begin(), interior.end());
      const MeshResult r = m.extract_mesh();
      ASSERT_EQ(r.mesh.tets.size(), interior.size());
      for (std::size_t t = 0; t < interior.size(); ++t)
        for (int k = 0; k < 4; ++k)
          ASSERT_EQ(r.mesh.vertices[r.mesh.tets[t][k]], tri.point(interior[t][k])) << "tet " << t << " vertex " << k;
      EXPECT_EQ(r.mesh.boundary.size(), faces);
      EXPECT_EQ(r.mesh.boundary_facet.size(), faces);
      EXPECT_EQ(r.mesh.vertices.capacity(), r.mesh.vertices.size());
    }
  }
  EXPECT_GT(in_place, 0);
}

// The labels completed after insertions and weight changes
// (RegularTriangulation::complete_labels: only the cells made since are
// labelled, from their neighbours) are a fresh fill's: checked after the
// insertions of REFINE (every one once rule 7 has started, every 16th
// before) and after PUMP's weight changes. Wherever the fresh fill is free
// of the order, every wall is a facet and the labels before were such a
// fill's, the completion must hold (a wrong rule for the new cells fails
// its check) and give the fill's labels, kExcludedOdd read as 0; and a check that
// passes implies even walls (extract.cpp, even_walls).
TEST(Memory, CompletedLabelsAreAFreshFillsAfterInsertionsAndWeightChanges) {
  std::vector<std::string> files;
  for (const char* name : {"spike.off", "edge_facet.off", "thin_wedge.off", "bracket.off", "slit.off"})
    files.push_back(std::string(WQMESH_EXAMPLE_MODELS) + "/" + name);
  const std::string shared = WQMESH_SHARED_MODELS;
  if (!shared.empty())
    for (const char* name : {"example012.stl", "20mm-xyz-cube.stl"}) files.push_back(shared + "/" + name);
  std::size_t checked = 0, completed = 0, after_rule7 = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const Input in = load(file);
    const mesher::Domain dom(in.plc, in.analysis);
    const MeshOptions o;
    const ProgressCallback none;
    mesher::Mesher m(dom, o, none);
    const RegularTriangulation& tri = m.triangulation();
    const mesher::Subcomplex& sub = m.subcomplex();
    bool valid_before = false;  // the cells hold the labels of a fill free of the order
    const auto check = [&](bool rule7) {
      std::vector<mesher::Tri> walls;
      for (const mesher::Subfacet& h : sub.subfacets())
        if (!dom.is_box_facet(h.facet)) walls.push_back(mesher::sorted(h.v));
      std::sort(walls.begin(), walls.end());
      walls.erase(std::unique(walls.begin(), walls.end()), walls.end());
      const auto wall = [&](int a, int b, int c) {
        return std::binary_search(walls.begin(), walls.end(), mesher::sorted({{a, b, c}}));
      };
      const auto flat = [&](const Tet& t) { return sub.flat_on_facet(t); };
      const RegularTriangulation::CellGraph g = tri.cell_graph();
      bool order_free = false;
      const std::vector<char> fresh = mesher::interior_labels(dom, sub, g, m.meter(), false, &order_free);
      const bool valid = order_free && sub.conforms();
      const auto on_p = [&](int v) { return sub.on_p(v); };
      const bool ok = tri.complete_labels(on_p, wall, walls.size(), flat);
      // A passing check implies even walls (label_cells_in_place asks
      // even_walls only when the check fails).
      if (ok) EXPECT_TRUE(order_free) << "after " << m.vertices().size() << " vertices";
      if (valid && valid_before) {
        ++checked;
        after_rule7 += rule7;
        EXPECT_TRUE(ok) << "after " << m.vertices().size() << " vertices";
        if (ok) {
          ++completed;
          std::vector<char> labels;
          tri.visit_labels([&](const Tet&, char& label) {
            labels.push_back(label == RegularTriangulation::kExcludedOdd ? char(0) : label);
          });
          EXPECT_EQ(labels, fresh) << "after " << m.vertices().size() << " vertices";
        }
      }
      if (!ok) tri.flood_labels(on_p, wall, flat);  // a fill to complete later
      valid_before = valid;
    };
    m.initialize();
    m.conform();
    bool rule7 = false;
    std::size_t insertions = 0;
    m.inserter().observer = [&](const mesher::Insertion&, int rule, int id) {
      if (id < 0) return;
      rule7 = rule7 || rule == 7;
      if (rule7 || ++insertions % 16 == 0) check(rule7);
    };
    m.refine();
    m.inserter().observer = nullptr;
    check(rule7);
    m.freeze_subcomplex();
    m.count_qmesh_slivers();
    m.pump();
    check(false);
  }
  EXPECT_GT(checked, 0u);
  EXPECT_EQ(completed, checked);
  if (!shared.empty()) EXPECT_GT(after_rule7, 0u);
}

// PUMP's first label table has room for the cells its weight changes make
// (Pump::kNewCellRoom): on models where it pumps, no second table is added.
TEST(Memory, PumpsNewCellsFitItsFirstLabelTable) {
  std::size_t pumped = 0;
  for (const std::string name : {"spike.off", "slit.off", "edge_facet.off", "thin_wedge.off"}) {
    SCOPED_TRACE(name);
    const LoadedModel s(name);
    mesher::Mesher m(s.dom, s.o, s.none);
    refine(m);
    mesher::Pump p = m.make_pump();
    p.run();
    pumped += p.pumped_vertices();
    EXPECT_EQ(p.label_tables(), 1u);
  }
  EXPECT_GT(pumped, 0u);
}

// PUMP on the labels in the cells (use_cell_labels) keeps its labels there,
// with no table (issue 15, the peak memory), and pumps as PUMP on a label
// table of its own scan does: the same weights, the same mesh. The labels
// it leaves in the cells are those of a fresh fill of the pumped
// triangulation, wherever the fill is free of the order.
TEST(Memory, PumpKeepsItsLabelsInTheCells) {
  std::size_t pumped = 0, in_cells = 0;
  for (const std::string name : {"spike.off", "edge_facet.off", "thin_wedge.off", "bracket.off"}) {
    SCOPED_TRACE(name);
    const LoadedModel s(name);
    // A larger sliver bound than the default (3 degrees) so that PUMP has
    // work on these small models.
    MeshOptions o = s.o;
    o.theta_deg = 20;
    mesher::Mesher a(s.dom, o, s.none), b(s.dom, o, s.none);
    refine(a);
    refine(b);
    RegularTriangulation::CellGraph scan;
    std::vector<char> scan_labels;
    std::vector<double> nn;
    bool cells = false;
    mesher::Extract(s.dom, o, a.triangulation(), a.vertices(), a.subcomplex(), a.balls(), nn, a.meter())
        .count_qmesh_slivers(scan, scan_labels, cells);
    if (!cells) continue;
    ++in_cells;
    mesher::Pump p = a.make_pump();
    p.use_cell_labels();
    p.run();
    EXPECT_EQ(p.label_tables(), 0u);
    mesher::Pump q = b.make_pump();
    q.run();
    EXPECT_GE(q.label_tables(), 1u);
    EXPECT_EQ(p.pumped_vertices(), q.pumped_vertices());
    pumped += p.pumped_vertices();
    const RegularTriangulation& ta = a.triangulation();
    for (int v = 0; v < ta.number_of_vertices(); ++v) EXPECT_EQ(ta.weight(v), b.triangulation().weight(v)) << v;
    // The labels PUMP left (0 or 1 on cells it or the count labelled) are
    // the fill's.
    const RegularTriangulation::CellGraph g = ta.cell_graph();
    bool order_free = false;
    const std::vector<char> fresh = mesher::interior_labels(s.dom, a.subcomplex(), g, a.meter(), false, &order_free);
    ASSERT_TRUE(order_free);
    std::size_t i = 0, compared = 0;
    ta.visit_labels([&](const Tet& t, char& label) {
      const bool finite = std::find(t.begin(), t.end(), kInfinite) == t.end();
      if (finite && !a.subcomplex().flat_on_facet(t) && label != RegularTriangulation::kUnlabelled) {
        EXPECT_EQ(label, fresh[i]) << i;
        ++compared;
      }
      ++i;
    });
    EXPECT_GT(compared, 0u);
    expect_same_mesh(a.extract_mesh(), b.extract_mesh());
  }
  EXPECT_GT(in_cells, 0u);
  EXPECT_GT(pumped, 0u);
}

// mesh_polyhedron frees V's triangulation and the subcomplex before the
// improvement phase, and the phase frees the stale per-tet measures before
// it builds its own arrays (improve.h): when the phase reports its start,
// the process holds less than it does once the run has returned (the
// finished result alone: the mesh, about 300 bytes per tet of measures and
// classes). Holding the triangulation (about 230 bytes per tet) and the
// subcomplex to the end, as before, gives more there than the whole result.
TEST(Memory, TheTriangulationIsFreedBeforeTheImprovementPhase) {
  if (!heap_is_measurable()) GTEST_SKIP() << "glibc's heap counters do not see this allocator (a sanitizer build)";
  const Input in = load(kSpike);
  MeshOptions o;
  o.max_size = 0.1;  // about 11,000 tets: the run's structures dwarf the rest of the process
  std::size_t at_improve = 0;
  std::string last;
  const ProgressCallback watch = [&](const Progress& p) {
    if (p.phase == "improve" && last != "improve") at_improve = heap_in_use();
    last = p.phase;
    return true;
  };
  const std::size_t before = heap_in_use();
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis, o, watch);
  const std::size_t after = heap_in_use();
  ASSERT_TRUE(r.stopped.empty()) << r.stop_message;
  ASSERT_GT(r.mesh.tets.size(), 5000u);
  ASSERT_EQ(r.quality.size(), r.mesh.tets.size());
  ASSERT_GT(at_improve, 0u) << "no progress call at the improvement phase's start";
  EXPECT_LT(at_improve - before, after - before)
      << "at the improvement phase's start the run held " << at_improve - before << " bytes, the finished result "
      << after - before << ": the mesher's pieces or the old measures were not freed";
}

// The facets' planar triangulations' pool (triangulation.cpp): a
// triangulation built while another's blocks were freed is the same as one
// built alone (no block handed out twice), the freed blocks serve a
// triangulation of the same size without a new chunk, the pool holds chunks
// while a triangulation lives and none once the last is gone, and a run's
// freeze after REFINE (Subcomplex::freeze) gives every chunk back.
TEST(Memory, PlanarTriangulationsPoolIsEmptiedWithTheLastTriangulation) {
  ASSERT_EQ(planar_pool_bytes(), 0u) << "a planar triangulation outlived its test";
  const auto build = [](PlanarDelaunay& d, int n, double shift) {
    d.set_plane({0, 0, 1});
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) d.insert({i + 0.37 * j * j / n + shift, j + 0.21 * i * i / n, 0}, i * n + j);
  };
  std::vector<std::array<int, 3>> alone;
  {
    PlanarDelaunay d;
    build(d, 40, 0);
    alone = d.triangles();
    EXPECT_GT(planar_pool_bytes(), 0u);
  }
  EXPECT_EQ(planar_pool_bytes(), 0u);
  {
    auto first = std::make_unique<PlanarDelaunay>();
    PlanarDelaunay other;
    build(*first, 30, 0.5);
    build(other, 25, 0.25);
    const std::vector<std::array<int, 3>> first_triangles = first->triangles();
    const std::size_t held = planar_pool_bytes();
    first.reset();  // its blocks stay in the pool while `other` lives
    EXPECT_EQ(planar_pool_bytes(), held);
    {
      PlanarDelaunay same;  // the same sizes of blocks: all of them reused
      build(same, 30, 0.5);
      EXPECT_EQ(same.triangles(), first_triangles);
      EXPECT_EQ(planar_pool_bytes(), held);
    }
    PlanarDelaunay again;
    build(again, 40, 0);
    EXPECT_EQ(again.triangles(), alone);
    EXPECT_GT(other.triangles().size(), 2u * 24 * 24 - 1);
  }
  EXPECT_EQ(planar_pool_bytes(), 0u);

  const LoadedModel s("spike.off");
  mesher::Mesher m(s.dom, s.o, s.none);
  refine(m);
  EXPECT_GT(planar_pool_bytes(), 0u);
  m.freeze_subcomplex();
  EXPECT_EQ(planar_pool_bytes(), 0u);
}

// PUMP's CellLabels (open-addressing tables) answers every look-up as a
// std::unordered_map does, through growth far beyond its first table's size
// (further tables beside it), with keys holding kInfinite and labels
// overwritten in whichever table holds them.
TEST(Memory, PumpsLabelTableAnswersAsAMap) {
  mesher::CellLabels table;
  table.reset(10);
  std::unordered_map<mesher::TetKey, char, mesher::TetKeyHash> map;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> id(-1, 300);
  auto key = [&] {
    mesher::TetKey t{{id(rng), id(rng), id(rng), id(rng)}};
    std::sort(t.begin(), t.end());
    return t;
  };
  for (int i = 0; i < 20000; ++i) {
    const mesher::TetKey t = key();
    const char label = static_cast<char>(rng() % 2);
    table.set(t, label);
    map[t] = label;
    const mesher::TetKey probe = key();
    const char* found = table.find(probe);
    const auto it = map.find(probe);
    ASSERT_EQ(found != nullptr, it != map.end()) << "look-up " << i;
    if (found) ASSERT_EQ(*found, it->second) << "look-up " << i;
  }
  // The keys outgrew the first table many times over: further tables were
  // added beside it.
  EXPECT_GT(table.tables(), 2u);
  for (const auto& [t, label] : map) {
    const char* found = table.find(t);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(*found, label);
  }
  table.reset(0);
  EXPECT_EQ(table.tables(), 1u);
  EXPECT_EQ(table.find(map.begin()->first), nullptr);
}

}  // namespace
}  // namespace wqmesh
