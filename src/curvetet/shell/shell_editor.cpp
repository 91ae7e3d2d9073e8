#include "curvetet/shell/shell_editor.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/shell/feature_tracking.hpp"
#include "curvetet/shell/straighten.hpp"

#include <algorithm>
#include <cmath>

namespace curvetet::shell {

ShellEditor::ShellEditor(Shell& s) : s_(s) { rebuild(); }

void ShellEditor::rebuild() {
  const int n = s_.num_vertices(), F = s_.num_prisms();
  vf_.assign(n, {});
  for (int f = 0; f < F; ++f)
    for (int v : s_.faces[f]) vf_[v].push_back(f);
  prism_points_.assign(F, {});
  for (int p = 0; p < static_cast<int>(s_.points.size()); ++p) {
    const int f = s_.points[p].image.prism;
    if (f >= 0 && f < F) prism_points_[f].push_back(p);
  }
  face_alive_.assign(F, 1);
  vertex_alive_.assign(n, 1);
  version_.assign(n, 0);
  face_batch_.assign(F, -1);
  alive_faces_ = F;
  // Cell: twice the mean middle edge length (caps are about that size).
  double total = 0;
  for (const auto& f : s_.faces)
    for (int k = 0; k < 3; ++k) total += (s_.middle[f[k]] - s_.middle[f[(k + 1) % 3]]).norm();
  const double mean = F > 0 ? total / (3.0 * F) : 1.0;
  grid_ = CapGrid(mean > 0 ? 2 * mean : 1.0);
  for (int f = 0; f < F; ++f)
    for (int side = 0; side < 2; ++side) grid_.insert(2 * f + side, cap_box(2 * f + side));
}

std::vector<int> ShellEditor::neighbours(int v) const {
  std::vector<int> out;
  for (int f : vf_[v])
    for (int w : s_.faces[f])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {
int moved_index(const StarCandidate& c, int v) {
  for (std::size_t i = 0; i < c.moved.size(); ++i)
    if (c.moved[i] == v) return static_cast<int>(i);
  return -1;
}
} // namespace

const Vec3& ShellEditor::bottom(const StarCandidate& c, int v) const {
  const int i = moved_index(c, v);
  return i >= 0 ? c.moved_bottom[i] : s_.bottom[v];
}
const Vec3& ShellEditor::middle(const StarCandidate& c, int v) const {
  const int i = moved_index(c, v);
  return i >= 0 ? c.moved_middle[i] : s_.middle[v];
}
const Vec3& ShellEditor::top(const StarCandidate& c, int v) const {
  const int i = moved_index(c, v);
  return i >= 0 ? c.moved_top[i] : s_.top[v];
}

PrismGeom ShellEditor::candidate_geom(const StarCandidate& c, int k) const {
  PrismGeom g;
  g.ids = c.faces[k];
  for (int j = 0; j < 3; ++j) {
    const int v = g.ids[j];
    const int i = moved_index(c, v);
    g.bottom[j] = i >= 0 ? c.moved_bottom[i] : s_.bottom[v];
    g.middle[j] = i >= 0 ? c.moved_middle[i] : s_.middle[v];
    g.top[j] = i >= 0 ? c.moved_top[i] : s_.top[v];
  }
  return g;
}

geometry::Box3 ShellEditor::cap_box(int cap) const {
  const Tri& t = s_.faces[cap / 2];
  const auto& P = cap % 2 == 0 ? s_.bottom : s_.top;
  return geometry::bounding_box(P[t[0]], P[t[1]], P[t[2]]);
}

std::vector<int> ShellEditor::commit(const StarCandidate& c, int batch) {
  // Features first: the plan compares moved positions with the current ones.
  // A new vertex (if any) gets id num_vertices().
  apply_feature_edit(s_, c, s_.num_vertices());
  apply_straightening(s_, c, s_.num_vertices());
  if (!c.reshaped.empty() && reshaped_batch_.empty()) reshaped_batch_.assign(s_.input.num_faces(), -1);
  for (int t : c.reshaped) reshaped_batch_[t] = batch;
  // 1. Retire the removed prisms.
  for (int f : c.removed) {
    for (int side = 0; side < 2; ++side) grid_.erase(2 * f + side, cap_box(2 * f + side));
    for (int v : s_.faces[f]) {
      auto& l = vf_[v];
      l.erase(std::remove(l.begin(), l.end(), f), l.end());
      ++version_[v];
    }
    face_alive_[f] = 0;
    prism_points_[f].clear();
    --alive_faces_;
  }
  // 2. Vertices: the new one, moved positions, the removed one.
  int new_vertex = -1;
  for (std::size_t i = 0; i < c.moved.size(); ++i) {
    int v = c.moved[i];
    if (v == kNewVertex) {
      new_vertex = v = s_.num_vertices();
      s_.bottom.push_back(c.moved_bottom[i]);
      s_.middle.push_back(c.moved_middle[i]);
      s_.top.push_back(c.moved_top[i]);
      s_.singular.push_back(0);
      vf_.emplace_back();
      vertex_alive_.push_back(1);
      version_.push_back(0);
    } else {
      s_.bottom[v] = c.moved_bottom[i];
      s_.middle[v] = c.moved_middle[i];
      s_.top[v] = c.moved_top[i];
    }
    ++version_[v];
  }
  if (c.removed_vertex >= 0) {
    if (!vf_[c.removed_vertex].empty())
      throw Error(ExitCode::internal, "shell coarsening: collapsed vertex still has faces");
    vertex_alive_[c.removed_vertex] = 0;
    ++version_[c.removed_vertex];
  }
  // 3. New prisms: reuse the removed slots first.
  const bool curved = !s_.middle_nodes.empty();
  if (curved && c.middle_nodes.size() != c.faces.size())
    throw Error(ExitCode::internal, "shell coarsening: a curved shell's candidate has no fitted middle nodes");
  std::vector<int> ids(c.faces.size());
  for (std::size_t k = 0; k < c.faces.size(); ++k) {
    Tri t = c.faces[k];
    for (int& v : t)
      if (v == kNewVertex) v = new_vertex;
    int f;
    if (k < c.removed.size()) {
      f = c.removed[k];
      s_.faces[f] = t;
      s_.tracked[f] = c.tracked[k];
      if (curved) s_.middle_nodes[f] = c.middle_nodes[k];
    } else {
      f = s_.num_prisms();
      s_.faces.push_back(t);
      s_.tracked.push_back(c.tracked[k]);
      if (curved) s_.middle_nodes.push_back(c.middle_nodes[k]);
      face_alive_.push_back(0);
      face_batch_.push_back(-1);
      prism_points_.emplace_back();
    }
    face_alive_[f] = 1;
    face_batch_[f] = batch;
    ++alive_faces_;
    for (int v : t) {
      vf_[v].push_back(f);
      ++version_[v];
    }
    for (int side = 0; side < 2; ++side) grid_.insert(2 * f + side, cap_box(2 * f + side));
    ids[k] = f;
  }
  for (std::size_t k = c.faces.size(); k < c.removed.size(); ++k) {
    s_.tracked[c.removed[k]].clear();
    if (curved) s_.middle_nodes[c.removed[k]].clear();
  }
  // 4. The map of the points that were in the removed prisms.
  for (const auto& im : c.images) {
    auto& p = s_.points[im.point];
    p.image = MapPoint{ids[im.local], im.u, im.v};
    prism_points_[ids[im.local]].push_back(im.point);
  }
  return ids;
}

bool ShellEditor::reshapes_batch_face(const StarCandidate& c, int batch) const {
  if (reshaped_batch_.empty()) return false;
  return std::any_of(c.reshaped.begin(), c.reshaped.end(), [&](int t) { return reshaped_batch_[t] == batch; });
}

void ShellEditor::compact() {
  const int F = s_.num_prisms(), n = s_.num_vertices();
  std::vector<int> fmap(F, -1), vmap(n, -1);
  int nf = 0, nv = 0;
  for (int v = 0; v < n; ++v)
    if (vertex_alive_[v]) vmap[v] = nv++;
  Shell& s = s_;
  std::vector<Tri> faces;
  std::vector<std::vector<int>> tracked;
  std::vector<std::vector<Vec3>> middle_nodes;
  for (int f = 0; f < F; ++f) {
    if (!face_alive_[f]) continue;
    fmap[f] = nf++;
    Tri t = s.faces[f];
    for (int& v : t) v = vmap[v];
    faces.push_back(t);
    tracked.push_back(std::move(s.tracked[f]));
    if (!s.middle_nodes.empty()) middle_nodes.push_back(std::move(s.middle_nodes[f]));
  }
  auto keep = [&](auto& vec) {
    std::decay_t<decltype(vec)> out;
    out.reserve(nv);
    for (int v = 0; v < n; ++v)
      if (vertex_alive_[v]) out.push_back(vec[v]);
    vec = std::move(out);
  };
  keep(s.bottom);
  keep(s.middle);
  keep(s.top);
  keep(s.singular);
  s.faces = std::move(faces);
  s.tracked = std::move(tracked);
  if (!s.middle_nodes.empty()) s.middle_nodes = std::move(middle_nodes);
  for (auto& p : s.points)
    if (p.image.prism >= 0) p.image.prism = fmap[p.image.prism];
  remap_feature_vertices(s.features, vmap, nv);
  reshaped_batch_.clear(); // batch ids restart with the next pass
  rebuild();
}

} // namespace curvetet::shell
