// An id table of the reader (reader_state.h): from an id to a small non-negative integer (an
// index into a scope's half-spaces, or an encoded solid reference), for scopes of up to millions
// of objects.
//
// The table stores no strings. The ids live in the scene objects themselves, so a slot holds only
// the id's 32-bit hash and the value, and every lookup and insertion is given `idOf(value)`, the
// id of the object a stored value names, to compare against. Open addressing with linear probing
// over a power-of-two array of 8-byte slots, at most half full: one allocation for the whole
// table (a node-based map allocated, and freed at the end of reading, one node per id), and a
// lookup touches one or two cache lines of slots plus the object it finds.
//
//   IdTable t;
//   t.Set("q1", 0, idOf);          // inserts, or replaces the value stored for "q1"
//   int v = t.Find("q1", idOf);    // 0; -1 when the id is not in the table
//
// idOf must be consistent with the values stored: idOf(v) is the id under which v was set, for
// as long as v is in the table (the reader only appends objects, so their ids never change).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

namespace quadrix::lang {

class IdTable {
  public:
    template <class IdOf>
    int Find(std::string_view id, const IdOf& idOf) const {
        if (slots_.empty()) return -1;
        const std::uint32_t h = Hash(id);
        for (std::size_t i = h & Mask();; i = (i + 1) & Mask()) {
            const Slot& s = slots_[i];
            if (s.value < 0) return -1;
            if (s.hash == h && std::string_view(idOf(s.value)) == id) return s.value;
        }
    }

    // Inserts `value` under `id`, or replaces the value already stored under it.
    template <class IdOf>
    void Set(std::string_view id, int value, const IdOf& idOf) {
        if (2 * (count_ + 1) > slots_.size()) Grow();
        const std::uint32_t h = Hash(id);
        for (std::size_t i = h & Mask();; i = (i + 1) & Mask()) {
            Slot& s = slots_[i];
            if (s.value < 0) {
                s = {h, value};
                ++count_;
                return;
            }
            if (s.hash == h && std::string_view(idOf(s.value)) == id) {
                s.value = value;
                return;
            }
        }
    }

    std::size_t Size() const { return count_; }

  private:
    struct Slot {
        std::uint32_t hash = 0;
        int value = -1;  // -1: empty
    };

    static std::uint32_t Hash(std::string_view id) {
        const std::size_t h = std::hash<std::string_view>{}(id);
        return static_cast<std::uint32_t>(h ^ (h >> 32));
    }
    std::size_t Mask() const { return slots_.size() - 1; }
    // Doubles the array; the stored hashes place the slots again without looking at any id.
    void Grow() {
        std::vector<Slot> old(slots_.empty() ? 16 : 2 * slots_.size());
        old.swap(slots_);
        for (const Slot& s : old) {
            if (s.value < 0) continue;
            std::size_t i = s.hash & Mask();
            while (slots_[i].value >= 0) i = (i + 1) & Mask();
            slots_[i] = s;
        }
    }

    std::vector<Slot> slots_;
    std::size_t count_ = 0;
};

}  // namespace quadrix::lang
