// The map assembled directly from pieces (arrangements/map_assembly.cpp, Franklin's
// step 10) against the same map built by CGAL's sweep (map_builder.cpp): random
// integer segment sets, full of the degeneracies the assembly must get right
// (shared and collinear edges, T-junctions, vertical edges, components nested in
// faces and touching only below one another's lowest vertex), are cut into the
// edges of their arrangement, each face given a random label; both builders must
// write the same regions and segments. And pieces that break the assembly's
// promise (meeting only at end points) are refused where it can see it.
#include <gtest/gtest.h>

#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>

#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "arrangements/json_writer.h"
#include "arrangements/map_builder.h"
#include "arrangements/rational.h"

namespace {

using namespace vismap;
using exact::FT;
using exact::P2;
using exact::P3;
using Arr = CGAL::Arrangement_2<CGAL::Arr_segment_traits_2<exact::K>>;

std::string json_of(VisibilityMap m) {
  m.stats = {};
  return to_json(m);
}

struct PieceSet {
  std::vector<MapPiece> pieces;
  std::vector<P3> lines;                 // each piece's line with depth (two points)
  std::vector<FacesList> faces;          // the faces lists pieces point to
};

// The edges of the arrangement of `segments` as pieces: faces labelled at random
// (-1 for the unbounded face), edges drawn at random, some doubled (two pieces on
// one edge, at different depths) and given in random direction and order.
PieceSet pieces_of(const std::vector<std::array<int, 4>>& segments, std::mt19937& rng) {
  Arr arr;
  std::vector<exact::Seg2> segs;
  for (const auto& s : segments) segs.emplace_back(P2(s[0], s[1]), P2(s[2], s[3]));
  CGAL::insert(arr, segs.begin(), segs.end());
  std::map<Arr::Face_const_handle, int> label;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
    label[f] = f->is_unbounded() ? -1 : static_cast<int>(rng() % 4) - 1;
  PieceSet out;
  out.faces = {{0}, {1}, {0, 2}, {0, 1}};
  out.lines.reserve(4 * arr.number_of_edges());
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const int copies = rng() % 5 == 0 ? 2 : 1;
    for (int c = 0; c < copies; ++c) {
      MapPiece m;
      const bool flip = rng() % 2;
      m.a = flip ? e->target()->point() : e->source()->point();
      m.b = flip ? e->source()->point() : e->target()->point();
      // Left of source -> target is the halfedge's face.
      m.left = label[flip ? e->twin()->face() : e->face()];
      m.right = label[flip ? e->face() : e->twin()->face()];
      // Visible or not (a piece that is neither visible nor a boundary is never
      // handed over); drawn where visible, except smooth seams (faces {0, 1}).
      m.visible = rng() % 3 != 0;
      if (!m.visible && m.left == m.right) m.visible = true;
      const int kind = static_cast<int>(rng() % 4);
      m.kind = kind == 2 ? EdgeKind::Intersection : kind == 3 ? EdgeKind::Smooth : EdgeKind::Border;
      m.drawn = m.visible && m.kind != EdgeKind::Smooth;
      m.faces = &out.faces[kind];
      m.order_face = out.faces[kind][0];
      const FT z = static_cast<int>(rng() % 3);
      out.lines.emplace_back(m.a.x(), m.a.y(), z);
      out.lines.emplace_back(m.b.x(), m.b.y(), z + static_cast<int>(rng() % 2));
      m.s = &out.lines[out.lines.size() - 2];
      m.t = &out.lines.back();
      out.pieces.push_back(m);
    }
  }
  std::shuffle(out.pieces.begin(), out.pieces.end(), rng);
  return out;
}

TEST(Assembly, SameMapAsTheSweepOnRandomDegenerateSegments) {
  std::mt19937 rng(20261121);
  int nonempty = 0, with_holes = 0;
  for (int round = 0; round < 400; ++round) {
    const int span = round % 2 == 0 ? 6 : 40;   // small: many coincidences
    const int n = 2 + static_cast<int>(rng() % 25);
    std::vector<std::array<int, 4>> segments;
    for (int i = 0; i < n; ++i) {
      std::array<int, 4> s;
      for (int& v : s) v = static_cast<int>(rng() % span);
      if (span > 6) {   // short: many small components
        s[2] = s[0] + static_cast<int>(rng() % 9) - 4;
        s[3] = s[1] + static_cast<int>(rng() % 9) - 4;
      }
      if (rng() % 4 == 0) s[2] = s[0];   // vertical
      if (s[0] == s[2] && s[1] == s[3]) continue;
      segments.push_back(s);
    }
    // Nested squares (holes in holes), and rectangles around parts of the scene:
    // components inside faces.
    if (rng() % 2 == 0) {
      const int cx = static_cast<int>(rng() % span), cy = static_cast<int>(rng() % span);
      for (int r = 1 + static_cast<int>(rng() % 2); r < 12; r += 2 + static_cast<int>(rng() % 3)) {
        segments.push_back({cx - r, cy - r, cx + r, cy - r});
        segments.push_back({cx + r, cy - r, cx + r, cy + r});
        segments.push_back({cx + r, cy + r, cx - r, cy + r});
        segments.push_back({cx - r, cy + r, cx - r, cy - r});
      }
    }
    for (int k = static_cast<int>(rng() % 6); k > 0; --k) {
      const int x0 = static_cast<int>(rng() % span), y0 = static_cast<int>(rng() % span);
      const int x1 = x0 + 1 + static_cast<int>(rng() % (span / 2)), y1 = y0 + 1 + static_cast<int>(rng() % (span / 2));
      segments.push_back({x0, y0, x1, y0});
      segments.push_back({x1, y0, x1, y1});
      segments.push_back({x1, y1, x0, y1});
      segments.push_back({x0, y1, x0, y0});
    }
    PieceSet set = pieces_of(segments, rng);
    std::vector<MapPiece> copy = set.pieces;
    VisibilityMap swept, assembled;
    build_map(set.pieces, swept);
    ASSERT_NO_THROW(assemble_map(copy, assembled)) << "round " << round;
    ASSERT_EQ(json_of(swept), json_of(assembled)) << "round " << round;
    nonempty += !swept.regions.empty();
    for (const Region& r : swept.regions) with_holes += !r.holes.empty();
  }
  // The rounds exercise what they are for.
  EXPECT_GT(nonempty, 300);
  EXPECT_GT(with_holes, 150);
}

// The assembly's passes run in chunks and parts on the threads (the ends'
// stand-ins, the components' union-find, the vertical rays' columns, the
// essential vertices, the chains): the map is the one of one thread. Thousands
// of small components (squares, some with a bar inside: a component in a face),
// enough edges for every part, half the ends named by their vertex.
TEST(Assembly, SameMapOnEveryThreadCount) {
  std::mt19937 rng(1130);
  std::vector<std::array<int, 4>> segments;
  for (int i = 0; i < 110; ++i)
    for (int j = 0; j < 110; ++j) {
      const int x = 10 * i + static_cast<int>(rng() % 3), y = 10 * j + static_cast<int>(rng() % 3);
      segments.push_back({x, y, x + 6, y});
      segments.push_back({x + 6, y, x + 6, y + 6});
      segments.push_back({x + 6, y + 6, x, y + 6});
      segments.push_back({x, y + 6, x, y});
      if (rng() % 3 == 0) segments.push_back({x + 1, y + 3, x + 5, y + 3});
    }
  PieceSet set = pieces_of(segments, rng);
  ASSERT_GT(set.pieces.size(), 3u * 16384u);   // (every thread count below gets parts of its own)
  std::map<std::pair<double, double>, int> name;
  auto id = [&](const P2& p) {
    const std::pair<double, double> at(CGAL::to_double(p.x()), CGAL::to_double(p.y()));   // (small integers: exact)
    return name.emplace(at, static_cast<int>(name.size())).first->second;
  };
  for (MapPiece& m : set.pieces)
    if (rng() % 2 == 0) {
      m.ida = id(m.a);
      m.idb = id(m.b);
    }
  std::string one;
  for (int threads : {1, 2, 3}) {
    std::vector<MapPiece> copy = set.pieces;
    VisibilityMap map;
    ASSERT_NO_THROW(assemble_map(copy, map, threads)) << threads << " threads";
    if (threads == 1) {
      EXPECT_GT(map.regions.size(), 5000u);
      EXPECT_GT(map.segments.size(), 20000u);
      one = json_of(map);
    } else {
      EXPECT_EQ(json_of(map), one) << threads << " threads";
    }
  }
}

TEST(Assembly, EmptyInputGivesAnEmptyMap) {
  std::vector<MapPiece> none;
  VisibilityMap m;
  assemble_map(none, m);
  EXPECT_TRUE(m.regions.empty());
  EXPECT_TRUE(m.segments.empty());
}

// Two collinear pieces from one vertex with different far ends overlap in part:
// the sweep would split them; the assembly was promised they do not occur.
TEST(Assembly, RefusesPiecesThatOverlapInPart) {
  const FacesList faces{0};
  const P3 s(FT(0), FT(0), FT(0)), t(FT(4), FT(0), FT(0));
  auto piece = [&](int x0, int x1) {
    MapPiece m;
    m.a = P2(x0, 0);
    m.b = P2(x1, 0);
    m.visible = m.drawn = true;
    m.faces = &faces;
    m.s = &s;
    m.t = &t;
    return m;
  };
  std::vector<MapPiece> pieces{piece(0, 2), piece(0, 4)};
  VisibilityMap m;
  EXPECT_THROW(assemble_map(pieces, m), std::logic_error);
  // A vertex inside another piece, below a component: also seen.
  std::vector<MapPiece> t_junction{piece(0, 4), piece(2, 2)};
  t_junction[1].b = P2(2, 3);
  EXPECT_THROW(assemble_map(t_junction, m), std::logic_error);
}

// A unit of square face 0 (lower-left corner at the origin, side 4), its four
// borders drawn, with extra pieces along its bottom edge or inside it; depths 1
// on the border, `z` on the extras.
struct Square {
  FacesList border{0}, seam{0, 1};
  std::vector<P3> lines;
  std::vector<MapPiece> pieces;
  Square() { lines.reserve(64); }
  MapPiece& add(int x0, int y0, int x1, int y1, int left, int right, int z, bool visible, bool drawn,
                EdgeKind kind = EdgeKind::Border) {
    MapPiece m;
    m.a = P2(x0, y0);
    m.b = P2(x1, y1);
    m.left = left;
    m.right = right;
    m.visible = visible;
    m.drawn = drawn;
    m.kind = kind;
    m.faces = kind == EdgeKind::Smooth ? &seam : &border;
    m.order_face = 0;
    lines.emplace_back(FT(x0), FT(y0), FT(z));
    lines.emplace_back(FT(x1), FT(y1), FT(z));
    m.s = &lines[lines.size() - 2];
    m.t = &lines.back();
    pieces.push_back(m);
    return pieces.back();
  }
  void frame(bool bottom) {   // counter-clockwise: face 0 on the left
    if (bottom) add(0, 0, 4, 0, 0, -1, 1, true, true);
    add(4, 0, 4, 4, 0, -1, 1, true, true);
    add(4, 4, 0, 4, 0, -1, 1, true, true);
    add(0, 4, 0, 2, 0, -1, 1, true, true);
    add(0, 2, 0, 0, 0, -1, 1, true, true);
  }
};

// The spec: where visible lines coincide, the first in (depth, face index) decides
// the segment, drawn or not. A nearer smooth seam (visible, not drawn) covers a
// farther border: nothing is drawn there; a farther seam does not.
TEST(Assembly, NearerUndrawnLineCoversAFartherDrawnOne) {
  for (bool builder_sweep : {false, true})
    for (int seam_depth : {0, 2}) {
      Square sq;
      sq.frame(true);
      sq.add(4, 0, 0, 0, -1, 0, seam_depth, true, false, EdgeKind::Smooth);
      VisibilityMap m;
      if (builder_sweep) build_map(sq.pieces, m);
      else assemble_map(sq.pieces, m);
      ASSERT_EQ(m.regions.size(), 1u);
      EXPECT_EQ(m.regions[0].outer.size(), 4u);
      EXPECT_EQ(m.segments.size(), seam_depth == 0 ? 3u : 4u) << "seam at depth " << seam_depth;
    }
}

// An undrawn visible piece inside one region bounds nothing and is drawn nowhere:
// it adds no vertex to the ring it touches (the left side's middle here).
TEST(Assembly, UndrawnPieceInsideARegionAddsNoVertex) {
  for (bool builder_sweep : {false, true}) {
    Square sq;
    sq.frame(true);
    sq.add(0, 2, 2, 2, 0, 0, 0, true, false, EdgeKind::Smooth);
    VisibilityMap m;
    if (builder_sweep) build_map(sq.pieces, m);
    else assemble_map(sq.pieces, m);
    ASSERT_EQ(m.regions.size(), 1u);
    EXPECT_EQ(m.regions[0].outer.size(), 4u);
    EXPECT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.segments.size(), 4u);
  }
}

// The spec's numbers: lowest terms, positive denominator, "n" for an integer,
// no "-0"; told without a gcd where the denominator is a power of two, so the
// other cases are made raw here (GMP's arithmetic would normalise them).
TEST(Canonical, LowestTermsWhateverTheInput) {
  auto raw = [](long n, long d) {
    mpq_class q;
    q.get_num() = n;
    q.get_den() = d;   // (not normalised)
    return q;
  };
  EXPECT_EQ(canonical(mpq_class(3)), "3");
  EXPECT_EQ(canonical(mpq_class(-0.0)), "0");
  EXPECT_EQ(canonical(mpq_class(7, 16)), "7/16");
  EXPECT_EQ(canonical(mpq_class(-7, 16)), "-7/16");
  EXPECT_EQ(canonical(mpq_class(-2, 3)), "-2/3");
  EXPECT_EQ(canonical(raw(2, 4)), "1/2");      // power of two, even numerator
  EXPECT_EQ(canonical(raw(0, 8)), "0");
  EXPECT_EQ(canonical(raw(6, 9)), "2/3");      // neither
  EXPECT_EQ(canonical(raw(3, -4)), "-3/4");    // negative denominator
  EXPECT_EQ(canonical(raw(-12, 1)), "-12");
  std::string s = "x=";
  append_canonical(s, raw(10, 4));
  EXPECT_EQ(s, "x=5/2");
  // Fractions over powers of two (their denominators' digits kept once made):
  // GMP's own text, for numerators of every size and exponents on both sides
  // of the kept ones, twice each (made, then kept).
  std::mt19937_64 rng(5);
  for (const unsigned long k : {0ul, 1ul, 52ul, 53ul, 64ul, 100ul, 1074ul, 4095ul, 4096ul, 5000ul})
    for (int round = 0; round < 2; ++round)
      for (const int limbs : {1, 2, 5}) {
        mpz_class n = 1;
        for (int l = 0; l < limbs; ++l) n = (n << 64) + mpz_class(std::to_string(rng()));
        n = n * 2 + 1;   // (odd: lowest terms)
        if (rng() % 2) n = -n;
        mpq_class q;
        q.get_num() = n;
        mpz_setbit(q.get_den_mpz_t(), k);
        mpz_clrbit(q.get_den_mpz_t(), 0);
        if (k == 0) q.get_den() = 1;
        std::string t = "p ";
        append_canonical(t, q);
        EXPECT_EQ(t, "p " + q.get_str()) << "2^" << k;
      }
}

// The map writer's numbers are GMP's, in lowest terms already: append_lowest_terms
// writes them as canonical() would, without its gcd; in_lowest_terms (its check
// where assertions are on) tells the values GMP's arithmetic leaves from raw ones.
TEST(Canonical, LowestTermsTakenAsTheyAre) {
  auto raw = [](long n, long d) {
    mpq_class q;
    q.get_num() = n;
    q.get_den() = d;
    return q;
  };
  for (const mpq_class& q : {raw(2, 4), raw(0, 8), raw(6, 9), raw(3, -4), raw(0, -1)})
    EXPECT_FALSE(in_lowest_terms(q)) << q.get_num() << " / " << q.get_den();
  std::mt19937_64 rng(11);
  auto big = [&](int limbs) {
    mpz_class n = 0;
    for (int l = 0; l < limbs; ++l) n = (n << 64) + mpz_class(std::to_string(rng()));
    return rng() % 2 ? mpz_class(-n) : n;
  };
  int dyadic = 0, other = 0;
  for (int i = 0; i < 400; ++i) {
    // Quotients and sums as an engine makes them: crossings over any
    // denominator, coordinates over powers of two, integers, zero.
    mpq_class q;
    switch (i % 4) {
      case 0: q = mpq_class(big(1 + i % 3)) / mpq_class(big(1 + i % 2) + 1); break;
      case 1: q = mpq_class(big(2)) / mpq_class(mpz_class(1) << (i % 200)); break;
      case 2: q = mpq_class(big(1)); break;
      default: q = mpq_class(big(1)) / 3 - mpq_class(big(1)) / 6 + mpq_class(1, 2); break;
    }
    ASSERT_TRUE(in_lowest_terms(q)) << q;
    (mpz_scan1(q.get_den_mpz_t(), 0) + 1 == mpz_sizeinbase(q.get_den_mpz_t(), 2) ? dyadic : other) += 1;
    std::string t = "v ";
    append_lowest_terms(t, q);
    EXPECT_EQ(t, "v " + canonical(q)) << q;
  }
  EXPECT_GT(dyadic, 100);
  EXPECT_GT(other, 100);
  EXPECT_TRUE(in_lowest_terms(mpq_class(0)));
  std::string zero;
  append_lowest_terms(zero, mpq_class(-0.0));
  EXPECT_EQ(zero, "0");
}

}  // namespace
