#include "arrangements/json_writer.h"

#include <cstdio>

#include "arrangements/rational.h"
#include "engine/parallel.h"

namespace vismap {
namespace {

void quoted(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') { out += '\\'; out += c; }
    else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else out += c;
  }
  out += '"';
}

void number(std::string& out, const mpq_class& q) { out += '"'; out += canonical(q); out += '"'; }

void point(std::string& out, const Point2& p) {
  out += '[';
  number(out, p.x);
  out += ',';
  number(out, p.y);
  out += ']';
}

void ring(std::string& out, const Ring& r, const std::vector<std::string>& text) {
  out += '[';
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (i) out += ',';
    out += text[r[i]];
  }
  out += ']';
}

void faces(std::string& out, const std::vector<int>& f) {
  out += '[';
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (k) out += ',';
    out += std::to_string(f[k]);
  }
  out += ']';
}

// "hidden" (only when asked for): segments with their own end points.
void hidden(std::string& out, const std::vector<HiddenSegment>& list) {
  out += ",\n\"hidden\":[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    const HiddenSegment& h = list[i];
    out += i ? ",\n" : "\n";
    out += "{\"from\":";
    point(out, h.from);
    out += ",\"to\":";
    point(out, h.to);
    out += ",\"kind\":\"";
    out += to_string(h.kind);
    out += "\",\"faces\":";
    faces(out, h.faces);
    out += '}';
  }
  out += ']';
}

}  // namespace

std::string to_json(const VisibilityMap& map, int threads) {
  std::string all;
  write_json(map, [&](const std::string& piece) { all += piece; }, threads);
  return all;
}

void write_json(const VisibilityMap& map, const std::function<void(const std::string&)>& sink, int threads) {
  std::string out;
  constexpr std::size_t kPiece = std::size_t{4} << 20;
  auto pass_on = [&] {   // hands over what has piled up, if it is a whole piece
    if (out.size() < kPiece) return;
    sink(out);
    out.clear();
  };
  out += "{\"format\":\"vismap\",\"version\":1,\n\"scene\":{\"file\":";
  quoted(out, map.scene_file);
  out += ",\"faces\":" + std::to_string(map.scene_faces) + "},\n";
  out += map.perspective ? "\"projection\":\"perspective\",\n" : "\"projection\":\"orthographic\",\n";
  out += "\"view_matrix\":[";
  for (int r = 0; r < 4; ++r) {
    out += r ? ",[" : "[";
    for (int c = 0; c < 4; ++c) {
      if (c) out += ',';
      number(out, map.view[r][c]);
    }
    out += ']';
  }
  // Each vertex's text once: most appear in several rings and segments. (Exact
  // decimals of rationals, the costliest part: chunks on `threads` threads.)
  std::vector<std::string> text(map.vertices.size());
  engine::parallel_chunks(static_cast<int>(text.size()), 4096, threads, [&](int, engine::Chunk r) {
    for (int v = r.begin; v < r.end; ++v) point(text[v], map.vertices[v]);
  });
  out.reserve(2 * kPiece);
  out += "],\n";
  if (map.has_regions) out += "\"regions\":[";
  for (std::size_t i = 0; i < map.regions.size() && map.has_regions; ++i) {
    const Region& g = map.regions[i];
    out += i ? ",\n" : "\n";
    out += "{\"face\":" + std::to_string(g.face) + ",\"outer\":";
    ring(out, g.outer, text);
    out += ",\"holes\":[";
    for (std::size_t h = 0; h < g.holes.size(); ++h) {
      if (h) out += ',';
      ring(out, g.holes[h], text);
    }
    out += "]}";
    pass_on();
  }
  if (map.has_regions) out += "],\n";
  out += "\"segments\":[";
  for (std::size_t i = 0; i < map.segments.size(); ++i) {
    const Segment& s = map.segments[i];
    out += i ? ",\n" : "\n";
    out += "{\"from\":";
    out += text[s.from];
    out += ",\"to\":";
    out += text[s.to];
    out += ",\"kind\":\"";
    out += to_string(s.kind);
    out += "\",\"faces\":";
    faces(out, s.faces);
    out += '}';
    pass_on();
  }
  out += "]";
  if (map.has_hidden) hidden(out, map.hidden);
  out += ",\n\"stats\":{\"seconds\":{";
  char buf[64];
  for (std::size_t i = 0; i < map.stats.seconds.size(); ++i) {
    if (i) out += ',';
    quoted(out, map.stats.seconds[i].first);
    std::snprintf(buf, sizeof buf, ":%.6f", map.stats.seconds[i].second);
    out += buf;
  }
  out += "},\"counts\":{";
  for (std::size_t i = 0; i < map.stats.counts.size(); ++i) {
    if (i) out += ',';
    quoted(out, map.stats.counts[i].first);
    out += ':' + std::to_string(map.stats.counts[i].second);
  }
  out += "}}}\n";
  sink(out);
}

}  // namespace vismap
