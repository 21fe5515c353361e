#include "arrangements/json_writer.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <string_view>

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

// (A map's numbers are GMP's, in lowest terms: engines make them by its
// arithmetic, or canonicalise what they assemble from integers.)
void number(std::string& out, const mpq_class& q) {
  out += '"';
  append_lowest_terms(out, q);
  out += '"';
}

void point(std::string& out, const Point2& p) {
  out += '[';
  number(out, p.x);
  out += ',';
  number(out, p.y);
  out += ']';
}

void ring(std::string& out, const Ring& r, const std::vector<std::string_view>& text) {
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

// A segment's object: from() and to() append its end points.
template <class From, class To>
void segment(std::string& out, From&& from, To&& to, EdgeKind kind, const std::vector<int>& f) {
  out += "{\"from\":";
  from();
  out += ",\"to\":";
  to();
  out += ",\"kind\":\"";
  out += to_string(kind);
  out += "\",\"faces\":";
  faces(out, f);
  out += '}';
}

// Items [0, n), item(i, text) appending item i's text, handed to `sink` in
// order: after what `out` holds, in blocks of 2048 items made on `threads`
// threads, each handed over by the thread that made it while the others make
// the next (a map's regions and segments are most of its JSON: tens of MB of
// text, whose copy into the file takes about as long as making it). Each block
// is given the room its predecessor took (+1/8), not grown by doubling (which
// copied it again and again).
template <class Item>
void in_blocks(std::size_t n, const Item& item, std::string& out, const std::function<void(std::string)>& sink,
               int threads) {
  constexpr std::size_t kBlock = 2048;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::atomic<std::size_t> last{0};   // (a hint: whichever block a thread finished last)
  engine::parallel_in_order<std::string>(
      static_cast<int>(blocks), threads,
      [&](int b) {
        std::string text;
        text.reserve(last.load(std::memory_order_relaxed) * 9 / 8);
        const std::size_t first = static_cast<std::size_t>(b) * kBlock;
        for (std::size_t i = first; i < std::min(n, first + kBlock); ++i) item(i, text);
        last.store(text.size(), std::memory_order_relaxed);
        return text;
      },
      [&](int, std::string text) {
        if (!out.empty()) {
          sink(std::move(out));
          out.clear();
        }
        sink(std::move(text));
      });
}

// "hidden" (only when asked for): segments with their own end points.
void hidden(const std::vector<HiddenSegment>& list, std::string& out,
            const std::function<void(std::string)>& sink, int threads) {
  out += ",\n\"hidden\":[";
  in_blocks(list.size(), [&](std::size_t i, std::string& o) {
    const HiddenSegment& h = list[i];
    o += i ? ",\n" : "\n";
    segment(o, [&] { point(o, h.from); }, [&] { point(o, h.to); }, h.kind, h.faces);
  }, out, sink, threads);
  out += ']';
}

}  // namespace

std::string to_json(const VisibilityMap& map, int threads) {
  std::string all;
  write_json(map, [&](std::string piece) { all += piece; }, threads);
  return all;
}

void write_json(const VisibilityMap& map, const std::function<void(std::string)>& sink, int threads) {
  std::string out;
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
  // A chunk's texts side by side in one string, each read through a view: not
  // a string of its own per vertex (half a million allocations on a 10^6-
  // triangle terrain), whose characters the rings fetched from wherever it was.
  std::vector<std::string_view> text(map.vertices.size());
  const int nv = static_cast<int>(text.size()), size = 512;
  std::vector<std::string> chunk_text(static_cast<std::size_t>(engine::chunk_count(nv, size)));
  engine::parallel_chunks(nv, size, threads, [&](int c, engine::Chunk r) {
    std::string& all = chunk_text[static_cast<std::size_t>(c)];
    std::vector<std::size_t> end;   // (views made once the string stops growing)
    end.reserve(static_cast<std::size_t>(r.end - r.begin));
    for (int v = r.begin; v < r.end; ++v) {
      point(all, map.vertices[static_cast<std::size_t>(v)]);
      end.push_back(all.size());
    }
    for (int v = r.begin, k = 0; v < r.end; ++v, ++k) {
      const std::size_t from = k ? end[static_cast<std::size_t>(k - 1)] : 0;
      text[static_cast<std::size_t>(v)] = std::string_view(all).substr(from, end[static_cast<std::size_t>(k)] - from);
    }
  });
  out += "],\n";
  if (map.has_regions) {
    out += "\"regions\":[";
    in_blocks(map.regions.size(), [&](std::size_t i, std::string& o) {
      const Region& g = map.regions[i];
      o += i ? ",\n" : "\n";
      o += "{\"face\":" + std::to_string(g.face) + ",\"outer\":";
      ring(o, g.outer, text);
      o += ",\"holes\":[";
      for (std::size_t h = 0; h < g.holes.size(); ++h) {
        if (h) o += ',';
        ring(o, g.holes[h], text);
      }
      o += "]}";
    }, out, sink, threads);
    out += "],\n";
  }
  out += "\"segments\":[";
  in_blocks(map.segments.size(), [&](std::size_t i, std::string& o) {
    const Segment& s = map.segments[i];
    o += i ? ",\n" : "\n";
    segment(o, [&] { o += text[s.from]; }, [&] { o += text[s.to]; }, s.kind, s.faces);
  }, out, sink, threads);
  out += "]";
  if (map.has_hidden) hidden(map.hidden, out, sink, threads);
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
  sink(std::move(out));
}

}  // namespace vismap
