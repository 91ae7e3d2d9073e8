#pragma once
// Rejections remembered across the coarsening's passes. A candidate rejected
// by an invariant that reads only its star (everything but the caps'
// intersection with the rest of the shell and the feature rules) is rejected
// again while its star is unchanged; the later rounds' collapse passes retry
// thousands of such edges whose stars no commit has touched. The star is
// identified by its content (compact() renumbers ids), so a hit stands for a
// check that would give the same verdict; a hash collision could only skip a
// candidate, never commit an unchecked one.
#include "curvetet/shell/shell_editor.hpp"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace curvetet::shell {

// What a rejected entry cost: candidates tried and rejections per reason
// (replayed into the pass statistics on a hit, so reports do not depend on
// the memo).
struct RejectionRecord {
  int tried = 0;
  std::array<long long, kRejectionCount> rejected{};
};

// Whether a rejection for this reason depends only on the star's content.
bool rejection_is_local(Rejection r);

// A 64-bit digest of everything a candidate on the edge (a, b) (or the
// vertex a, b = -1) reads from the shell: the faces around a and b in
// adjacency order with their vertices' positions (by first appearance, so
// ids do not enter), valences and singular flags, their curved middle
// nodes, tracked input faces and mapped points, and the thickness at their
// vertices when that rule is on. Valid only for shells without features
// (their straightening reads beyond the star).
std::uint64_t star_signature(const ShellEditor& e, int a, int b, const std::vector<double>* thickness);

class RejectionMemo {
 public:
  const RejectionRecord* find(std::uint64_t signature) const {
    const auto it = records_.find(signature);
    return it == records_.end() ? nullptr : &it->second;
  }
  void remember(std::uint64_t signature, const RejectionRecord& r) { records_[signature] = r; }

 private:
  std::unordered_map<std::uint64_t, RejectionRecord> records_;
};

} // namespace curvetet::shell
