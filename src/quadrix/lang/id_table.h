// An id table of the reader (reader_state.h): from an id to a small non-negative integer (an
// index into a scope's half-spaces, or an encoded solid reference), for scopes of up to millions
// of objects.
//
// The table stores no strings. The ids live in the scene objects themselves, so a slot holds only
// the id's 32-bit hash and the value, and every lookup and insertion is given `idOf(value)`, the
// id of the object a stored value names, to compare against. Open addressing with linear probing
// over a power-of-two array of 8-byte slots, at most half full: one allocation for the whole
// table (a node-based map allocated, and freed at the end of reading, one node per id), and a
// lookup touches one or two cache lines of slots plus the object it finds. Numbered ids keep
// their order in the table by groups of 16 (Hash below).
//
//   IdTable t;
//   t.Set("q1", 0, idOf);          // inserts, or replaces the value stored for "q1"
//   int v = t.Find("q1", idOf);    // 0; -1 when the id is not in the table
//
// idOf must be consistent with the values stored: idOf(v) is the id under which v was set, for
// as long as v is in the table (the reader only appends objects, so their ids never change).
//
// util/hash_slots.h is the general form (64-bit hashes from the caller, spread by a mix) used by
// the flattener and the BRL-CAD converter; this one keeps the placement its own Hash needs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "quadrix/util/huge_pages.h"

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
            if (s.hash == h && Same(idOf(s.value), id)) return s.value;
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
            if (s.hash == h && Same(idOf(s.value), id)) {
                s.value = value;
                return;
            }
        }
    }

    std::size_t Size() const { return count_; }

    // Makes room for `count` ids in all without growing again (a big input's estimate,
    // ReaderState::ReserveForText): the table then grows once instead of at each doubling.
    void Reserve(std::size_t count) {
        std::size_t slots = slots_.empty() ? 16 : slots_.size();
        while (slots < 2 * count) slots *= 2;
        if (slots > slots_.size()) Rehash(slots);
    }

  private:
    struct Slot {
        std::uint32_t hash = 0;
        int value = -1;  // -1: empty
    };

  public:
    // Ids that end in a number, as generated scenes write them (q0, q1, ..., s99999), keep their
    // order in groups of 16: the hash of "q1234" is that of the block ("q", 4 digits, 1234 / 16)
    // times 16, plus 1234 % 16. A scene that names its objects in order, and refers to them in
    // order, then touches the table a cache line at a time instead of at a random slot per id
    // (one cache miss per lookup in a table of megabytes: a tenth of reading 100,000 spheres).
    // Other ids, and the blocks, are spread by a multiplicative hash.
    static std::uint32_t Hash(std::string_view id) {
        std::size_t digits = 0;
        while (digits < id.size() && digits < 9 && IsDigit(id[id.size() - 1 - digits])) ++digits;
        std::uint64_t number = 0;
        if (digits > 0 && digits < 9) {
            for (std::size_t i = id.size() - digits; i < id.size(); ++i)
                number = number * 10 + static_cast<std::uint64_t>(id[i] - '0');
            id.remove_suffix(digits);
        } else {
            digits = 0;  // no number, or a long one: the whole id is hashed
        }
        std::uint64_t h = 0xcbf29ce484222325ull ^ digits;  // FNV-1a over the rest
        for (char c : id) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
        constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ull;
        if (digits == 0) return static_cast<std::uint32_t>((h * kGolden) >> 32);
        const auto block = static_cast<std::uint32_t>(((h + (number >> 4)) * kGolden) >> 32);
        return block << 4 | static_cast<std::uint32_t>(number & 15);
    }

  private:
    static bool IsDigit(char c) { return c >= '0' && c <= '9'; }
    // std::string_view's ==, without a call to memcmp for the short ids of most scenes.
    static bool Same(std::string_view a, std::string_view b) {
        if (a.size() != b.size()) return false;
        if (a.size() > 16) return a == b;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (a[i] != b[i]) return false;
        return true;
    }
    std::size_t Mask() const { return slots_.size() - 1; }
    // Doubles the array; the stored hashes place the slots again without looking at any id.
    void Grow() { Rehash(slots_.empty() ? 16 : 2 * slots_.size()); }
    void Rehash(std::size_t size) {
        std::vector<Slot> old;
        old.reserve(size);
        AdviseHugePages(old.data(), size * sizeof(Slot));
        old.resize(size);
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
