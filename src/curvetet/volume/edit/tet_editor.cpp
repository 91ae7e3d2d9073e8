#include "curvetet/volume/edit/tet_editor.hpp"

#include "curvetet/highorder/node_ordering.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace curvetet::volume::edit {
namespace {

std::array<int, 3> sorted(int a, int b, int c) {
  std::array<int, 3> k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

} // namespace

TetEditor::TetEditor(const mesh::TetMesh& m) : order_(m.order), np_(m.tet_nodes()) {
  source_.order = m.order;
  source_.boundary = m.boundary;
  source_.boundary_tags = m.boundary_tags;
  source_.lines = m.lines;
  source_.line_tags = m.line_tags;
  source_.groups = m.groups;
  for (int i = 0; i < np_; ++i) {
    const auto n = highorder::tet_node(order_, i);
    weights_.push_back({order_ - n[0] - n[1] - n[2], n[0], n[1], n[2]});
  }
  nodes_ = m.nodes;
  key_of_.assign(nodes_.size(), Key{});
  key_of_.front().fill(-1);
  std::fill(key_of_.begin(), key_of_.end(), key_of_.front());
  refs_.assign(nodes_.size(), 0);
  frozen_.assign(nodes_.size(), 0);

  const int n = m.num_tets();
  std::vector<Corners> corners(n);
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 4; ++k) corners[t][k] = m.tet(t)[k];
  stars_ = TetStars(std::move(corners), static_cast<int>(nodes_.size()));
  tet_nodes_.assign(m.tets.begin(), m.tets.end());
  tags_.resize(n);
  shapes_.resize(n);
  shape_known_.assign(n, 0);
  std::map<std::array<int, 3>, int> face_uses;
  for (int t = 0; t < n; ++t) {
    const Corners& c = stars_.corners(t);
    tags_[t] = m.tet_tags.empty() ? 0 : m.tet_tags[t];
    for (int i = 0; i < np_; ++i) {
      const int id = m.tet(t)[i];
      const Key key = node_key(c, i);
      if (key_of_[id][0] >= 0 && key_of_[id] != key) throw std::invalid_argument("TetEditor: node shared by two lattice points");
      if (!node_of_.insert(key, id) && node_of_.find(key) != id)
        throw std::invalid_argument("TetEditor: the mesh is not conforming (one lattice point, two nodes)");
      key_of_[id] = key;
    }
    for (const auto& f : highorder::kTetFaces) ++face_uses[sorted(c[f[0]], c[f[1]], c[f[2]])];
    ref_nodes(t);
    ++live_;
  }
  const int tn = m.triangle_nodes();
  for (int b = 0; b < m.num_boundary(); ++b) {
    const int* ids = m.boundary_triangle(b);
    boundary_faces_.insert(sorted(ids[0], ids[1], ids[2]));
    for (int k = 0; k < 3; ++k) frozen_[ids[k]] = 1;
    for (int k = 0; k < tn; ++k) ref(ids[k]); // pinned
  }
  for (int id : m.lines) ref(id);
  for (const auto& [f, uses] : face_uses)
    if (uses == 1) {
      for (int v : f) frozen_[v] = 1;
      boundary_faces_.insert(f);
    }
}

TetEditor::Key TetEditor::node_key(const Corners& c, int local) const {
  std::array<std::pair<int, int>, 4> pairs;
  int used = 0;
  for (int k = 0; k < 4; ++k)
    if (weights_[local][k] > 0) pairs[used++] = {c[k], weights_[local][k]};
  for (int i = 1; i < used; ++i) // insertion sort by vertex (at most 4)
    for (int j = i; j > 0 && pairs[j].first < pairs[j - 1].first; --j) std::swap(pairs[j], pairs[j - 1]);
  Key key;
  key.fill(-1);
  for (int k = 0; k < used; ++k) {
    key[2 * k] = pairs[k].first;
    key[2 * k + 1] = pairs[k].second;
  }
  return key;
}

void TetEditor::positions(int t, Vec3* out) const {
  const int* ids = nodes(t);
  for (int i = 0; i < np_; ++i) out[i] = nodes_[ids[i]];
}

bool TetEditor::is_boundary_face(int a, int b, int c) const { return boundary_faces_.count(sorted(a, b, c)) > 0; }

void TetEditor::ref(int node) {
  if (refs_[node]++ == 0) node_of_.insert(key_of_[node], node);
}

void TetEditor::unref(int node) {
  if (--refs_[node] == 0) node_of_.erase(key_of_[node]);
}

void TetEditor::ref_nodes(int t) {
  const int* ids = nodes(t);
  for (int i = 0; i < np_; ++i) ref(ids[i]);
}

void TetEditor::unref_nodes(int t) {
  const int* ids = nodes(t);
  for (int i = 0; i < np_; ++i) unref(ids[i]);
}

const TetShape& TetEditor::shape(int t) const {
  if (!shape_known_[t]) {
    Vec3 x[165]; // order <= 8
    positions(t, x);
    const auto s = tet_shape(order_, x);
    shapes_[t] = s ? *s : kInvertedShape;
    shape_known_[t] = 1;
  }
  return shapes_[t];
}

bool TetEditor::amips_below(int t, double bound) const {
  if (shape_known_[t]) return shapes_[t].max_amips < bound;
  Vec3 x[165];
  positions(t, x);
  const auto s = tet_shape(order_, x, bound);
  if (!s) return false;
  shapes_[t] = *s;
  shape_known_[t] = 1;
  return true;
}

void TetEditor::refresh_shape(int t) {
  shape_known_[t] = 0;
  if (open_) journal_.push_back({Op::forget_shape, t, Vec3::Zero()}); // undone moves leave it stale again
}

void TetEditor::begin() {
  if (open_) throw std::logic_error("TetEditor: nested transaction");
  open_ = true;
  first_new_node_ = num_nodes();
  journal_.clear();
  added_.clear();
  killed_.clear();
}

void TetEditor::kill(int t) {
  stars_.kill(t);
  unref_nodes(t);
  --live_;
  journal_.push_back({Op::kill, t, Vec3::Zero()});
  killed_.push_back(t);
}

int TetEditor::add(Corners c, int tag) { // by value: c may be one of ours
  const int t = num_slots();
  tags_.push_back(tag);
  tet_nodes_.resize(tet_nodes_.size() + np_);
  int* ids = tet_nodes_.data() + static_cast<std::size_t>(t) * np_;
  for (int i = 0; i < 4; ++i) ids[i] = c[i];
  for (int i = 4; i < np_; ++i) {
    const Key key = node_key(c, i);
    if (const int id = node_of_.find(key); id >= 0) {
      ids[i] = id;
      continue;
    }
    // A new node on the straight simplex of its corners.
    Vec3 p = Vec3::Zero();
    for (int k = 0; k < 4; ++k) p += (double(weights_[i][k]) / order_) * nodes_[c[k]];
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back(p);
    key_of_.push_back(key);
    refs_.push_back(0);
    stars_.add_vertex();
    frozen_.push_back(0);
    journal_.push_back({Op::new_node, id, Vec3::Zero()});
    ids[i] = id;
  }
  stars_.add(c);
  ref_nodes(t); // registers the new nodes' keys (first reference)
  shapes_.emplace_back();
  shape_known_.push_back(0);
  ++live_;
  journal_.push_back({Op::add, t, Vec3::Zero()});
  added_.push_back(t);
  return t;
}

int TetEditor::add_vertex(const Vec3& p) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(p);
  Key key;
  key.fill(-1);
  key[0] = id;
  key[1] = order_;
  key_of_.push_back(key);
  refs_.push_back(0);
  stars_.add_vertex();
  frozen_.push_back(0);
  journal_.push_back({Op::new_node, id, Vec3::Zero()});
  return id;
}

void TetEditor::move_node(int id, const Vec3& p) {
  journal_.push_back({Op::move, id, nodes_[id]});
  nodes_[id] = p;
}

void TetEditor::move_new_vertex(int v, const Vec3& d) {
  std::vector<int> moved;
  for (int t : stars_.star(v)) {
    refresh_shape(t);
    const int* ids = nodes(t);
    for (int i = 0; i < np_; ++i) {
      const int id = ids[i];
      if (std::find(moved.begin(), moved.end(), id) != moved.end()) continue;
      const Key& k = key_of_[id];
      for (int j = 0; j < 8 && k[j] >= 0; j += 2)
        if (k[j] == v) {
          move_node(id, nodes_[id] + (double(k[j + 1]) / order_) * d);
          moved.push_back(id);
        }
    }
  }
}

Vec3 TetEditor::straight_position(int node) const {
  const Key& k = key_of_[node];
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < 8 && k[j] >= 0; j += 2) p += (double(k[j + 1]) / order_) * nodes_[k[j]];
  return p;
}

void TetEditor::relax_new_nodes() {
  constexpr int kSweeps = 8; // Gauss-Seidel; a star is a few node layers deep
  // The transaction's nodes are the ids from first_new_node_ on; vertices
  // among them (add_vertex) are not relaxed.
  std::vector<int> local(nodes_.size() - first_new_node_, -1); // new node - first_new_node_ -> index
  std::vector<int> ids;
  for (int id = first_new_node_; id < num_nodes(); ++id)
    if (key_of_[id][1] != order_) {
      local[id - first_new_node_] = static_cast<int>(ids.size());
      ids.push_back(id);
    }
  if (ids.empty()) return;
  const auto index_of = [&](int id) { return id < first_new_node_ ? -1 : local[id - first_new_node_]; };
  // Per new node, on the lattices of the added tets: its new neighbours and
  // the summed displacement (from straight) of the others, which stay put.
  std::vector<std::vector<int>> free(ids.size());
  std::vector<Vec3> fixed_sum(ids.size(), Vec3::Zero());
  std::vector<int> degree(ids.size(), 0);
  const auto link_to = [&](int i, int w) {
    ++degree[i];
    const int j = index_of(w);
    if (j >= 0) free[i].push_back(j);
    else fixed_sum[i] += nodes_[w] - straight_position(w);
  };
  for (int t : added_) {
    const int* n = nodes(t);
    for (const auto& [a, b] : highorder::tet_lattice_edges(order_)) {
      if (const int ia = index_of(n[a]); ia >= 0) link_to(ia, n[b]);
      if (const int ib = index_of(n[b]); ib >= 0) link_to(ib, n[a]);
    }
  }
  std::vector<Vec3> d(ids.size(), Vec3::Zero());
  for (int sweep = 0; sweep < kSweeps; ++sweep)
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (degree[i] == 0) continue;
      Vec3 sum = fixed_sum[i];
      for (int j : free[i]) sum += d[j];
      d[i] = sum / static_cast<double>(degree[i]);
    }
  for (std::size_t i = 0; i < ids.size(); ++i) nodes_[ids[i]] = straight_position(ids[i]) + d[i];
}

void TetEditor::commit() {
  open_ = false;
  journal_.clear();
}

void TetEditor::rollback() {
  for (auto e = journal_.rbegin(); e != journal_.rend(); ++e) switch (e->op) {
      case Op::add:
        unref_nodes(e->id);
        stars_.pop_slot();
        tags_.pop_back();
        shapes_.pop_back();
        shape_known_.pop_back();
        tet_nodes_.resize(tet_nodes_.size() - np_);
        --live_;
        break;
      case Op::kill:
        stars_.revive(e->id);
        ref_nodes(e->id);
        ++live_;
        break;
      case Op::move: nodes_[e->id] = e->old; break;
      case Op::forget_shape: shape_known_[e->id] = 0; break;
      case Op::new_node:
        nodes_.pop_back();
        key_of_.pop_back();
        refs_.pop_back();
        stars_.pop_vertex();
        frozen_.pop_back();
        break;
    }
  open_ = false;
  journal_.clear();
}

mesh::TetMesh TetEditor::to_mesh() const {
  mesh::TetMesh out = source_;
  std::vector<int> renumber(nodes_.size(), -1);
  for (int t = 0; t < num_slots(); ++t) {
    if (!stars_.alive(t)) continue;
    const int* ids = nodes(t);
    for (int i = 0; i < np_; ++i) {
      int& r = renumber[ids[i]];
      if (r < 0) {
        r = static_cast<int>(out.nodes.size());
        out.nodes.push_back(nodes_[ids[i]]);
      }
      out.tets.push_back(r);
    }
    out.tet_tags.push_back(tags_[t]);
  }
  const auto remap = [&](std::vector<int>& ids) {
    for (int& id : ids) {
      if (renumber[id] < 0) throw std::logic_error("TetEditor: a boundary node lost its tets");
      id = renumber[id];
    }
  };
  remap(out.boundary);
  remap(out.lines);
  return out;
}

} // namespace curvetet::volume::edit
