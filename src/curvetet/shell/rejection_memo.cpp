#include "curvetet/shell/rejection_memo.hpp"

#include <algorithm>
#include <cstring>

namespace curvetet::shell {

bool rejection_is_local(Rejection r) {
  switch (r) {
    case Rejection::caps_intersection: // against every cap of the shell
    case Rejection::feature:           // feature chains reach beyond the star
    case Rejection::batch_conflict:    // against the same batch's commits
      return false;
    default: return true;
  }
}

namespace {

// Sequence-sensitive, every input bit reaching every output bit.
class Digest {
 public:
  void add(std::uint64_t x) {
    h_ += x + 0x9e3779b97f4a7c15ull;
    h_ = (h_ ^ (h_ >> 30)) * 0xbf58476d1ce4e5b9ull;
    h_ = (h_ ^ (h_ >> 27)) * 0x94d049bb133111ebull;
    h_ ^= h_ >> 31;
  }
  void add(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    add(bits);
  }
  void add(const Vec3& p) {
    for (int k = 0; k < 3; ++k) add(p[k]);
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0;
};

} // namespace

std::uint64_t star_signature(const ShellEditor& e, int a, int b, const std::vector<double>* thickness) {
  const Shell& s = e.shell();
  Digest d;
  std::vector<int> seen; // shell vertex ids by first appearance
  auto local = [&](int v) {
    for (std::size_t i = 0; i < seen.size(); ++i)
      if (seen[i] == v) return static_cast<std::uint64_t>(i);
    seen.push_back(v);
    d.add(s.bottom[v]);
    d.add(s.middle[v]);
    d.add(s.top[v]);
    d.add(static_cast<std::uint64_t>(s.singular[v]));
    d.add(static_cast<std::uint64_t>(e.faces_of(v).size()));
    if (thickness && v < static_cast<int>(thickness->size())) d.add((*thickness)[v]);
    return static_cast<std::uint64_t>(seen.size() - 1);
  };
  // Candidates list removed faces by id: the ids' relative order counts
  // (compact() keeps it), not their values.
  std::vector<int> star;
  for (int v : {a, b})
    if (v >= 0) star.insert(star.end(), e.faces_of(v).begin(), e.faces_of(v).end());
  std::sort(star.begin(), star.end());
  for (int v : {a, b}) {
    if (v < 0) continue;
    d.add(local(v));
    for (int f : e.faces_of(v)) {
      d.add(static_cast<std::uint64_t>(std::lower_bound(star.begin(), star.end(), f) - star.begin()));
      for (int w : s.faces[f]) d.add(local(w));
      if (!s.middle_nodes.empty())
        for (const auto& p : s.middle_nodes[f]) d.add(p);
      d.add(static_cast<std::uint64_t>(s.tracked[f].size()));
      for (int t : s.tracked[f]) d.add(static_cast<std::uint64_t>(t));
      d.add(static_cast<std::uint64_t>(e.points_in(f).size()));
      for (int p : e.points_in(f)) d.add(static_cast<std::uint64_t>(p));
    }
  }
  // Neighbour lists are sorted by vertex id: the ids' relative order counts.
  std::vector<int> by_id = seen;
  std::sort(by_id.begin(), by_id.end());
  for (int v : seen) d.add(static_cast<std::uint64_t>(std::lower_bound(by_id.begin(), by_id.end(), v) - by_id.begin()));
  return d.value();
}

} // namespace curvetet::shell
