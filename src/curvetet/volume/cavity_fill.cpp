#include "curvetet/volume/cavity_fill.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/chebyshev_centre.hpp"
#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/peel_fill.hpp"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace curvetet::volume {
namespace {

constexpr int kUnset = std::numeric_limits<int>::min();
// Rounds of growing the cavity (around edges where its sectors meet, or
// behind the faces that hide a piece's centre), and the largest piece worth
// an LP: past these, the layered fill is the faster way. Growing behind
// whatever blocks closes within 6 rounds wherever it does on the 21 good
// meshes, hence its own, shorter limit.
constexpr int kMaxGrowth = 24;
constexpr int kMaxGrowthAnyBlocker = 12;
constexpr std::size_t kMaxPieceFaces = 2000;
// The largest piece worth peeling (peel_fill.hpp: each step costs a pass
// over the front per candidate tried), the orders tried and the steps each
// may take (backtracking included) per face of the piece; and the steps one
// fill may spend on peeling in all (a scan has many pieces that no order
// peels, each a few hundred steps).
constexpr std::size_t kMaxPeelFaces = 200;
constexpr int kPeelAttempts = 4;
constexpr long kPeelStepsPerFace = 4;
constexpr long kPeelStepsPerFill = 8192;

// Winding number of every tet outside the cavity, by crossing faces from
// the hull (winding 0 beyond it); +1 when going against a triangle's outward
// normal. Tets the walk cannot reach without entering the cavity join it.
// False if two paths disagree.
bool wind(const BackgroundMesh& bg, const std::vector<mesh::Tri>& surface,
          const std::vector<std::array<int, 4>>& face_of, std::vector<char>& removed, std::vector<int>& w) {
  const int nt = static_cast<int>(bg.tets.size());
  const auto& p = bg.points;
  w.assign(nt, kUnset);
  std::deque<int> queue;
  auto entering = [&](int t, int k) { // across the face of t opposite corner k
    const int f = face_of[t][k];
    if (f < 0) return 0;
    const auto& tri = surface[f];
    return geometry::orient3d(p[tri[0]], p[tri[1]], p[tri[2]], p[bg.tets[t][k]]) < 0 ? 1 : -1;
  };
  bool consistent = true;
  auto assign = [&](int t, int value) {
    if (w[t] == kUnset) {
      w[t] = value;
      queue.push_back(t);
    } else {
      consistent = consistent && w[t] == value;
    }
  };
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k)
      if (!removed[t] && bg.neighbours[t][k] < 0) assign(t, entering(t, k));
  while (!queue.empty() && consistent) {
    const int t = queue.front();
    queue.pop_front();
    for (int k = 0; k < 4; ++k) {
      const int n = bg.neighbours[t][k];
      if (n < 0 || removed[n]) continue;
      int j = 0;
      while (bg.neighbours[n][j] != t) ++j;
      assign(n, w[t] + entering(n, j));
    }
  }
  for (int t = 0; t < nt; ++t)
    if (!removed[t] && w[t] == kUnset) removed[t] = 1;
  return consistent;
}

// The faces bounding the wanted side (winding `keep`) of the cavity, each
// oriented to see that side on its positive side, and the kept tet across
// each (-1 for surface triangles and the hull).
struct CavityBoundary {
  std::vector<mesh::Tri> faces;
  std::vector<int> across;
};
CavityBoundary cavity_boundary(const BackgroundMesh& bg, const std::vector<mesh::Tri>& surface,
                               const std::vector<std::array<int, 4>>& face_of, const std::vector<int>& missing,
                               const std::vector<char>& removed, const std::vector<int>& w, int keep) {
  const auto& p = bg.points;
  CavityBoundary out;
  for (std::size_t r = 0; r < bg.tets.size(); ++r) {
    if (!removed[r]) continue;
    const auto& q = bg.tets[r];
    for (int k = 0; k < 4; ++k) {
      mesh::Tri face{q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]};
      const int f = face_of[r][k], n = bg.neighbours[r][k];
      int side; // winding on r's side of the face
      if (f >= 0) {
        const auto& tri = surface[f];
        side = geometry::orient3d(p[tri[0]], p[tri[1]], p[tri[2]], p[q[k]]) < 0 ? 1 : 0;
      } else if (n >= 0 && removed[n]) {
        continue; // inside the cavity
      } else {
        side = n < 0 ? 0 : w[n];
      }
      if (side != keep) continue;
      if (geometry::orient3d(p[face[0]], p[face[1]], p[face[2]], p[q[k]]) < 0) std::swap(face[1], face[2]);
      out.faces.push_back(face);
      out.across.push_back(f >= 0 ? -1 : n);
    }
  }
  for (int f : missing) {
    const auto& t = surface[f];
    out.faces.push_back(keep == 1 ? mesh::Tri{t[0], t[2], t[1]} : t); // inside lies behind the outward normal
    out.across.push_back(-1);
  }
  return out;
}

// The faces split into closed oriented surfaces, or the edges where they do
// not close (unordered edge keys). Where several sectors of the cavity meet
// at an edge, each face there is paired with the next face around the edge
// on the side it bounds (angles in doubles: a wrong pairing could only make
// a mesh that fails the exact verification, which the caller checks).
struct Pieces {
  std::vector<std::vector<int>> pieces;
  std::vector<std::uint64_t> bad_edges;
};
Pieces closed_pieces(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces) {
  struct Use {
    int face, apex;
    bool forward; // the face runs along the edge from its smaller id
  };
  std::unordered_map<std::uint64_t, std::vector<Use>> uses;
  for (int i = 0; i < static_cast<int>(faces.size()); ++i)
    for (int e = 0; e < 3; ++e) {
      const int a = faces[i][e], b = faces[i][(e + 1) % 3];
      uses[edge_key(a, b)].push_back({i, faces[i][(e + 2) % 3], a < b});
    }
  std::vector<int> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto unite = [&](int i, int j) { parent[root(i)] = root(j); };
  Pieces out;
  for (auto& [key, around] : uses) {
    const auto forward = std::count_if(around.begin(), around.end(), [](const Use& u) { return u.forward; });
    if (2 * forward != static_cast<std::ptrdiff_t>(around.size())) {
      out.bad_edges.push_back(key);
      continue;
    }
    if (around.size() == 2) {
      unite(around[0].face, around[1].face);
      continue;
    }
    // Around the edge u -> v (u the smaller id), a forward face bounds the
    // side counter-clockwise from it (seen along u -> v): it pairs with the
    // next face that way, which must run backward.
    const int u = static_cast<int>(key >> 32), v = static_cast<int>(key & 0xffffffffu);
    const mesh::Vec3 d = (p[v] - p[u]).normalized();
    const mesh::Vec3 x = d.unitOrthogonal(), y = d.cross(x);
    std::vector<std::pair<double, int>> order;
    for (int k = 0; k < static_cast<int>(around.size()); ++k) {
      const mesh::Vec3 w = p[around[k].apex] - p[u];
      order.emplace_back(std::atan2(w.dot(y), w.dot(x)), k);
    }
    std::sort(order.begin(), order.end());
    // Start at a forward face so that pairs are (forward, next backward).
    std::size_t first = 0;
    while (!around[order[first].second].forward) ++first;
    bool alternates = true;
    for (std::size_t k = 0; k < order.size(); k += 2) {
      const Use& a = around[order[(first + k) % order.size()].second];
      const Use& b = around[order[(first + k + 1) % order.size()].second];
      alternates = alternates && a.forward && !b.forward;
      if (alternates) unite(a.face, b.face);
    }
    if (!alternates) out.bad_edges.push_back(key);
  }
  if (!out.bad_edges.empty()) return out;
  std::unordered_map<int, int> piece_of;
  for (int i = 0; i < static_cast<int>(faces.size()); ++i) {
    const auto [it, fresh] = piece_of.emplace(root(i), static_cast<int>(out.pieces.size()));
    if (fresh) out.pieces.emplace_back();
    out.pieces[it->second].push_back(i);
  }
  return out;
}

// Adds to the cavity every tet around the given edges.
void remove_around(const std::vector<std::array<int, 4>>& tets, const std::vector<std::uint64_t>& edges,
                   std::vector<char>& removed) {
  const std::unordered_set<std::uint64_t> wanted(edges.begin(), edges.end());
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int i = 0; i < 4 && !removed[t]; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (wanted.count(edge_key(tets[t][i], tets[t][j]))) {
          removed[t] = 1;
          break;
        }
}

// A point seeing every face of a piece strictly on its positive side, or
// (without one) the faces, as indices into the piece, that do not see the
// centre tried.
struct Kernel {
  std::optional<mesh::Vec3> point;
  std::vector<int> blocking;
};
// The piece's centre `s`, checked exactly: the faces that do not see it
// strictly, or s as the point when none.
Kernel check_centre(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces,
                    const std::vector<int>& piece, const mesh::Vec3& s) {
  Kernel out;
  for (int i = 0; i < static_cast<int>(piece.size()); ++i) {
    const auto& f = faces[piece[i]];
    if (geometry::orient3d(p[f[0]], p[f[1]], p[f[2]], s) <= 0) out.blocking.push_back(i);
  }
  if (out.blocking.empty()) out.point = s;
  return out;
}
// The centre of the largest ball inside all the half-spaces, by an LP
// solved exactly (CGAL, Gmpzf), rounded.
std::optional<mesh::Vec3> exact_centre(const std::vector<HalfSpace>& halves) {
  // Variables x, y, z, r: maximize r subject to n_i . x - r >= b_i.
  CGAL::Quadratic_program<double> lp(CGAL::LARGER, false, 0, false, 0);
  for (int i = 0; i < static_cast<int>(halves.size()); ++i) {
    for (int d = 0; d < 3; ++d) lp.set_a(d, i, halves[i].normal[d]);
    lp.set_a(3, i, -1.0);
    lp.set_b(i, halves[i].offset);
  }
  lp.set_c(3, -1.0);
  const auto solution = CGAL::solve_linear_program(lp, CGAL::Gmpzf());
  if (!solution.is_optimal()) return std::nullopt;
  mesh::Vec3 s;
  auto value = solution.variable_values_begin();
  for (int d = 0; d < 3; ++d, ++value) s[d] = CGAL::to_double(*value);
  return s;
}
// That centre from the LP in doubles first, from the exact LP where the
// doubles' centre does not pass (checked exactly either way).
Kernel kernel_point(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces,
                    const std::vector<int>& piece) {
  std::vector<HalfSpace> halves;
  mesh::Vec3 lo = p[faces[piece[0]][0]], hi = lo;
  for (int i : piece) {
    const auto& f = faces[i];
    const mesh::Vec3 n = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).normalized();
    if (!n.allFinite()) return {};
    halves.push_back({n, n.dot(p[f[0]])});
    for (int x : f) {
      lo = lo.cwiseMin(p[x]);
      hi = hi.cwiseMax(p[x]);
    }
  }
  auto exactly = [&]() -> Kernel {
    const auto s = exact_centre(halves);
    return s ? check_centre(p, faces, piece, *s) : Kernel{};
  };
  // The piece is closed, so its kernel lies within its bounding box.
  const auto centre = chebyshev_centre(halves, lo, hi);
  if (!centre) return exactly();
  auto out = check_centre(p, faces, piece, centre->point);
  // A kernel too thin for doubles may still hold a point the exact LP finds.
  if (!out.point && centre->radius > -1e-9 * (hi - lo).norm()) return exactly();
  return out;
}

// Whether s sees every face of the piece strictly from its positive side.
bool sees_all(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces, const std::vector<int>& piece,
              const mesh::Vec3& s) {
  return std::all_of(piece.begin(), piece.end(), [&](int i) {
    return geometry::orient3d(p[faces[i][0]], p[faces[i][1]], p[faces[i][2]], s) > 0;
  });
}

long peel_steps(std::size_t faces) { return kPeelStepsPerFace * static_cast<long>(faces); }

// A piece filled by peeling: its tets, whose corners past the background's
// points (ids np + k) are the apexes of the cones over what peeling left.
struct PeeledPiece {
  std::vector<std::array<int, 4>> tets;
  std::vector<mesh::Vec3> apexes;
};

// Peels a piece without kernel point (peel_fill.hpp). Where every attempt
// gets stuck, what one leaves may still close with cones, each closed piece
// of it from a kernel point (a twisted remainder, like Schönhardt's prism,
// needs one).
std::optional<PeeledPiece> peel_piece(const std::vector<mesh::Vec3>& p, const std::vector<mesh::Tri>& faces) {
  const int np = static_cast<int>(p.size());
  for (const auto& attempt : peel_tetrahedralize(p, faces, peel_steps(faces.size()), kPeelAttempts)) {
    const auto split = closed_pieces(p, attempt.rest);
    if (!split.bad_edges.empty()) continue;
    PeeledPiece out{attempt.tets, {}};
    bool closed = true;
    for (const auto& rest : split.pieces) {
      const auto kernel = kernel_point(p, attempt.rest, rest);
      if (!(closed = kernel.point.has_value())) break;
      const int id = np + static_cast<int>(out.apexes.size());
      out.apexes.push_back(*kernel.point);
      for (int i : rest) out.tets.push_back({attempt.rest[i][0], attempt.rest[i][1], attempt.rest[i][2], id});
    }
    if (closed) return out;
  }
  return std::nullopt;
}

// The kept tets of side `keep` and the cones over the cavity's pieces, the
// cavity growing until every piece has a kernel point: around edges where
// two of its sectors meet, the tets there; behind the faces that hide a
// piece's centre, the kept tets there (first those without a surface face
// when `off_surface_first`). With `peel`, a piece without a kernel point is
// first peeled (no new point); it grows only when that gets stuck. `too_big`
// tells a failure on kMaxPieceFaces.
std::optional<SideTets> cone_cavity(const BackgroundMesh& bg, const std::vector<mesh::Tri>& surface,
                                    const std::vector<std::array<int, 4>>& face_of, const std::vector<int>& missing,
                                    std::vector<char> removed, const std::vector<int>& w, int keep,
                                    bool off_surface_first, bool peel, bool& too_big) {
  too_big = false;
  const int nt = static_cast<int>(bg.tets.size());
  SideTets out;
  const int np = static_cast<int>(bg.points.size());
  std::unordered_map<std::uint64_t, mesh::Vec3> apex_of; // by piece (its faces' keys, mixed)
  std::unordered_map<std::uint64_t, std::optional<std::pair<std::vector<mesh::Tri>, std::optional<PeeledPiece>>>> peeled;
  long peel_steps_left = kPeelStepsPerFill;
  for (int round = 0;; ++round) {
    if (round > (off_surface_first ? kMaxGrowth : kMaxGrowthAnyBlocker)) {
      logger().debug("volume: the cavity has a piece without kernel point or with pinched edges");
      return std::nullopt;
    }
    const auto boundary = cavity_boundary(bg, surface, face_of, missing, removed, w, keep);
    const auto& faces = boundary.faces;
    const auto split = closed_pieces(bg.points, faces);
    if (!split.bad_edges.empty()) {
      remove_around(bg.tets, split.bad_edges, removed);
      continue;
    }
    out.steiner.clear();
    std::vector<std::array<int, 4>> cones;
    bool grown = false;
    for (const auto& piece : split.pieces) {
      if (piece.size() > kMaxPieceFaces) {
        logger().debug("volume: a cavity piece has grown to {} faces", piece.size());
        too_big = true;
        return std::nullopt;
      }
      // Pieces that did not grow keep their point (an LP each is the cost).
      std::uint64_t key = piece.size();
      for (int i : piece) key += mix64(face_key(faces[i][0], faces[i][1], faces[i][2])); // any order
      const auto known = apex_of.find(key);
      const auto kernel = known != apex_of.end() && sees_all(bg.points, faces, piece, known->second)
                              ? Kernel{known->second, {}}
                              : kernel_point(bg.points, faces, piece);
      if (kernel.point) apex_of[key] = *kernel.point;
      if (!kernel.point && peel && piece.size() <= kMaxPeelFaces && peel_steps_left > 0) {
        // Pieces that did not grow are not peeled again (their faces in
        // order: peeling is deterministic).
        std::vector<mesh::Tri> piece_faces;
        for (int i : piece) piece_faces.push_back(faces[i]);
        std::sort(piece_faces.begin(), piece_faces.end());
        auto& tried = peeled[key];
        if (!tried || tried->first != piece_faces) {
          tried.emplace(piece_faces, peel_piece(bg.points, piece_faces));
          peel_steps_left -= kPeelAttempts * peel_steps(piece.size());
        }
        if (const auto& filled = tried->second) {
          const int shift = static_cast<int>(out.steiner.size());
          for (auto t : filled->tets) {
            for (int& v : t) v += v >= np ? shift : 0;
            cones.push_back(t);
          }
          out.steiner.insert(out.steiner.end(), filled->apexes.begin(), filled->apexes.end());
          continue;
        }
      }
      if (!kernel.point) {
        // The kept tets behind the faces that block the centre join the
        // cavity. Where only surface triangles block it (a kernel too thin
        // for a double point: thin wedges), all the kept tets around do:
        // farther from the wedge's edge, its kernel is wider.
        auto on_surface = [&](int t) {
          return std::any_of(face_of[t].begin(), face_of[t].end(), [](int f) { return f >= 0; });
        };
        bool helped = false;
        for (int pass = off_surface_first ? 0 : 1; pass < 2 && !helped; ++pass)
          for (int i : kernel.blocking)
            if (const int t = boundary.across[piece[i]]; t >= 0 && (pass == 1 || !on_surface(t))) {
              removed[t] = 1;
              helped = true;
            }
        for (int i = 0; i < static_cast<int>(piece.size()) && !helped; ++i)
          if (const int t = boundary.across[piece[i]]; t >= 0) {
            removed[t] = 1;
            helped = true;
          }
        if (!helped) {
          logger().debug("volume: a cavity piece of {} faces has no kernel point", piece.size());
          return std::nullopt;
        }
        grown = true;
        continue;
      }
      const int id = np + static_cast<int>(out.steiner.size());
      out.steiner.push_back(*kernel.point);
      for (int i : piece) cones.push_back({faces[i][0], faces[i][1], faces[i][2], id});
    }
    if (grown) continue;
    for (int t = 0; t < nt; ++t)
      if (!removed[t] && w[t] == keep) out.tets.push_back(bg.tets[t]);
    out.tets.insert(out.tets.end(), cones.begin(), cones.end());
    logger().debug("volume: {} tets around {} missing triangles replaced by {} pieces of {} tets ({} growth rounds)",
                   std::count(removed.begin(), removed.end(), 1), missing.size(), split.pieces.size(), cones.size(),
                   round);
    return out;
  }
}

} // namespace

std::optional<SideTets> side_tets(const BackgroundMesh& bg, const std::vector<mesh::Tri>& surface,
                                  const std::vector<std::array<int, 4>>& face_of, const std::vector<int>& missing,
                                  bool inside) {
  const int nt = static_cast<int>(bg.tets.size());
  std::vector<char> removed(nt, 0);
  if (!missing.empty()) {
    std::vector<mesh::Tri> tris;
    tris.reserve(missing.size());
    for (int f : missing) tris.push_back(surface[f]);
    const auto meeting = triangles_meeting_tets(bg, tris, /*interior=*/true);
    for (int t = 0; t < nt; ++t) removed[t] = !meeting[t].empty();
  }
  std::vector<int> w;
  if (!wind(bg, surface, face_of, removed, w)) {
    logger().debug("volume: inconsistent winding numbers around the cavity");
    return std::nullopt;
  }
  const int keep = inside ? 1 : 0;
  if (missing.empty()) {
    SideTets out;
    for (int t = 0; t < nt; ++t)
      if (!removed[t] && w[t] == keep) out.tets.push_back(bg.tets[t]);
    return out;
  }
  // Growing behind whatever blocks suits most pieces; where that makes a
  // piece creep along the surface (each kept tet with a surface face brings
  // it in: sliver_anchor's pieces did past 12 rounds), growing away from
  // the surface first does. A piece grown past kMaxPieceFaces grew so in
  // the other order too on every good mesh (cheese_genus133: 1.2 s more).
  // Where neither closes, pieces without a kernel point are peeled instead:
  // on thingi10k_44901 the cavity grows into the whole main part, whose
  // solid beside its needle triangles is thinner than any double point.
  bool too_big = false;
  if (auto out = cone_cavity(bg, surface, face_of, missing, removed, w, keep, false, false, too_big)) return out;
  if (!too_big)
    if (auto out = cone_cavity(bg, surface, face_of, missing, removed, w, keep, true, false, too_big)) return out;
  return cone_cavity(bg, surface, face_of, missing, removed, w, keep, false, true, too_big);
}

} // namespace curvetet::volume
