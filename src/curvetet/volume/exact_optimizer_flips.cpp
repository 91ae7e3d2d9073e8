#include "curvetet/volume/exact_optimizer.hpp"

#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/tet_amips.hpp"

#include <algorithm>
#include <vector>

namespace curvetet::volume::exact {

bool Optimizer::flip_32(int a, int b) { return flip_32(a, b, edge_ring(a, b)); }

bool Optimizer::flip_32(int a, int b, const std::vector<int>& ring) {
  if (ring.size() != 3) return reject(FillReject::topology);
  std::vector<int> others;
  for (int t : ring)
    for (int x : stars_.corners(t))
      if (x != a && x != b) others.push_back(x);
  std::sort(others.begin(), others.end());
  // closed ring: three vertices, each twice
  if (!(others.size() == 6 && others[0] == others[1] && others[2] == others[3] && others[4] == others[5] &&
        others[1] != others[2] && others[3] != others[4]))
    return reject(FillReject::topology);
  const int c = others[0], d = others[2], e = others[4];
  if (face_exists(c, d, e)) return reject(FillReject::duplicate_entity);
  double old_max = 0;
  for (int t : ring) old_max = std::max(old_max, tet_energy(t));
  // a and b must lie strictly on opposite sides of cde (then ab pierces it).
  const int sa = m_.v.orient(c, d, e, a), sb = m_.v.orient(c, d, e, b);
  if (sa == 0 || sb != -sa) return reject(FillReject::positivity);
  Tet t1 = sa > 0 ? Tet{c, d, e, a} : Tet{d, c, e, a};
  Tet t2 = sa > 0 ? Tet{d, c, e, b} : Tet{c, d, e, b};
  const double new_max = std::max(energy(t1), energy(t2));
  if (!(new_max < old_max || new_max <= coarsen_energy_)) return reject(FillReject::no_gain);
  for (int t : ring) kill(t);
  add(t1);
  add(t2);
  ++stats_.flips;
  return true;
}

std::vector<int> Optimizer::interior_ring(int a, int b) const {
  std::vector<int> ring = edge_ring(a, b);
  if (ring.size() < 3 || ring_cycle(a, b, ring).empty()) ring.clear();
  return ring;
}

bool Optimizer::remove_edge(int a, int b, const std::vector<int>& ring) {
  const int k = static_cast<int>(ring.size());
  if (k < 4 || k > 7) return reject(FillReject::topology);
  const auto c = ring_cycle(a, b, ring);
  if (c.empty()) return reject(FillReject::topology);
  double best_max = 0;
  for (int t : ring) best_max = std::max(best_max, tet_energy(t));
  std::vector<Tet> best;
  for (int i = 0; i < k; ++i) {
    if (!fan_may_beat(a, b, c, i, best_max)) continue;
    auto nt = fan_tets(a, b, c, i);
    double m = 0;
    for (const auto& t : nt) m = std::max(m, energy(t));
    if (!nt.empty() && m < best_max) {
      best_max = m;
      best = std::move(nt);
    }
  }
  if (best.empty()) return reject(FillReject::no_gain);
  for (int t : ring) kill(t);
  for (const auto& t : best) add(t);
  ++stats_.flips;
  return true;
}

bool Optimizer::remove_edge_then_32(int a, int b) {
  std::vector<int> ring = edge_ring(a, b);
  const int k = static_cast<int>(ring.size());
  if (k < 4 || k > 6) return reject(FillReject::topology);
  const auto c = ring_cycle(a, b, ring);
  if (c.empty()) return reject(FillReject::topology);
  double old_max = 0;
  for (int t : ring) old_max = std::max(old_max, tet_energy(t));
  const double bound = std::max(old_max, coarsen_energy_);
  for (int i = 0; i < k; ++i) {
    const auto nt = fan_tets(a, b, c, i);
    if (nt.empty()) continue;
    double new_max = 0;
    for (const auto& t : nt) new_max = std::max(new_max, energy(t));
    if (!(new_max <= bound)) continue;
    begin_journal();
    ring = edge_ring(a, b); // an undone fan put back copies of the ring
    for (int t : ring) kill(t);
    for (const auto& t : nt) add(t);
    int removed = 0;
    for (bool progress = true; progress;) {
      progress = false;
      for (int m = 0; m < k; ++m)
        for (int end : {a, b})
          if (flip_32(end, c[m])) {
            ++removed;
            progress = true;
          }
    }
    journaling_ = false;
    if (removed > k - 4) { // 2(k-2) - removed < k
      ++stats_.flips;
      return true;
    }
    undo_journal();
    // try the next fan
  }
  return reject(FillReject::no_gain);
}

bool Optimizer::fan_may_beat(int a, int b, const std::vector<int>& c, int i, double bound) const {
  const int k = static_cast<int>(c.size());
  const auto& d = m_.v.d;
  for (int j = 1; j <= k - 2; ++j) {
    const Vec3 &p = d[c[i]], &q = d[c[(i + j) % k]], &r = d[c[(i + j + 1) % k]];
    for (int apex : {a, b})
      if (std::min(tet_amips(p, q, r, d[apex]), tet_amips(q, p, r, d[apex])) >= bound) return false;
  }
  return true;
}

std::vector<Tet> Optimizer::fan_tets(int a, int b, const std::vector<int>& c, int i) const {
  const int k = static_cast<int>(c.size());
  for (int j = 2; j <= k - 2; ++j)
    if (edge_exists(c[i], c[(i + j) % k]) || too_long(c[i], c[(i + j) % k])) return {};
  std::vector<Tet> out;
  int sign = 0;
  for (int j = 1; j <= k - 2; ++j) {
    Tet ta{c[i], c[(i + j) % k], c[(i + j + 1) % k], a}, tb{c[i], c[(i + j) % k], c[(i + j + 1) % k], b};
    const int sa = m_.v.orient(ta[0], ta[1], ta[2], ta[3]), sb = m_.v.orient(tb[0], tb[1], tb[2], tb[3]);
    if (sa == 0 || sb != -sa || (sign != 0 && sa != sign)) return {};
    sign = sa;
    if (sa < 0) std::swap(ta[0], ta[1]);
    else std::swap(tb[0], tb[1]);
    out.push_back(ta);
    out.push_back(tb);
  }
  return out;
}

bool Optimizer::flip_23(int t, int k) {
  const Tet q = stars_.corners(t);
  const int d = q[k];
  std::array<int, 3> f;
  for (int i = 0, j = 0; i < 4; ++i)
    if (i != k) f[j++] = q[i];
  // (f0, f1, f2, d) is q up to moving corner k last: parity 3 - k.
  if ((3 - k) % 2 == 1) std::swap(f[0], f[1]);
  int other = -1;
  for (int s : stars_.star(f[0])) {
    if (s == t) continue;
    const Tet& r = stars_.corners(s);
    if (std::find(r.begin(), r.end(), f[1]) != r.end() && std::find(r.begin(), r.end(), f[2]) != r.end()) {
      other = s;
      break;
    }
  }
  if (other < 0) return reject(FillReject::topology);
  int e = -1;
  for (int x : stars_.corners(other))
    if (x != f[0] && x != f[1] && x != f[2]) e = x;
  if (edge_exists(d, e)) return reject(FillReject::duplicate_entity);
  NewTetRule rule;
  rule.max_energy = std::max(tet_energy(t), tet_energy(other));
  rule.strict = true;
  rule.energy_reason = FillReject::no_gain;
  std::vector<Tet> nt(3);
  for (int i = 0; i < 3; ++i) nt[i] = {f[i], f[(i + 1) % 3], e, d}; // positive iff de pierces f
  if (const auto why = broken_invariant(nt, rule)) return reject(*why);
  kill(t);
  kill(other);
  for (auto& x : nt) add(x);
  ++stats_.flips;
  return true;
}

} // namespace curvetet::volume::exact
