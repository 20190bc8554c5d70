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
// The resident memory too (issue 15: the peak RSS is the goal's measure): a
// second thread reads /proc/self/statm every millisecond and keeps the
// largest RSS seen, with the live heap, the phase and malloc's own counts
// (mallinfo2: the main arena's bytes from the system, those free in it, the
// mmapped blocks) at that moment; each phase's line gives the process's
// high-water mark (VmHWM) at its end, so the phase that set the peak RSS is
// the one whose VmHWM is the run's. After the run the .mesh text and the
// statistics are made as `wqmesh mesh -o M.mesh --stats` makes them (phase
// "output"), since they belong to that command's peak.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <fcntl.h>
#include <malloc.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <new>
#include <string>
#include <thread>
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

/// The resident set of the process in bytes (/proc/self/statm's second
/// field), read without allocating; 0 when it cannot be read.
long long resident_bytes() {
  const int fd = ::open("/proc/self/statm", O_RDONLY);
  if (fd < 0) return 0;
  char text[128];
  const ssize_t n = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (n <= 0) return 0;
  text[n] = 0;
  const char* q = text;
  while (*q && *q != ' ') ++q;
  return std::atoll(q) * ::sysconf(_SC_PAGESIZE);
}

/// The process's peak resident set so far (VmHWM of /proc/self/status), in
/// bytes; 0 when it cannot be read.
long long high_water_bytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.compare(0, 6, "VmHWM:") == 0) return std::atoll(line.c_str() + 6) * 1024;
  return 0;
}

std::atomic<int> g_phase{-1};
std::atomic<bool> g_sampling{true};
/// Milliseconds since the run's start, and those of the last progress call.
const auto g_t0 = std::chrono::steady_clock::now();
long long now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - g_t0).count();
}
std::atomic<long long> g_last_call_ms{0};
/// What the sampler saw at the largest RSS.
struct RssPeak {
  long long rss = 0, live = 0, arena = 0, free_in_arena = 0, mmapped = 0, ms = 0, last_call_ms = 0;
  int phase = -1;
};

void sample(RssPeak* peak) {
  while (g_sampling) {
    const long long rss = resident_bytes();
    if (rss > peak->rss) {
      peak->rss = rss;
      peak->live = g_live.load();
      peak->phase = g_phase.load();
      peak->ms = now_ms();
      peak->last_call_ms = g_last_call_ms.load();
      // mallinfo2 walks the free lists: only when the peak grew by 1 MB.
      static long long last = 0;
      if (rss > last + (1 << 20)) {
        last = rss;
        const struct mallinfo2 m = mallinfo2();
        peak->arena = static_cast<long long>(m.arena);
        peak->free_in_arena = static_cast<long long>(m.fordblks);
        peak->mmapped = static_cast<long long>(m.hblkhd);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
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
      long long start, peak, hwm, rss;
    };
    std::vector<Span> spans;
    spans.reserve(16);
    const long long base = g_live.load();
    RssPeak rss;
    std::thread sampler(sample, &rss);
    const auto close = [&] {
      if (!spans.empty()) spans.back().peak = g_peak.load(), spans.back().hwm = high_water_bytes();
    };
    const wqmesh::Result result = wqmesh::mesh(in, options, [&](const wqmesh::MeshProgress& p) {
      const std::string name = wqmesh::to_string(p.phase);
      if (spans.empty() || spans.back().phase != name) {
        close();
        g_peak = g_live.load();
        spans.push_back({name, g_live.load(), 0, 0, resident_bytes()});
        g_phase = static_cast<int>(spans.size()) - 1;
      }
      g_last_call_ms = now_ms();
      return true;
    });
    close();
    // What `wqmesh mesh -o M.mesh --stats S` makes after the run.
    g_peak = g_live.load();
    spans.push_back({"output", g_live.load(), 0, 0, resident_bytes()});
    g_phase = static_cast<int>(spans.size()) - 1;
    const long long run_end_ms = now_ms();
    g_last_call_ms = run_end_ms;
    if (result.conforming()) {
      std::ofstream sink("/dev/null", std::ios::binary);
      result.write(sink, wqmesh::OutputFormat::medit);
    }
    const std::string stats = result.stats_json(0);
    close();
    g_sampling = false;
    sampler.join();
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
      std::printf(
          "  %-10s at its start %8.1f MB %6.0f B/tet (RSS %7.1f MB)   peak %8.1f MB %6.0f B/tet   VmHWM at its end "
          "%8.1f "
          "MB\n",
          s.phase.c_str(), mb(s.start - base), per(s.start), mb(s.rss), mb(s.peak - base), per(s.peak), mb(s.hwm));
    std::printf("  result held after the run %.1f MB %.0f B/tet\n", mb(after - base), per(after));
    std::printf("peak %.1f MB %.0f B/tet in %s\n", mb(top - base), per(top), where.c_str());
    std::printf("peak RSS (VmHWM) %.1f MB %.0f B/tet\n", mb(spans.back().hwm), per(spans.back().hwm + base));
    std::printf(
        "largest RSS sampled %.1f MB in %s: live heap %.1f MB; malloc: arena %.1f MB (%.1f free), mmapped %.1f MB\n",
        mb(rss.rss), rss.phase >= 0 ? spans[rss.phase].phase.c_str() : "?", mb(rss.live - base), mb(rss.arena),
        mb(rss.free_in_arena), mb(rss.mmapped));
    std::printf("  at %.2f s, %.2f s after the last progress call (the run ended at %.2f s)\n", rss.ms / 1e3,
                (rss.ms - rss.last_call_ms) / 1e3, run_end_ms / 1e3);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
