// The drawings (arrangements/drawing.h, svg_writer, dxf_writer), checked as a
// user would: chains cover the map's lines exactly once and are maximal; the
// SVG parses, has a layer per class and a <path> per chain; DXF reads back
// through ezdxf with a LINE or POLYLINE per chain on each class's layer; dashes
// cut into sub-paths lie on the line; pages are in mm; reordering for the pen
// keeps every chain and shortens the travel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "arrangements/dxf_writer.h"
#include "arrangements/svg_writer.h"
#include "bench/scene_gen.h"
#include "engine/visibility.h"
#include "tests/test_support.h"

namespace {

namespace fs = std::filesystem;
using vismap::Chain;
using vismap::LineClass;

struct Made {
  vismap::Scene scene;
  vismap::View view;
  vismap::VisibilityMap map;
};

Made make(const std::string& file, const vismap::Vec3& dir) {
  Made m;
  m.scene = vismap::read_scene((fs::path(VISMAP_DATA_DIR) / file).string());
  vismap::Camera cam;
  cam.dir = dir;
  m.view = vismap::make_view(cam, m.scene);
  vismap::Options opt;
  opt.hidden = true;
  m.map = vismap::visibility_franklin(m.scene, m.view, opt);
  return m;
}

// A line as a drawing shows it: its class and its two ends (as doubles), unordered.
using Key = std::tuple<int, double, double, double, double>;
Key key(LineClass c, std::array<double, 2> a, std::array<double, 2> b) {
  if (b < a) std::swap(a, b);
  return {static_cast<int>(c), a[0], a[1], b[0], b[1]};
}

std::multiset<Key> map_lines(const vismap::VisibilityMap& map) {
  std::multiset<Key> out;
  auto d = [](const vismap::Point2& p) { return std::array<double, 2>{p.x.get_d(), p.y.get_d()}; };
  for (const auto& s : map.segments) out.insert(key(vismap::class_of(s.kind, false), d(map.at(s.from)), d(map.at(s.to))));
  for (const auto& h : map.hidden) out.insert(key(LineClass::Hidden, d(h.from), d(h.to)));
  return out;
}

std::multiset<Key> chain_lines(const std::vector<Chain>& chains) {
  std::multiset<Key> out;
  for (const Chain& c : chains) {
    const std::size_t n = c.screen.size();
    for (std::size_t i = 0; i + 1 < n + (c.closed ? 1 : 0); ++i) out.insert(key(c.cls, c.screen[i], c.screen[(i + 1) % n]));
  }
  return out;
}

int python_exit(const std::string& script) {
  const std::string py = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const fs::path file = fs::temp_directory_path() / ("vismap_drawing_" + std::to_string(::getpid()) + ".py");
  std::ofstream(file) << script;
  const int rc = std::system((py + " '" + file.string() + "'").c_str());
  fs::remove(file);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(Chains, CoverTheMapsLinesOnceAndAreMaximal) {
  for (const auto& [file, dir] : {std::pair{"interpenetrating_boxes.off", vismap::Vec3{-1, -2, -4}},
                                  std::pair{"cube_diagonal.off", vismap::Vec3{-1, -1, -1}},
                                  std::pair{"l_prism_notch.off", vismap::Vec3{-1, -2, -3}}}) {
    const Made m = make(file, dir);
    ASSERT_FALSE(m.map.hidden.empty()) << file;
    for (bool provenance : {false, true}) {
      const vismap::Drawing d = vismap::make_drawing(m.map, {}, provenance, false);
      EXPECT_EQ(chain_lines(d.chains), map_lines(m.map)) << file << ": the chains are not the map's lines";
      // Maximal: an open chain ends where its class has other than two lines;
      // inside a chain, exactly two meet.
      std::map<std::tuple<int, double, double>, int> degree;
      for (const Key& k : map_lines(m.map)) {
        ++degree[{std::get<0>(k), std::get<1>(k), std::get<2>(k)}];
        ++degree[{std::get<0>(k), std::get<3>(k), std::get<4>(k)}];
      }
      for (const Chain& c : d.chains) {
        auto deg = [&](const std::array<double, 2>& p) { return degree[{static_cast<int>(c.cls), p[0], p[1]}]; };
        for (std::size_t i = 1; i + 1 < c.screen.size() && !provenance; ++i) {
          EXPECT_EQ(deg(c.screen[i]), 2) << file << ": a chain passes a vertex of its class's degree " << deg(c.screen[i]);
        }
        if (!c.closed && !provenance) {
          EXPECT_NE(deg(c.screen.front()), 2) << file << ": a chain could go on at its start";
          EXPECT_NE(deg(c.screen.back()), 2) << file << ": a chain could go on at its end";
        }
      }
    }
  }
}

TEST(Svg, LayersAndOnePathPerChainAndItParses) {
  const Made m = make("interpenetrating_boxes.off", {-1, -2, -4});
  for (const char* style : {"shaded", "technical", "plotter"}) {
    vismap::SvgOptions opt;
    ASSERT_TRUE(vismap::preset_style(style, opt.style));
    opt.page.width = 0;
    vismap::parse_page("a4", opt.page);
    const vismap::Drawing d = vismap::make_drawing(m.map, opt.page, false, false);
    const std::string svg = vismap::to_svg(m.map, d, m.scene, m.view, opt);
    const bool portrait = svg.find("width=\"210.000mm\" height=\"297.000mm\"") != std::string::npos;
    const bool landscape = svg.find("width=\"297.000mm\" height=\"210.000mm\"") != std::string::npos;
    EXPECT_TRUE(portrait != landscape) << style << ": not an A4 page in mm";
    EXPECT_EQ(landscape, d.at.width > d.at.height);
    std::size_t paths = 0, fills = 0;   // (a region's path starts with its fill)
    for (std::size_t at = svg.find("<path d="); at != std::string::npos; at = svg.find("<path d=", at + 1)) ++paths;
    for (std::size_t at = svg.find("<path fill="); at != std::string::npos; at = svg.find("<path fill=", at + 1)) ++fills;
    EXPECT_EQ(paths, d.chains.size()) << style;
    EXPECT_EQ(fills, opt.style.fills ? m.map.regions.size() : 0u) << style;
    for (const char* layer : {"hidden", "crease", "outline", "intersection"})
      EXPECT_NE(svg.find(std::string("inkscape:label=\"") + layer + "\""), std::string::npos) << style << ": no " << layer << " layer";
    EXPECT_EQ(svg.find("stroke-dasharray") != std::string::npos, std::string(style) != "plotter") << style;
    const fs::path file = fs::temp_directory_path() / ("vismap_drawing_" + std::to_string(::getpid()) + ".svg");
    std::ofstream(file) << svg;
    EXPECT_EQ(python_exit("import xml.etree.ElementTree as E\nE.parse('" + file.string() + "')\n"), 0) << style << ": not XML";
    fs::remove(file);
  }
}

TEST(Svg, ProvenanceOnEveryPath) {
  const Made m = make("interpenetrating_boxes.off", {-1, -2, -4});
  vismap::SvgOptions opt;
  opt.provenance = true;
  const std::string svg = vismap::to_svg(m.map, m.scene, m.view, opt);
  std::size_t lines = 0, tagged = 0;
  for (std::size_t at = svg.find("<path d="); at != std::string::npos; at = svg.find("<path d=", at + 1)) {
    const std::string path = svg.substr(at, svg.find('>', at) - at);
    if (path.find("fill=") != std::string::npos) continue;   // a region
    ++lines;
    tagged += path.find("data-kind=\"") != std::string::npos && path.find("data-faces=\"") != std::string::npos;
  }
  EXPECT_GT(lines, 0u);
  EXPECT_EQ(tagged, lines);
}

TEST(Dxf, ReadsBackThroughEzdxfWithAnEntityPerChain) {
  if (python_exit("import ezdxf\n") != 0) GTEST_SKIP() << "python3-ezdxf is not installed (scripts/install-deps.sh installs it)";
  const Made m = make("interpenetrating_boxes.off", {-1, -2, -4});
  const vismap::Drawing d = vismap::make_drawing(m.map, {}, false, false);
  const fs::path file = fs::temp_directory_path() / ("vismap_drawing_" + std::to_string(::getpid()) + ".dxf");
  std::ofstream(file) << vismap::to_dxf(d);
  std::map<std::string, int> want;
  for (const Chain& c : d.chains) ++want[vismap::class_name(c.cls)];
  std::string expect = "{";
  for (const auto& [layer, n] : want) expect += "'" + layer + "': " + std::to_string(n) + ",";
  expect += "}";
  const std::string script = "import ezdxf, collections, sys\n"
                             "d = ezdxf.readfile('" + file.string() + "')\n"
                             "got = collections.Counter(e.dxf.layer for e in d.modelspace() if e.dxftype() in ('LINE', 'POLYLINE'))\n"
                             "assert dict(got) == " + expect + ", dict(got)\n"
                             "assert d.layers.get('hidden').dxf.linetype == 'HIDDEN'\n";
  EXPECT_EQ(python_exit(script), 0) << "ezdxf disagrees";
  fs::remove(file);
}

TEST(Dashes, CutPiecesLieOnTheLineAndFollowThePattern) {
  const std::vector<std::array<double, 2>> line{{0, 0}, {10, 0}, {10, 7}};
  const std::vector<double> dash{3, 1};
  const auto pieces = vismap::dashed(line, false, dash);
  double drawn = 0;
  for (const auto& p : pieces) {
    double len = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) len += std::hypot(p[i + 1][0] - p[i][0], p[i + 1][1] - p[i][1]);
    EXPECT_LE(len, 3 + 1e-9);
    drawn += len;
    for (const auto& q : p) EXPECT_TRUE((q[1] == 0 && q[0] >= 0 && q[0] <= 10) || (q[0] == 10 && q[1] >= 0 && q[1] <= 7));
  }
  // 17 units: dashes at 0-3, 4-7, 8-11, 12-15, 16-17: 13 drawn, in 5 pieces.
  EXPECT_EQ(pieces.size(), 5u);
  EXPECT_NEAR(drawn, 13, 1e-9);
}

TEST(Travel, ReorderingKeepsEveryChainAndShortensTheTravel) {
  vismap::Scene scene = vismap::gen::random_squares_depth(200, 3, 7);
  vismap::Camera cam;
  cam.dir = vismap::Vec3{-0.3, -0.5, -1};
  const vismap::View view = vismap::make_view(cam, scene);
  vismap::Options opt;
  opt.hidden = true;
  const vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, opt);
  vismap::PageOptions page;
  vismap::parse_page("a3", page);
  const vismap::Drawing before = vismap::make_drawing(map, page, false, false);
  const vismap::Drawing after = vismap::make_drawing(map, page, false, true);
  EXPECT_EQ(chain_lines(after.chains), chain_lines(before.chains));
  EXPECT_DOUBLE_EQ(after.travel_before, vismap::travel(before.chains, before.at));
  EXPECT_LT(after.travel_after, 0.5 * after.travel_before) << "nearest-next order should at least halve random order's travel";
  for (std::size_t i = 1; i < after.chains.size(); ++i)
    EXPECT_LE(after.chains[i - 1].cls, after.chains[i].cls) << "classes (pens) must stay together";
}

TEST(Page, SizesScalesAndStyles) {
  vismap::PageOptions p;
  EXPECT_TRUE(vismap::parse_page("300x200mm", p));
  EXPECT_EQ(p.width, 300);
  EXPECT_EQ(p.height, 200);
  EXPECT_FALSE(vismap::parse_page("a5", p));
  EXPECT_FALSE(vismap::parse_page("300x200", p));
  double s = 0;
  EXPECT_TRUE(vismap::parse_scale("1:50", s));
  EXPECT_DOUBLE_EQ(s, 0.02);
  EXPECT_FALSE(vismap::parse_scale("1:0", s));
  vismap::DrawingStyle st;
  ASSERT_TRUE(vismap::preset_style("technical", st));
  EXPECT_EQ(st.line[static_cast<int>(LineClass::Outline)].width, 0.5);
  EXPECT_EQ(st.line[static_cast<int>(LineClass::Hidden)].width, 0.25);
  EXPECT_FALSE(st.line[static_cast<int>(LineClass::Hidden)].dash.empty());
  std::string error;
  EXPECT_TRUE(vismap::override_line_style("hidden:width=0.18,color=#808080,dash=2/1", st, error)) << error;
  EXPECT_EQ(st.line[static_cast<int>(LineClass::Hidden)].color, "#808080");
  EXPECT_TRUE(vismap::override_line_style("crease:dash=none", st, error));
  EXPECT_FALSE(vismap::override_line_style("edges:width=1", st, error));
  EXPECT_FALSE(vismap::override_line_style("hidden:dash=2", st, error));
  EXPECT_FALSE(vismap::override_line_style("hidden:color=\"x\"", st, error));
  // At 1:N on a page, a screen unit is 1/N mm.
  const Made m = make("cube_diagonal.off", {-1, -1, -1});
  vismap::PageOptions a4;
  vismap::parse_page("a4", a4);
  a4.scale = 1.0 / 20;
  const vismap::Placement at = vismap::place(m.map, a4);
  EXPECT_TRUE(at.mm);
  EXPECT_DOUBLE_EQ(at.k, 0.05);
}

}  // namespace

#ifdef VISMAP_TEST_CAIRO
#include <cairo.h>

#include "arrangements/cairo_writer.h"

namespace {

struct Raster {
  int w = 0, h = 0;
  std::vector<std::array<int, 3>> px;
  const std::array<int, 3>& at(int x, int y) const { return px[static_cast<std::size_t>(y) * w + x]; }
};

Raster read_png(const fs::path& file) {
  Raster r;
  cairo_surface_t* s = cairo_image_surface_create_from_png(file.c_str());
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(s);
    r.w = cairo_image_surface_get_width(s);
    r.h = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x) {
        std::uint32_t v;
        std::memcpy(&v, data + y * stride + 4 * x, 4);
        r.px.push_back({static_cast<int>((v >> 16) & 255), static_cast<int>((v >> 8) & 255), static_cast<int>(v & 255)});
      }
  }
  cairo_surface_destroy(s);
  return r;
}

// The share of pixels, away from lines (no dark pixel within 2 in either
// raster), whose colours differ by more than a few levels.
double disagreement(const Raster& a, const Raster& b) {
  auto dark = [](const Raster& r, int x, int y) {
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int u = std::clamp(x + dx, 0, r.w - 1), v = std::clamp(y + dy, 0, r.h - 1);
        const auto& c = r.at(u, v);
        if (c[0] + c[1] + c[2] < 3 * 100) return true;
      }
    return false;
  };
  std::size_t compared = 0, differ = 0;
  for (int y = 0; y < std::min(a.h, b.h); ++y)
    for (int x = 0; x < std::min(a.w, b.w); ++x) {
      if (dark(a, x, y) || dark(b, x, y)) continue;
      ++compared;
      for (int c = 0; c < 3; ++c)
        if (std::abs(a.at(x, y)[c] - b.at(x, y)[c]) > 6) { ++differ; break; }
    }
  return compared ? static_cast<double>(differ) / compared : 1;
}

bool have(const char* tool) { return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0; }

TEST(Cairo, PngPdfAndSvgRastersAgreeAwayFromLines) {
  if (!have("rsvg-convert") || !have("pdftoppm")) GTEST_SKIP() << "rsvg-convert or pdftoppm missing (scripts/install-deps.sh installs them)";
  const Made m = make("interpenetrating_boxes.off", {-1, -2, -4});
  vismap::SvgOptions opt;   // shaded: the fills are what is compared
  const vismap::Drawing d = vismap::make_drawing(m.map, opt.page, false, false);
  const fs::path dir = fs::temp_directory_path() / ("vismap_cairo_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "map.svg") << vismap::to_svg(m.map, d, m.scene, m.view, opt);
  for (const char* f : {"png", "pdf", "eps"})
    std::ofstream(dir / (std::string("map.") + f), std::ios::binary) << vismap::to_cairo(m.map, d, m.scene, m.view, opt, f);
  const std::string eps = vismap_test::slurp(dir / "map.eps");
  EXPECT_EQ(eps.rfind("%!PS-Adobe-3.0 EPSF-3.0", 0), 0u) << "not an EPS file";
  const std::string q = "'" + dir.string() + "/";
  ASSERT_EQ(std::system(("rsvg-convert -o " + q + "svg.png' " + q + "map.svg'").c_str()), 0);
  ASSERT_EQ(std::system(("pdftoppm -png -r 96 -singlefile " + q + "map.pdf' " + q + "pdf'").c_str()), 0);
  const Raster png = read_png(dir / "map.png"), svg = read_png(dir / "svg.png"), pdf = read_png(dir / "pdf.png");
  ASSERT_GT(png.w, 100);
  EXPECT_NEAR(svg.w, png.w, 1);
  EXPECT_NEAR(svg.h, png.h, 1);
  EXPECT_NEAR(pdf.w, png.w, 1);
  EXPECT_NEAR(pdf.h, png.h, 1);
  EXPECT_LT(disagreement(png, svg), 0.005) << "the PNG's fills differ from the SVG's";
  EXPECT_LT(disagreement(pdf, svg), 0.005) << "the PDF's fills differ from the SVG's";
  // The raster is not blank: the fills are there.
  std::size_t grey = 0;
  for (const auto& c : png.px) grey += c[0] < 250 && c[0] > 100;
  EXPECT_GT(grey, png.px.size() / 10);
  fs::remove_all(dir);
}

}  // namespace
#endif
