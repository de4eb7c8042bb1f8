// A table of small integer values under 64-bit hashes the caller has already computed, for the
// lookups of "the first item equal to this one" over many items (the bodies of a flattened scene,
// the placements of a BRL-CAD model). Open addressing with linear probing over one array of
// 16-byte slots: no node per entry (std::unordered_map allocates one), and no key stored here,
// since the caller keeps its items and says whether a candidate is equal (several items may share
// a hash, and then each is a candidate in turn).
//
//   HashSlots slots(n);                                    // room for n values without growing
//   int first = slots.Find(h, [&](int v) { return Same(items[v], item); });
//   if (first < 0) slots.Insert(h, index);
//
// Values are non-negative ints (indices). The table doubles when it would be more than half full.
// Find tries the values stored under the hash in probe order, which need not be the order of
// insertion: callers insert an item only when Find found none equal to it, so that no two stored
// items are equal and the answer does not depend on that order.
//
// lang::IdTable (lang/id_table.h) is the same scheme specialised for the reader's ids: 8-byte
// slots of 32-bit hashes placed by their low bits, which its hash keeps in the order of numbered
// ids (q0, q1, ...) so that reading a big scene touches the table a cache line at a time. That
// placement needs its own hash; here any 64-bit hash is spread by a multiplicative mix. The two
// are kept apart for that reason, not by accident.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace quadrix {

class HashSlots {
  public:
    explicit HashSlots(std::size_t expected = 0) { Reserve(expected); }

    // Room for `n` values in all without growing.
    void Reserve(std::size_t n) {
        if (2 * n > slots_.size()) Rehash(2 * n);
    }

    // The first value stored under `hash` (in probe order) for which same(value) is true, or -1.
    template <class Same>
    int Find(std::uint64_t hash, Same&& same) const {
        if (slots_.empty()) return -1;
        for (std::size_t i = Home(hash);; i = (i + 1) & mask_) {
            const Slot& s = slots_[i];
            if (s.value < 0) return -1;
            if (s.hash == hash && same(s.value)) return s.value;
        }
    }

    void Insert(std::uint64_t hash, int value) {
        if (2 * (count_ + 1) > slots_.size()) Rehash(2 * (count_ + 1));
        Place({hash, value});
        ++count_;
    }

    std::size_t size() const { return count_; }

  private:
    struct Slot {
        std::uint64_t hash = 0;
        int value = -1;  // -1: empty
    };
    // The slot a hash starts probing at: the high bits of a multiplicative mix, so that hashes
    // whose low bits agree (FNV-1a of short keys) still spread.
    std::size_t Home(std::uint64_t hash) const {
        return static_cast<std::size_t>((hash * 0x9E3779B97F4A7C15ull) >> shift_);
    }
    void Place(const Slot& s) {
        std::size_t i = Home(s.hash);
        while (slots_[i].value >= 0) i = (i + 1) & mask_;
        slots_[i] = s;
    }
    // The least power of two >= max(16, n) slots, every value placed again.
    void Rehash(std::size_t n) {
        std::size_t size = 16;
        int bits = 4;
        while (size < n) {
            size *= 2;
            ++bits;
        }
        std::vector<Slot> old = std::move(slots_);
        slots_.assign(size, Slot{});
        mask_ = size - 1;
        shift_ = 64 - bits;
        for (const Slot& s : old)
            if (s.value >= 0) Place(s);
    }

    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    int shift_ = 64;
    std::size_t count_ = 0;
};

}  // namespace quadrix
