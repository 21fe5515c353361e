// Newell's depth sort against Franklin's grid, on the same scenes: which of the
// two exact engines is faster, and how many fragments the depth sort makes.
//
//   squares_top/<engine>/D:<D>/N:<N>       Franklin's random squares seen along
//                                          -z: all parallel to the screen, so
//                                          the depth order is plain sorting
//   squares_oblique/<engine>/D:<D>/N:<N>   the same seen obliquely: depth ranges
//                                          overlap, the five tests do real work
//   boxes/<engine>/N:<N>                   interpenetrating boxes: every
//                                          piercing face pair must be split
//   triangles/<engine>/N:<N>               random triangles in general position
//
// Counters: us_per_face; faces; fragments (Newell: fragments written to the
// list, Franklin: the faces it keeps, one fragment each); splits (by plane and
// by cut) and reorders (Newell only); segments and regions of the map (the
// same for both engines). Wall time, the map's destruction included.
#include <benchmark/benchmark.h>

#include <charconv>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "bench/scene_gen.h"
#include "engine/camera.h"
#include "engine/visibility.h"

namespace {

constexpr std::uint64_t kSeed = 1972;   // one fixed scene per point: runs are comparable

std::int64_t counted(const vismap::VisibilityMap& m, const std::string& name) {
  for (const auto& [k, v] : m.stats.counts)
    if (k == name) return v;
  return 0;
}

using MakeScene = std::function<vismap::Scene(std::size_t n)>;

void bm_engine(benchmark::State& state, MakeScene make, vismap::Vec3 dir, bool newell) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const vismap::Scene scene = make(n);   // outside the timed loop
  vismap::Camera camera;
  camera.dir = dir;
  const vismap::View view = vismap::make_view(camera, scene);
  const vismap::Options options;

  double seconds = 0;
  std::int64_t fragments = 0, splits = 0, reorders = 0;
  std::size_t segments = 0, regions = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    vismap::VisibilityMap map = newell ? vismap::visibility_newell(scene, view, options)
                                       : vismap::visibility_franklin(scene, view, options);
    segments = map.segments.size();
    regions = map.regions.size();
    if (newell) {
      fragments = counted(map, "fragments_written");
      splits = counted(map, "splits_by_plane") + counted(map, "splits_by_cut");
      reorders = counted(map, "reorders");
    } else {
      fragments = counted(map, "facets") - counted(map, "culled_outside_view") - counted(map, "culled_edge_on") -
                  counted(map, "culled_back_faces") - counted(map, "culled_behind_blocking_face");
    }
    benchmark::DoNotOptimize(map);
    map = {};
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const auto faces = static_cast<double>(scene.faces.size());
  state.SetComplexityN(state.range(0));
  state.counters["us_per_face"] = seconds * 1e6 / (static_cast<double>(state.iterations()) * faces);
  state.counters["faces"] = faces;
  state.counters["fragments"] = static_cast<double>(fragments);
  if (newell) {
    state.counters["splits"] = static_cast<double>(splits);
    state.counters["reorders"] = static_cast<double>(reorders);
  }
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["regions"] = static_cast<double>(regions);
}

std::string number(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// <scene>/<engine><params>/N:<n>, both engines side by side.
void family(const std::string& scene, const std::string& params, const MakeScene& make, vismap::Vec3 dir,
            std::initializer_list<int> sizes) {
  for (bool newell : {false, true}) {
    const std::string name = scene + (newell ? "/newell" : "/franklin") + params;
    auto* b = benchmark::RegisterBenchmark(name.c_str(), bm_engine, make, dir, newell);
    b->ArgName("N");
    for (int n : sizes) b->Arg(n);
    b->Unit(benchmark::kMillisecond)->UseRealTime()->Complexity(benchmark::oAuto);
  }
}

void register_all() {
  using namespace vismap::gen;
  const vismap::Vec3 top{0, 0, -1}, oblique{-0.3, -0.5, -1}, corner{-1, -2, -1.5};
  for (double d : {1.0, 5.0, 20.0}) {
    auto squares = [d](std::size_t n) { return random_squares_depth(n, d, kSeed); };
    family("squares_top", "/D:" + number(d), squares, top, {1000, 3000, 10000});
    family("squares_oblique", "/D:" + number(d), squares, oblique, {1000, 3000, 10000});
  }
  family("boxes", "", [](std::size_t n) { return interpenetrating_boxes(n, kSeed); }, corner, {5, 10, 20, 40});
  family("triangles", "", [](std::size_t n) { return random_triangles(n, 0.1, kSeed); }, corner, {300, 1000, 3000});
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
