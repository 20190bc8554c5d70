// wqmesh: the peak of the live C++ heap of one run, phase by phase (issue
// 15, item 3; BENCHMARKS.md "Memory at the peak"). A developer's measuring
// tool, built on demand (EXCLUDE_FROM_ALL):
//   cmake --build build/native --target wqmesh_heap_phases
//   build/native/bin/wqmesh_heap_phases MODEL [--max-size X] [--no-improve]
// Every operator new and delete of the process is counted (the bytes
// malloc_usable_size gives for the block, so the allocator's rounding is in),
// so the figures are those of the C++ containers of the mesher and CGAL, not
// of the process (no code, no stack, no allocator slack: peak RSS,
// /usr/bin/time -f %M, is the process's). The phases are the progress
// callback's: a phase's peak is the largest heap between its first call and
// the next phase's first call, so "pump" includes the extraction that follows
// PUMP (it makes no progress call) and "improve" the classes at the end.
// Prints one line per phase (peak MB, bytes per output tet), the whole run's
// peak and where it was, and the output tets.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <malloc.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <wqmesh/wqmesh.h>

namespace {

std::atomic<long long> g_live{0}, g_peak{0};

void* counted(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  const long long now = g_live += static_cast<long long>(malloc_usable_size(p));
  long long peak = g_peak.load();
  while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {}
  return p;
}

void uncounted(void* p) {
  if (!p) return;
  g_live -= static_cast<long long>(malloc_usable_size(p));
  std::free(p);
}

}  // namespace

void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { uncounted(p); }
void operator delete[](void* p) noexcept { uncounted(p); }
void operator delete(void* p, std::size_t) noexcept { uncounted(p); }
void operator delete[](void* p, std::size_t) noexcept { uncounted(p); }

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MODEL [--max-size X] [--no-improve]\n", argv[0]);
    return 1;
  }
  try {
    wqmesh::Options options;
    for (int i = 2; i < argc; ++i) {
      if (!std::strcmp(argv[i], "--max-size") && i + 1 < argc)
        options.set("maxSize", std::atof(argv[++i]));
      else if (!std::strcmp(argv[i], "--no-improve"))
        options.set("improve", 0);
      else {
        std::fprintf(stderr, "unknown argument %s\n", argv[i]);
        return 1;
      }
    }
    const wqmesh::Polyhedron in = wqmesh::Polyhedron::read_file(argv[1], options);
    if (!in.valid()) {
      std::fprintf(stderr, "%s: %s\n", argv[1], in.error_message().c_str());
      return 2;
    }
    struct Span {
      std::string phase;
      long long start, peak;
    };
    std::vector<Span> spans;
    spans.reserve(16);
    const long long base = g_live.load();
    const auto close = [&] {
      if (!spans.empty()) spans.back().peak = g_peak.load();
    };
    const wqmesh::Result result = wqmesh::mesh(in, options, [&](const wqmesh::MeshProgress& p) {
      const std::string name = wqmesh::to_string(p.phase);
      if (spans.empty() || spans.back().phase != name) {
        close();
        g_peak = g_live.load();
        spans.push_back({name, g_live.load(), 0});
      }
      return true;
    });
    close();
    const std::size_t tets = result.mesh().tets.size();
    const long long after = g_live.load();
    long long top = 0;
    std::string where;
    for (const Span& s : spans)
      if (s.peak > top) top = s.peak, where = s.phase;
    const auto mb = [](long long b) { return double(b) / (1 << 20); };
    const auto per = [&](long long b) { return tets ? double(b - base) / double(tets) : 0.0; };
    std::printf("model %s: %zu tets, %zu vertices; heap before the run %.1f MB\n", argv[1], tets,
                result.mesh().vertices.size(), mb(base));
    for (const Span& s : spans)
      std::printf("  %-10s at its start %8.1f MB %6.0f B/tet   peak %8.1f MB %6.0f B/tet\n", s.phase.c_str(),
                  mb(s.start - base), per(s.start), mb(s.peak - base), per(s.peak));
    std::printf("  result held after the run %.1f MB %.0f B/tet\n", mb(after - base), per(after));
    std::printf("peak %.1f MB %.0f B/tet in %s\n", mb(top - base), per(top), where.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
