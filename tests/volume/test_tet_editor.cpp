// The tet-mesh editor of the curved optimization (volume/edit/): transactions
// that roll back bit for bit, lattice-keyed conforming nodes, frozen boundary
// corners, and the topology of its operations (2-3 flip, 3-2 flip, collapse
// with the link condition, edge split) and of check_new_tets. Every mesh is
// tiny, straight and drawn below; the operations are run the way the
// scheduler runs them (kill, add the new vertex, add, check, commit).
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/volume/edit/invariants.hpp"
#include "curvetet/volume/edit/operations.hpp"
#include "curvetet/volume/edit/tet_editor.hpp"
#include "straight_mesh.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace curvetet::volume::edit {
namespace {

using highorder::kTetFaces;
using Face = std::array<int, 3>;

constexpr StarLimits kLoose{1e6, 0}; // any positive straight tet passes

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (b - a).dot((c - a).cross(d - a)); }

Face sorted_face(int a, int b, int c) {
  Face f{a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

Corners sorted_corners(Corners c) {
  std::sort(c.begin(), c.end());
  return c;
}

using test::straight_mesh;

// Unit cube, corner i at (i & 1, i >> 1 & 1, i >> 2 & 1), centre 8. The
// sides at corner 0 are cut by the diagonals 0-3, 0-5, 0-6, the sides at
// corner 7 by 7-1, 7-2, 7-4; each of the 12 triangles is coned to the
// centre (12 tets; only the centre is free).
//
//        6 ------- 7
//       /|        /|        z
//      4 ------- 5 |        |  y
//      | |   8   | |        | /
//      | 2 ------|-3        |/___ x
//      |/        |/
//      0 ------- 1
constexpr int kCentre = 8;
mesh::TetMesh cube_with_centre(int order) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  points.emplace_back(0.5, 0.5, 0.5);
  const std::vector<Face> sides = {{0, 3, 1}, {0, 2, 3}, {0, 1, 5}, {0, 5, 4}, {0, 4, 6}, {0, 6, 2}, // at 0
                                   {4, 5, 7}, {4, 7, 6}, {2, 7, 3}, {2, 6, 7}, {1, 3, 7}, {1, 7, 5}}; // at 7
  std::vector<Corners> tets;
  for (const Face& f : sides) tets.push_back({kCentre, f[0], f[1], f[2]}); // outward face opposite the centre
  return straight_mesh(points, tets, order);
}

// Two tets on the free face 0 1 2 (a triangular bipyramid, all 5 vertices
// on the hull): 3 above the plane z = 0, 4 below, segment 3-4 through the
// face, so the 2-3 flip of 0 1 2 is valid.
//
//            3
//          / | \          tets (0,1,2,3) above z = 0,
//        0 - 2 - 1        (1,0,2,4) below (2 behind 0-1)
//          \ | /
//            4
mesh::TetMesh bipyramid(int order) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25, 0.25, 1}, {0.25, 0.25, -1}};
  return straight_mesh(points, {{0, 1, 2, 3}, {1, 0, 2, 4}}, order);
}

// Tet 0 1 2 3 split at its centroid 4 into four tets, then 5 put at the
// centroid of 4 1 2 3, splitting that one into four (7 tets; 4, 5 free).
//
//            3
//           /|\          4 sees 1 2 3 only through 5: faces 4 2 3 and
//          / 4 \         1 2 3 both exist, tet 4 1 2 3 does not.
//         /  5  \ .
//        0 ----- 1
//         \     /
//            2
mesh::TetMesh stacked_tet() {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  p.push_back((p[0] + p[1] + p[2] + p[3]) / 4);
  p.push_back((p[4] + p[1] + p[2] + p[3]) / 4);
  // Replacing one corner at a time by an inner point keeps the orientation.
  const auto star = [](const Corners& in, int v) {
    std::vector<Corners> out;
    for (int k = 0; k < 4; ++k) {
      Corners c = in;
      c[k] = v;
      out.push_back(c);
    }
    return out;
  };
  std::vector<Corners> tets;
  for (const Corners& c : star({0, 1, 2, 3}, 4)) {
    if (c != Corners{4, 1, 2, 3}) {
      tets.push_back(c);
      continue;
    }
    for (const Corners& d : star(c, 5)) tets.push_back(d);
  }
  return straight_mesh(p, tets, 2);
}

// Runs p as the scheduler does, leaving the transaction open; returns the
// new vertex (kNewVertex if none).
int run(TetEditor& e, const Proposal& p) {
  e.begin();
  for (int t : p.kill) e.kill(t);
  const int v = p.adds_vertex ? e.add_vertex(p.new_vertex) : kNewVertex;
  for (auto [c, tag] : p.add) {
    std::replace(c.begin(), c.end(), kNewVertex, v);
    e.add(c, tag);
  }
  return v;
}

std::set<Corners> live_tets(const TetEditor& e) { // sorted corners
  std::set<Corners> out;
  for (int t = 0; t < e.num_slots(); ++t)
    if (e.alive(t)) out.insert(sorted_corners(e.corners(t)));
  return out;
}

int find_tet(const TetEditor& e, const Corners& corners) {
  for (int t = 0; t < e.num_slots(); ++t)
    if (e.alive(t) && sorted_corners(e.corners(t)) == sorted_corners(corners)) return t;
  return -1;
}

int local_index(const Corners& c, int v) { return static_cast<int>(std::find(c.begin(), c.end(), v) - c.begin()); }

double signed_volume(const TetEditor& e, int t) {
  const Corners& c = e.corners(t);
  return orient(e.position(c[0]), e.position(c[1]), e.position(c[2]), e.position(c[3])) / 6;
}

void expect_all_positive(const TetEditor& e) {
  for (int t = 0; t < e.num_slots(); ++t)
    if (e.alive(t)) {
      EXPECT_GT(signed_volume(e, t), 0) << "tet " << t;
    }
}

double total_volume(const TetEditor& e) {
  double v = 0;
  for (int t = 0; t < e.num_slots(); ++t)
    if (e.alive(t)) v += signed_volume(e, t);
  return v;
}

// Hull faces of the live tets (faces used once), sorted corner triples.
std::set<Face> hull_faces(const TetEditor& e) {
  std::map<Face, int> uses;
  for (int t = 0; t < e.num_slots(); ++t)
    if (e.alive(t))
      for (const auto& f : kTetFaces) {
        const Corners& c = e.corners(t);
        ++uses[sorted_face(c[f[0]], c[f[1]], c[f[2]])];
      }
  std::set<Face> out;
  for (const auto& [f, n] : uses)
    if (n == 1) out.insert(f);
  return out;
}

std::set<Face> boundary_corner_sets(const mesh::TetMesh& m) {
  std::set<Face> out;
  for (int b = 0; b < m.num_boundary(); ++b) {
    const int* ids = m.boundary_triangle(b);
    out.insert(sorted_face(ids[0], ids[1], ids[2]));
  }
  return out;
}

void expect_same_mesh(const mesh::TetMesh& a, const mesh::TetMesh& b) {
  EXPECT_EQ(a.order, b.order);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) EXPECT_TRUE(a.nodes[i] == b.nodes[i]) << "node " << i; // exact
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.tet_tags, b.tet_tags);
  EXPECT_EQ(a.boundary, b.boundary);
  EXPECT_EQ(a.boundary_tags, b.boundary_tags);
  EXPECT_EQ(a.lines, b.lines);
}

// Each lattice point of the mesh is one node and each node one lattice
// point: the (corner node, integer weight > 0) key of every tet node and
// boundary-triangle node maps to a single id, and back. Every node sits on
// the straight simplex of its corners, to 1e-12.
void expect_conforming_and_straight(const mesh::TetMesh& m) {
  using Key = std::vector<std::pair<int, int>>;
  std::map<Key, int> node_at;
  std::map<int, Key> key_of;
  const auto key = [](const int* corners, const int* weights, int n) {
    Key k;
    for (int j = 0; j < n; ++j)
      if (weights[j] > 0) k.emplace_back(corners[j], weights[j]);
    std::sort(k.begin(), k.end());
    return k;
  };
  const auto visit = [&](const Key& k, int id) {
    const auto at = node_at.emplace(k, id).first;
    EXPECT_EQ(at->second, id) << "one lattice point, two nodes";
    const auto of = key_of.emplace(id, k).first;
    EXPECT_TRUE(of->second == k) << "node " << id << " at two lattice points";
  };
  const int p = m.order;
  for (int t = 0; t < m.num_tets(); ++t) {
    const int* ids = m.tet(t);
    for (int i = 0; i < m.tet_nodes(); ++i) {
      const auto n = highorder::tet_node(p, i);
      const int w[4] = {p - n[0] - n[1] - n[2], n[0], n[1], n[2]};
      visit(key(ids, w, 4), ids[i]);
      Vec3 straight = Vec3::Zero();
      for (int j = 0; j < 4; ++j) straight += (double(w[j]) / p) * m.nodes[ids[j]];
      EXPECT_LE((m.nodes[ids[i]] - straight).norm(), 1e-12) << "tet " << t << " node " << i;
    }
  }
  for (int b = 0; b < m.num_boundary(); ++b) {
    const int* ids = m.boundary_triangle(b);
    for (int i = 0; i < m.triangle_nodes(); ++i) {
      const auto n = highorder::triangle_node(p, i);
      const int w[3] = {p - n[0] - n[1], n[0], n[1]};
      const Key k = key(ids, w, 3);
      EXPECT_TRUE(node_at.count(k)) << "boundary triangle " << b << " node " << i << " is no tet's";
      visit(k, ids[i]);
    }
  }
  EXPECT_EQ(key_of.size(), m.nodes.size()) << "unused nodes";
}

// --- frozen vertices ---------------------------------------------------

TEST(TetEditor, FrozenVerticesAreTheCornersOfBoundaryTrianglesAndHullFaces) {
  const mesh::TetMesh listed = cube_with_centre(2);
  mesh::TetMesh unlisted = listed; // hull faces alone freeze the same corners
  unlisted.boundary.clear();
  unlisted.boundary_tags.clear();
  for (const mesh::TetMesh& m : {listed, unlisted}) {
    const TetEditor e(m);
    for (int v = 0; v < 8; ++v) EXPECT_TRUE(e.frozen(v)) << v;
    EXPECT_FALSE(e.frozen(kCentre));
    EXPECT_TRUE(e.is_boundary_face(0, 1, 3));
    EXPECT_FALSE(e.is_boundary_face(kCentre, 0, 1));
  }
}

// --- 1. transactions -----------------------------------------------------

// A fresh editor's to_mesh() is the input renumbered (same tets, node for
// node, same boundary), and is its own fixed point.
TEST(TetEditor, ToMeshIsTheInputRenumbered) {
  const mesh::TetMesh input = cube_with_centre(4);
  const mesh::TetMesh out = TetEditor(input).to_mesh();
  ASSERT_EQ(out.num_tets(), input.num_tets());
  ASSERT_EQ(out.nodes.size(), input.nodes.size());
  for (int t = 0; t < input.num_tets(); ++t)
    for (int i = 0; i < input.tet_nodes(); ++i)
      EXPECT_TRUE(out.nodes[out.tet(t)[i]] == input.nodes[input.tet(t)[i]]);
  ASSERT_EQ(out.boundary.size(), input.boundary.size());
  for (std::size_t i = 0; i < input.boundary.size(); ++i)
    EXPECT_TRUE(out.nodes[out.boundary[i]] == input.nodes[input.boundary[i]]);
  expect_same_mesh(TetEditor(out).to_mesh(), out);
}

TEST(TetEditor, RollbackRestoresTheMeshBitForBit) {
  TetEditor e(cube_with_centre(4));
  const mesh::TetMesh original = e.to_mesh();
  const int nodes = e.num_nodes();

  // Split centre-7 (new vertex and nodes), move its vertex and one node of
  // a tet left alone, and re-add a killed tet with another tag.
  Proposal split_7;
  Reject why{};
  ASSERT_TRUE(split(e, kCentre, 7, split_7, &why));
  const int v = run(e, split_7);
  e.move_new_vertex(v, Vec3(0.05, -0.02, 0.01));
  const int kept = find_tet(e, {kCentre, 0, 3, 1});
  ASSERT_GE(kept, 0);
  e.move_node(e.nodes(kept)[e.nodes_per_tet() - 1], Vec3(0.3, 0.3, 0.1)); // its interior node
  const Corners kept_corners = e.corners(kept); // a copy: add() grows the corner array
  e.kill(kept);
  e.add(kept_corners, 5);
  ASSERT_NE(e.num_nodes(), nodes);
  ASSERT_NE(e.num_live(), 12);
  e.rollback();

  expect_same_mesh(e.to_mesh(), original);
  EXPECT_EQ(e.num_live(), 12);
  EXPECT_EQ(e.num_slots(), 12);
  EXPECT_EQ(e.num_nodes(), nodes);
  EXPECT_TRUE(e.has_edge(kCentre, 7));
  EXPECT_EQ(e.tets_of(kCentre).size(), 12u);

  // The lattice registry is restored too: the same split, committed, shares
  // the surviving nodes.
  run(e, split_7);
  e.commit();
  EXPECT_EQ(e.num_live(), 12 - 6 + 12);
  expect_conforming_and_straight(e.to_mesh());
}

// The cached shapes are part of what rollback must restore: a tet whose
// node moved (and whose shape was re-evaluated, as refresh_shape asks)
// must report its old shape again afterwards.
TEST(TetEditor, RollbackRestoresTheShapeOfATetWhoseNodeMoved) {
  TetEditor e(bipyramid(2));
  const TetShape before = e.shape(0);
  const int node = e.nodes(0)[4]; // on edge 0-1
  const Vec3 at = e.position(node);
  e.begin();
  e.move_node(node, e.position(node) + Vec3(0.05, 0.02, 0.03));
  e.refresh_shape(0);
  ASSERT_NE(e.shape(0).max_amips, before.max_amips);
  e.rollback();
  EXPECT_TRUE(e.position(node) == at);
  EXPECT_EQ(e.shape(0).max_amips, before.max_amips);
  EXPECT_EQ(e.shape(0).min_scaled_jacobian, before.min_scaled_jacobian);
}

TEST(TetEditor, RejectsANonConformingMesh) {
  mesh::TetMesh m = bipyramid(2);
  // Tet 1 gets its own copy of the node on the shared edge 0-1.
  const int np = m.tet_nodes();
  const int shared = m.tets[4]; // tet 0, node 4: edge 0-1
  std::replace(m.tets.begin() + np, m.tets.end(), shared, static_cast<int>(m.nodes.size()));
  m.nodes.push_back(m.nodes[shared]);
  EXPECT_THROW(TetEditor{m}, std::invalid_argument);
}

// --- 2, 3. flips -----------------------------------------------------------

TEST(TetEditor, FlipTwoThreeKeepsTheMeshConformingAndTheNewEdgeStraight) {
  const int order = 3;
  TetEditor e(bipyramid(order));
  const int t = find_tet(e, {0, 1, 2, 3});
  Proposal flip;
  Reject why{};
  ASSERT_TRUE(flip_face(e, t, local_index(e.corners(t), 3), flip, &why)); // face 0 1 2, opposite 3
  EXPECT_EQ(flip.kill.size(), 2u);
  EXPECT_EQ(flip.add.size(), 3u);
  run(e, flip);
  EXPECT_FALSE(check_new_tets(e, kLoose));
  e.commit();

  EXPECT_EQ(live_tets(e), (std::set<Corners>{{0, 1, 3, 4}, {1, 2, 3, 4}, {0, 2, 3, 4}}));
  EXPECT_TRUE(e.has_edge(3, 4));
  EXPECT_FALSE(e.has_face(0, 1, 2));
  expect_all_positive(e);
  EXPECT_NEAR(total_volume(e), 1.0 / 3, 1e-15); // two tets of base 1/2, height 1

  const mesh::TetMesh m = e.to_mesh();
  expect_conforming_and_straight(m);
  // V + 2E + F with V = 5, E = 10 (3 on the rim, 6 to the apexes, 3-4), F = 9 (6 hull, 3 around 3-4).
  EXPECT_EQ(m.nodes.size(), 5u + 2 * 10 + 9);

  // The new edge 3-4: its two nodes at 1/3 and 2/3, one node each in all three tets.
  std::map<int, int> node_by_weight_on_3;
  for (int s = 0; s < e.num_slots(); ++s) {
    if (!e.alive(s)) continue;
    const Corners& c = e.corners(s);
    for (int i = 4; i < e.nodes_per_tet(); ++i) {
      const auto n = highorder::tet_node(order, i);
      const int w[4] = {order - n[0] - n[1] - n[2], n[0], n[1], n[2]};
      int w3 = 0, w4 = 0, elsewhere = 0;
      for (int k = 0; k < 4; ++k) (c[k] == 3 ? w3 : c[k] == 4 ? w4 : elsewhere) += w[k];
      if (elsewhere > 0) continue; // not on the edge 3-4
      const int id = e.nodes(s)[i];
      const auto [it, inserted] = node_by_weight_on_3.emplace(w3, id);
      EXPECT_EQ(it->second, id) << "edge 3-4 node with weight " << w3 << " on 3 differs between tets";
      const Vec3 straight = (double(w3) * e.position(3) + double(w4) * e.position(4)) / order;
      EXPECT_LE((e.position(id) - straight).norm(), 1e-15);
    }
  }
  EXPECT_EQ(node_by_weight_on_3.size(), 2u);
}

TEST(TetEditor, FlipTwoThreeThenThreeTwoGivesBackTheTwoTets) {
  TetEditor e(bipyramid(2));
  const std::set<Corners> before = live_tets(e);
  const int t = find_tet(e, {0, 1, 2, 3});
  Proposal flip;
  Reject why{};
  ASSERT_TRUE(flip_face(e, t, local_index(e.corners(t), 3), flip, &why));
  run(e, flip);
  e.commit();

  std::vector<Proposal> back;
  ASSERT_TRUE(remove_edge(e, 3, 4, back, &why));
  ASSERT_EQ(back.size(), 1u); // a ring of 3 has one triangulation
  EXPECT_EQ(back[0].kill.size(), 3u);
  run(e, back[0]);
  EXPECT_FALSE(check_new_tets(e, kLoose));
  e.commit();

  EXPECT_EQ(live_tets(e), before);
  EXPECT_FALSE(e.has_edge(3, 4));
  EXPECT_TRUE(e.has_face(0, 1, 2));
  expect_all_positive(e);
  const mesh::TetMesh m = e.to_mesh();
  expect_conforming_and_straight(m);
  EXPECT_EQ(m.nodes.size(), 5u + 9); // V + E: the two tets again
}

TEST(TetEditor, FlipsRefuseHullFacesAndHullEdges) {
  TetEditor e(bipyramid(2));
  const int t = find_tet(e, {0, 1, 2, 3});
  Proposal p;
  Reject why{};
  EXPECT_FALSE(flip_face(e, t, local_index(e.corners(t), 0), p, &why)); // face 1 2 3 is on the hull
  EXPECT_EQ(why, Reject::boundary_edge);
  std::vector<Proposal> ring;
  EXPECT_FALSE(remove_edge(e, 0, 1, ring, &why));
  EXPECT_EQ(why, Reject::boundary_edge);
}

// --- 4, 5. collapse --------------------------------------------------------

// The centre onto corner 0: the 6 tets at 0 die, the other 6 become the
// cone from 0 over the three sides at 7.
TEST(TetEditor, CollapseOfTheCentreOntoACornerKeepsTheBoundary) {
  const mesh::TetMesh input = cube_with_centre(2);
  TetEditor e(input);
  const mesh::TetMesh before = e.to_mesh();
  Proposal p;
  Reject why{};
  ASSERT_TRUE(collapse(e, kCentre, 0, p, &why)) << to_string(why);
  EXPECT_EQ(p.kill.size(), 12u);
  EXPECT_EQ(p.add.size(), 6u);
  run(e, p);
  EXPECT_FALSE(check_new_tets(e, kLoose));
  e.commit();

  EXPECT_EQ(e.num_live(), 6);
  EXPECT_TRUE(e.tets_of(kCentre).empty());
  for (const Corners& c : live_tets(e)) EXPECT_EQ(c[0], 0) << "every tet is on corner 0";
  expect_all_positive(e);
  EXPECT_NEAR(total_volume(e), 1.0, 1e-15);

  // Same boundary: the hull faces are the input's boundary triangles, and
  // its nodes are untouched.
  EXPECT_EQ(hull_faces(e), boundary_corner_sets(input));
  const mesh::TetMesh after = e.to_mesh();
  expect_conforming_and_straight(after);
  ASSERT_EQ(after.boundary.size(), before.boundary.size());
  for (std::size_t i = 0; i < before.boundary.size(); ++i)
    EXPECT_TRUE(after.nodes[after.boundary[i]] == before.nodes[before.boundary[i]]) << "boundary node " << i;
}

TEST(TetEditor, CollapseOfAFrozenVertexIsRejected) {
  const TetEditor e(cube_with_centre(2));
  Proposal p;
  Reject why{};
  EXPECT_FALSE(collapse(e, 7, kCentre, p, &why));
  EXPECT_EQ(why, Reject::frozen);
  EXPECT_FALSE(collapse(e, 0, 1, p, &why));
  EXPECT_EQ(why, Reject::frozen);
}

// Collapsing 4 onto 1 would turn tet 4 5 2 3 into a second copy of
// 1 5 2 3 and double the boundary face 1 2 3 (edge 2-3 is in the links of 4
// and 1, not in that of edge 4-1): the link condition refuses it, and 4
// onto 2 or 3 alike. 4 onto 0 passes and leaves the valid star of 5; a
// pair that is no edge is refused too.
TEST(TetEditor, LinkConditionRejectsACollapseThatDuplicatesATet) {
  TetEditor e(stacked_tet());
  ASSERT_EQ(e.num_live(), 7);
  EXPECT_FALSE(e.frozen(4));
  EXPECT_FALSE(e.frozen(5));
  EXPECT_TRUE(e.is_boundary_face(1, 2, 3));
  Proposal p;
  Reject why{};
  for (int b : {1, 2, 3}) {
    EXPECT_FALSE(collapse(e, 4, b, p, &why)) << "4 onto " << b;
    EXPECT_EQ(why, Reject::link_condition) << "4 onto " << b;
  }
  ASSERT_FALSE(e.has_edge(5, 0));
  EXPECT_FALSE(collapse(e, 5, 0, p, &why));
  EXPECT_EQ(why, Reject::link_condition);
  EXPECT_TRUE(collapse(e, 5, 4, p, &why)) << to_string(why); // undoes the insertion of 5

  ASSERT_TRUE(collapse(e, 4, 0, p, &why)) << to_string(why);
  run(e, p);
  EXPECT_FALSE(check_new_tets(e, kLoose));
  e.commit();
  EXPECT_EQ(live_tets(e), (std::set<Corners>{{0, 1, 2, 5}, {0, 1, 3, 5}, {0, 2, 3, 5}, {1, 2, 3, 5}}));
  expect_all_positive(e);
  EXPECT_NEAR(total_volume(e), 1.0 / 6, 1e-15);
  expect_conforming_and_straight(e.to_mesh());
}

// --- 6. check_new_tets -----------------------------------------------------

//  one tet (0,1,2,3) = (origin, x, y, z), order 2
TEST(TetEditor, CheckNewTetsRejectsAnInvertedTetAndAcceptsAGoodOne) {
  TetEditor e(straight_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2, 3}}, 2));

  e.begin();
  e.kill(0);
  e.add({0, 2, 1, 3}, mesh::kDomainTag); // inverted
  EXPECT_EQ(check_new_tets(e, kLoose), Reject::energy);
  EXPECT_EQ(check_new_tets(e, {std::numeric_limits<double>::infinity(), -1e9}), Reject::energy);
  e.rollback();

  e.begin();
  e.kill(0);
  e.add({0, 1, 2, 3}, mesh::kDomainTag);
  EXPECT_FALSE(check_new_tets(e, kLoose));
  EXPECT_EQ(check_new_tets(e, {3.0, 0}), Reject::energy);            // AMIPS >= 3 for any tet
  EXPECT_EQ(check_new_tets(e, {1e6, 2.0}), Reject::scaled_jacobian); // scaled Jacobian <= 1
  e.commit();
  expect_conforming_and_straight(e.to_mesh());
}

// --- 7. split --------------------------------------------------------------

TEST(TetEditor, SplitOfAnInteriorEdgeAddsOneFreeVertexAndRollsBack) {
  TetEditor e(cube_with_centre(2));
  const mesh::TetMesh before = e.to_mesh();
  const int nodes = e.num_nodes();
  Proposal p;
  Reject why{};
  ASSERT_TRUE(split(e, kCentre, 0, p, &why)) << to_string(why);
  const std::size_t shell = p.kill.size();
  EXPECT_EQ(shell, 6u); // the tets at corner 0
  EXPECT_EQ(p.add.size(), 2 * shell);
  EXPECT_TRUE(p.adds_vertex);
  EXPECT_TRUE(p.new_vertex == Vec3(0.25, 0.25, 0.25));

  const int v = run(e, p);
  EXPECT_FALSE(check_new_tets(e, kLoose));
  EXPECT_FALSE(e.frozen(v));
  EXPECT_TRUE(e.position(v) == p.new_vertex);
  EXPECT_EQ(e.num_live(), 12 - 6 + 12);
  EXPECT_EQ(e.tets_of(v).size(), 2 * shell);
  EXPECT_FALSE(e.has_edge(kCentre, 0));
  EXPECT_EQ(e.neighbours(v), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, kCentre}));
  int on_centre = 0, on_corner = 0;
  for (int t : e.tets_of(v)) {
    const Corners& c = e.corners(t);
    on_centre += std::count(c.begin(), c.end(), kCentre);
    on_corner += std::count(c.begin(), c.end(), 0);
  }
  EXPECT_EQ(on_centre, 6);
  EXPECT_EQ(on_corner, 6);
  expect_all_positive(e);
  EXPECT_NEAR(total_volume(e), 1.0, 1e-15);
  expect_conforming_and_straight(e.to_mesh());

  e.rollback();
  expect_same_mesh(e.to_mesh(), before);
  EXPECT_EQ(e.num_nodes(), nodes);
  EXPECT_EQ(e.num_live(), 12);
  EXPECT_TRUE(e.has_edge(kCentre, 0));
}

TEST(TetEditor, SplitOfAHullEdgeIsRejected) {
  const TetEditor e(cube_with_centre(2));
  Proposal p;
  Reject why{};
  EXPECT_FALSE(split(e, 0, 1, p, &why));
  EXPECT_EQ(why, Reject::boundary_edge);
}


// --- 8. shapes ------------------------------------------------------------

// A tet whose Jacobian is not positive has an infinite AMIPS in the cache
// (it used to read an empty optional: the shape left in that slot before).
TEST(TetEditor, ShapeOfAnInvertedTetIsInfinite) {
  TetEditor e(straight_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2, 3}}, 2));
  e.begin();
  e.kill(0);
  const int good = e.add({0, 1, 2, 3}, mesh::kDomainTag);
  EXPECT_LT(e.shape(good).max_amips, 10);
  e.rollback();
  e.begin();
  e.kill(0);
  const int inverted = e.add({0, 2, 1, 3}, mesh::kDomainTag);
  EXPECT_EQ(inverted, good); // the same slot
  EXPECT_EQ(e.shape(inverted).max_amips, std::numeric_limits<double>::infinity());
  EXPECT_LT(e.shape(inverted).min_scaled_jacobian, 0);
  e.rollback();
}


// relax_new_nodes: the nodes a flip creates stay straight where every kept
// node is (a harmonic extension of zero), and where a kept node is bent they
// follow it, by no more than it moved and in its direction (maximum
// principle of the discrete harmonic extension).
TEST(TetEditor, RelaxedNewNodesFollowTheBentNodesTheyMeet) {
  const int order = 3;
  for (const double bend : {0.0, 0.05}) {
    mesh::TetMesh m = bipyramid(order);
    const Vec3 on_face = (m.nodes[0] + m.nodes[1] + m.nodes[3]) / 3; // the node of hull face 0 1 3, kept
    const Vec3 delta(0, -bend, 0);                         // outward, off the bipyramid
    int bent = -1;
    for (int i = 0; i < static_cast<int>(m.nodes.size()); ++i)
      if ((m.nodes[i] - on_face).norm() < 1e-15) bent = i;
    ASSERT_GE(bent, 0);
    m.nodes[bent] += delta;
    TetEditor e(m);
    const int t = find_tet(e, {0, 1, 2, 3});
    Proposal flip;
    Reject why{};
    ASSERT_TRUE(flip_face(e, t, local_index(e.corners(t), 3), flip, &why));
    run(e, flip);
    const int first_new = static_cast<int>(m.nodes.size());
    e.relax_new_nodes();
    double largest = 0;
    for (int s : e.added())
      for (int i = 4; i < e.nodes_per_tet(); ++i) {
        const int id = e.nodes(s)[i];
        if (id < first_new) continue;
        const auto n = highorder::tet_node(order, i);
        const int w[4] = {order - n[0] - n[1] - n[2], n[0], n[1], n[2]};
        Vec3 straight = Vec3::Zero();
        for (int k = 0; k < 4; ++k) straight += (double(w[k]) / order) * e.position(e.corners(s)[k]);
        const Vec3 d = e.position(id) - straight;
        if (bend == 0) {
          EXPECT_LE(d.norm(), 1e-15);
          continue;
        }
        EXPECT_LE(d.norm(), delta.norm() * (1 + 1e-12));
        EXPECT_GE(d.dot(delta), -1e-15);
        largest = std::max(largest, d.norm());
      }
    if (bend > 0) EXPECT_GT(largest, 0.01 * bend);
    e.rollback();
    EXPECT_EQ(e.to_mesh().nodes, TetEditor(m).to_mesh().nodes);
  }
}

} // namespace
} // namespace curvetet::volume::edit
