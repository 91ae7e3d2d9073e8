#include "curvetet/volume/edit/tet_stars.hpp"

#include "curvetet/volume/mesh_keys.hpp"

#include <algorithm>
#include <stdexcept>

namespace curvetet::volume::edit {

namespace {

bool holds(const Corners& c, int v) { return std::find(c.begin(), c.end(), v) != c.end(); }

void leave(std::vector<int>& star, int t) {
  const auto it = std::find(star.begin(), star.end(), t);
  if (it == star.end()) throw std::logic_error("TetStars: a tet missing from its corner's star");
  star.erase(it);
}

} // namespace

TetStars::TetStars(std::vector<Corners> tets, int num_vertices)
    : corners_(std::move(tets)), alive_(corners_.size(), 1), star_(num_vertices) {
  for (int t = 0; t < num_slots(); ++t)
    for (const int v : corners_[t]) star_[v].push_back(t);
}

int TetStars::add_vertex() {
  star_.emplace_back();
  return num_vertices() - 1;
}

int TetStars::add(const Corners& c) {
  const int t = num_slots();
  corners_.push_back(c); // c may be one of ours: read corners_[t] from here on
  alive_.push_back(1);
  for (const int v : corners_[t]) star_[v].push_back(t);
  return t;
}

void TetStars::kill(int t) {
  if (!alive_[t]) throw std::logic_error("TetStars: kill of a dead tet");
  alive_[t] = 0;
  for (const int v : corners_[t]) leave(star_[v], t);
}

void TetStars::rename_corner(int t, int from, int to) {
  if (!alive_[t]) throw std::logic_error("TetStars: rename in a dead tet");
  for (int& v : corners_[t])
    if (v == from) v = to;
  leave(star_[from], t);
  star_[to].push_back(t);
}

void TetStars::revive(int t) {
  if (alive_[t]) throw std::logic_error("TetStars: revival of a live tet");
  alive_[t] = 1;
  for (const int v : corners_[t]) star_[v].push_back(t);
}

void TetStars::pop_slot() {
  kill(num_slots() - 1);
  corners_.pop_back();
  alive_.pop_back();
}

void TetStars::pop_vertex() {
  if (!star_.back().empty()) throw std::logic_error("TetStars: removal of a vertex that has tets");
  star_.pop_back();
}

bool TetStars::has_edge(int a, int b) const {
  for (const int t : star_[a])
    if (holds(corners_[t], b)) return true;
  return false;
}

bool TetStars::has_face(int a, int b, int c) const {
  for (const int t : star_[a])
    if (holds(corners_[t], b) && holds(corners_[t], c)) return true;
  return false;
}

std::vector<int> TetStars::edge_ring(int a, int b) const {
  std::vector<int> ring;
  for (const int t : star_[a])
    if (holds(corners_[t], b)) ring.push_back(t);
  return ring;
}

std::vector<int> TetStars::ring_cycle(int a, int b, const std::vector<int>& ring) const {
  std::vector<std::array<int, 2>> links;
  for (const int t : ring) {
    std::array<int, 2> e;
    int j = 0;
    for (const int x : corners_[t])
      if (x != a && x != b) e[j++] = x;
    links.push_back(e);
  }
  return volume::ring_cycle(links);
}

std::vector<int> TetStars::neighbours(int v) const {
  std::vector<int> out;
  for (const int t : star_[v])
    for (const int w : corners_[t])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

} // namespace curvetet::volume::edit
