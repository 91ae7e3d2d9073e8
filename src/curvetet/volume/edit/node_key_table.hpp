#pragma once
// The editor's map from a lattice key to its live node (tet_editor.hpp). Every
// preview adds and removes hundreds of keys; std::unordered_map paid a heap
// allocation for each, so this is an open-addressing table (linear probing,
// deletion by backward shift): no allocation except when it grows.
#include "curvetet/volume/edit/integer_hash.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace curvetet::volume::edit {

// (vertex, weight) x 4 sorted by vertex, padded with -1; a real key has
// key[0] >= 0, so key[0] = -1 marks an empty slot.
using NodeKey = std::array<int, 8>;

class NodeKeyTable {
 public:
  NodeKeyTable() { slots_.resize(16); }

  // The node of key, or -1.
  int find(const NodeKey& key) const {
    for (std::size_t i = home(key);; i = (i + 1) & mask()) {
      const Slot& s = slots_[i];
      if (s.key[0] < 0) return -1;
      if (s.key == key) return s.node;
    }
  }

  // Sets key's node; returns false (and leaves it) if key already had one.
  bool insert(const NodeKey& key, int node) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    for (std::size_t i = home(key);; i = (i + 1) & mask()) {
      Slot& s = slots_[i];
      if (s.key[0] < 0) {
        s = {key, node};
        ++size_;
        return true;
      }
      if (s.key == key) return false;
    }
  }

  // Removes key if present.
  void erase(const NodeKey& key) {
    std::size_t i = home(key);
    for (;; i = (i + 1) & mask()) {
      if (slots_[i].key[0] < 0) return;
      if (slots_[i].key == key) break;
    }
    // Backward shift: pull later entries of the probe run into the hole
    // unless their home lies cyclically in (hole, j].
    for (std::size_t j = (i + 1) & mask();; j = (j + 1) & mask()) {
      if (slots_[j].key[0] < 0) break;
      const std::size_t h = home(slots_[j].key);
      const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
      if (stays) continue;
      slots_[i] = slots_[j];
      i = j;
    }
    slots_[i].key[0] = -1;
    --size_;
  }

  std::size_t size() const { return size_; }

 private:
  struct Slot {
    NodeKey key{-1};
    int node = -1;
  };

  std::size_t mask() const { return slots_.size() - 1; }

  std::size_t home(const NodeKey& key) const { return IntegerHash{}(key) & mask(); }

  void grow() {
    std::vector<Slot> old(2 * slots_.size());
    old.swap(slots_);
    size_ = 0;
    for (const Slot& s : old)
      if (s.key[0] >= 0) insert(s.key, s.node);
  }

  std::vector<Slot> slots_;
  std::size_t size_ = 0;
};

} // namespace curvetet::volume::edit
