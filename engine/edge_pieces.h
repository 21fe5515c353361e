// Stage 2: edges matched geometrically in world space. Wherever facet boundaries
// overlap along a segment in 3D (same end points, T-junctions, polygon soups)
// they share one edge piece. Exact: lines are grouped by an exact rational key.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/small_vec.h"
#include "engine/world_facets.h"

namespace vismap::engine {

// (8 bytes: a million pieces hold one or two inline.)
struct Sharer {
  int facet;
  std::uint32_t edge : 31;     // facet edge index (v[edge] -> v[edge+1]); facets may have 10^6 corners
  std::uint32_t forward : 1;   // the facet's edge runs from a to b
};
static_assert(sizeof(Sharer) == 8);

struct WorldPiece {
  std::uint32_t a, b;             // canonical vertex ids of the end points
  SmallVec<Sharer, 2> sharers;    // every facet edge covering the piece (mostly one or two)
};

// A piece's place among the pieces of its first sharing facet: its line's
// cells, then its place in the sweeps along the lines (edge_pieces.cpp). Unique
// to the piece, and the same whatever the facets' order.
struct PieceRank {
  std::uint64_t cells;
  std::uint32_t seq;
  bool operator<(const PieceRank& o) const { return cells != o.cells ? cells < o.cells : seq < o.seq; }
};

struct MatchedEdges {
  std::vector<WorldPiece> pieces;   // in the order of their first sharing facet, then of their ranks
  std::vector<PieceRank> rank;      // rank[i]: pieces[i]'s
};

// Pieces in the order of their first sharing facet (then deterministic). cell_bits sets how finely lines
// are told apart before exact keys decide (see edge_pieces.cpp); any value gives
// the same pieces, only the work differs (tests vary it to reach every path).
std::vector<WorldPiece> match_edges(const Scene& scene, const WorldFacets& wf, int cell_bits = 20,
                                    int threads = 1);
MatchedEdges match_edges_ranked(const Scene& scene, const WorldFacets& wf, int cell_bits = 20, int threads = 1);

// The pieces that vertex pairs alone give, on a surface that may be a disk:
// facet edges between the same two vertices share one piece, and nothing else
// is matched. Those are match_edges' pieces wherever no vertex of the scene lies
// inside an edge of it, as on a surface certified a height field
// (engine/height_fields.h: its projection is one to one): the caller must know
// that. Only for facets that are all triangles, no two vertices joined by more
// than two facet edges, V - E + F = 1 and three pieces or more of one facet
// (a disk's counts, the only surface that certificate passes); else nullopt.
// Each piece as match_edges gives it; in the order of their first sharing
// facet, then of their vertex pairs (their ranks, vertex_pair_ranks).
// local[id]: input vertex id's number in the order the facets first use them
// (number_by_first_use), nused of them; a pair's edges are then found near
// each other in memory. On `threads` threads; the same pieces for any count.
std::optional<std::vector<WorldPiece>> pieces_of_vertex_pairs(const Scene& scene, const WorldFacets& wf,
                                                               const std::vector<std::uint32_t>& local,
                                                               std::size_t nused, int threads = 1);
// The ranks of pieces_of_vertex_pairs' pieces: their vertex pairs (unique, and
// the same whatever the facets' order, so that renumber_facets keeps them).
std::vector<PieceRank> vertex_pair_ranks(const std::vector<WorldPiece>& pieces);

// The hash of the cells that tell the line through p and q (p != q) apart at
// cell_bits: from doubles with error bounds where they decide, else from
// intervals, else from the line's exact key; with exact_only, from the exact
// key alone. The same value either way (a test checks): a piece's rank, hence
// the output, never depends on which decided.
std::uint64_t line_cells(const Vec3& p, const Vec3& q, int cell_bits, bool exact_only = false);

// The pieces of `m` with facet f renumbered new_index[f], in the order
// match_edges gives for the facets in their new order (the same pieces: only
// the facets' numbers and order differ). For many views of one scene: the
// edges are matched once, and each view orders the facets as it sees them.
MatchedEdges renumber_facets(const MatchedEdges& m, const std::vector<std::uint32_t>& new_index, int threads = 1);

}  // namespace vismap::engine
