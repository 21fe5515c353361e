// import vismap: the library's API (include/vismap/vismap.h) for Python.
//
//   m = vismap.compute("part.stl", dir=(-1, -2, -3), hidden=True)
//   m.segments          # (S, 2, 2) float64: each visible segment's two end points
//   m.to_json()         # the command line's JSON, byte for byte
//   m.write("part.svg", style="technical")
//
// Coordinates are the nearest doubles to the exact values; exact_vertices(),
// exact_segments() and exact_hidden() give them as fractions.Fraction. The GIL
// is released while a map is computed or written.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "vismap/vismap.h"

namespace py = pybind11;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::optional<vismap::Vec3> vec3(const std::optional<std::vector<double>>& v, const char* name) {
  if (!v) return std::nullopt;
  if (v->size() != 3) throw py::value_error(std::string(name) + " must have three components");
  return vismap::Vec3{(*v)[0], (*v)[1], (*v)[2]};
}

// One ring of vertex indices, each checked against the vertex count.
vismap::IndexRing ring_from(const py::handle& ring, std::size_t vertices, const std::string& what) {
  vismap::IndexRing r;
  for (const py::handle i : ring) {
    const long long k = py::cast<long long>(i);
    if (k < 0 || k >= static_cast<long long>(vertices))
      throw py::index_error(what + " names vertex " + std::to_string(k) + ", but there are " +
                            std::to_string(vertices) + " vertices");
    r.push_back(static_cast<std::uint32_t>(k));
  }
  return r;
}

// A scene from numpy: vertices N x 3, faces an F x k integer array or a list of
// index lists (polygons of any size); holes, optional, a dict from a face's
// index to its list of hole rings.
vismap::Scene scene_from(const Array& vertices, const py::object& faces, const py::object& holes,
                         const std::string& name) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) throw py::value_error("vertices must be an N x 3 array");
  vismap::Scene s;
  s.file = name;
  auto v = vertices.unchecked<2>();
  s.vertices.reserve(v.shape(0));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) s.vertices.push_back({v(i, 0), v(i, 1), v(i, 2)});
  for (const py::handle face : faces)
    s.faces.push_back(ring_from(face, s.vertices.size(), "face " + std::to_string(s.faces.size())));
  if (holes.is_none()) return s;
  for (const auto& [key, rings] : py::cast<py::dict>(holes)) {
    const long long f = py::cast<long long>(key);
    if (f < 0 || f >= static_cast<long long>(s.faces.size()))
      throw py::index_error("holes name face " + std::to_string(f) + ", but there are " +
                            std::to_string(s.faces.size()) + " faces");
    if (s.holes.size() <= static_cast<std::size_t>(f)) s.holes.resize(static_cast<std::size_t>(f) + 1);
    for (const py::handle ring : rings) {
      const std::string what = "hole " + std::to_string(s.holes[f].size()) + " of face " + std::to_string(f);
      s.holes[f].push_back(ring_from(ring, s.vertices.size(), what));
    }
  }
  return s;
}

py::array_t<double> scene_vertices(const vismap::Scene& s) {
  py::array_t<double> out({static_cast<py::ssize_t>(s.vertices.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    o(i, 0) = s.vertices[i].x;
    o(i, 1) = s.vertices[i].y;
    o(i, 2) = s.vertices[i].z;
  }
  return out;
}

py::array_t<double> points(const std::vector<vismap::Point>& ps) {
  py::array_t<double> out({static_cast<py::ssize_t>(ps.size()), py::ssize_t{2}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    o(i, 0) = ps[i].x;
    o(i, 1) = ps[i].y;
  }
  return out;
}

// (n, 2, 2): each line's two end points.
template <class EndPoints>
py::array_t<double> lines(std::size_t n, EndPoints ends) {
  py::array_t<double> out({static_cast<py::ssize_t>(n), py::ssize_t{2}, py::ssize_t{2}});
  auto o = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < n; ++i) {
    const auto [a, b] = ends(i);
    o(i, 0, 0) = a.x;
    o(i, 0, 1) = a.y;
    o(i, 1, 0) = b.x;
    o(i, 1, 1) = b.y;
  }
  return out;
}

py::tuple fraction_point(const py::object& fraction, const vismap::ExactPoint& p) {
  return py::make_tuple(fraction(p.x), fraction(p.y));
}

py::array_t<double> ring_points(const vismap::Map& m, const vismap::Ring& ring) {
  std::vector<vismap::Point> ps;
  ps.reserve(ring.size());
  for (std::uint32_t v : ring) ps.push_back(m.vertices()[v]);
  return points(ps);
}

vismap::DrawingOptions drawing_options(const std::string& style, const std::variant<std::string, std::vector<std::string>>& line,
                                       const std::string& page, const std::string& scale, double margin,
                                       bool lines_only, bool optimize_travel, bool svg_data,
                                       const std::string& shading, const std::optional<std::vector<double>>& light) {
  vismap::DrawingOptions d;
  d.style = style;
  if (const auto* one = std::get_if<std::string>(&line)) {
    if (!one->empty()) d.lines.push_back(*one);
  } else {
    d.lines = std::get<std::vector<std::string>>(line);
  }
  d.page = page;
  d.scale = scale;
  d.margin = margin;
  d.lines_only = lines_only;
  d.optimize_travel = optimize_travel;
  d.svg_data = svg_data;
  d.shading = shading;
  d.light = vec3(light, "light");
  return d;
}

// The drawing keywords, shared by to_svg, drawing and write.
#define VISMAP_DRAWING_ARGS                                                                              \
  py::kw_only(), py::arg("style") = "shaded", py::arg("line") = std::string(), py::arg("page") = "",    \
      py::arg("scale") = "", py::arg("margin") = 10.0, py::arg("lines_only") = false,                    \
      py::arg("optimize_travel") = false, py::arg("svg_data") = false, py::arg("shading") = "",         \
      py::arg("light") = py::none()

using LineArg = std::variant<std::string, std::vector<std::string>>;
using Light = std::optional<std::vector<double>>;

}  // namespace

PYBIND11_MODULE(vismap, mod) {
  mod.doc() = "Exact visibility maps of polygon scenes: visible regions, visible and hidden lines, drawings.";
  py::register_exception<vismap::InputError>(mod, "InputError", PyExc_ValueError);

  py::class_<vismap::Scene>(mod, "Scene",
                            "Vertices (N x 3 doubles), polygons (lists of vertex indices) and, optionally, "
                            "holes: {face index: [hole ring, ...]} (a face with holes must be planar).")
      .def(py::init([](const Array& vertices, const py::object& faces, const py::object& holes,
                       const std::string& name) { return scene_from(vertices, faces, holes, name); }),
           py::arg("vertices"), py::arg("faces"), py::arg("holes") = py::none(), py::arg("name") = "")
      .def_property_readonly("vertices", &scene_vertices)
      .def_property_readonly("faces", [](const vismap::Scene& s) { return s.faces; })
      .def_property_readonly("holes",
                             [](const vismap::Scene& s) {
                               py::dict out;
                               for (std::size_t f = 0; f < s.holes.size(); ++f)
                                 if (!s.holes[f].empty()) out[py::int_(f)] = s.holes[f];
                               return out;
                             })
      .def_readonly("name", &vismap::Scene::file)
      .def("__repr__", [](const vismap::Scene& s) {
        return "<vismap.Scene " + (s.file.empty() ? std::string() : s.file + ": ") + std::to_string(s.vertices.size()) +
               " vertices, " + std::to_string(s.faces.size()) + " faces>";
      });

  mod.def(
      "read_scene",
      [](const std::string& path, const std::string& format) {
        py::gil_scoped_release unlocked;
        return vismap::read_scene(path, {}, format);
      },
      py::arg("path"), py::arg("format") = "", "Reads an OFF, OBJ, STL or PLY file (format by its extension unless named).");

  py::class_<vismap::Map>(mod, "Map", "The exact visibility map (docs/format.md).")
      .def_property_readonly("vertices", [](const vismap::Map& m) { return points(m.vertices()); },
                             "(V, 2) float64: the map's vertices (nearest doubles), in lexicographic order")
      .def_property_readonly(
          "segments",
          [](const vismap::Map& m) {
            const auto& s = m.segments();
            return lines(s.size(), [&](std::size_t i) { return std::pair(m.vertices()[s[i].from], m.vertices()[s[i].to]); });
          },
          "(S, 2, 2) float64: each visible segment's end points")
      .def_property_readonly(
          "segment_vertices",
          [](const vismap::Map& m) {
            py::array_t<std::uint32_t> out({static_cast<py::ssize_t>(m.segments().size()), py::ssize_t{2}});
            auto o = out.mutable_unchecked<2>();
            for (std::size_t i = 0; i < m.segments().size(); ++i) {
              o(i, 0) = m.segments()[i].from;
              o(i, 1) = m.segments()[i].to;
            }
            return out;
          },
          "(S, 2) uint32: each segment's end points as indices into vertices")
      .def_property_readonly("segment_kinds",
                             [](const vismap::Map& m) {
                               std::vector<std::string> k;
                               for (const auto& s : m.segments()) k.push_back(vismap::to_string(s.kind));
                               return k;
                             })
      .def_property_readonly("segment_faces",
                             [](const vismap::Map& m) {
                               py::list out;
                               for (const auto& s : m.segments()) out.append(py::tuple(py::cast(s.faces)));
                               return out;
                             })
      .def_property_readonly(
          "hidden",
          [](const vismap::Map& m) {
            const auto& h = m.hidden();
            return lines(h.size(), [&](std::size_t i) { return std::pair(h[i].from, h[i].to); });
          },
          "(H, 2, 2) float64: each hidden line's end points (empty unless computed with hidden=True)")
      .def_property_readonly("hidden_kinds",
                             [](const vismap::Map& m) {
                               std::vector<std::string> k;
                               for (const auto& h : m.hidden()) k.push_back(vismap::to_string(h.kind));
                               return k;
                             })
      .def_property_readonly("hidden_faces",
                             [](const vismap::Map& m) {
                               py::list out;
                               for (const auto& h : m.hidden()) out.append(py::tuple(py::cast(h.faces)));
                               return out;
                             })
      .def_property_readonly(
          "regions",
          [](const vismap::Map& m) {
            py::list out;
            for (const vismap::Region& r : m.regions()) {
              py::list holes;
              for (const vismap::Ring& h : r.holes) holes.append(ring_points(m, h));
              out.append(py::make_tuple(r.face, ring_points(m, r.outer), holes));
            }
            return out;
          },
          "[(face, outer (k, 2) array counter-clockwise, [hole arrays, clockwise]), ...]")
      .def_property_readonly("has_regions", &vismap::Map::has_regions)
      .def_property_readonly("has_hidden", &vismap::Map::has_hidden)
      .def_property_readonly("perspective", &vismap::Map::perspective)
      .def(
          "exact_vertices",
          [](const vismap::Map& m) {
            const py::object fraction = py::module_::import("fractions").attr("Fraction");
            py::list out;
            for (std::uint32_t i = 0; i < m.vertices().size(); ++i) out.append(fraction_point(fraction, m.exact(i)));
            return out;
          },
          "the vertices as (Fraction, Fraction)")
      .def(
          "exact_segments",
          [](const vismap::Map& m) {
            const py::object fraction = py::module_::import("fractions").attr("Fraction");
            py::list out;
            for (const auto& s : m.segments())
              out.append(py::make_tuple(fraction_point(fraction, m.exact(s.from)), fraction_point(fraction, m.exact(s.to))));
            return out;
          },
          "each segment's end points as ((Fraction, Fraction), (Fraction, Fraction))")
      .def(
          "exact_hidden",
          [](const vismap::Map& m) {
            const py::object fraction = py::module_::import("fractions").attr("Fraction");
            py::list out;
            for (std::size_t i = 0; i < m.hidden().size(); ++i) {
              const auto ends = m.exact_hidden(i);
              out.append(py::make_tuple(fraction_point(fraction, ends[0]), fraction_point(fraction, ends[1])));
            }
            return out;
          },
          "each hidden line's end points as ((Fraction, Fraction), (Fraction, Fraction))")
      .def(
          "to_json",
          [](const vismap::Map& m) {
            std::string text;
            {
              py::gil_scoped_release unlocked;
              text = m.to_json();
            }
            return text;
          },
          "the command line's JSON text, byte for byte")
      .def(
          "to_svg",
          [](const vismap::Map& m, const std::string& style, const LineArg& line, const std::string& page,
             const std::string& scale, double margin, bool lines_only, bool optimize_travel, bool svg_data,
             const std::string& shading, const Light& light) {
            const auto d = drawing_options(style, line, page, scale, margin, lines_only, optimize_travel, svg_data, shading, light);
            py::gil_scoped_release unlocked;
            return m.drawing(d, "svg");
          },
          VISMAP_DRAWING_ARGS, "the drawing as SVG text")
      .def(
          "drawing",
          [](const vismap::Map& m, const std::string& format, const std::string& style, const LineArg& line,
             const std::string& page, const std::string& scale, double margin, bool lines_only, bool optimize_travel,
             bool svg_data, const std::string& shading, const Light& light) {
            const auto d = drawing_options(style, line, page, scale, margin, lines_only, optimize_travel, svg_data, shading, light);
            std::string bytes;
            {
              py::gil_scoped_release unlocked;
              bytes = m.drawing(d, format);
            }
            return py::bytes(bytes);
          },
          py::arg("format") = "svg", VISMAP_DRAWING_ARGS, "the drawing's bytes: svg, dxf, pdf, eps or png")
      .def(
          "write",
          [](const vismap::Map& m, const std::string& path, const std::string& style, const LineArg& line,
             const std::string& page, const std::string& scale, double margin, bool lines_only, bool optimize_travel,
             bool svg_data, const std::string& shading, const Light& light) {
            const auto d = drawing_options(style, line, page, scale, margin, lines_only, optimize_travel, svg_data, shading, light);
            py::gil_scoped_release unlocked;
            m.write(path, d);
          },
          py::arg("path"), VISMAP_DRAWING_ARGS,
          "writes the map by the file's extension (.json, .svg, .dxf, .pdf, .eps, .png), whole or not at all")
      .def("__repr__", [](const vismap::Map& m) {
        return "<vismap.Map " + std::to_string(m.regions().size()) + " regions, " + std::to_string(m.segments().size()) +
               " segments, " + std::to_string(m.hidden().size()) + " hidden lines>";
      });

  mod.def(
      "compute",
      [](const std::variant<std::string, vismap::Scene>& scene, const std::optional<std::vector<double>>& dir,
         const std::optional<std::vector<double>>& eye, const std::optional<std::vector<double>>& target,
         std::optional<double> fov, const std::optional<std::vector<double>>& up, double crease, bool smooth,
         bool hidden, const std::string& algorithm, int threads, bool regions, const std::string& format) {
        vismap::Camera camera;
        camera.dir = vec3(dir, "dir");
        camera.eye = vec3(eye, "eye");
        camera.target = vec3(target, "target");
        camera.fov_deg = fov;
        camera.up = vec3(up, "up");
        vismap::Options options;
        options.crease_deg = crease;
        if (!(crease >= 0 && crease <= 180)) throw py::value_error("crease must be between 0 and 180 degrees");
        options.smooth = smooth;
        options.hidden = hidden;
        options.regions = regions;
        options.threads = threads;
        if (threads < 0) throw py::value_error("threads must be 0 (every usable core) or more");
        if (algorithm == "franklin") options.algorithm = vismap::Algorithm::Franklin;
        else if (algorithm == "newell") options.algorithm = vismap::Algorithm::Newell;
        else if (algorithm == "bsp") options.algorithm = vismap::Algorithm::Bsp;
        else throw py::value_error("algorithm is 'franklin', 'newell' or 'bsp', got '" + algorithm + "'");
        py::gil_scoped_release unlocked;
        if (const auto* path = std::get_if<std::string>(&scene))
          return vismap::compute(vismap::read_scene(*path, {}, format), camera, options);
        return vismap::compute(std::get<vismap::Scene>(scene), camera, options);
      },
      py::arg("scene"), py::kw_only(), py::arg("dir") = py::none(), py::arg("eye") = py::none(),
      py::arg("target") = py::none(), py::arg("fov") = py::none(), py::arg("up") = py::none(),
      py::arg("crease") = 30.0, py::arg("smooth") = false, py::arg("hidden") = false,
      py::arg("algorithm") = "franklin", py::arg("threads") = 0, py::arg("regions") = true, py::arg("format") = "",
      "The exact visibility map of a scene (a file's path or a Scene) seen orthographically along dir, or in "
      "perspective from eye towards target with a vertical field of view fov (degrees); with no camera, the whole "
      "scene obliquely.");
}
