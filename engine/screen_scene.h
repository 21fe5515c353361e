// Stage 4: the scene in screen space (x, y, depth), exact. Facets are projected
// (and clipped at the near plane), edge pieces get their kinds, and everything a
// scene does not need is dropped and counted. Internal to the engine (CGAL types).
#pragma once
#include <CGAL/Bbox_2.h>
#include <boost/iterator/indirect_iterator.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/exact_kernel.h"
#include "engine/image_table.h"
#include "engine/small_vec.h"
#include "engine/visibility.h"
#include "engine/world_facets.h"
#include "engine/world_scene.h"

namespace vismap::exact {
VISMAP_KERNEL_BEGIN
struct ExactSource;   // (engine/lazy_leaves.h: what lazy exact values are computed from)
VISMAP_KERNEL_END
}  // namespace vismap::exact

namespace vismap::engine {
using namespace vismap::exact;
VISMAP_KERNEL_BEGIN

enum class Facing : std::uint8_t { Front, Back, EdgeOn };

// A facet's corners, read as a sequence of points: the vertex images they are
// (the screen scene's table, which outlives the facets) referred to, not copied
// (a copy is four counted handles); a corner the near plane's cut made is kept
// here. Inline up to four corners.
class Corners {
 public:
  using Iterator = boost::indirect_iterator<const P3* const*>;
  const P3& operator[](std::size_t k) const { return *at_[k]; }
  std::size_t size() const { return at_.size(); }
  bool empty() const { return at_.empty(); }
  const P3& front() const { return *at_[0]; }
  const P3& back() const { return *at_[at_.size() - 1]; }
  Iterator begin() const { return Iterator(at_.begin()); }
  Iterator end() const { return Iterator(at_.end()); }
  void refer(const P3& image) { at_.push_back(&image); }
  void keep(P3 cut) {   // (at most two per facet: a convex polygon's cut by a plane)
    const int k = cut_ ? 1 : 0;   // (the block is made for the first)
    if (!cut_) cut_ = std::make_unique<std::array<P3, 2>>();
    (*cut_)[k] = std::move(cut);
    at_.push_back(&(*cut_)[k]);
  }
  void clear() { at_.clear(); }

 private:
  SmallVec<const P3*, 4> at_;
  std::unique_ptr<std::array<P3, 2>> cut_;
};

// A canonical vertex id (an input vertex's index; make_screen_scene refuses
// scenes of 2^31 vertices or more), or -1: none.
using VertexId = std::int32_t;

// A facet's depth plane z = a x + b y + c (a facet that is not edge-on):
// intervals that contain its coefficients, and where those are not the exact
// values themselves, the screen scene's ExactSource, which makes the exact ones
// from the world by facet number (most planes are never needed exactly: three
// lazy numbers per facet were 192 bytes; this is 64).
class DepthPlane {
 public:
  DepthPlane() = default;
  // Coefficients that are doubles exactly.
  static DepthPlane of_doubles(double a, double b, double c);
  // Intervals of coefficients whose exact values `source` makes for `facet`.
  static DepthPlane of_source(const Interval& a, const Interval& b, const Interval& c, const ExactSource& source,
                              std::uint32_t facet);
  // Coefficients computed as rationals, kept by `source` as facet's plane.
  static DepthPlane of_rationals(const mpq_class& a, const mpq_class& b, const mpq_class& c, const ExactSource& source,
                                 std::uint32_t facet);

  // Coefficient k's interval (0: a, 1: b, 2: c).
  const Interval& approx(int k) const { return approx_[static_cast<std::size_t>(k)]; }
  // The three coefficients, exactly.
  std::array<mpq_class, 3> exact() const;
  // Coefficient k as a kernel number (a lazy leaf where it is not a double),
  // for the constructions that need one: made at each call.
  FT number(int k) const;
  // The same plane, exactly.
  bool operator==(const DepthPlane& o) const;

 private:
  std::array<Interval, 3> approx_{Interval(0), Interval(0), Interval(0)};
  const ExactSource* source_ = nullptr;   // (null: the intervals are points, the exact values)
  std::uint32_t facet_ = 0;
};

// What is known of every facet, whether its whole Facet is made or not (a
// lines-only drawing makes those near its lines only: ScreenScene::facet).
// 40 bytes.
struct FacetBrief {
  int face = -1;                 // input face index
  Facing facing = Facing::EdgeOn;
  bool occluder = false;         // hides and labels: not edge-on, not culled
  bool projected = false;        // has a screen polygon (not all behind the near plane)
  CGAL::Bbox_2 box;              // contains the exact projection
};

// (The small fields first, packed: 144 bytes, the depth plane held apart (a
// lines-only drawing makes few); a million facets are common. Boxes and depth
// ranges stay doubles: an orthographic view does not translate, and a float's
// step near a georeferenced 5e6 is 0.5.)
struct Facet : FacetBrief {
  bool planar = true;            // false: a fan piece of a non-planar polygon
  // Bit k: edge v[k] -> v[k+1] lies on a diagonal inside the polygon (a
  // triangulation's or a fan's edge, EdgeRole::Internal; such facets are
  // triangles, at most four corners after the near-plane cut).
  std::uint8_t diagonals = 0;
  bool split = false;            // WorldFacet::split: across each diagonal, the polygon goes on in its plane
  bool on_diagonal(std::size_t k) const { return k < 8 && ((diagonals >> k) & 1u); }
  // A triangle of a simple planar polygon with a diagonal: touching another
  // facet's plane along it, the polygon may cross that plane there.
  bool may_cross_at_diagonal() const { return split && diagonals != 0; }
  double zlo = 0, zhi = 0;       // contains the exact depths over the facet (of its vertices)
  Corners v;                     // convex polygon, screen space, input order
  SmallVec<VertexId, 4> id;      // id[k]: v[k]'s canonical vertex id, or -1 where the near
                                 // plane cut the polygon (as Curve::vs): connectivity answers
                                 // some predicates without arithmetic
  const DepthPlane* plane = nullptr;   // depth(x, y) = a x + b y + c (not edge-on), kept in
                                       // ScreenScene::planes; null until made
  FT depth_at(const P2& p) const { return plane->number(0) * p.x() + plane->number(1) * p.y() + plane->number(2); }
  // Whether canonical vertex v (not -1) is a corner: then it lies in the plane.
  bool has_vertex(long v) const { return v >= 0 && std::find(id.begin(), id.end(), v) != id.end(); }
};

// A line that may be drawn or bound a region: an edge piece, or (added by the
// engine) the intersection line of two facets.
struct Curve {
  const P3 *s = nullptr, *t = nullptr;   // screen end points with depth: vertex images
                                 // (ScreenScene::images) or points in ScreenScene::ends
  VertexId vs = -1, vt = -1;     // end point identity (canonical vertex id) or -1
  SmallInts sharers;             // facets whose boundary it is (for intersections: the two facets)
  SmallInts sharer_edge;         // per sharer: k where its edge v[k] -> v[k+1] holds the curve
                                 // (its screen polygon's, which the near plane's cut renumbers:
                                 // screen_edge_of), or -1 (none, or not known)
  SmallInts faces;               // faces written in the JSON, ascending; empty = never drawn
  EdgeKind kind = EdgeKind::Border;
  bool drawn = false;
  // A facet that hides on each side of it on screen (two sharers, both
  // occluders, on opposite sides): on no outline, so whatever passes behind it
  // is hidden on both sides there (cut_curves skips such crossings).
  bool covered = false;
  int order_face = 0;            // lowest face index: ties in (depth, face index)
  CGAL::Bbox_2 box;
};

struct CurveMaker;   // (screen_scene.cpp: what making a curve from an edge piece needs)

struct ScreenScene {
  std::shared_ptr<const ExactSource> exact;   // (first: every lazy leaf refers to it)
  ImageTable images;             // the used vertices' images (before the facets: they refer to them)
  // Where the images are left for later (a lines-only drawing: make_images makes
  // those it needs), each one's intervals, by place; else empty.
  std::vector<ImageBounds> image_bounds;
  // Where even those intervals are made only when asked (sparse(): a lean
  // orthographic scene, whose lines-only drawing reads a few per cent of its
  // vertices), per place, whether they are made (make_bounds); an interval not
  // made is computed where it is read (kept_bounds), the same values.
  std::vector<char> bounds_made;
  bool sparse() const { return !bounds_made.empty(); }
  // The facets, by index (a curve's sharers, a cell's list): each one's Facet
  // (facet()), or, where a lines-only drawing keeps only briefs (lean(): most
  // facets lie far from its lines), those make_facets made, at made_at's places.
  // brief() reads what every facet has.
  std::vector<Facet> facets;
  std::vector<FacetBrief> briefs;       // lean: every facet's
  std::vector<std::uint32_t> made_at;   // lean: facet fi's place in `facets`, or kNotMade
  static constexpr std::uint32_t kNotMade = UINT32_MAX;
  bool lean() const { return !briefs.empty(); }
  std::size_t facet_count() const { return lean() ? briefs.size() : facets.size(); }
  const FacetBrief& brief(std::size_t fi) const { return lean() ? briefs[fi] : facets[fi]; }
  const Facet& facet(std::size_t fi) const { return lean() ? facets[made_place(fi)] : facets[fi]; }
  Facet& facet(std::size_t fi) { return lean() ? facets[made_place(fi)] : facets[fi]; }
  // Facet fi where it is made, else null.
  const Facet* made_facet(std::size_t fi) const {
    if (!lean()) return &facets[fi];
    return made_at.empty() || made_at[fi] == kNotMade ? nullptr : &facets[made_at[fi]];
  }
  // (A lean scene's made facets keep their brief's flag too.)
  void set_occluder(std::size_t fi, bool occluder) {
    if (!lean()) {
      facets[fi].occluder = occluder;
      return;
    }
    briefs[fi].occluder = occluder;
    if (!made_at.empty() && made_at[fi] != kNotMade) facets[made_at[fi]].occluder = occluder;
  }
  // The facets' depth planes, in chunks that never move (Facet::plane points
  // into them): every facet's, or where a lines-only drawing leaves them for
  // later, those make_depth_planes makes.
  std::vector<std::vector<DepthPlane>> planes;
  // Per facet: its component where that is known not to meet itself (a closed
  // one that closed_components took as such, having tested it: engine/culling.h;
  // an open surface that is a graph over a plane, engine/height_fields.h), else
  // -1. Two facets of one such solid never pierce each other.
  std::vector<int> solid;
  std::vector<Curve> curves;
  // Curve end points that are not vertex images (near-plane cuts, intersection-
  // line ends), where the curves point: lists that are only appended to, so
  // nothing they hold moves (one per chunk of curves made in parallel).
  std::deque<std::deque<P3>> ends;
  int scale_exp = 0;             // screen coordinates are the spec's times 2^scale_exp
  bool planes_later = false;     // the facets' depth planes not made yet (a lines-only drawing:
                                 // make_depth_planes makes those its cells list)
  // Steps 5-8 may look only near the drawn lines: a lines-only drawing made from
  // its judged pieces, whose planes are made late (false: at everything, as for
  // a whole map).
  bool near_drawn_lines() const { return planes_later; }
  const std::vector<Vec3>* world = nullptr;   // the input's vertices (canonical ids index them)
  // Latent curves (lines only, when asked): edge pieces that are not drawn, each
  // known by its piece's number (latent_box: its box, made when asked) until
  // make_latent_curves makes the ones a drawing needs. (A million latent pieces'
  // boxes kept were 32 MB, most of them read once or twice.)
  std::vector<int> latent_piece;
  std::shared_ptr<const CurveMaker> maker;

  // Image p's intervals as it had them when made (kept ones, where the images are
  // left for later: the same values, read without the image), for a corner or a
  // curve's end; any other point's own.
  // kept_place: p's place among the images where those are left for later, else -1.
  std::ptrdiff_t kept_place(const P3& p) const {
    const std::less<const P3*> before;
    if (image_bounds.empty() || before(&p, images.data()) || !before(&p, images.data() + images.size())) return -1;
    return &p - images.data();
  }
  ImageBounds kept_bounds(std::ptrdiff_t u) const {
    const auto at = static_cast<std::size_t>(u);
    return bounds_made.empty() || bounds_made[at] ? image_bounds[at] : bounds_now(at);
  }
  Interval x_of(const P3& p) const { const auto u = kept_place(p); return u >= 0 ? kept_bounds(u).x : approx_of(p.x); }
  Interval y_of(const P3& p) const { const auto u = kept_place(p); return u >= 0 ? kept_bounds(u).y : approx_of(p.y); }
  Interval z_of(const P3& p) const { const auto u = kept_place(p); return u >= 0 ? kept_bounds(u).z : approx_of(p.z); }

 private:
  std::uint32_t made_place(std::size_t fi) const {
    const std::uint32_t at = made_at.empty() ? kNotMade : made_at[fi];
    if (at == kNotMade) not_made();
    return at;
  }
  [[noreturn]] static void not_made();
  ImageBounds bounds_now(std::size_t u) const;   // (the maker's bounds_of)
};

// Facet fi's solid (ScreenScene::solid), or -1; and whether every occluder is in
// one (then the piercing searches have no pair of neighbours to settle).
inline int solid_of(const ScreenScene& ss, int fi) { return ss.solid.empty() ? -1 : ss.solid[static_cast<std::size_t>(fi)]; }
inline bool occluders_all_in_solids(const ScreenScene& ss) {
  if (ss.solid.empty()) return false;
  for (std::size_t fi = 0; fi < ss.facet_count(); ++fi)
    if (ss.brief(fi).occluder && ss.solid[fi] < 0) return false;
  return true;
}
// Whether every occluder is in one solid (a terrain alone): then no pair of
// facets can pierce each other.
inline bool occluders_in_one_solid(const ScreenScene& ss) {
  if (ss.solid.empty()) return false;
  int one = -1;
  for (std::size_t fi = 0; fi < ss.facet_count(); ++fi) {
    if (!ss.brief(fi).occluder) continue;
    if (ss.solid[fi] < 0 || (one >= 0 && ss.solid[fi] != one)) return false;
    one = ss.solid[fi];
  }
  return true;
}

// Whether world facets already walk the screen in their own order (a terrain's
// grid rows, a scanned mesh's strips): make_screen_scene then keeps their order
// for a lines-only drawing rather than sorting them along a Morton curve. Told
// from a sample of consecutive pairs; false under 2^16 facets (screen_scene.cpp).
bool walk_the_screen(const WorldFacets& wf, const Scene& scene, const View& view);

// With `latent`, curves that are not drawn are left latent (a lines-only drawing
// needs only those near a drawn one: most of a smooth mesh's edges are not).
// Without `cull`, back faces of closed solids stay occluders and their edges
// curves (the hidden lines need every edge).
// With `world` (what no camera changes, kept by a series of views), the facets,
// edge pieces and closed components are taken from it, not made again: the
// same screen scene.
ScreenScene make_screen_scene(const Scene& scene, const View& view, const Options& opt,
                              Stats& stats, bool latent = false, bool cull = true, const WorldScene* world = nullptr);

// Edge k of a world facet with corners v (input vertex ids) as an edge of its
// screen facet: make_screen_scene keeps the corners in front of the near plane
// (`in_front(id)`) and puts a cut point where an edge crosses it, in the
// facet's order. The screen facet's edge (from its corner j to j + 1) that
// holds the part of edge k in front, j, or -1 (none is). Where nothing is cut: k.
template <class Ids, class InFront>
int screen_edge_of(const Ids& v, int k, InFront in_front) {
  int at = 0;   // the screen index of the next corner
  for (std::size_t j = 0, n = v.size(); j < n; ++j) {
    const bool fa = in_front(v[j]), fb = in_front(v[(j + 1) % n]);
    if (static_cast<int>(j) == k) return fa || fb ? at : -1;   // (from a's image, or from the cut to b's)
    at += fa;
    at += fa != fb;
  }
  return -1;
}

// Whether input vertex v lies in the plane of facet f, in the world, exactly (no
// gcd): false also where f has no three input corners spanning its plane.
bool in_world_plane(const std::vector<Vec3>& input, long v, const Facet& f);

// The world facets the screen facets were made from (index for index), where
// the scene keeps them (latent curves, or made without culling); else null.
const WorldFacets* world_facets_of(const ScreenScene& ss);
// The depth planes of the facets `which` marks, where make_screen_scene left them
// for later (ScreenScene::planes_later). In parallel.
void make_depth_planes(ScreenScene& ss, const std::vector<char>& which, int threads);
// The world's edge pieces that latent curves are made from (ScreenScene::latent_piece), or null.
const std::vector<WorldPiece>* latent_pieces_of(const ScreenScene& ss);
// Latent curve i's box, as its curve's would be (its ends' boxes).
CGAL::Bbox_2 latent_box(const ScreenScene& ss, std::size_t i);
// Latent curve i's end points as the images they are (ScreenScene::images; its box is
// theirs), or null for an end cut at the near plane.
std::array<const P3*, 2> latent_ends(const ScreenScene& ss, std::size_t i);

// Makes the images of the vertices at `places` (ScreenScene::images) that are not
// made yet, where make_screen_scene left them for later (else none is left). In
// parallel.
void make_images(ScreenScene& ss, const std::vector<std::uint32_t>& places, int threads);
// Makes the images of facet fi's corners for every facet `which` marks (every
// facet where `which` is empty).
void make_corner_images(ScreenScene& ss, const std::vector<char>& which, int threads);

// In a sparse scene (ScreenScene::sparse), makes the intervals of the images at
// `places` that are not made yet, and the boxes of the facets `which` marks that
// have none yet (their briefs', as a lean scene's are made), in parallel. Else
// nothing: every brief has its box.
void make_bounds(ScreenScene& ss, const std::vector<std::uint32_t>& places, int threads);
void make_boxes(ScreenScene& ss, const std::vector<char>& which, int threads);
// In a sparse scene, the boxes of runs of `run` consecutive facets (every
// facet's, occluder or not; the last run may be shorter): each holds the box of
// every facet of its run, from their world corners' box (intervals: no image
// made; where those overflow, the facets' own boxes, made). Else empty.
std::vector<CGAL::Bbox_2> world_run_boxes(ScreenScene& ss, int run, int threads);

// In a lean scene (ScreenScene::lean), makes the Facets of the facets `which`
// marks (every facet where `which` is empty) that are not made yet, from their
// briefs and world facets, as make_screen_scene would have; in facet order
// (those made before may move). Else nothing.
void make_facets(ScreenScene& ss, const std::vector<char>& which, int threads);
// Facet fi's corners (its screen polygon's), whether its Facet is made or not:
// a lean scene's facets keep all their corners (the near plane cuts none), the
// images of their world facet's vertices.
SmallVec<const P3*, 4> corners_of(const ScreenScene& ss, std::size_t fi);

// Makes the latent curves whose flag in `wanted` is set, appended to ss.curves in
// latent order (as make_screen_scene would have made them); no curve is latent
// after it. Chunks of them in parallel.
void make_latent_curves(ScreenScene& ss, const std::vector<char>& wanted, int threads);

// The intersection line from s to t of facets fa and fb (of faces face_a, face_b):
// a curve drawn for both faces. Its end points are kept in `ends`.
Curve intersection_curve(const P3& s, const P3& t, int fa, int fb, int face_a, int face_b, std::deque<P3>& ends);

// Each curve's faces list, as the map takes it (the map points at these; they
// outlive the curves).
std::vector<SmallInts> faces_lists(const std::vector<Curve>& curves, int threads = 1);

// Depth along a curve at a screen point p on it (depth is affine along a screen line).
FT depth_on(const Curve& c, const P2& p);

VISMAP_KERNEL_END
}  // namespace vismap::engine
