// Check 1 (format): the JSON's shape, canonical numbers, ring orientation and
// the per-segment rules that need no geometry of the scene.
#include "verify/map_doc.h"

#include <algorithm>
#include <charconv>

#include "verify/json.h"
#include "verify/rational.h"

namespace vismap_check {

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::Border: return "border";
    case Kind::Silhouette: return "silhouette";
    case Kind::Crease: return "crease";
    case Kind::Smooth: return "smooth";
    case Kind::Intersection: return "intersection";
  }
  return "?";
}

std::string describe(const MapSegment& s) {
  std::string f;
  for (std::uint32_t i : s.faces) f += (f.empty() ? "" : ",") + std::to_string(i);
  return "from " + str(s.from) + " to " + str(s.to) + " " + kind_name(s.kind) + " [" + f + "]";
}

namespace {

class Reader {
 public:
  Reader(const vismap::Scene& scene, Failures& fail) : scene_(scene), fail_(fail) {}

  MapDoc read(const Json& root) {
    MapDoc doc;
    if (!root.is(Json::Type::Object)) {
      fail_.add("format: top level is not an object");
      return doc;
    }
    static const char* const kKeys[] = {"format", "version", "scene", "projection",
                                        "view_matrix", "regions", "segments", "stats"};
    for (const auto& [k, v] : root.members) {
      bool known = k == "hidden";   // (optional: only when hidden lines were asked for)
      for (const char* want : kKeys) known = known || k == want;
      if (!known) fail_.add("format: unknown top-level key \"" + k + "\"");
    }
    for (const char* want : kKeys)
      if (!root.get(want)) fail_.add(std::string("format: missing top-level key \"") + want + "\"");

    const Json* format = root.get("format");
    if (format && !(format->is(Json::Type::String) && format->text == "vismap"))
      fail_.add("format: \"format\" is not \"vismap\"");
    const Json* version = root.get("version");
    if (version && !(version->is(Json::Type::Number) && version->text == "1"))
      fail_.add("format: \"version\" is not the number 1");
    if (const Json* sc = root.get("scene")) scene_info(*sc);
    if (const Json* st = root.get("stats"); st && !st->is(Json::Type::Object))
      fail_.add("format: \"stats\" is not an object");

    bool ok = true;
    const Json* proj = root.get("projection");
    if (proj && proj->is(Json::Type::String) &&
        (proj->text == "orthographic" || proj->text == "perspective")) {
      doc.perspective = proj->text == "perspective";
    } else {
      if (proj) fail_.add("format: \"projection\" is not \"orthographic\" or \"perspective\"");
      ok = false;
    }
    const Json* vm = root.get("view_matrix");
    if (!vm || !matrix(*vm, doc)) ok = false;
    if (ok && !doc.perspective) {
      static const int kLast[4] = {0, 0, 0, 1};
      for (int j = 0; j < 4; ++j)
        if (doc.m[3][j] != kLast[j]) {
          fail_.add("format: orthographic view_matrix's last row is not 0,0,0,1");
          break;
        }
    }
    if (const Json* regs = root.get("regions")) {
      if (!regs->is(Json::Type::Array)) {
        fail_.add("format: \"regions\" is not an array");
        ok = false;
      } else {
        for (std::size_t i = 0; i < regs->items.size(); ++i) region(regs->items[i], i, doc);
      }
    } else {
      ok = false;
    }
    if (const Json* segs = root.get("segments")) {
      if (!segs->is(Json::Type::Array)) {
        fail_.add("format: \"segments\" is not an array");
        ok = false;
      } else {
        for (std::size_t i = 0; i < segs->items.size(); ++i) segment(segs->items[i], i, doc);
      }
    } else {
      ok = false;
    }
    if (const Json* hid = root.get("hidden")) {
      doc.has_hidden = true;
      if (!hid->is(Json::Type::Array)) {
        fail_.add("format: \"hidden\" is not an array");
        ok = false;
      } else {
        for (std::size_t i = 0; i < hid->items.size(); ++i) segment(hid->items[i], i, doc, true);
        hidden_order(doc.hidden);
      }
    }
    doc.usable = ok;
    return doc;
  }

 private:
  const vismap::Scene& scene_;
  Failures& fail_;

  void scene_info(const Json& sc) {
    if (!sc.is(Json::Type::Object)) {
      fail_.add("format: \"scene\" is not an object");
      return;
    }
    const Json* file = sc.get("file");
    if (!file || !file->is(Json::Type::String)) fail_.add("format: scene.file is not a string");
    const Json* faces = sc.get("faces");
    std::uint64_t n = 0;
    if (!faces || !integer(*faces, n)) {
      fail_.add("format: scene.faces is not a non-negative integer");
    } else if (n != scene_.faces.size()) {
      fail_.add("format: scene.faces is " + std::to_string(n) + " but the scene has " +
                std::to_string(scene_.faces.size()) + " polygons");
    }
  }

  static bool integer(const Json& v, std::uint64_t& out) {
    if (!v.is(Json::Type::Number)) return false;
    const std::string& t = v.text;
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos) return false;
    if (t.size() > 1 && t[0] == '0') return false;
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc() && p == t.data() + t.size();
  }

  bool face_index(const Json& v, const std::string& where, std::uint32_t& out) {
    std::uint64_t n = 0;
    if (!integer(v, n)) {
      fail_.add("format: " + where + " is not a non-negative integer");
      return false;
    }
    if (n >= scene_.faces.size()) {
      fail_.add("format: " + where + " = " + std::to_string(n) + " is not a face of the scene");
      return false;
    }
    out = static_cast<std::uint32_t>(n);
    return true;
  }

  bool number(const Json& v, const std::string& where, mpq_class& out) {
    if (!v.is(Json::Type::String)) {
      fail_.add("format: " + where + " is a JSON " + type_name(v.type) + ", not a rational string");
      return false;
    }
    std::string why;
    if (!parse_canonical(v.text, out, why)) {
      fail_.add("format: " + where + " = \"" + v.text + "\" is not canonical: " + why);
      return false;
    }
    return true;
  }

  bool point(const Json& v, const std::string& where, P2& out) {
    if (!v.is(Json::Type::Array) || v.items.size() != 2) {
      fail_.add("format: " + where + " is not a pair of numbers");
      return false;
    }
    bool a = number(v.items[0], where + "[0]", out.x);
    bool b = number(v.items[1], where + "[1]", out.y);
    return a && b;
  }

  bool matrix(const Json& v, MapDoc& doc) {
    if (!v.is(Json::Type::Array) || v.items.size() != 4) {
      fail_.add("format: view_matrix is not 4 rows");
      return false;
    }
    bool ok = true;
    for (int i = 0; i < 4; ++i) {
      const Json& row = v.items[i];
      if (!row.is(Json::Type::Array) || row.items.size() != 4) {
        fail_.add("format: view_matrix row " + std::to_string(i) + " does not have 4 entries");
        ok = false;
        continue;
      }
      for (int j = 0; j < 4; ++j)
        ok = number(row.items[j], "view_matrix[" + std::to_string(i) + "][" + std::to_string(j) + "]",
                    doc.m[i][j]) && ok;
    }
    return ok;
  }

  // A ring: no repeated consecutive vertex (cyclically, so no closing vertex),
  // at least 3 vertices, signed area of the required sign.
  bool ring(const Json& v, const std::string& where, bool outer, std::vector<P2>& out) {
    if (!v.is(Json::Type::Array)) {
      fail_.add("format: " + where + " is not an array of points");
      return false;
    }
    bool ok = true;
    for (std::size_t i = 0; i < v.items.size(); ++i) {
      P2 p;
      if (point(v.items[i], where + "[" + std::to_string(i) + "]", p)) out.push_back(std::move(p));
      else ok = false;
    }
    if (!ok) return false;
    if (out.size() < 3) {
      fail_.add("format: " + where + " has fewer than 3 vertices");
      return false;
    }
    for (std::size_t i = 0; i < out.size(); ++i)
      if (out[i] == out[(i + 1) % out.size()]) {
        fail_.add("format: " + where + " repeats vertex " + str(out[i]) +
                  (i + 1 == out.size() ? " as a closing vertex" : " consecutively"));
        return false;
      }
    int s = sgn(area2(out));
    if (outer && s <= 0) {
      fail_.add("format: " + where + " (outer ring) is not counter-clockwise: twice its area is " +
                str(mpq_class(area2(out))));
      return false;
    }
    if (!outer && s >= 0) {
      fail_.add("format: " + where + " (hole) is not clockwise: twice its area is " + str(mpq_class(area2(out))));
      return false;
    }
    return true;
  }

  void region(const Json& v, std::size_t i, MapDoc& doc) {
    std::string where = "regions[" + std::to_string(i) + "]";
    if (!v.is(Json::Type::Object)) {
      fail_.add("format: " + where + " is not an object");
      return;
    }
    for (const auto& [k, x] : v.members)
      if (k != "face" && k != "outer" && k != "holes") fail_.add("format: " + where + " has unknown key \"" + k + "\"");
    MapRegion r;
    bool ok = true;
    const Json* face = v.get("face");
    if (!face) {
      fail_.add("format: " + where + " has no \"face\"");
      ok = false;
    } else {
      ok = face_index(*face, where + ".face", r.face) && ok;
    }
    const Json* outer = v.get("outer");
    if (!outer) {
      fail_.add("format: " + where + " has no \"outer\"");
      ok = false;
    } else {
      ok = ring(*outer, where + ".outer", true, r.outer) && ok;
    }
    const Json* holes = v.get("holes");
    if (!holes || !holes->is(Json::Type::Array)) {
      fail_.add("format: " + where + ".holes is missing or not an array");
      ok = false;
    } else {
      for (std::size_t h = 0; h < holes->items.size(); ++h) {
        std::vector<P2> ringv;
        if (ring(holes->items[h], where + ".holes[" + std::to_string(h) + "]", false, ringv))
          r.holes.push_back(std::move(ringv));
        else
          ok = false;
      }
    }
    if (!ok) return;   // a broken region would only cause confusing geometric failures
    r.box = box_of(r.outer);
    doc.regions.push_back(std::move(r));
  }

  // Hidden segments run from the lexicographically smaller end and are sorted
  // by (from, to) (the spec's canonical form).
  void hidden_order(const std::vector<MapSegment>& h) {
    auto less = [](const P2& l, const P2& r) { return l.x < r.x || (l.x == r.x && l.y < r.y); };
    for (std::size_t i = 0; i < h.size(); ++i) {
      if (!less(h[i].from, h[i].to)) fail_.add("format: hidden[" + std::to_string(i) + "] runs from its larger end");
      if (i > 0 && !(less(h[i - 1].from, h[i].from) || (h[i - 1].from == h[i].from && less(h[i - 1].to, h[i].to))))
        fail_.add("format: hidden[" + std::to_string(i) + "] is out of (from, to) order");
    }
  }

  void segment(const Json& v, std::size_t i, MapDoc& doc, bool hidden = false) {
    std::string where = (hidden ? "hidden[" : "segments[") + std::to_string(i) + "]";
    if (!v.is(Json::Type::Object)) {
      fail_.add("format: " + where + " is not an object");
      return;
    }
    for (const auto& [k, x] : v.members)
      if (k != "from" && k != "to" && k != "kind" && k != "faces")
        fail_.add("format: " + where + " has unknown key \"" + k + "\"");
    MapSegment s;
    bool ok = true;
    const Json* from = v.get("from");
    const Json* to = v.get("to");
    const Json* kind = v.get("kind");
    const Json* faces = v.get("faces");
    if (!from || !to || !kind || !faces) {
      fail_.add("format: " + where + " lacks one of from, to, kind, faces");
      return;
    }
    ok = point(*from, where + ".from", s.from) && ok;
    ok = point(*to, where + ".to", s.to) && ok;
    if (ok && s.from == s.to) {
      fail_.add("format: " + where + " has from == to " + str(s.from));
      ok = false;
    }
    static const Kind kKinds[] = {Kind::Border, Kind::Silhouette, Kind::Crease, Kind::Smooth, Kind::Intersection};
    bool known = false;
    if (kind->is(Json::Type::String))
      for (Kind k : kKinds)
        if (kind->text == kind_name(k)) {
          s.kind = k;
          known = true;
        }
    if (!known) {
      fail_.add("format: " + where + ".kind is not one of border, silhouette, crease, smooth, intersection");
      ok = false;
    }
    if (!faces->is(Json::Type::Array) || faces->items.empty()) {
      fail_.add("format: " + where + ".faces is not a non-empty array");
      ok = false;
    } else {
      for (std::size_t j = 0; j < faces->items.size(); ++j) {
        std::uint32_t f = 0;
        if (!face_index(faces->items[j], where + ".faces[" + std::to_string(j) + "]", f)) {
          ok = false;
          continue;
        }
        if (!s.faces.empty() && f <= s.faces.back()) {
          fail_.add("format: " + where + ".faces is not strictly ascending");
          ok = false;
        }
        s.faces.push_back(f);
      }
    }
    if (ok && known) {
      std::size_t n = s.faces.size();
      bool count_ok = s.kind == Kind::Border ? n == 1 : s.kind == Kind::Crease ? n >= 2 : n == 2;
      if (!count_ok) {
        fail_.add("format: " + where + " is " + kind_name(s.kind) + " with " + std::to_string(n) + " faces");
        ok = false;
      }
    }
    if (!ok) return;
    s.box = box_of(s.from, s.to);
    (hidden ? doc.hidden : doc.segments).push_back(std::move(s));
  }
};

}  // namespace

std::vector<const P2*> vertices_on(const MapDoc& doc, const P2& a, const P2& b) {
  std::vector<const P2*> out;
  const mpq_class& x0 = std::min(a.x, b.x);
  const mpq_class& x1 = std::max(a.x, b.x);
  auto it = std::lower_bound(doc.vertices.begin(), doc.vertices.end(), x0,
                             [](const P2& p, const mpq_class& x) { return p.x < x; });
  for (; it != doc.vertices.end() && it->x <= x1; ++it)
    if (on_segment(*it, a, b)) out.push_back(&*it);
  return out;
}

MapDoc read_map(const std::string& json_text, const vismap::Scene& scene, Failures& fail) {
  Json root;
  try {
    root = parse_json(json_text);
  } catch (const JsonError& e) {
    fail.add(std::string("format: ") + e.what());
    return MapDoc{};
  }
  MapDoc doc = Reader(scene, fail).read(root);
  std::vector<Box> boxes;
  for (const MapRegion& r : doc.regions) boxes.push_back(r.box);
  doc.region_grid.build(boxes);
  boxes.clear();
  for (const MapSegment& s : doc.segments) boxes.push_back(s.box);
  doc.segment_grid.build(boxes);
  boxes.clear();
  for (const MapSegment& s : doc.hidden) boxes.push_back(s.box);
  doc.hidden_grid.build(boxes);
  auto& v = doc.vertices;
  for (const MapRegion& r : doc.regions) {
    v.insert(v.end(), r.outer.begin(), r.outer.end());
    for (const auto& h : r.holes) v.insert(v.end(), h.begin(), h.end());
  }
  for (const MapSegment& s : doc.segments) {
    v.push_back(s.from);
    v.push_back(s.to);
  }
  auto less = [](const P2& l, const P2& r) { return l.x < r.x || (l.x == r.x && l.y < r.y); };
  std::sort(v.begin(), v.end(), less);
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return doc;
}

}  // namespace vismap_check
