// Newell, Newell & Sancha 1972, the extended algorithm, decided exactly.
//
// The list starts with every occluding facet, farthest first (by the depth of
// its farthest point). The top face P is written once it obscures none of the
// faces Q still listed whose farthest point is at least as far as P's nearest:
// for each such Q the five tests of increasing cost (x extents, y extents, P
// behind Q's plane, Q in front of P's plane, projections disjoint) try to prove
// that P may be written first. When all five fail, tests 3 and 4 reversed try
// to prove that Q may go first; if so and Q was never moved, Q goes to the top,
// marked, and becomes P. Otherwise one face is split and the fragments (and the
// other face, unmarked) go back into the list by their farthest depth:
//   1. P by Q's plane, if P has vertices strictly on both sides of it;
//   2. else Q by P's plane, if Q has;
//   3. else (the paper halves P here) P along the line of one of Q's screen
//      edges, or Q along one of P's: a cut by a plane containing the line of sight.
//
// Why the third split is not the paper's halving. With exact tests it is reached
// only when Q is marked: if Q may be moved and tests 3 and 4 reversed fail, then
// P is neither on-or-behind Q's plane (test 3) nor on-or-in-front of it (test 4
// reversed), so P has vertices strictly on both sides and split 1 applies (two
// faces in one plane always pass one of the two, by face index). The paper's
// halving served twisted faces and rounding; what is left exactly is a genuine
// cycle (Newell's three sticks), where neither face need cross the other's
// plane, and halving would give new vertices at arbitrary midpoints and no
// bound on how often it recurs. A cut along an edge line of Q separates the part
// of P over Q from the rest. Every split line is then a plane-plane crossing or
// an edge line of some fragment, so all split lines come from one finite set of
// lines (input edge lines and crossings of facet planes, projected): fragments
// are unions of cells of a finite arrangement, every split makes two non-empty
// pieces, between two splits each step writes a face or marks one, and so the
// loop ends.
//
// Equal depth: a face in another's plane counts as behind it when its index is
// higher (the spec's order (depth, face index)); the test for which faces P
// might obscure includes those whose farthest point is exactly at P's nearest.
#include "engine/newell_order.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "engine/newell_geometry.h"

namespace vismap::engine {
namespace {

using namespace newell;

// Some edge of the convex, counter-clockwise polygon a has all of b on its
// closed outer side (separating axis): their interiors are disjoint.
bool separated_by_edge_of(const std::vector<P3>& a, const std::vector<P3>& b) {
  const std::size_t n = a.size();
  for (std::size_t k = 0; k < n; ++k) {
    const P2 p = a[k].xy(), q = a[(k + 1) % n].xy();
    bool out = true;
    for (const P3& w : b)
      if (CGAL::orientation(p, q, w.xy()) == CGAL::LEFT_TURN) { out = false; break; }
    if (out) return true;
  }
  return false;
}

// The parts of X where f > 0 and where f < 0 (f changes sign on X). New vertices
// are exact leaves, their depth on X's facet plane.
std::pair<Fragment, Fragment> split_fragment(const Fragment& X, const Line& f, const Facet& F, int plane) {
  const std::size_t n = X.v.size();
  std::vector<int> sg(n);
  for (std::size_t k = 0; k < n; ++k) sg[k] = plane >= 0 && X.cut_on[k] == plane ? 0 : f.sign_at(X.v[k]);
  Fragment pos{X.facet, X.face, {}, {}, {}, {}}, neg{X.facet, X.face, {}, {}, {}, {}};
  std::vector<std::uint64_t> pos_on, neg_on;   // which of X's edges each corner lies on
  auto put = [](Fragment& y, std::vector<std::uint64_t>& on, const P3& p, int cut, std::uint64_t edges) {
    y.v.push_back(p);
    y.cut_on.push_back(cut);
    on.push_back(edges);
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = (k + 1) % n;
    const P3 &a = X.v[k], &b = X.v[k1];
    if (sg[k] >= 0) put(pos, pos_on, a, X.cut_on[k], on_corner(k, n));
    if (sg[k] <= 0) put(neg, neg_on, a, X.cut_on[k], on_corner(k, n));
    if (sg[k] * sg[k1] < 0) {   // the line crosses this edge strictly inside
      const auto [x, y] = edge_crossing(a, b, f);
      const P3 c{x, y, leaf(depth_of(F, x, y))};
      put(pos, pos_on, c, plane, on_edge(k));
      put(neg, neg_on, c, plane, on_edge(k));
    }
  }
  pos.edge = part_edges(pos_on, X.edge);
  neg.edge = part_edges(neg_on, X.edge);
  pos.box = box_of(pos.v);
  neg.box = box_of(neg.v);
  return {std::move(pos), std::move(neg)};
}

class DepthSort {
 public:
  DepthSort(const ScreenScene& ss, Stats& st) : ss_(ss), st_(st) {}

  std::vector<Fragment> run() {
    for (int fi = 0; fi < static_cast<int>(ss_.facets.size()); ++fi) {
      const Facet& f = ss_.facets[fi];
      if (!f.occluder) continue;
      Fragment x{fi, f.face, {}, {}, {}, f.box};
      const std::size_t n = f.v.size();
      FragmentCorners corners(x);
      for (std::size_t k = 0; k < n; ++k) corners.add(f.v[k], on_corner(k, n));
      std::vector<int> own(n);   // (its edges are the facet's own)
      for (std::size_t k = 0; k < n; ++k) own[k] = static_cast<int>(k);
      corners.close(own, f.facing == Facing::Back);
      x.cut_on.assign(x.v.size(), -1);
      insert(add(std::move(x)));
    }
    st_.count("faces_considered", static_cast<std::int64_t>(items_.size()));
    while (!marked_.empty() || !sorted_.empty()) step();
    st_.count("pair_tests", pair_tests_);
    st_.count("reorders", reorders_);
    st_.count("splits_by_plane", plane_splits_);
    st_.count("splits_by_cut", cut_splits_);
    st_.count("fragments_written", static_cast<std::int64_t>(out_.size()));
    return std::move(out_);
  }

 private:
  struct Item {
    Fragment f;
    FT xmin, xmax, ymin, ymax, zmin, zmax;   // exact extents; larger depth is farther
    bool marked = false;
  };
  struct Key {
    FT zmax;
    int id;
  };
  struct FarthestFirst {
    bool operator()(const Key& a, const Key& b) const {
      auto c = CGAL::compare(a.zmax, b.zmax);
      return c != CGAL::EQUAL ? c == CGAL::LARGER : a.id < b.id;
    }
  };

  const ScreenScene& ss_;
  Stats& st_;
  std::vector<Item> items_;                 // every fragment made; split ones are left behind
  std::vector<int> marked_;                 // the head of the list: faces moved there, top last
  std::set<Key, FarthestFirst> sorted_;     // the rest, farthest first
  std::vector<Fragment> out_;
  std::int64_t pair_tests_ = 0, reorders_ = 0, plane_splits_ = 0, cut_splits_ = 0;

  const Facet& facet(int id) const { return ss_.facets[items_[id].f.facet]; }

  // Two facets in one plane (pieces of one polygon, or coplanar faces).
  bool same_plane(int f, int g) const {
    if (f == g) return true;
    const Facet &F = ss_.facets[f], &G = ss_.facets[g];
    return *F.plane == *G.plane;
  }

  int add(Fragment f) {
    Item it;
    it.xmin = it.xmax = f.v[0].x;
    it.ymin = it.ymax = f.v[0].y;
    it.zmin = it.zmax = f.v[0].z;
    for (const P3& p : f.v) {
      if (p.x < it.xmin) it.xmin = p.x;
      if (p.x > it.xmax) it.xmax = p.x;
      if (p.y < it.ymin) it.ymin = p.y;
      if (p.y > it.ymax) it.ymax = p.y;
      if (p.z < it.zmin) it.zmin = p.z;
      if (p.z > it.zmax) it.zmax = p.z;
    }
    it.f = std::move(f);
    items_.push_back(std::move(it));
    return static_cast<int>(items_.size()) - 1;
  }
  void insert(int id) {
    items_[id].marked = false;
    sorted_.insert(Key{items_[id].zmax, id});
  }
  void remove(int id) {
    if (items_[id].marked) marked_.erase(std::find(marked_.begin(), marked_.end(), id));
    else sorted_.erase(Key{items_[id].zmax, id});
  }
  int top() const { return marked_.empty() ? sorted_.begin()->id : marked_.back(); }

  // The five tests: false when one proves that P may be written before Q.
  // Leaves in sp / sq the sides of Q's plane P lies on, and of P's plane Q lies on.
  bool may_obscure(int p, int q, int& sp, int& sq) const {
    const Item &P = items_[p], &Q = items_[q];
    // 1, 2. The extents on the screen do not overlap (touching is not overlapping).
    if (!CGAL::do_overlap(P.f.box, Q.f.box)) return false;
    if (!(P.xmin < Q.xmax && Q.xmin < P.xmax)) return false;
    if (!(P.ymin < Q.ymax && Q.ymin < P.ymax)) return false;
    // 3. P wholly behind (or on) Q's plane; in one plane, the higher face index is behind.
    sp = same_plane(P.f.facet, Q.f.facet) ? 0 : sides_of_plane(P.f.v, P.f.cut_on, Q.f.facet, facet(q));
    sq = 0;
    const bool coplanar = sp == 0;
    if (coplanar) { if (P.f.face >= Q.f.face) return false; }
    else if (!(sp & kFront)) return false;
    // 4. Q wholly in front of (or on) P's plane.
    if (!coplanar) {
      sq = sides_of_plane(Q.f.v, Q.f.cut_on, P.f.facet, facet(p));
      if (!(sq & kBehind)) return false;
    }
    // 5. The projections do not overlap.
    if (separated_by_edge_of(P.f.v, Q.f.v) || separated_by_edge_of(Q.f.v, P.f.v)) return false;
    return true;
  }

  // Tests 3 and 4 with P and Q exchanged: Q wholly behind P's plane, or P wholly in front of Q's.
  bool may_go_first(int p, int q, int sp, int sq) const {
    if (sp == 0) return items_[q].f.face >= items_[p].f.face;   // one plane
    return !(sq & kFront) || !(sp & kBehind);
  }

  void step() {
    const int p = top();
    const FT& near_p = items_[p].zmin;
    int q = -1, sp = 0, sq = 0;
    auto obscured = [&](int c) {
      if (c == p || items_[c].zmax < near_p) return false;
      ++pair_tests_;
      return may_obscure(p, c, sp, sq);
    };
    for (auto it = marked_.rbegin(); it != marked_.rend() && q < 0; ++it)
      if (obscured(*it)) q = *it;
    for (auto it = sorted_.begin(); it != sorted_.end() && q < 0; ++it) {
      if (it->zmax < near_p) break;   // this and all after are wholly nearer than P
      if (obscured(it->id)) q = it->id;
    }
    if (q < 0) {   // P obscures nothing still listed: write it
      remove(p);
      out_.push_back(std::move(items_[p].f));
      return;
    }
    if (!items_[q].marked && may_go_first(p, q, sp, sq)) {   // reorder: Q to the top, marked
      remove(q);
      items_[q].marked = true;
      marked_.push_back(q);
      ++reorders_;
      return;
    }
    split(p, q, sp, sq);
  }

  // Replaces X by its two parts on either side of f (both inserted unmarked).
  void replace(int x, const Line& f, int plane) {
    remove(x);
    auto [a, b] = split_fragment(items_[x].f, f, facet(x), plane);
    int ia = add(std::move(a)), ib = add(std::move(b));
    insert(ia);
    insert(ib);
  }

  void split(int p, int q, int sp, int sq) {
    // The other face goes back among the unmarked ones, in its place by depth.
    auto reinsert = [&](int o) { if (items_[o].marked) { remove(o); insert(o); } };
    if (sp == kBoth) {   // 1. P by Q's plane
      ++plane_splits_;
      replace(p, plane_crossing(facet(p), facet(q)), items_[q].f.facet);
      reinsert(q);
      return;
    }
    if (sq == kBoth) {   // 2. Q by P's plane
      ++plane_splits_;
      replace(q, plane_crossing(facet(q), facet(p)), items_[p].f.facet);
      reinsert(p);
      return;
    }
    // 3. A cycle (Q is marked): cut one face along an edge line of the other.
    for (auto [x, y] : {std::pair{p, q}, std::pair{q, p}}) {
      const auto& e = items_[y].f.v;
      for (std::size_t k = 0; k < e.size(); ++k) {
        Line f = line_through(e[k], e[(k + 1) % e.size()]);
        if (sides_of(items_[x].f.v, f) != kBoth) continue;
        ++cut_splits_;
        replace(x, f, -1);
        reinsert(y);
        return;
      }
    }
    throw std::logic_error("newell: two faces in a cycle with equal projections and no split (engine bug)");
  }
};

}  // namespace

void FragmentCorners::add(const P3& p, std::uint64_t edges) {
  if (f_.v.empty() || !equal_points(f_.v.back().xy(), p.xy())) {
    f_.v.push_back(p);
    on_.push_back(0);
  }
  on_.back() |= edges;
}

bool FragmentCorners::close(const std::vector<int>& labels, bool reverse) {
  std::vector<P3>& v = f_.v;
  while (v.size() > 1 && equal_points(v.front().xy(), v.back().xy())) {
    v.pop_back();
    on_.front() |= on_.back();
    on_.pop_back();
  }
  f_.edge = part_edges(on_, labels);
  if (reverse) {
    std::reverse(v.begin(), v.end());
    f_.edge = reversed_edges(f_.edge);
  }
  return v.size() >= 3;
}

std::vector<Fragment> depth_sort(const ScreenScene& ss, Stats& stats) { return DepthSort(ss, stats).run(); }

}  // namespace vismap::engine
