// Franklin 1980's experiment, redone: random squares seen from +z.
//
//   squares/D:<D>/N:<N>   N = 1000 .. 100000 at constant depth complexity D;
//                         the paper claims time linear in N (fit_exponent.py
//                         prints the measured exponent).
//   squares_depth/D:<D>/N:10000
//                         D = 0.1 .. 30 at fixed N; the paper claims time does
//                         not grow with D.
//   squares_float/D:5/N:<N>
//                         the same engine compiled on plain doubles
//                         (visibility_franklin_float): what exactness costs.
//
// Counters: us_per_face (wall time per face), faces, segments and regions of
// the visibility map; where the time goes: s_<phase> (the engine's own phase
// timings, seconds per run) and the exact work per run (predicates,
// predicates_exact, constructed_points, pieces), read by bench/run_all (f). Wall time (UseRealTime) so any threads the engine uses
// are counted. Run with --benchmark_format=json > out.json for fit_exponent.py.
#include <benchmark/benchmark.h>

#include <charconv>
#include <chrono>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

#include "bench/scene_gen.h"
#include "engine/camera.h"
#include "engine/visibility.h"

namespace {

constexpr std::uint64_t kSeed = 1980;  // one fixed scene per (N, D): runs are comparable

using Engine = vismap::VisibilityMap (*)(const vismap::Scene&, const vismap::View&,
                                         const vismap::Options&, const vismap::engine::WorldScene*);

void bm_squares(benchmark::State& state, double depth, Engine engine) {
  const auto n = static_cast<std::size_t>(state.range(0));
  // Built outside the timed loop: only the engine is measured.
  const vismap::Scene scene = vismap::gen::random_squares_depth(n, depth, kSeed);
  vismap::Camera camera;  // --dir 0,0,-1: orthographic, looking down from +z
  camera.dir = vismap::Vec3{0, 0, -1};
  const vismap::View view = vismap::make_view(camera, scene);
  const vismap::Options options;

  std::size_t segments = 0, regions = 0, invalid = 0, profiled = 0;
  double seconds = 0;  // own wall clock: Google Benchmark's inverted rates print as "s"
  std::map<std::string, double> phases;   // summed over the runs that returned a map
  vismap::Stats last;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    vismap::VisibilityMap map;
    try {
      map = engine(scene, view, options, nullptr);
    } catch (const std::logic_error&) {   // the float variant's labels may contradict each other
      ++invalid;                          // (found when the map is assembled: the time still counts)
    }
    segments = map.segments.size();
    regions = map.regions.size();
    if (!map.stats.seconds.empty()) {
      ++profiled;
      for (const auto& [name, t] : map.stats.seconds) phases[name] += t;
      last = std::move(map.stats);
    }
    benchmark::DoNotOptimize(map);
    map = {};  // free the map inside the timed region: its destruction is part of the cost
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  const auto faces = static_cast<double>(n);
  state.SetComplexityN(state.range(0));
  state.counters["us_per_face"] =
      seconds * 1e6 / (static_cast<double>(state.iterations()) * faces);
  state.counters["faces"] = faces;
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["regions"] = static_cast<double>(regions);
  state.counters["D"] = depth;
  state.counters["invalid_maps"] = static_cast<double>(invalid);
  for (const auto& [name, t] : phases) state.counters["s_" + name] = t / static_cast<double>(profiled);
  for (const char* name : {"predicates", "predicates_exact", "constructed_points", "pieces"})
    state.counters[name] = static_cast<double>(last.counted(name));
}

std::string number(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

void register_all() {
  // N sweep at constant D: one family per D, so each gets its own complexity fit.
  for (double depth : {5.0, 20.0}) {
    auto* b = benchmark::RegisterBenchmark(("squares/D:" + number(depth)).c_str(), bm_squares, depth,
                                           vismap::visibility_franklin);
    b->ArgName("N");
    for (int n : {1000, 3000, 10000, 30000, 100000}) b->Arg(n);
    b->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Complexity(benchmark::oAuto);
  }
  // D sweep at N = 10000, as Franklin's SPHERES experiment varied D from 0.1 to 30.
  for (double depth : {0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0}) {
    benchmark::RegisterBenchmark(("squares_depth/D:" + number(depth)).c_str(), bm_squares, depth,
                                 vismap::visibility_franklin)
        ->ArgName("N")
        ->Arg(10000)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MeasureProcessCPUTime();
  }
  // The float variant on the D = 5 scenes: compare with squares/D:5 run for run.
  auto* f = benchmark::RegisterBenchmark("squares_float/D:5", bm_squares, 5.0, vismap::visibility_franklin_float);
  f->ArgName("N");
  for (int n : {1000, 3000, 10000, 30000, 100000}) f->Arg(n);
  f->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
