#include "engine/embedded_stars.h"

#include <algorithm>
#include <cstdint>

#include "engine/parallel.h"
#include "engine/star_link.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

namespace {

// A facet that can belong to an embedded star: an occluding triangle of three
// distinct input corners, not a split polygon's triangle (a crossing along such
// a triangle's diagonal goes on beyond it, in the polygon).
bool plain_triangle(const Facet& f) {
  return f.occluder && f.id.size() == 3 && f.id[0] >= 0 && f.id[1] >= 0 && f.id[2] >= 0 && f.id[0] != f.id[1] &&
         f.id[1] != f.id[2] && f.id[0] != f.id[2] && !f.may_cross_at_diagonal();
}

// A plain triangle's corners, turned counter-clockwise on the screen: their
// canonical ids and their images' places in ScreenScene::images (a facet is
// 144 bytes: the stars are made from this table, read in one pass).
struct Triangle {
  VertexId id[3];
  std::uint32_t place[3];
};

// The plain triangles (id[0] = -1 for other facets), and the vertices that
// some other facet touches (a polygon's piece, a facet cut at the near plane,
// culled or edge-on): their stars are not told. Chunks of facets in parallel.
struct Triangles {
  std::vector<Triangle> of_facet;
  std::vector<VertexId> spoilt;
};

Triangles triangles_of(const ScreenScene& ss, int threads) {
  const int nf = static_cast<int>(ss.facet_count()), size = 4096;
  Triangles t;
  t.of_facet.resize(ss.facet_count());
  std::vector<std::vector<VertexId>> spoilt(static_cast<std::size_t>(chunk_count(nf, size)));
  parallel_chunks(nf, size, threads, [&](int c, Chunk r) {
    for (int fi = r.begin; fi < r.end; ++fi) {
      const Facet& f = ss.facet(static_cast<std::size_t>(fi));
      Triangle& tri = t.of_facet[static_cast<std::size_t>(fi)];
      if (!plain_triangle(f)) {
        tri.id[0] = -1;
        for (VertexId v : f.id)
          if (v >= 0) spoilt[static_cast<std::size_t>(c)].push_back(v);
        continue;
      }
      const std::size_t turned[3] = {0, f.facing == Facing::Front ? 1u : 2u, f.facing == Facing::Front ? 2u : 1u};
      for (std::size_t k = 0; k < 3; ++k) {
        tri.id[k] = f.id[turned[k]];
        tri.place[k] = static_cast<std::uint32_t>(&f.v[turned[k]] - ss.images.data());
      }
    }
  });
  for (const auto& list : spoilt) t.spoilt.insert(t.spoilt.end(), list.begin(), list.end());
  return t;
}

// An edge of a vertex's link: the side a -> b (images' places) of a triangle
// (v, a, b) that turns counter-clockwise on the screen.
struct LinkEdge {
  std::uint32_t a, b;
};

// Each vertex's link edges (compressed rows, in facet order) and its image's
// place; vertices whose stars are not told have none.
struct Links {
  std::vector<std::uint32_t> first;   // vertex v's edges: edges[first[v] .. first[v + 1])
  std::vector<LinkEdge> edges;
  std::vector<std::uint32_t> place;
};

Links links_of(const Triangles& t, std::size_t vertices) {
  Links l;
  l.first.assign(vertices + 1, 0);
  l.place.assign(vertices, 0);
  std::vector<char> spoilt(vertices, 0);
  for (VertexId v : t.spoilt) spoilt[static_cast<std::size_t>(v)] = 1;
  for (const Triangle& tri : t.of_facet)
    if (tri.id[0] >= 0)
      for (VertexId v : tri.id) ++l.first[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < vertices; ++v)
    if (spoilt[v]) l.first[v + 1] = 0;
  for (std::size_t v = 0; v < vertices; ++v) l.first[v + 1] += l.first[v];
  l.edges.resize(l.first[vertices]);
  std::vector<std::uint32_t> next(l.first.begin(), l.first.end() - 1);
  for (const Triangle& tri : t.of_facet) {
    if (tri.id[0] < 0) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tri.id[k]);
      if (spoilt[v]) continue;
      l.edges[next[v]++] = LinkEdge{tri.place[(k + 1) % 3], tri.place[(k + 2) % 3]};
      l.place[v] = tri.place[k];
    }
  }
  return l;
}

// The vertex images' y, as intervals in one table by place (a lazy number's
// interval lies in its own node: read once each, not once per link).
class ImageHeights {
 public:
  ImageHeights(const ScreenScene& ss, int threads) : images_(ss.images.data()), y_(ss.images.size()) {
    parallel_chunks(static_cast<int>(y_.size()), 4096, threads, [&](int, Chunk r) {
      for (int u = r.begin; u < r.end; ++u)   // (a slot not made: behind the near plane, never asked)
        if (ss.images.made(static_cast<std::size_t>(u))) y_[static_cast<std::size_t>(u)] = approx_of(images_[u].y);
    });
  }
  // Whether image a is on or below the horizontal line through image v,
  // exactly (vertex images are leaves whose intervals hold them tightly: the
  // exact values are rarely needed). Decided on the intervals read before the
  // threads started, then on exact values, never on a lazy number's live
  // interval: a leaf's interval narrows when some thread makes its exact value,
  // and CGAL's counted comparison would then count by which thread came first
  // (the stats must not depend on the thread count).
  bool on_or_below(std::uint32_t a, std::uint32_t v) const {
    const Interval &ay = y_[a], &vy = y_[v];
    if (ay.sup() <= vy.inf()) return true;
    if (ay.inf() > vy.sup()) return false;
    return to_mpq(images_[a].y) <= to_mpq(images_[v].y);
  }

 private:
  const P3* images_;
  std::vector<Interval> y_;
};

// Whether the triangles of link edges e[0..n) around the vertex with image
// place v tile a disk around it on the screen (engine/star_link.h).
bool embedded(const LinkEdge* e, std::size_t n, std::uint32_t v, const ImageHeights& heights) {
  return goes_round_once(
      n, [&](std::size_t i) { return e[i].a; }, [&](std::size_t i) { return e[i].b; },
      [&](std::size_t i) { return heights.on_or_below(e[i].a, v); });
}

}  // namespace

EmbeddedStars::EmbeddedStars(const ScreenScene& ss, int threads, bool wanted) {
  // (Canonical ids index the input's vertices.)
  const std::size_t vertices = ss.world ? ss.world->size() : 0;
  embedded_.assign(vertices, 0);
  if (vertices == 0 || !wanted) return;
  const Links links = links_of(triangles_of(ss, threads), vertices);
  const ImageHeights heights(ss, threads);
  parallel_chunks(static_cast<int>(vertices), 4096, threads, [&](int, Chunk r) {
    for (int v = r.begin; v < r.end; ++v) {
      const auto uv = static_cast<std::size_t>(v);
      const std::uint32_t b = links.first[uv], n = links.first[uv + 1] - b;
      embedded_[uv] = embedded(links.edges.data() + b, n, links.place[uv], heights);
    }
  });
}

long EmbeddedStars::count() const { return static_cast<long>(std::count(embedded_.begin(), embedded_.end(), 1)); }

VISMAP_KERNEL_END
}  // namespace vismap::engine
