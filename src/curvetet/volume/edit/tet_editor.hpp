#pragma once
// An editable conforming order-P tet mesh (DESIGN.md §9): the one editor the
// curved optimization's operations run on. It owns adjacency (live tets per
// corner vertex), kill/add of tets, and an undo journal: begin() opens a
// transaction, commit() keeps it, rollback() restores the mesh bit for bit.
//
// Nodes are identified by their lattice key: the (corner vertex, integer
// barycentric weight) pairs with weight > 0 (weights sum to P), as in
// highorder/conforming_nodes.hpp. A new tet therefore shares the nodes of
// every edge and face that is still alive in the mesh (curved ones
// included); an edge, face or interior that does not exist yet gets new nodes
// on the straight simplex of its corners (paper §4.3: new interior entities
// start straight). This is only sound while a vertex set names at most one
// entity, which operations keep (link condition, no duplicate entity).
//
// Frozen: the corners of the listed boundary triangles and of hull faces
// (faces used once). Their nodes, and those of listed boundary triangles and
// lines, are pinned: they never lose their last reference, so the boundary,
// its curved nodes and the feature curves never change.
// Corner vertex ids are node ids (of the input mesh, or made by add_vertex).
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/volume/edit/integer_hash.hpp"
#include "curvetet/volume/edit/node_key_table.hpp"
#include "curvetet/volume/edit/tet_stars.hpp"
#include "curvetet/volume/edit/tet_shape.hpp"

#include <array>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace curvetet::volume::edit {

using Vec3 = Eigen::Vector3d;

class TetEditor {
 public:
  // Copies the mesh; throws std::invalid_argument if it is not conforming.
  explicit TetEditor(const mesh::TetMesh& mesh);

  int order() const { return order_; }
  int nodes_per_tet() const { return np_; }

  // Tet slots, dead ones included (ids stay valid until compaction).
  int num_slots() const { return stars_.num_slots(); }
  int num_live() const { return live_; }
  bool alive(int t) const { return stars_.alive(t); }
  const Corners& corners(int t) const { return stars_.corners(t); }
  const int* nodes(int t) const { return tet_nodes_.data() + static_cast<std::size_t>(t) * np_; }
  int tag(int t) const { return tags_[t]; }
  // Shape of tet t (evaluated on first use, then cached); kInvertedShape
  // when a sample's Jacobian is not positive.
  const TetShape& shape(int t) const;
  // Whether tet t's max AMIPS is below bound (stops at the first sample
  // that is not, without caching).
  bool amips_below(int t, double bound) const;
  void positions(int t, Vec3* out) const;
  const Vec3& position(int node) const { return nodes_[node]; }
  int num_nodes() const { return static_cast<int>(nodes_.size()); } // ids; corners among them have tets

  // Live tets having corner v (any order).
  const std::vector<int>& tets_of(int v) const { return stars_.star(v); }
  const TetStars& stars() const { return stars_; }
  // Vertices sharing a live tet with v, ascending.
  std::vector<int> neighbours(int v) const { return stars_.neighbours(v); }
  bool frozen(int v) const { return frozen_[v]; }
  bool is_boundary_face(int a, int b, int c) const;
  bool has_edge(int a, int b) const { return stars_.has_edge(a, b); }
  bool has_face(int a, int b, int c) const { return stars_.has_face(a, b, c); }

  // Transactions (not nested). Inside one: kill live tets, add tets, move
  // nodes.
  void begin();
  void kill(int t);
  int add(Corners corners, int tag);
  int add_vertex(const Vec3& p); // a free vertex (its id), for the tets added next
  void move_node(int id, const Vec3& p);
  // Moves vertex v (made by add_vertex in the open transaction) by d, and
  // with it every node of its tets by its weight on v, so they stay straight.
  void move_new_vertex(int v, const Vec3& d);
  // Places the nodes the open transaction created on new edges, faces and
  // interiors (they start straight) by the discrete harmonic extension of
  // the displacement from straight of the nodes they meet, so a curved face
  // bends a new tet over its whole height, not only in its first node layer.
  void relax_new_nodes();
  const std::vector<int>& added() const { return added_; }
  const std::vector<int>& killed() const { return killed_; }
  void commit();
  void rollback();

  // Re-evaluates the shape of live tet t (after node moves); inside a
  // transaction the rollback forgets it again.
  void refresh_shape(int t);

  // The live mesh, nodes renumbered compactly (boundary, lines, tags and
  // groups carried over).
  mesh::TetMesh to_mesh() const;

 private:
  using Key = NodeKey;
  Key node_key(const Corners& c, int local) const;
  Vec3 straight_position(int node) const; // on the straight simplex of its key's corners
  void ref_nodes(int t); // node references of slot t
  void unref_nodes(int t);
  void ref(int node);
  void unref(int node);

  enum class Op : std::uint8_t { add, kill, move, new_node, forget_shape };
  struct Entry {
    Op op;
    int id;
    Vec3 old;
  };

  mesh::TetMesh source_; // boundary, lines, groups (tets and nodes are ours)
  int order_ = 1, np_ = 4, live_ = 0;
  std::vector<std::array<int, 4>> weights_; // per local node: weights on the 4 corners
  std::vector<Vec3> nodes_;
  std::vector<Key> key_of_;
  std::vector<int> refs_;
  NodeKeyTable node_of_; // live nodes
  TetStars stars_; // corners and stars, by node id (corner vertices are nodes)
  std::vector<int> tet_nodes_;
  std::vector<int> tags_;
  mutable std::vector<TetShape> shapes_;
  mutable std::vector<char> shape_known_;
  std::vector<char> frozen_;
  std::unordered_set<std::array<int, 3>, IntegerHash> boundary_faces_; // sorted corner triples
  bool open_ = false;
  int first_new_node_ = 0; // of the open transaction
  std::vector<Entry> journal_;
  std::vector<int> added_, killed_;
};

} // namespace curvetet::volume::edit
