// vismap as a library: the exact visibility map of a polygon scene seen by a
// camera, its segments and hidden lines, its JSON and its drawings.
//
//   vismap::Scene scene = vismap::read_scene("part.stl");
//   vismap::Camera camera;
//   camera.dir = vismap::Vec3{-1, -2, -3};
//   vismap::Map map = vismap::compute(scene, camera);
//   for (const vismap::Segment& s : map.segments()) ... map.vertices()[s.from] ...
//   map.write("part.svg");
//
// Plain C++20: no CGAL, GMP or Boost type appears here. Exact values are given
// as text ("-3", "7/16": lowest terms, as the JSON writes them) beside the
// nearest doubles. Errors are exceptions: InputError for a bad scene file,
// std::invalid_argument for an impossible camera or option, std::runtime_error
// for an output that cannot be written.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#define VISMAP_API __attribute__((visibility("default")))

namespace vismap {

// --- The scene ---------------------------------------------------------------

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

// Vertices and polygons (indices into `vertices`, in order around the polygon);
// a face's index is its position in `faces`.
//
// A face may have holes: holes[f] lists face f's hole rings (`holes` may be
// shorter than `faces`, or empty: faces past its end have none). A face with
// holes must be planar, each hole inside its outer ring and outside the other
// holes, no two rings crossing (they may share corners); a hole's edges are
// border edges of its face, and its orientation does not matter (the outer
// ring's says which side is the front).
using IndexRing = std::vector<std::uint32_t>;
struct Scene {
  std::string file;                                 // a name for messages and the JSON
  std::vector<Vec3> vertices;                       // finite doubles: the exact input
  std::vector<IndexRing> faces;                     // each face's outer ring
  std::vector<std::vector<IndexRing>> holes;        // each face's hole rings (optional)

  const std::vector<IndexRing>& holes_of(std::size_t face) const {
    static const std::vector<IndexRing> none;
    return face < holes.size() ? holes[face] : none;
  }
};

// Bad input. what() is the whole message and already names the file, and the
// line (or byte offset for binary formats) where there is one: "a.off:12: ...".
class VISMAP_API InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Refuse counts that cannot be real before allocating for them.
struct ReadLimits {
  std::uint64_t max_vertices = 50'000'000;
  std::uint64_t max_faces = 50'000'000;
  std::uint64_t max_face_degree = 1'000'000;
  // Bytes a whole run may use (0: no limit). A file larger than this, or a scene
  // whose estimated need is larger, is refused before anything is allocated for
  // it, as soon as its counts are known.
  std::uint64_t max_memory = 0;
  // Threads a reader may use (a large OFF file is parsed in pieces side by side);
  // the scene read is the same for every count.
  int threads = 1;
};

// Reads OFF, OBJ, STL (ASCII/binary), PLY (ASCII/binary) or vismap's own JSON
// scene (.vmscene.json: faces with holes; docs/format.md). `format` ("off",
// "obj", "stl", "ply", "vmscene", any case) forces one; when empty, a file's
// format comes from its extension (case-insensitive; .json is a vmscene), and
// standard input's (path "-") from its content. Throws InputError on any
// malformed input.
VISMAP_API Scene read_scene(const std::string& path, const ReadLimits& limits = {}, const std::string& format = "");

// The same from bytes already in memory; `format` is "off", "obj", "stl", "ply" or "vmscene".
VISMAP_API Scene read_scene_bytes(std::string_view bytes, const std::string& name, const std::string& format,
                                  const ReadLimits& limits = {});

// --- The camera and the options ----------------------------------------------

// Orthographic (dir) or perspective (eye, with target and fov). With nothing
// given: the whole scene, seen obliquely. docs/format.md defines the matrix.
struct Camera {
  std::optional<Vec3> dir;          // orthographic, looking along dir
  std::optional<Vec3> eye;          // perspective: the eye point
  std::optional<Vec3> target;       //   looked at (default: the scene's centre)
  std::optional<double> fov_deg;    //   vertical field of view (default 40)
  std::optional<Vec3> up;           // default 0,0,1 (0,1,0 when parallel to the view)
};

enum class Algorithm { Franklin, Newell, Bsp };   // all give the same map

struct Options {
  double crease_deg = 30;   // dihedral angle above which a shared edge is a crease
  double grid_c = 2.5;      // Franklin's c in B = c * min(sqrt(N), 1/L)
  bool smooth = false;      // also draw smooth edges
  bool hidden = false;      // also the hidden lines
  bool regions = true;      // false: the segments alone (a lines-only drawing), computing
                            // only what the drawn lines need; the map has no regions
  Algorithm algorithm = Algorithm::Franklin;
  int threads = 0;          // 0: every usable core (one below 8192 faces); the map is
                            // the same, byte for byte, for every count
};

// --- The map -------------------------------------------------------------------

enum class EdgeKind : std::uint8_t { Border, Silhouette, Crease, Smooth, Intersection };
VISMAP_API const char* to_string(EdgeKind k);   // "border", "silhouette", ...

// Rings and segment ends are indices into the map's vertices.
using Ring = std::vector<std::uint32_t>;

struct Region {
  int face = -1;                  // the input face it shows
  Ring outer;                     // counter-clockwise
  std::vector<Ring> holes;        // each clockwise
};

struct Segment {
  std::uint32_t from = 0, to = 0;   // from < to (lexicographic)
  EdgeKind kind = EdgeKind::Border;
  std::vector<int> faces;           // ascending
};

struct Point {
  double x = 0, y = 0;              // the nearest doubles to the exact values
};

struct ExactPoint {
  std::string x, y;                 // "0", "-3", "7/16" (lowest terms)
};

// A hidden line (with Options::hidden): its own end points, from < to.
struct HiddenLine {
  Point from, to;
  EdgeKind kind = EdgeKind::Border;
  std::vector<int> faces;
};

// How a drawing looks; the same choices as the command line's, as text.
struct DrawingOptions {
  std::string style = "shaded";     // shaded, technical or plotter
  std::vector<std::string> lines;   // restyle a class: "hidden:width=0.2,color=#888,dash=2/1"
  std::string page;                 // "" (a canvas), "a4", "a3", "letter" or "WxHmm"
  std::string scale;                // "" (fit the page) or "1:N"
  double margin = 10;               // mm, when fitting the page
  bool lines_only = false;          // no filled regions
  bool optimize_travel = false;     // order the paths to shorten pen-up travel
  bool svg_data = false;            // data-kind and data-faces on every SVG path
  std::string shading;              // "" or "R,N,B" / "R,N,B,S,M" (Newell's intensity)
  std::optional<Vec3> light;        // towards the light (default: at the eye)
};

// The exact visibility map (docs/format.md). Cheap to copy (shared, immutable).
class VISMAP_API Map {
 public:
  // Distinct, in lexicographic order of their exact values.
  const std::vector<Point>& vertices() const;
  ExactPoint exact(std::uint32_t vertex) const;

  bool has_regions() const;                       // false when computed without regions
  const std::vector<Region>& regions() const;
  const std::vector<Segment>& segments() const;
  bool has_hidden() const;                        // hidden lines were asked for
  const std::vector<HiddenLine>& hidden() const;  // sorted by (from, to)
  std::array<ExactPoint, 2> exact_hidden(std::size_t i) const;

  bool perspective() const;
  std::size_t scene_faces() const;

  // The JSON text, byte for byte the command line's (--json, without --stats).
  std::string to_json() const;
  // A drawing: "svg", "dxf", "pdf", "eps" or "png" (the last three need a build
  // with cairo). Throws std::invalid_argument for a bad option or format.
  std::string drawing(const DrawingOptions& options = {}, const std::string& format = "svg") const;
  // One file, by its extension: .json, or a drawing (.svg, .dxf, .pdf, .eps, .png);
  // written whole or not at all.
  void write(const std::string& path, const DrawingOptions& options = {}) const;

  struct Impl;
  explicit Map(std::shared_ptr<const Impl> impl);
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

// The map of `scene` seen by `camera`. Throws std::invalid_argument for an
// impossible camera (zero direction, eye on target, fov outside (0, 180)).
VISMAP_API Map compute(Scene scene, const Camera& camera = {}, const Options& options = {});

}  // namespace vismap
