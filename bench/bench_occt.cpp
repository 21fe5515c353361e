// The peers side by side (issue 4): OpenCASCADE's hidden-line removal against
// vismap's exact Franklin engine on the same scenes and the same view.
//
//   vismap   visibility_franklin (exact), the map's destruction included, as
//            bench_franklin times it
//   poly     OCCT's polygonal HLR: BRepMesh_IncrementalMesh on the shape, then
//            HLRBRep_PolyAlgo + HLRBRep_PolyHLRToShape (the mesh is part of the
//            time: the algorithm needs it)
//   exact    OCCT's exact HLR on the B-rep: HLRBRep_Algo (Add, Projector,
//            Update, Hide) + HLRBRep_HLRToShape
//
// Scene: Franklin's random squares (bench/scene_gen.h, random_squares_depth(N,
// D, seed 1980): the same scenes as bench_franklin's squares/D:5), each square
// an OCCT planar face (BRepBuilderAPI_MakePolygon + BRepBuilderAPI_MakeFace),
// all in one compound (the squares share no edges: nothing to sew). Building
// the B-rep is timed apart ("build"), not in the HLR totals.
//
// View: orthographic along --dir (default 0,0,-1, vismap's `--dir 0,0,-1`).
// vismap's screen axes are r = dir x up / |...| and u = r x dir (engine/camera.cpp);
// OCCT's projector is gp_Ax2(origin, -dir, r): its Z axis points to the eye and
// its X axis is r, so the two screens coincide (scale 1, same orientation).
//
// Visible line length: vismap's, the sum of its visible segments' lengths on
// the screen (the exact map's end points rounded to doubles); OCCT's, the total
// length (BRepGProp::LinearProperties) of the visible compounds in the
// projector's plane: VCompound (sharp edges) + OutLineVCompound (outlines) +
// Rg1LineVCompound (smooth edges; vismap draws those only with --smooth, and
// planar squares have none) -- each reported apart as well.
//
// Times are process CPU time (CLOCK_PROCESS_CPUTIME_ID) and wall time; for vismap
// also the engine's own phase timings (wall clock, in the CSV's last column).
//
//   bench_occt [--N 1000,3000,10000] [--D 5] [--reps 3] [--engines vismap,poly,exact]
//              [--dir X,Y,Z] [--deflection 0.01] [--csv]
//   bench_occt --mesh SCENE.off [--reps 3] [--engines poly] [--dir X,Y,Z] [--csv]
//
// Without --csv: a Markdown table of medians. With --csv: one CSV row per run
// (bench/run_all collects them).
//
// --mesh: a real mesh instead of the random squares (bench/run_all, section f).
// The mesh is read with vismap's reader (engine/scene.h) and built as OCCT faces
// that share their edges: one TopoDS_Vertex per mesh vertex, one TopoDS_Edge per
// mesh edge, each face a planar face on the wire of its (shared) edges, all in
// one compound ("build", not in the totals). Edges are not marked as smooth
// (no BRepLib::EncodeRegularity), so every mesh edge counts as a sharp edge, as
// with vismap's --crease 0 (except that OCCT also draws the edges between two
// coplanar faces, which vismap merges). The N and D columns of the CSV hold the
// face count and 0; a "scene" column names the file.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <unordered_map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <GProp_GProps.hxx>
#include <HLRAlgo_Projector.hxx>
#include <HLRBRep_Algo.hxx>
#include <HLRBRep_HLRToShape.hxx>
#include <HLRBRep_PolyAlgo.hxx>
#include <HLRBRep_PolyHLRToShape.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Ax2.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include "bench/cpu_time.h"
#include "bench/scene_gen.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace {

using namespace vismap;

using vismap::bench::cpu_now;
double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Timer {
  double cpu0 = cpu_now(), wall0 = wall_now();
  double cpu() const { return cpu_now() - cpu0; }
  double wall() const { return wall_now() - wall0; }
};

struct Result {
  double cpu = 0, wall = 0;          // the total that is compared
  double build = 0, mesh = 0;        // OCCT: B-rep construction (not in the total), meshing (poly, in the total)
  double length = 0;                 // visible line length
  double len_sharp = 0, len_outline = 0, len_smooth = 0;
  std::size_t edges = 0;             // visible edges (OCCT) or segments (vismap)
  std::string phases;                // vismap: the engine's phase timings (wall), "name=s;name=s"
};

double length_of(const TopoDS_Shape& s) {
  if (s.IsNull()) return 0;
  GProp_GProps props;
  BRepGProp::LinearProperties(s, props);
  return props.Mass();
}

std::size_t count_edges(const TopoDS_Shape& s) {
  if (s.IsNull()) return 0;
  std::size_t n = 0;
  for (TopExp_Explorer e(s, TopAbs_EDGE); e.More(); e.Next()) ++n;
  return n;
}

// The scene as one compound of planar faces (one per polygon). TopoDS_Builder,
// not its subclass BRep_Builder: Debian's OCCT 7.6.3 headers lack
// NCollection_AliasedArray.hxx, which BRep_Builder.hxx pulls in (through
// Poly_Triangulation.hxx); the compound needs only MakeCompound and Add.
TopoDS_Compound make_shape(const Scene& scene) {
  TopoDS_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const auto& face : scene.faces) {
    BRepBuilderAPI_MakePolygon poly;
    for (auto i : face) {
      const Vec3& p = scene.vertices[i];
      poly.Add(gp_Pnt(p.x, p.y, p.z));
    }
    poly.Close();
    if (!poly.IsDone()) throw std::runtime_error("BRepBuilderAPI_MakePolygon failed");
    BRepBuilderAPI_MakeFace mf(poly.Wire(), /*OnlyPlane=*/Standard_True);
    if (!mf.IsDone()) throw std::runtime_error("BRepBuilderAPI_MakeFace failed");
    builder.Add(compound, mf.Face());
  }
  return compound;
}

// A mesh as OCCT faces sharing vertices and edges (--mesh): HLR then sees each
// mesh edge once, with its two faces. Degenerate faces (repeated or collinear
// corners) that OCCT refuses are skipped and counted.
std::size_t g_mesh_skipped = 0;
TopoDS_Compound make_mesh_shape(const Scene& scene) {
  TopoDS_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  std::vector<TopoDS_Vertex> verts(scene.vertices.size());
  auto vertex = [&](std::uint32_t i) -> const TopoDS_Vertex& {
    if (verts[i].IsNull()) {
      const Vec3& p = scene.vertices[i];
      verts[i] = BRepBuilderAPI_MakeVertex(gp_Pnt(p.x, p.y, p.z));
    }
    return verts[i];
  };
  std::unordered_map<std::uint64_t, TopoDS_Edge> edges;
  g_mesh_skipped = 0;
  for (const auto& face : scene.faces) {
    try {
      BRepBuilderAPI_MakeWire wire;
      bool ok = face.size() >= 3;
      for (std::size_t k = 0; ok && k < face.size(); ++k) {
        std::uint32_t a = face[k], b = face[(k + 1) % face.size()];
        if (a == b) { ok = false; break; }
        const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        auto it = edges.find(key);
        if (it == edges.end()) {
          BRepBuilderAPI_MakeEdge me(vertex(std::min(a, b)), vertex(std::max(a, b)));
          if (!me.IsDone()) { ok = false; break; }
          it = edges.emplace(key, me.Edge()).first;
        }
        wire.Add(it->second);
        if (!wire.IsDone()) ok = false;
      }
      if (!ok) { ++g_mesh_skipped; continue; }
      BRepBuilderAPI_MakeFace mf(wire.Wire(), /*OnlyPlane=*/Standard_True);
      if (!mf.IsDone()) { ++g_mesh_skipped; continue; }
      builder.Add(compound, mf.Face());
    } catch (const Standard_Failure&) {
      ++g_mesh_skipped;
    }
  }
  return compound;
}

// OCCT's projector for vismap's orthographic view: Z to the eye (-dir), X = r.
HLRAlgo_Projector projector_for(const View& view) {
  const auto& m = view.m;   // rows r, u, f (orthographic, unit vectors)
  const gp_Dir to_eye(-m[2][0], -m[2][1], -m[2][2]);
  const gp_Dir right(m[0][0], m[0][1], m[0][2]);
  return HLRAlgo_Projector(gp_Ax2(gp_Pnt(0, 0, 0), to_eye, right));
}

Result run_vismap(const Scene& scene, const View& view) {
  Result r;
  Timer t;
  VisibilityMap map = visibility_franklin(scene, view, Options{});
  double len = 0;
  for (const Segment& s : map.segments) {
    const Point2 &from = map.at(s.from), &to = map.at(s.to);
    const double dx = to.x.get_d() - from.x.get_d(), dy = to.y.get_d() - from.y.get_d();
    len += std::sqrt(dx * dx + dy * dy);
  }
  r.edges = map.segments.size();
  for (const auto& [name, sec] : map.stats.seconds) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%s=%.4f", r.phases.empty() ? "" : ";", name.c_str(), sec);
    r.phases += buf;
  }
  map = {};   // destruction included, as in bench_franklin
  r.cpu = t.cpu();
  r.wall = t.wall();
  r.length = r.len_sharp = len;   // (the length sum itself is negligible)
  return r;
}

// The visible lines' lengths and edge counts, by OCCT's three kinds (outside the timing).
void measure_lines(Result& r, const TopoDS_Shape& sharp, const TopoDS_Shape& outline, const TopoDS_Shape& smooth) {
  r.len_sharp = length_of(sharp);
  r.len_outline = length_of(outline);
  r.len_smooth = length_of(smooth);
  r.length = r.len_sharp + r.len_outline + r.len_smooth;
  r.edges = count_edges(sharp) + count_edges(outline) + count_edges(smooth);
}

Result run_poly(const Scene& scene, const View& view, double deflection, bool mesh = false) {
  Result r;
  Timer tb;
  const TopoDS_Compound shape = mesh ? make_mesh_shape(scene) : make_shape(scene);
  r.build = tb.cpu();
  Timer t;
  BRepMesh_IncrementalMesh mesher(shape, deflection, /*isRelative=*/Standard_False, /*angle=*/0.5,
                                  /*isInParallel=*/Standard_False);
  r.mesh = t.cpu();
  Handle(HLRBRep_PolyAlgo) algo = new HLRBRep_PolyAlgo();
  algo->Load(shape);
  algo->Projector(projector_for(view));
  algo->Update();
  HLRBRep_PolyHLRToShape to_shape;
  to_shape.Update(algo);
  const TopoDS_Shape sharp = to_shape.VCompound();
  const TopoDS_Shape outline = to_shape.OutLineVCompound();
  const TopoDS_Shape smooth = to_shape.Rg1LineVCompound();
  r.cpu = t.cpu();
  r.wall = t.wall();
  measure_lines(r, sharp, outline, smooth);
  return r;
}

Result run_exact(const Scene& scene, const View& view, bool mesh = false) {
  Result r;
  Timer tb;
  const TopoDS_Compound shape = mesh ? make_mesh_shape(scene) : make_shape(scene);
  r.build = tb.cpu();
  Timer t;
  Handle(HLRBRep_Algo) algo = new HLRBRep_Algo();
  algo->Add(shape);
  algo->Projector(projector_for(view));
  algo->Update();
  algo->Hide();
  HLRBRep_HLRToShape to_shape(algo);
  const TopoDS_Shape sharp = to_shape.VCompound();
  const TopoDS_Shape outline = to_shape.OutLineVCompound();
  const TopoDS_Shape smooth = to_shape.Rg1LineVCompound();
  r.cpu = t.cpu();
  r.wall = t.wall();
  measure_lines(r, sharp, outline, smooth);
  return r;
}

template <class T>
std::vector<T> parse_list(const std::string& s, const std::function<T(const std::string&)>& conv) {
  std::vector<T> out;
  std::stringstream in(s);
  std::string tok;
  while (std::getline(in, tok, ',')) out.push_back(conv(tok));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_occt [--N 1000,3000,10000] [--D 5] [--reps 3] [--engines vismap,poly,exact]\n"
               "                  [--dir X,Y,Z] [--deflection 0.01] [--csv]\n"
               "       bench_occt --mesh SCENE.off [--reps 3] [--engines poly] [--dir X,Y,Z] [--csv]\n");
  return 2;
}

// Runs body, turning OpenCASCADE's and the standard library's exceptions into a
// message and exit status 1.
int guarded(const std::function<void()>& body) {
  try {
    body();
  } catch (const Standard_Failure& f) {
    std::fprintf(stderr, "bench_occt: OpenCASCADE failed: %s\n", f.GetMessageString());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_occt: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes = {1000, 3000, 10000};
  std::vector<std::string> engines = {"vismap", "poly", "exact"};
  double depth = 5, deflection = 0.01;
  int reps = 3;
  bool csv = false;
  Vec3 dir{0, 0, -1};
  std::string mesh_path;
  bool engines_given = false;
  try {
    for (int k = 1; k < argc; ++k) {
      const std::string a = argv[k];
      auto value = [&]() -> std::string {
        if (k + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++k];
      };
      if (a == "--N") sizes = parse_list<long>(value(), [](const std::string& s) { return std::stol(s); });
      else if (a == "--D") depth = std::stod(value());
      else if (a == "--reps") reps = std::stoi(value());
      else if (a == "--engines") {
        engines = parse_list<std::string>(value(), [](const std::string& s) { return s; });
        engines_given = true;
      } else if (a == "--mesh") mesh_path = value();
      else if (a == "--deflection") deflection = std::stod(value());
      else if (a == "--csv") csv = true;
      else if (a == "--dir") {
        const auto d = parse_list<double>(value(), [](const std::string& s) { return std::stod(s); });
        if (d.size() != 3) throw std::invalid_argument("--dir needs X,Y,Z");
        dir = Vec3{d[0], d[1], d[2]};
      } else return usage();
    }
    if (!mesh_path.empty() && !engines_given) engines = {"poly"};
    for (const auto& e : engines)
      if (e != "vismap" && e != "poly" && e != "exact") throw std::invalid_argument("unknown engine " + e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_occt: %s\n", e.what());
    return usage();
  }

  if (!mesh_path.empty()) {
    return guarded([&] {
      const Scene scene = read_scene(mesh_path);
      Camera camera;
      camera.dir = dir;
      const View view = make_view(camera, scene);
      const std::string name = mesh_path.substr(mesh_path.find_last_of('/') + 1);
      if (csv)
        std::printf("scene,faces,engine,rep,cpu_s,wall_s,build_s,mesh_s,visible_length,length_sharp,length_outline,"
                    "length_smooth,edges,skipped_faces\n");
      else
        std::printf("| scene | faces | engine | CPU s | wall s | build s | visible length | edges |\n"
                    "|---|---:|---|---:|---:|---:|---:|---:|\n");
      std::fflush(stdout);
      for (const std::string& e : engines) {
        for (int rep = 0; rep < reps; ++rep) {
          Result r = e == "vismap" ? run_vismap(scene, view)
                     : e == "poly" ? run_poly(scene, view, deflection, true)
                                   : run_exact(scene, view, true);
          if (csv)
            std::printf("%s,%zu,%s,%d,%.6f,%.6f,%.6f,%.6f,%.12g,%.12g,%.12g,%.12g,%zu,%zu\n", name.c_str(),
                        scene.faces.size(), e.c_str(), rep, r.cpu, r.wall, r.build, r.mesh, r.length, r.len_sharp,
                        r.len_outline, r.len_smooth, r.edges, e == "vismap" ? std::size_t(0) : g_mesh_skipped);
          else
            std::printf("| %s | %zu | %s | %.3f | %.3f | %.3f | %.9g | %zu |\n", name.c_str(), scene.faces.size(),
                        e.c_str(), r.cpu, r.wall, r.build, r.length, r.edges);
          std::fflush(stdout);
        }
      }
    });
  }

  if (csv) {
    std::printf("N,D,engine,rep,cpu_s,wall_s,build_s,mesh_s,visible_length,length_sharp,length_outline,"
                "length_smooth,edges,phases\n");
  } else {
    std::printf("| N | engine | CPU s (median of %d) | wall s | visible length | edges / segments |\n", reps);
    std::printf("|---:|---|---:|---:|---:|---:|\n");
  }
  std::fflush(stdout);
  return guarded([&] {
    for (long n : sizes) {
      const Scene scene = gen::random_squares_depth(static_cast<std::size_t>(n), depth, 1980);
      Camera camera;
      camera.dir = dir;
      const View view = make_view(camera, scene);
      for (const std::string& e : engines) {
        std::vector<double> cpus, walls;
        Result last;
        for (int rep = 0; rep < reps; ++rep) {
          Result r = e == "vismap" ? run_vismap(scene, view)
                     : e == "poly" ? run_poly(scene, view, deflection)
                                   : run_exact(scene, view);
          cpus.push_back(r.cpu);
          walls.push_back(r.wall);
          last = r;
          if (csv) {
            std::printf("%ld,%g,%s,%d,%.6f,%.6f,%.6f,%.6f,%.12g,%.12g,%.12g,%.12g,%zu,%s\n", n, depth, e.c_str(), rep,
                        r.cpu, r.wall, r.build, r.mesh, r.length, r.len_sharp, r.len_outline, r.len_smooth, r.edges,
                        r.phases.c_str());
            std::fflush(stdout);
          }
        }
        if (!csv) {
          std::printf("| %ld | %s | %.3f | %.3f | %.9g | %zu |\n", n, e.c_str(), median(cpus), median(walls),
                      last.length, last.edges);
          std::fflush(stdout);
        }
      }
    }
  });
}
